"""Forward kinematics: every assembly mode, from the closures' solvers.

Closures solved through an eliminant (a 3-RPS closure: :mod:`.rps`) give the outer modes,
closures with a triangular lex basis the inner ones (one back-substitution for all of them,
polished by Gauss-Newton steps on the leg generators): mode = r * 2**len(bits) + m.
"""

from __future__ import annotations

import numpy

from . import rps as rps_solver
from .backsubstitution import backsubstitute
from .inputs import against_modes, columns, stacked
from .newton import kernel_system, newton_step
from .status import (
    COND_RTOL,
    FORWARD_SINGULAR,
    INPUT_SINGULAR,
    NO_REAL_SOLUTION,
    OK,
    ON_BOUNDARY,
    RESIDUAL_RTOL,
    UNVERIFIED,
    VERIFY_RTOL,
)


def closure_system(spec, q, study, par):
    """Residuals f (..., m) of the leg generators and their Jacobian (..., m, n) in the
    unknowns, at the back-substituted Study coordinates ``study``."""
    return kernel_system(spec.newton, [*columns(study), *columns(q), *par],
                         study.shape[:-1], len(spec.unknowns))


STEP_RTOL = 1e-14  # a Gauss-Newton step this small relative to 1 + |x| ends the polish


def _flat_rows(arrays, shape):
    """Each array broadcast to the leading ``shape`` and flattened to rows (a scalar stays
    a scalar): what the kernels take, row by row."""
    out = []
    for a in arrays:
        a = numpy.asarray(a, dtype=float)
        out.append(a if a.ndim == 0 else numpy.broadcast_to(a, shape).reshape(-1))
    return out


def polish(spec, q, study, par, iterations=6):
    """Gauss-Newton steps on the leg generators, from the lex-basis solution: the normal
    equations of the equilibrated system (:func:`equilibrated`, scaled as :func:`verify`
    scales it), not ``J^T J step = J^T f`` as it comes.  The generators' rows differ by up
    to 16 orders of magnitude where a tan-half-angle joint is near a half-turn (urrh_rcm
    with alpha2 = 3.1378: rows from 1 to 5e16); the raw normal equations (condition
    squared, 1e31) moved a correct lex-basis solution 5 mm off there, and the check
    declared the mode UNVERIFIED: a real assembly lost.  No SVD cut here (verify's
    pseudo-inverse): near a pivot locus it converges to a least-squares point where no
    assembly is.  Each row stops once its step is below STEP_RTOL (1 + |x|), or where the
    step is not defined: the kernels are evaluated on the rows still moving only (a
    lex-basis solution needs one or two steps).

    Returns the polished unknowns and the closure system ``(f, J)`` at them for
    :func:`verify`: a row that stopped keeps the residuals and Jacobian of its last
    evaluation (before its last step, below STEP_RTOL (1 + |x|), or at its unchanged
    unknowns), so that only the rows still moving after ``iterations`` steps are evaluated
    again (about a third fewer evaluations of the Newton kernel)."""
    n = len(spec.unknowns)
    shape = study.shape[:-1]
    x = study.reshape(-1, n).copy()
    qr = numpy.broadcast_to(q, shape + q.shape[-1:]).reshape(-1, q.shape[-1])
    pr = _flat_rows(par, shape)
    rows = numpy.flatnonzero(numpy.isfinite(x).all(axis=-1))
    f_at, jac_at = None, None  # (N, m), (N, m, n): NaN where x is not finite

    def evaluate(at, xs):
        nonlocal f_at, jac_at
        f, jac = closure_system(spec, qr[at], xs, [p if p.ndim == 0 else p[at] for p in pr])
        if f_at is None:
            f_at = numpy.full((len(x),) + f.shape[-1:], numpy.nan)
            jac_at = numpy.full((len(x),) + jac.shape[-2:], numpy.nan)
        return f, jac

    for _ in range(iterations):
        if rows.size == 0:
            break
        sub = x[rows]
        with numpy.errstate(all="ignore"):
            f, jac = evaluate(rows, sub)
            js, fs, scale, finite = equilibrated(f, jac, sub)
            jt = numpy.swapaxes(js, -1, -2)
            scaled, ok = newton_step((jt @ fs[..., None])[..., 0], jt @ js, finite)
            step = scaled * scale
            moving = ok & (numpy.abs(scaled) > STEP_RTOL).any(axis=-1)
        x[rows] = numpy.where(ok[..., None], sub - step, sub)
        stopped = ~moving
        f_at[rows[stopped]], jac_at[rows[stopped]] = f[stopped], jac[stopped]
        rows = rows[moving]
    with numpy.errstate(all="ignore"):
        if f_at is None:  # no finite row: the system's shapes from (at most) one, all NaN
            evaluate(rows[:0] if len(x) == 0 else numpy.arange(1), x[:1])
        if rows.size:  # still moving after the last step: the system where they ended
            f_at[rows], jac_at[rows] = evaluate(rows, x[rows])
    return x.reshape(study.shape), (f_at.reshape(shape + f_at.shape[-1:]),
                                    jac_at.reshape(shape + jac_at.shape[-2:]))


