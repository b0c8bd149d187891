"""Parametric generators of standard structures (scenes built in code)."""
