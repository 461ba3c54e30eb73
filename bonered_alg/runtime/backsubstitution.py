"""Back-substitution through a table of linear and quadratic steps (IK, FK, passive joints).

A step is ``(degree, kernel, bit)``: the kernel returns the coefficients ``(A, B, C)`` of
``A x^2 + B x + C`` (``A`` unused for degree 1) from the inputs and the unknowns solved
before it; ``bit`` is the bit of the mode that selects the ``-sqrt`` root of a quadratic.
Where no step reads an earlier unknown, ``coefficients`` may give every step's ``(A, B,
C)`` from the inputs in one call (a generated module's ``_step_coefficients``: one CSE
program over all the steps), used in place of the step kernels.
"""

from __future__ import annotations

import numpy

from .inputs import contiguous_columns, rows_last
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
                   per_step=None, coefficients=None):
    """Solve ``steps`` in order (linear or quadratic in one unknown each); NaN on failure.

    The per-step record (``per_step``) comes from :func:`backsubstitute_detailed`; without
    it, :func:`backsubstitute_lean` gives the same roots, NaN and status codes with fewer
    array operations."""
    if per_step is not None:
        return backsubstitute_detailed(inputs, steps, indices, n_out, mode, par, with_status,
                                       per_step, coefficients)
    return backsubstitute_lean(inputs, steps, indices, n_out, mode, par, with_status,
                               coefficients)


def _all_coefficients(cols, par, coefficients):
    """Each step's ``(A, B, C)`` from the one kernel ``coefficients`` (a list, one triple
    per step), or None without it."""
    if coefficients is None:
        return None
    values = coefficients(*cols, *par)
    return [values[i:i + 3] for i in range(0, len(values), 3)]


def _step_coefficients(k, kern, cols, solved, par, fused):
    """Step ``k``'s ``(A, B, C)``: its kernel's, or from ``fused`` (:func:`_all_coefficients`),
    whose entry is then released."""
    if fused is None:
        return kern(*cols, *solved, *par)
    out, fused[k] = fused[k], None
    return out


def backsubstitute_lean(inputs, steps, indices, n_out, mode, par, with_status=False,
                        coefficients=None):
    """:func:`backsubstitute_detailed` without the per-step record, in fewer operations.

    The status is the code of the first step that fails (earlier steps are then all valid,
    so its code does not depend on the NaN the detailed form passes on), else ON_BOUNDARY
    where some step has a double root, else OK; INVALID_INPUT where an input is not finite.
    It is computed on the poses where something happened only.  A quadratic step whose
    ``B`` is the constant 0 (``A q^2 + C``, a distance leg) takes its root as
    ``+-sqrt(-4 A C) / (2 A)``, the general rule's value: with ``B = 0`` its tolerance
    ``DISC_RTOL B^2`` is 0, so a negative discriminant (NaN root) is exactly no real root.
    """
    shape = inputs.shape[:-1]
    cols = contiguous_columns(inputs)
    out = numpy.empty((n_out,) + shape)
    records = [] if with_status else None
    with numpy.errstate(all="ignore"):
        failed = _roots(cols, steps, indices, out, mode, par, records,
                        _all_coefficients(cols, par, coefficients))
        if failed is None:
            failed = numpy.zeros(shape, dtype=bool)
        status = None
        if with_status:  # from each step's root before the rows are set to NaN
            status = _lean_status(inputs, shape, failed, [out[i, ...] for i in indices],
                                  records)
        if failed.any():
            out[:, failed] = numpy.nan
    return rows_last(out), status


def _roots(cols, steps, indices, out, mode, par, records=None, fused=None):
    """Each step's root written into its row of ``out`` (n_out, ...) in place; returns
    where some root is not finite (None where every root is).  A step that fails gives NaN
    or infinity (no real root: the discriminant set to NaN below its tolerance), and the
    later steps take that on; the roots of valid configurations are the general rule's,
    operation for operation.  ``records`` (a list) receives what the status needs of each
    step; ``fused``, each step's coefficients where already computed
    (:func:`_all_coefficients`), released as each step is solved."""
    solved = []
    for k, ((degree, kern, bit), index) in enumerate(zip(steps, indices)):
        a, b, c = _step_coefficients(k, kern, cols, solved, par, fused)
        dest = out[index, ...]
        record = _step_root(degree, a, b, c, (mode >> bit) & 1 if degree == 2 else 0, dest)
        solved.append(dest)
        if records is not None:
            records.append(record)
    if not solved:
        return None
    # one sum instead of a finiteness test per root: a sum of finite numbers is finite
    # unless it overflows, and a sum with a NaN or an infinity is not (where it is not
    # finite, the roots are tested one by one)
    if numpy.isfinite(numpy.add.reduce(out, axis=None)):
        return None
    failed = ~numpy.isfinite(solved[0])
    for dest in solved[1:]:
        failed |= ~numpy.isfinite(dest)
    return failed