def verify(spec, q, study, par, status, system=None):
    """The check of every back-substituted mode on the closure equations (the leg
    generators; ``system``: their residuals and Jacobian at ``study`` where :func:`polish`
    has them, else evaluated here), equilibrated (:func:`equilibrated`): one more
    Gauss-Newton step must change no unknown by more than VERIFY_RTOL (1 + |x|) and no
    equation's residual may exceed RESIDUAL_RTOL of its row, else the mode is UNVERIFIED
    and NaN (a step divided by a pivot near zero: e.g. Pro-Hep-LCT's lower lex basis on
    t1 = +-w1).  A verified mode where the column-scaled Jacobian is nearly rank deficient
    is FORWARD_SINGULAR (two assembly modes merge); elsewhere a verified mode is OK even
    where a quadratic step of the basis had a double root (ON_BOUNDARY there means a double
    root of the basis, not a boundary)."""
    with numpy.errstate(all="ignore"):
        f, jac = closure_system(spec, q, study, par) if system is None else system
        js, fs, _, finite = equilibrated(f, jac, study)
        step, cond_ok = _scaled_step(js, fs, finite)
        verified = finite & (numpy.abs(step) <= VERIFY_RTOL).all(axis=-1)
        # a zero step alone admits a least-squares point of an overdetermined system (J^T f
        # = 0, f not 0: urrh_rcm has 11 generators in 4 unknowns) where no assembly is
        verified &= (numpy.abs(fs) <= RESIDUAL_RTOL).all(axis=-1)
    solved = numpy.isfinite(study).all(axis=-1)
    study = numpy.where(solved[..., None] & ~verified[..., None], numpy.nan, study)
    if status is None:
        return study, None
    solved &= (status == OK) | (status == ON_BOUNDARY)
    new = numpy.where(~verified, UNVERIFIED, numpy.where(cond_ok, OK, FORWARD_SINGULAR))
    return study, numpy.where(solved, new, status).astype(numpy.int8)


# det(G) / trace(G)^n above this certifies sigma_min / sigma_max >= 1e-4 (G = J^T J): the
# Jacobian far from rank deficiency (COND_RTOL), the normal equations accurate (cond(G) <=
# 1e8: the step to about 1e-8 of itself)
CERTIFIED_GRAM = 1e-8


