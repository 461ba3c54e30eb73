"""The Newton step of a batch of small square systems, where it is defined."""

from __future__ import annotations

import numpy


def newton_step(f, jac, good):
    """The Newton step ``J^-1 f`` (..., n) where ``good`` and J (..., n, n) is invertible
    (zero elsewhere), and where it was taken.  With ``J^T J`` and ``J^T f`` for J and f,
    the Gauss-Newton step of an overdetermined system."""
    eye = numpy.eye(jac.shape[-1])
    good = good & (numpy.abs(numpy.linalg.det(numpy.where(good[..., None, None], jac,
                                                          eye))) > 0.0)
    step = numpy.linalg.solve(numpy.where(good[..., None, None], jac, eye),
                              numpy.where(good[..., None], f, 0.0)[..., None])[..., 0]
    return step, good