def _times(minus, k, value):
    """``-k * value`` where ``minus``, else ``k * value``: ``minus`` 0 or 1, or an array of
    them that broadcasts against the poses (one working mode per entry of an axis of
    modes, :func:`..fk.checked_modes`), the same numbers either way."""
    if not isinstance(minus, numpy.ndarray):  # (numpy.ndim costs more than the rest)
        return (-k if minus else k) * value
    return numpy.where(minus.astype(bool), -k * value, k * value)


def _one_sign(b) -> int:
    """1 where every entry of the array ``b`` is > 0, -1 where every one is < 0, else 0
    (a zero, a NaN, both signs, or a scalar): one reduction, the one that the first
    entry's sign says."""
    if not isinstance(b, numpy.ndarray) or b.ndim == 0 or b.size == 0:
        return 0
    first = b.flat[0]
    if first > 0.0:
        return 1 if numpy.minimum.reduce(b, axis=None) > 0.0 else 0
    if first < 0.0:
        return -1 if numpy.maximum.reduce(b, axis=None) < 0.0 else 0
    return 0


def _step_root(degree, a, b, c, minus, dest):
    """The root of one step written into ``dest`` (the root with ``-sqrt`` where ``minus``:
    0 or 1, or an array of them, :func:`_times`); returns the step's record for the status
    (:func:`_roots`)."""
    if degree == 1:
        numpy.divide(c, b, out=dest)
        numpy.negative(dest, out=dest)  # -(c/b) is (-c)/b: negation is exact
        return ("linear", b)
    if numpy.ndim(b) == 0 and b == 0.0:
        disc = 0.0 - 4.0 * a * c
        ssq = numpy.sqrt(disc)  # NaN where negative: no real root
        # -sqrt / 2A is sqrt / -2A: IEEE negation and division are sign-symmetric
        numpy.divide(ssq, _times(minus, 2.0, a), out=dest)
        return ("pure", disc)
    bb = b * b
    disc = bb - 4.0 * a * c
    # sqrt(disc) where every discriminant is >= 0 (the sum of the square roots is then
    # finite: one reduction tells), else sqrt(max(disc, 0)) with NaN where no real root:
    # there max(disc, 0) is 0, and subtracting True makes it -1 (numpy.where and masked
    # copies cost several arithmetic passes each).  The same numbers either way
    sq = numpy.sqrt(disc)
    if not numpy.isfinite(numpy.add.reduce(sq, axis=None)):
        no_real = disc < -DISC_RTOL * bb
        sq = numpy.sqrt(numpy.maximum(disc, 0.0) - no_real)
    # s = |B| + sqrt(disc) never cancels: the root with +sqrt is s / 2A where B <= 0 and
    # 2C / -s where B > 0; the one with -sqrt, -s / 2A where B >= 0 and 2C / s where B < 0
    # -- the detailed form's (+-sqrt - B) / 2A and 2C / (-B -+ sqrt), the same numbers (a
    # zero root may differ in its sign).  Written as s / -2A for -s / 2A and -2C / s for
    # 2C / -s (the same numbers: IEEE negation and division are sign-symmetric), the
    # other branch's value divided into ``dest`` where it applies (no temporary array)
    sign = _one_sign(b) if not isinstance(minus, numpy.ndarray) else 0
    if sign:  # B of one sign throughout (as in a workspace's chunk): |B| is B or -B, and
        # one branch applies to every pose: the near root s / -+2A for the -sqrt root
        # where B > 0 and the +sqrt root where B < 0, else the far root -+2C / s (the
        # numbers of the general rule below)
        s = numpy.add(b, sq, out=sq) if sign > 0 else numpy.subtract(sq, b, out=sq)
        if (sign > 0) == bool(minus):
            numpy.divide(s, _times(minus, 2.0, a), out=dest)
        else:
            numpy.divide(_times(1 - minus, 2.0, c), s, out=dest)
        return ("quadratic", disc, bb)
    s = numpy.abs(b)
    if s.shape == sq.shape:
        s += sq
    else:  # B has fewer entries (a scalar; one per configuration beside the modes' axis)
        s = s + sq
    # where one branch applies to every pose, only that branch is divided: the same
    # numbers, one or two passes fewer
    if not isinstance(minus, numpy.ndarray):
        other = (b < 0.0) if minus else (b > 0.0)
    else:
        other = numpy.where(minus.astype(bool), b < 0.0, b > 0.0)
    if numpy.ndim(other) and other.all():
        numpy.divide(_times(1 - minus, 2.0, c), s, out=dest)
    else:
        numpy.divide(s, _times(minus, 2.0, a), out=dest)
        if numpy.ndim(other) == 0 or other.any():
            numpy.divide(_times(1 - minus, 2.0, c), s, out=dest, where=other)
    return ("quadratic", disc, bb)