def equilibrated(f, jac, x):
    """The closure system ``(f, J)`` at ``x`` equilibrated: each column of J times
    ``1 + |x_j|`` (steps then come relative to the unknowns), then each equation divided by
    its row's norm (the generators' units differ: mm^2, mm^4, ...; a tan-half-angle near a
    half-turn makes rows of 1e16).  Returns ``(js, fs, 1 + |x|, finite)``: zero rows where
    f, J or x is not finite."""
    finite = numpy.isfinite(jac).all(axis=(-2, -1)) & numpy.isfinite(f).all(axis=-1)
    finite &= numpy.isfinite(x).all(axis=-1)
    if finite.all():  # the usual case: no row to zero (the same numbers, fewer passes)
        scale = 1.0 + numpy.abs(x)
        js = jac * scale[..., None, :]
    else:
        scale = 1.0 + numpy.abs(numpy.where(finite[..., None], x, 0.0))
        js = numpy.where(finite[..., None, None], jac * scale[..., None, :], 0.0)
        f = numpy.where(finite[..., None], f, 0.0)
    # each row's norm as numpy.linalg.norm computes it (sqrt of the reduced squares)
    rows = numpy.sqrt(numpy.add.reduce(js * js, axis=-1))
    rows[rows == 0] = 1.0
    return js / rows[..., None], f / rows, scale, finite


def _scaled_step(js, fs, finite):
    """The Gauss-Newton step (..., n) of the row-scaled system ``js step = fs`` (..., m, n)
    by least squares, and whether ``js`` is far from rank deficiency (sigma_min > COND_RTOL
    sigma_max); NaN steps where not ``finite``.

    Where ``det(G) / trace(G)^n > CERTIFIED_GRAM`` (G = js^T js, whose eigenvalues are
    sigma^2: each at most the trace, so sigma_min^2 / sigma_max^2 >= det(G) / trace(G)^n),
    the step solves the normal equations ``G step = js^T fs`` and the rank test passes;
    elsewhere both come from the SVD, the pseudo-inverse with the singular values below
    COND_RTOL of the largest cut.  The two agree where both apply (the same least-squares
    step); the normal equations take 1/20 of the time of numpy's batched SVD, which costs
    about 3 us per small matrix (urrh_rcm: 40 % of forward kinematics)."""
    n = js.shape[-1]
    jt = numpy.swapaxes(js, -1, -2)
    gram, rhs = jt @ js, jt @ fs[..., None]
    trace = numpy.trace(gram, axis1=-2, axis2=-1)
    certified = finite & (numpy.linalg.det(gram) > CERTIFIED_GRAM * trace ** n)
    step, _ = newton_step(rhs[..., 0], gram, certified)  # certified: det(G) > 0
    step[~finite] = numpy.nan
    cond_ok = certified.copy()
    hard = finite & ~certified
    if hard.any():
        u, sv, vt = numpy.linalg.svd(js[hard], full_matrices=False)
        cond_ok[hard] = sv[..., -1] > COND_RTOL * sv[..., 0]
        kept = sv > COND_RTOL * sv[..., :1]
        inv = numpy.where(kept, 1.0 / numpy.where(kept, sv, 1.0), 0.0)
        proj = numpy.einsum("...ji,...j->...i", u, fs[hard])
        step[hard] = numpy.einsum("...ij,...i->...j", vt, inv * proj)
    return step, cond_ok


def checked_mode(spec, steps, index, q, mode, par, with_status):
    """Study coordinates (..., n) and status of one mode of a back-substitution plan,
    polished and checked (``verify``)."""
    return checked_modes(spec, steps, index, q, (mode,), par, with_status)[0]


# configurations x modes polished and checked in one pass (checked_modes): on a few
# configurations every mode at once (the Python cost of a pass is then paid once, not once
# per mode), on many one mode at a time (the Newton kernels' temporaries stay in cache).
# Measured on this project's machine, urrh_rcm's fk_status on 30, 100, 300 and 1,000
# configurations: 11,000, 18,400, 22,600 and 27,000 per s with 2,048 rows; 2,000, 5,200,
# 14,000 and 23,800 one mode at a time; 10,100, 14,200, 24,600 and 21,100 all at once
MODE_ROWS = 2048


