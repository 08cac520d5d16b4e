"""mdcalc: a command-line calculator for machine dynamics."""

__version__ = "0.1.0"