def step_mode_bits(steps, uses=None):
    """``(coefficient bits, root bits)``: per step, the sorted mode bits its coefficients
    depend on (those of the roots it reads, ``uses``: per step, the indices of the earlier
    steps whose roots its coefficients contain; None: every earlier step) and those its
    root depends on (these and its own bit, for a quadratic).  The rule behind
    :func:`backsubstitute_modes` and the compiled ``bonered_solve_all``."""
    uses = [tuple(range(k)) for k in range(len(steps))] if uses is None else uses
    coeff_bits: list[tuple[int, ...]] = []
    root_bits: list[tuple[int, ...]] = []
    for k, (degree, _, bit) in enumerate(steps):
        cb = sorted({b for j in uses[k] for b in root_bits[j]})
        coeff_bits.append(tuple(cb))
        root_bits.append(tuple(sorted(set(cb) | ({bit} if degree == 2 else set()))))
    return coeff_bits, root_bits


def backsubstitute_modes(inputs, steps, indices, n_out, modes, par, uses=None,
                         coefficients=None):
    """``backsubstitute_lean(inputs, ..., mode, par)[0]`` of every mode in ``modes``, the
    same numbers, with each step's coefficients evaluated once per choice of the roots its
    kernel reads and both roots of a quadratic from one set of coefficients.  ``uses``: per
    step, the indices of the earlier steps whose roots its coefficients contain (None: every
    earlier step).  A Stewart platform's six legs read no other leg: six kernel
    evaluations for its 64 modes (384 mode by mode; 63 when each step is taken to read
    every earlier one) and the Study map once.  Yields ``(mode, q (..., n_out))`` in the
    order of ``modes``, each ``q`` assembled when it is asked for (the roots are what is
    kept, with their finiteness).

    The numbers are the lean form's: a step's coefficients do not depend on the roots it
    does not read, and a mode's joints are NaN wherever one of its roots is not finite,
    which is the lean form's rule (its NaN roots also reach later kernels as inputs).
    ``coefficients``: as for :func:`backsubstitute` (no step then reads an earlier root)."""
    shape = inputs.shape[:-1]
    cols = contiguous_columns(inputs)
    coeff_bits, root_bits = step_mode_bits(steps, uses)

    def key(mode, bits):
        return tuple((mode >> b) & 1 for b in bits)

    def assignments(bits):
        for n in range(2 ** len(bits)):
            yield sum(((n >> i) & 1) << b for i, b in enumerate(bits))

    # per step: {root key: (root, finite)}
    roots: list[dict] = []
    with numpy.errstate(all="ignore"):
        fused = _all_coefficients(cols, par, coefficients)
        for k, (degree, kern, bit) in enumerate(steps):
            found: dict = {}
            for partial in assignments(coeff_bits[k]):
                if fused is not None:  # no step reads an earlier root: one assignment
                    a, b, c = fused[k]
                else:
                    # each earlier root at the bits this assignment sets (0 for the
                    # others: a root the kernel does not read may be any of its values)
                    args = [roots[j][key(partial, root_bits[j])][0] for j in range(k)]
                    a, b, c = kern(*cols, *args, *par)
                for minus in ((0, 1) if degree == 2 else (0,)):
                    dest = numpy.empty(shape)
                    _step_root(degree, a, b, c, minus, dest)
                    mode = partial | (minus << bit) if degree == 2 else partial
                    found[key(mode, root_bits[k])] = (dest, numpy.isfinite(dest))
            roots.append(found)
    for mode in modes:
        q = numpy.empty((n_out,) + shape)
        good = None
        for k, index in enumerate(indices):
            root, finite = roots[k][key(mode, root_bits[k])]
            q[index, ...] = root
            good = finite if good is None else good & finite
        if good is not None and not good.all():
            q[:, ~good] = numpy.nan
        yield mode, rows_last(q)