def modes_per_pass(shape) -> int:
    """How many modes of configurations of leading ``shape`` go in one pass: as many as
    make at most MODE_ROWS rows, at least one."""
    return max(1, MODE_ROWS // max(int(numpy.prod(shape, dtype=numpy.int64)), 1))


def checked_modes(spec, steps, index, q, modes, par, with_status):
    """:func:`checked_mode` of each mode in ``modes``, as many modes together as make at
    most MODE_ROWS rows (at least one), the modes an axis beside the configurations': one
    back-substitution (each step's root of its own sign per mode), one polish and one
    check per group.  The same numbers whatever the grouping (each row's arithmetic is its
    own, as in chunks of configurations: ``model.FK_CHUNK``); on one configuration, one
    pass of each kernel and of numpy's small-matrix routines instead of one per mode."""
    modes = list(modes)
    per = modes_per_pass(q.shape[:-1])
    qm, pm = q[..., None, :], against_modes(par)
    out = []
    for lo in range(0, len(modes), per):
        group = numpy.array(modes[lo:lo + per])
        inputs = numpy.broadcast_to(qm, q.shape[:-1] + (len(group),) + q.shape[-1:])
        study, status = backsubstitute(inputs, steps, index, len(spec.unknowns), group, pm,
                                       with_status)
        polished, system = polish(spec, qm, study, pm)
        study, status = verify(spec, qm, polished, pm, status, system)
        out += [(study[..., k, :], None if status is None else status[..., k])
                for k in range(len(group))]
    return out


def primary_mode(spec, q, study, par):
    """The mode of ``spec.steps`` a solution belongs to: bit b is set where the quadratic
    step with bit b has 2 A x + B < 0 at the solution (its ``-sqrt`` root)."""
    mode = numpy.zeros(study.shape[:-1], dtype=int)
    qc = columns(q)
    with numpy.errstate(all="ignore"):
        for k, (degree, kern, bit) in enumerate(spec.steps):
            if degree != 2:
                continue
            before = [study[..., spec.index[j]] for j in range(k)]
            a, b, _ = kern(*qc, *before, *par)
            x = study[..., spec.index[k]]
            mode = mode | ((2.0 * a * x + b < 0.0).astype(int) << bit)
    return mode


def from_charts(spec, q, par, solved):
    """The modes of ``spec.steps`` that failed (NaN), filled from the other elimination
    orders' plans (``spec.charts``) where these give a checked solution not returned yet:
    in the slot of the mode it belongs to (``primary_mode``), else in the first free slot
    (on a locus where the first basis has a double root the two modes are one slot).  A
    mode still unsolved (UNVERIFIED, or a division by an exactly zero pivot) where every
    mode of a chart has no real solution is NO_REAL_SOLUTION: that chart solves there."""
    studies = numpy.stack([st for st, _ in solved], axis=-2)  # (..., M, n)
    with_status = solved[0][1] is not None
    statuses = numpy.stack([s for _, s in solved], axis=-1) if with_status else None
    n_modes = studies.shape[-2]
    slots = numpy.arange(n_modes)
    for steps, index in spec.charts:
        bits = sum(1 for degree, _, _ in steps if degree == 2)
        none_real = numpy.ones(studies.shape[:-2], dtype=bool)
        found = checked_modes(spec, steps, index, q, range(2 ** bits), par, True)
        # the mode each solution belongs to, of all of the chart's modes in one evaluation
        wants = primary_mode(spec, q[..., None, :],
                             numpy.stack([st for st, _ in found], axis=-2), against_modes(par))
        for k, (study, status) in enumerate(found):
            none_real &= status == NO_REAL_SOLUTION
            good = numpy.isfinite(study).all(axis=-1)
            scale = 1.0 + numpy.abs(study[..., None, :])
            with numpy.errstate(invalid="ignore"):
                same = (numpy.abs(studies - study[..., None, :]) <= 1e-7 * scale).all(axis=-1)
            free = numpy.isnan(studies).any(axis=-1)
            good &= ~same.any(axis=-1) & free.any(axis=-1)
            want = wants[..., k]
            first_free = numpy.argmax(free, axis=-1)
            slot = numpy.where(numpy.take_along_axis(free, want[..., None], axis=-1)[..., 0],
                               want, first_free)
            put = good[..., None] & (slots == slot[..., None])  # (..., M)
            studies = numpy.where(put[..., None], study[..., None, :], studies)
            if with_status:
                statuses = numpy.where(put, status[..., None], statuses).astype(numpy.int8)
        if with_status:  # a chart regular here finds no real solution: there is none
            unsolved = numpy.isnan(studies).any(axis=-1)
            statuses = numpy.where(none_real[..., None] & unsolved, NO_REAL_SOLUTION,
                                   statuses).astype(numpy.int8)
    return [(studies[..., m, :], statuses[..., m] if with_status else None)
            for m in range(n_modes)]


def input_singular(model, pose, q, par, status):
    """INPUT_SINGULAR for a real mode at which a pivot of Ji vanishes: the pose solves the
    closure equations, but the joints do not determine it (e.g. a planar 3-PRP stage turned
    to its input singularity assembles for any strokes)."""
    n = len(model.joints)
    values = model._jac_values(pose, q, par)  # noqa: SLF001 - the runtime's own helper
    with numpy.errstate(all="ignore"):
        singular = model.pivot_singular(values[:n], values[n:2 * n], status.shape)
    return numpy.where((status == OK) & singular, INPUT_SINGULAR, status).astype(numpy.int8)


def solve_all(model, q, par, with_status, spec=None):
    """Poses (..., modes, len(POSE)) and statuses (..., modes) of every assembly mode;
    ``spec``: ``model.fk`` or its twin with compiled kernels (``FastPath.forward_kinematics``)."""
    spec = model.fk if spec is None else spec
    shape = q.shape[:-1]
    if spec.rps is not None:
        rps, rps_status = rps_solver.solve(spec.rps, q, par)
    else:
        rps = numpy.zeros(shape + (1, 0))
        rps_status = numpy.zeros(shape + (1,), dtype=numpy.int8)
    # the back-substitution modes do not depend on the eliminant's mode
    n_modes = 2 ** len(spec.mode_bits)
    if spec.steps:
        solved = checked_modes(spec, spec.steps, spec.index, q, range(n_modes), par,
                               with_status)
    else:
        solved = [(numpy.zeros(shape + (0,)),
                   numpy.zeros(shape, dtype=numpy.int8) if with_status else None)] * n_modes
    if spec.charts and any(numpy.isnan(study).any() for study, _ in solved):
        solved = from_charts(spec, q, par, solved)
    # every pair (eliminant mode r, back-substitution mode m), r-major; as many pairs in
    # one evaluation of the pose kernel (and of the pivots' kernel) as make MODE_ROWS rows
    pairs = [(r, m) for r in range(rps.shape[-2]) for m in range(len(solved))]
    per = modes_per_pass(shape)
    pm = against_modes(par)
    poses, statuses = [], []
    for lo in range(0, len(pairs), per):
        rr = [r for r, _ in pairs[lo:lo + per]]
        mm = [m for _, m in pairs[lo:lo + per]]
        study = numpy.stack([solved[m][0] for m in mm], axis=-2)  # (..., pairs, n)
        with numpy.errstate(all="ignore"):
            values = spec.pose(*[rps[..., rr, i] for i in range(rps.shape[-1])],
                               *columns(study), *pm)
        poses.append(stacked(values, shape + (len(rr),)))
        if with_status:
            rps_code = rps_status[..., rr]
            status = numpy.stack([solved[m][1] for m in mm], axis=-1)
            status = numpy.where(rps_code != OK, rps_code, status)
            q_all = numpy.broadcast_to(q[..., None, :], status.shape + q.shape[-1:])
            statuses.append(input_singular(model, poses[-1], q_all, pm, status))
    return (numpy.concatenate(poses, axis=-2),
            numpy.concatenate(statuses, axis=-1) if with_status else None)
