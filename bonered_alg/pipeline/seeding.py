"""sympy's random numbers, seeded for a derivation: the same work on every run.

sympy's multivariate factorization (Wang's algorithm, ``factortools.dmp_zz_wang``) and a few
other routines draw evaluation points from ``sympy.core.random``, which is seeded from the
operating system at import.  The factors are unique, so the outputs never depended on it,
but the time did: a derivation's factoring took seconds in most runs and tens of minutes in
some (the README example's derivation of pro_hep_lct in a test worker whose earlier tests
had drawn other numbers).  Seeded, each derivation draws the same numbers on every run.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

SEED = 15


@contextmanager
def seeded_sympy_random(seed: int = SEED) -> Iterator[None]:
    """Within the block, sympy's random generators start from ``seed``; their state is
    restored afterwards."""
    from sympy.core import random as sympy_random

    saved = (sympy_random.rng.getstate(), sympy_random._assumptions_rng.getstate())
    sympy_random.seed(seed)
    try:
        yield
    finally:
        sympy_random.rng.setstate(saved[0])
        sympy_random._assumptions_rng.setstate(saved[1])