def _lean_status(inputs, shape, failed, roots, records):
    """The status codes of :func:`backsubstitute_lean` (its docstring says the rule), from
    each step's ``roots`` (not finite where the step failed or an earlier one did) and its
    ``records``."""

    def flat(v):  # an array of the poses' shape as it is (broadcast_to costs microseconds)
        if isinstance(v, numpy.ndarray) and v.shape == shape:
            return v.reshape(-1)
        return numpy.reshape(numpy.broadcast_to(v, shape), -1)

    invalid = flat(~numpy.all(numpy.isfinite(inputs), axis=-1))
    special = flat(failed) | invalid
    for kind, *arrays in records:
        if kind == "pure":
            special |= flat(arrays[0] == 0.0)
        elif kind == "quadratic":
            special |= flat(numpy.abs(arrays[0]) <= DISC_RTOL * arrays[1])
    status = numpy.zeros(special.shape, dtype=numpy.int8)
    if special.any():
        idx = numpy.flatnonzero(special)
        codes = numpy.zeros(len(idx), dtype=numpy.int8)
        decided = numpy.zeros(len(idx), dtype=bool)
        boundary = numpy.zeros(len(idx), dtype=bool)
        for (kind, *arrays), root in zip(records, roots):
            bad = ~numpy.isfinite(flat(root)[idx])
            sub = [flat(v)[idx] for v in arrays]
            if kind == "linear":
                code = numpy.where(sub[0] == 0, INPUT_SINGULAR, JOINT_AT_INFINITY)
                here = numpy.zeros(len(idx), dtype=bool)
            elif kind == "pure":
                code = numpy.where(sub[0] < 0, NO_REAL_SOLUTION, JOINT_AT_INFINITY)
                here = sub[0] == 0.0
            else:
                code = numpy.where(sub[0] < -DISC_RTOL * sub[1], NO_REAL_SOLUTION,
                                   JOINT_AT_INFINITY)
                here = numpy.abs(sub[0]) <= DISC_RTOL * sub[1]
            first = bad & ~decided  # the first failure wins
            codes[first] = code[first]
            decided |= bad
            boundary |= ~decided & here
        codes[~decided & boundary] = ON_BOUNDARY
        codes[invalid[idx]] = INVALID_INPUT
        status[idx] = codes
    return status.reshape(shape)


def backsubstitute_detailed(inputs, steps, indices, n_out, mode, par, with_status=False,
                            per_step=None, coefficients=None):
    """Solve ``steps`` in order (linear or quadratic in one unknown each); NaN on failure.

    ``inputs`` has shape (..., n_in); the result has shape (..., n_out) with unknown k at
    ``indices[k]``, all NaN where any step fails (a view whose columns are contiguous);
    status codes are computed on request.
    Quadratic roots are taken in the form that never subtracts nearly equal numbers.

    ``per_step``, a dict, receives ``codes`` (..., len(steps)): each step's own status
    (NOT_SOLVED where its coefficients use an unknown an earlier step failed to give: a
    polynomial of finite numbers is never NaN), ``discriminants`` (one array per step,
    None for a linear step) and ``roots`` (each step's root before the all-or-nothing rule).
    ``coefficients``: as for :func:`backsubstitute`.
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
        fused = _all_coefficients(cols, par, coefficients)
        for k, ((degree, kern, bit), index) in enumerate(zip(steps, indices)):
            a, b, c = _step_coefficients(k, kern, cols, solved, par, fused)
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
        per_step["roots"] = rows_last(out).copy()
    # a configuration is reachable as a whole or not at all: the status says which leg failed
    out[:, failed] = numpy.nan
    return rows_last(out), status
