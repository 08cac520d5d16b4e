"""The version of mdcalc: one place, read by pyproject.toml (setuptools' ``attr:``)
and written into every JSON document. A leaf: it imports nothing."""

__version__ = "0.1.0"
