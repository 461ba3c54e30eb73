"""Back-substitution through a table of linear and quadratic steps (IK, FK, passive joints).

A step is ``(degree, kernel, bit)``: the kernel returns the coefficients ``(A, B, C)`` of
``A x^2 + B x + C`` (``A`` unused for degree 1) from the inputs and the unknowns solved
before it; ``bit`` is the bit of the mode that selects the ``-sqrt`` root of a quadratic.
"""

from __future__ import annotations

import numpy

from .inputs import contiguous_columns
from .status import (
    DISC_RTOL,
    INPUT_SINGULAR,
    INVALID_INPUT,
    JOINT_AT_INFINITY,
    NO_REAL_SOLUTION,
    NOT_SOLVED,
    OK,
    ON_BOUNDARY,
)


def backsubstitute(inputs, steps, indices, n_out, mode, par, with_status=False,
                   per_step=None):
    """Solve ``steps`` in order (linear or quadratic in one unknown each); NaN on failure.

    ``inputs`` has shape (..., n_in); the result has shape (..., n_out) with unknown k at
    ``indices[k]``, all NaN where any step fails (a view whose columns are contiguous);
    status codes are computed on request.
    Quadratic roots are taken in the form that never subtracts nearly equal numbers.

    ``per_step``, a dict, receives ``codes`` (..., len(steps)): each step's own status
    (NOT_SOLVED where its coefficients use an unknown an earlier step failed to give: a
    polynomial of finite numbers is never NaN), ``discriminants`` (one array per step,
    None for a linear step) and ``roots`` (each step's root before the all-or-nothing rule).
    """
    shape = inputs.shape[:-1]
    # contiguous columns (numpy's loops on strided arrays are about 1.7 times slower); a
    # no-op where the caller keeps its inputs column by column
    cols = contiguous_columns(inputs)
    out = numpy.empty((n_out,) + shape)  # one unknown per row: contiguous columns again
    status = numpy.zeros(shape, dtype=numpy.int8) if with_status else None
    if with_status:
        status[~numpy.all(numpy.isfinite(inputs), axis=-1)] = INVALID_INPUT
    solved = []
    failed = numpy.zeros(shape, dtype=bool)
    codes, discs = [], []
    with numpy.errstate(all="ignore"):
        for (degree, kern, bit), index in zip(steps, indices):
            a, b, c = kern(*cols, *solved, *par)
            if per_step is not None:
                nan_in = numpy.isnan(b) | numpy.isnan(c) | (numpy.isnan(a) if degree == 2
                                                            else False)
            if degree == 1:
                root = numpy.asarray(-c / b, dtype=float)
                bad = ~numpy.isfinite(root)
                no_real = None
                pivot_zero = bad & (b == 0)  # det Ji = 0 exactly: an input singularity
                disc = None
            else:
                minus = (mode >> bit) & 1  # the root with -sqrt(disc)
                bb = b * b
                disc = bb - 4.0 * a * c
                ssq = numpy.sqrt(numpy.maximum(disc, 0.0))
                if minus:  # sign * sqrt and sign * b <= 0 without multiplying by the sign
                    ssq = -ssq
                near = (b >= 0.0) if minus else (b <= 0.0)
                root = numpy.where(near, (ssq - b) / (2.0 * a), (2.0 * c) / (-b - ssq))
                no_real = disc < -DISC_RTOL * bb
                bad = no_real | ~numpy.isfinite(root)
                pivot_zero = None
            if with_status or per_step is not None:
                # NaN for the later steps (NOT_SOLVED) and the per-step roots; without a
                # status the failed poses are set to NaN once, at the end
                root = numpy.where(bad, numpy.nan, root)
            if with_status:
                new = numpy.where(bad, JOINT_AT_INFINITY, OK)
                if pivot_zero is not None:
                    new = numpy.where(pivot_zero, INPUT_SINGULAR, new)
                if no_real is not None:
                    new = numpy.where(no_real, NO_REAL_SOLUTION, new)
                    on_boundary = ~bad & (numpy.abs(disc) <= DISC_RTOL * bb)
                    new = numpy.where(on_boundary, ON_BOUNDARY, new)
                # the first failure wins; a failure overrides an earlier ON_BOUNDARY
                replace = (status == OK) | ((status == ON_BOUNDARY) & bad)
                status = numpy.where(replace, new, status).astype(numpy.int8)
                if per_step is not None:
                    codes.append(numpy.where(nan_in, NOT_SOLVED, new).astype(numpy.int8))
                    discs.append(disc)
            out[index, ...] = root
            solved.append(root)
            failed |= bad
    if per_step is not None:
        per_step["codes"] = (numpy.stack(codes, axis=-1) if codes
                             else numpy.zeros(shape + (0,), dtype=numpy.int8))
        per_step["discriminants"] = discs
        per_step["roots"] = numpy.moveaxis(out, 0, -1).copy()
    # a configuration is reachable as a whole or not at all: the status says which leg failed
    out[:, failed] = numpy.nan
    return numpy.moveaxis(out, 0, -1), status
