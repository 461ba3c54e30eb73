"""Surgical tool manipulation in Study parameters (004 Sect. 2.1) and its use with a
generated mechanism module (numeric; imports numpy, never sympy)."""
