"""Maths shared by several problems. No CLI, no I/O, no printing."""
