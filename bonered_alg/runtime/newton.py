"""The Newton step of a batch of small square systems, where it is defined, and the
systems themselves from a kernel that returns residuals then Jacobian."""

from __future__ import annotations

import numpy

from .inputs import broadcast


def kernel_system(kern, args, shape, n):
    """Residuals f (..., m) and Jacobian J (..., m, n) from a kernel returning the m
    residuals then J row-major, at ``args`` broadcast to the leading ``shape``; both
    C-contiguous, as numpy.stack gives them (numpy's small matrix products sum in an order
    that depends on the layout: the same numbers only from the same layout).  Where
    ``kern`` is a compiled twin (:class:`.compiled.RowKernel`), from its one array."""
    matrix = getattr(kern, "matrix", None)
    if matrix is not None:
        out, at, rows = matrix(*args)
        out = numpy.broadcast_to(out[:, :rows].reshape((len(out),) + at), (len(out),) + shape)
        m = len(out) // (n + 1)
        return (numpy.ascontiguousarray(numpy.moveaxis(out[:m], 0, -1)),
                numpy.ascontiguousarray(numpy.moveaxis(out[m:], 0, -1)).reshape(
                    shape + (m, n)))
    vals = [broadcast(v, shape) for v in kern(*args)]
    m = len(vals) // (n + 1)
    return (numpy.stack(vals[:m], axis=-1),
            numpy.stack(vals[m:], axis=-1).reshape(shape + (m, n)))


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
