"""Fixed runtime part of every generated IK module (copied verbatim into ``generated/``).

It relies on names the generated part defines: ``MECHANISM``, ``PARAMETERS``,
``PARAMETER_NOTES``, ``PARAMETER_UNITS``, ``POSE``, ``JOINTS``, ``_STEPS``, ``_SOLVE_INDEX``,
``_ji``, ``_jo``, ``_jo_study``, ``_jac``, ``_SINGULARITIES``.
"""

RUNTIME = '''
# ---------------------------------------------------------------- status codes
OK = 0
NO_REAL_SOLUTION = 1
JOINT_AT_INFINITY = 2
ON_BOUNDARY = 3
INPUT_SINGULAR = 4
INVALID_INPUT = 5
STROKE_LIMIT = 6
PASSIVE_JOINT_LIMIT = 7
STATUS = {
    OK: "ok",
    NO_REAL_SOLUTION: "no real solution: the pose is outside the reach of the leg that "
                      "drives this joint (negative discriminant)",
    JOINT_AT_INFINITY: "joint parameter at infinity (a tan-half-angle at joint angle pi, or "
                       "an overflow)",
    ON_BOUNDARY: "on the workspace boundary of a leg (double root, input singularity): the "
                 "joint values are valid, the Jacobian is not",
    INPUT_SINGULAR: "input singularity: a pivot of Ji vanishes (det Ji = 0); the joint "
                    "value is undetermined or unbounded and dq/dX is not defined",
    INVALID_INPUT: "non-finite pose coordinate",
    STROKE_LIMIT: "an actuator stroke is outside its range (LIMITS, kind 'stroke')",
    PASSIVE_JOINT_LIMIT: "a passive joint angle is outside its range (LIMITS, kind 'passive')",
}
_DISC_RTOL = 1e-10
_DET_RTOL = 1e-12


def _params(func, params):
    unknown = sorted(set(params) - set(PARAMETERS))
    if unknown:
        raise TypeError(f"{MECHANISM}.{func}: unknown geometric parameter(s) {unknown}; "
                        f"expected some of {list(PARAMETERS)}")
    out = []
    for name, default in PARAMETERS.items():
        value = params.get(name, default)
        if value is None:
            raise ValueError(
                f"{MECHANISM}.{func}: geometric parameter {name!r} has no published value "
                f"({PARAMETER_NOTES[name]}); pass {name}=<value in {PARAMETER_UNITS[name]}>")
        value = numpy.asarray(value, dtype=float)
        if not numpy.all(numpy.isfinite(value)):
            raise ValueError(f"{MECHANISM}.{func}: geometric parameter {name!r} is not finite")
        out.append(value)
    return out


def _pose(func, pose):
    p = numpy.asarray(pose, dtype=float)
    if p.ndim == 0 or p.shape[-1] != len(POSE):
        raise ValueError(f"{MECHANISM}.{func}: pose must have shape (..., {len(POSE)}) with "
                         f"coordinates {POSE}, got shape {p.shape}")
    return p


def _joints(func, q, shape):
    q = numpy.asarray(q, dtype=float)
    if q.ndim == 0 or q.shape[-1] != len(JOINTS):
        raise ValueError(f"{MECHANISM}.{func}: joints must have shape (..., {len(JOINTS)}) "
                         f"with coordinates {JOINTS}, got shape {q.shape}")
    return numpy.broadcast_to(q, shape + (len(JOINTS),))


def _mode(func, mode):
    if not isinstance(mode, (int, numpy.integer)) or not 0 <= int(mode) < MODES:
        raise ValueError(f"{MECHANISM}.{func}: mode must be an integer in [0, {MODES}), "
                         f"got {mode!r}; see MODE_BITS")
    return int(mode)


def _backsubstitute(inputs, steps, indices, n_out, mode, par, with_status=False):
    """Solve ``steps`` in order (linear or quadratic in one unknown each); NaN on failure.

    ``inputs`` has shape (..., n_in); the result has shape (..., n_out) with unknown k at
    ``indices[k]``, all NaN where any step fails; status codes (``STATUS``) are computed only
    on request.
    """
    shape = inputs.shape[:-1]
    cols = [inputs[..., i] for i in range(inputs.shape[-1])]
    out = numpy.empty(shape + (n_out,))
    status = numpy.zeros(shape, dtype=numpy.int8) if with_status else None
    if with_status:
        status[~numpy.all(numpy.isfinite(inputs), axis=-1)] = INVALID_INPUT
    solved = []
    failed = numpy.zeros(shape, dtype=bool)
    with numpy.errstate(all="ignore"):
        for (degree, kern, bit), index in zip(steps, indices):
            a, b, c = kern(*cols, *solved, *par)
            if degree == 1:
                root = numpy.asarray(-c / b, dtype=float)
                bad = ~numpy.isfinite(root)
                no_real = None
                pivot_zero = bad & (b == 0)  # det Ji = 0 exactly: an input singularity
            else:
                sign = -1.0 if (mode >> bit) & 1 else 1.0
                bb = b * b
                disc = bb - 4.0 * a * c
                ssq = sign * numpy.sqrt(numpy.maximum(disc, 0.0))
                # numerically stable roots: never subtract nearly equal numbers
                root = numpy.where(sign * b <= 0.0, (ssq - b) / (2.0 * a), (2.0 * c) / (-b - ssq))
                no_real = disc < -_DISC_RTOL * bb
                bad = no_real | ~numpy.isfinite(root)
                pivot_zero = None
            root = numpy.where(bad, numpy.nan, root)
            if with_status:
                new = numpy.where(bad, JOINT_AT_INFINITY, OK)
                if pivot_zero is not None:
                    new = numpy.where(pivot_zero, INPUT_SINGULAR, new)
                if no_real is not None:
                    new = numpy.where(no_real, NO_REAL_SOLUTION, new)
                    on_boundary = ~bad & (numpy.abs(disc) <= _DISC_RTOL * bb)
                    new = numpy.where(on_boundary, ON_BOUNDARY, new)
                # the first failure wins; a failure overrides an earlier ON_BOUNDARY
                replace = (status == OK) | ((status == ON_BOUNDARY) & bad)
                status = numpy.where(replace, new, status).astype(numpy.int8)
            out[..., index] = root
            solved.append(root)
            failed |= bad
    # a configuration is reachable as a whole or not at all: the status says which leg failed
    out[failed] = numpy.nan
    return out, status


def _solve(pose, mode, par, with_status=False, limits=True):
    """Inverse kinematics of one working mode; NaN at input singularities of linear steps
    and, with ``limits``, outside the ranges of ``LIMITS``.

    A linear step ``B q + C = 0`` is singular where its pivot ``B = dG/dq`` vanishes
    relative to the generator's derivatives (the joint is then undetermined or infinite).
    """
    shape = pose.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = _study(*[pose[..., i] for i in range(len(POSE))], *par)
    study = numpy.empty(shape + (len(STUDY_POSE),))
    for i, v in enumerate(values):
        study[..., i] = v
    q, status = _backsubstitute(study, _STEPS, _SOLVE_INDEX, len(JOINTS), mode, par,
                                with_status)
    if with_status:
        status[~numpy.all(numpy.isfinite(pose), axis=-1)] = INVALID_INPUT
    if _CHECK_PIVOTS:
        q, status = _pivot_check(study, q, status, par, with_status)
    if limits and LIMITS:
        q, status = _limit_check(pose, q, status, par, with_status)
    return q, status


def _limit_check(pose, q, status, par, with_status):
    shape = pose.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = _limit_values(*[pose[..., i] for i in range(len(POSE))],
                               *[q[..., i] for i in range(len(JOINTS))], *par)
    violated = {"stroke": numpy.zeros(shape, dtype=bool),
                "passive": numpy.zeros(shape, dtype=bool)}
    for v, (_, lower, upper, kind, _, _) in zip(values, LIMITS):
        v = numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
        violated[kind] |= (v < lower) | (v > upper)
    ok = numpy.all(numpy.isfinite(q), axis=-1)
    out = violated["stroke"] | violated["passive"]
    q[out] = numpy.nan
    if with_status:
        status = numpy.where(ok & violated["passive"] & (status == OK), PASSIVE_JOINT_LIMIT,
                             status)
        status = numpy.where(ok & violated["stroke"] & (status != INVALID_INPUT)
                             & ((status == OK) | (status == PASSIVE_JOINT_LIMIT)),
                             STROKE_LIMIT, status).astype(numpy.int8)
    return q, status


def limit_values(pose, q, **params):
    """The quantities bounded by ``LIMITS`` at ``(pose, q)``: dict name -> array."""
    pose = _pose("limit_values", pose)
    shape = pose.shape[:-1]
    q = _joints("limit_values", q, shape)
    par = _params("limit_values", params)
    if not LIMITS:
        return {}
    values = _limit_values(*[pose[..., i] for i in range(len(POSE))],
                           *[q[..., i] for i in range(len(JOINTS))], *par)
    return {lim[0]: numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
            for lim, v in zip(LIMITS, values)}


def _pivot_check(study, q, status, par, with_status):
    shape = study.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = _pivots(*[study[..., i] for i in range(study.shape[-1])],
                         *[q[..., i] for i in range(len(JOINTS))], *par)
        half = len(values) // 2
        singular = numpy.zeros(shape, dtype=bool)
        for d, sc in zip(values[:half], values[half:]):
            singular |= numpy.abs(d) <= _DET_RTOL * numpy.abs(sc)
    singular &= numpy.all(numpy.isfinite(q), axis=-1)
    q[singular] = numpy.nan
    if with_status:
        status = numpy.where(singular & (status == OK), INPUT_SINGULAR, status).astype(
            numpy.int8)
    return q, status


def ik(pose, mode=0, limits=True, **params):
    """Active joints ``JOINTS`` for poses ``(..., len(POSE))``; NaN where unreachable.

    ``mode`` selects the working mode (see ``MODE_BITS``); ``ik_status`` says why a result is
    NaN.  With ``limits`` (default) poses outside the ranges of ``LIMITS`` are unreachable
    too.  Geometric parameters are keyword arguments (defaults: ``PARAMETERS``).
    """
    q, _ = _solve(_pose("ik", pose), _mode("ik", mode), _params("ik", params), False, limits)
    return q


def ik_status(pose, mode=0, limits=True, **params):
    """Status code per pose (``STATUS`` explains each code) for ``ik(pose, mode, limits)``."""
    _, status = _solve(_pose("ik_status", pose), _mode("ik_status", mode),
                       _params("ik_status", params), True, limits)
    return status


def ik_all(pose, limits=True, **params):
    """All working modes: array ``(..., MODES, len(JOINTS))``; NaN where a mode is unreachable."""
    pose, par = _pose("ik_all", pose), _params("ik_all", params)
    return numpy.stack([_solve(pose, m, par, False, limits)[0] for m in range(MODES)], axis=-2)


def _matrices(pose, q, par):
    shape = pose.shape[:-1]
    cols = [pose[..., i] for i in range(len(POSE))]
    qc = [q[..., i] for i in range(len(JOINTS))]
    n = len(JOINTS)

    def mat(values, m):
        vals = [numpy.broadcast_to(numpy.asarray(v, dtype=float), shape) for v in values]
        return numpy.stack(vals, axis=-1).reshape(shape + (n, m))

    return (mat(_ji(*cols, *qc, *par), n), mat(_jo(*cols, *qc, *par), len(POSE)),
            mat(_jo_study(*cols, *qc, *par), len(STUDY_POSE)))


def input_jacobian(pose, q, **params):
    """``Ji = dG/dq`` (rows: ``IK_GENERATORS``, columns: ``JOINTS``), 004 eq. (19)-(21)."""
    pose = _pose("input_jacobian", pose)
    q = _joints("input_jacobian", q, pose.shape[:-1])
    return _matrices(pose, q, _params("input_jacobian", params))[0]


def output_jacobian(pose, q, **params):
    """``Jo = dG/dy`` in the Study coordinates ``STUDY_POSE`` (004 eq. 19-21 form)."""
    pose = _pose("output_jacobian", pose)
    q = _joints("output_jacobian", q, pose.shape[:-1])
    return _matrices(pose, q, _params("output_jacobian", params))[2]


def jacobian(pose, mode=0, limits=True, **params):
    """``J = dq/dX`` (..., len(JOINTS), len(POSE)), X as listed in POSE; NaN where invalid.

    ``J = -Ji^{-1} dG/dX``, solved by forward substitution (Ji is triangular in the order the
    IK solves the joints); NaN where the IK fails or a pivot ``dG_k/dq_k`` vanishes relative
    to its row (an input singularity), see ``jacobian_status``.
    """
    J, _ = _jacobian("jacobian", pose, mode, params, False, limits)
    return J


def jacobian_status(pose, mode=0, limits=True, **params):
    """Status per pose for ``jacobian``: an IK status, or INPUT_SINGULAR."""
    _, status = _jacobian("jacobian_status", pose, mode, params, True, limits)
    return status


def _jacobian(func, pose, mode, params, with_status, limits=True):
    pose, mode, par = _pose(func, pose), _mode(func, mode), _params(func, params)
    q, status = _solve(pose, mode, par, True, limits)
    shape = pose.shape[:-1]
    n, m = len(JOINTS), len(POSE)
    cols = [pose[..., i] for i in range(m)]
    qc = [q[..., i] for i in range(n)]
    with numpy.errstate(all="ignore"):
        values = _jac(*cols, *qc, *par)
        pivots, scales, entries = values[:n], values[n:2 * n], values[2 * n:]
        singular = numpy.zeros(shape, dtype=bool)
        for d, sc in zip(pivots, scales):
            singular |= ~(numpy.abs(d) > _DET_RTOL * sc)
        J = numpy.empty(shape + (n * m,))
        for k, e in enumerate(entries):
            J[..., k] = e
    # a double root of a quadratic step (ON_BOUNDARY) is an input singularity as well
    singular |= status == ON_BOUNDARY
    J = J.reshape(shape + (n, m))
    J[singular] = numpy.nan
    ik_ok = (status == OK) | (status == ON_BOUNDARY)
    status = numpy.where(ik_ok & singular, INPUT_SINGULAR, status).astype(numpy.int8)
    return J, (status if with_status else None)


def singularities(pose, q, **params):
    """Singularity polynomials evaluated at ``(pose, q)``: dict name -> array (zero = singular).

    ``SINGULARITY_MEANING`` says what each one is.
    """
    pose = _pose("singularities", pose)
    shape = pose.shape[:-1]
    q = _joints("singularities", q, shape)
    par = _params("singularities", params)
    cols = [pose[..., i] for i in range(len(POSE))]
    qc = [q[..., i] for i in range(len(JOINTS))]
    return {name: numpy.broadcast_to(numpy.asarray(kern(*cols, *qc, *par)[0], dtype=float),
                                     shape)
            for name, kern in _SINGULARITIES.items()}


def _fk_inputs(func, q):
    if not FK_MODES:
        raise NotImplementedError(f"{MECHANISM}.{func}: forward kinematics is not generated "
                                  f"for this mechanism: {FK_NOTE}")
    q = numpy.asarray(q, dtype=float)
    if q.ndim == 0 or q.shape[-1] != len(JOINTS):
        raise ValueError(f"{MECHANISM}.{func}: joints must have shape (..., {len(JOINTS)}) "
                         f"with coordinates {JOINTS}, got shape {q.shape}")
    return q


def _fk_polish(q, study, par, iterations=2):
    """Newton steps on the (well-conditioned) leg generators, from the lex-basis solution."""
    n = len(FK_UNKNOWNS)
    shape = study.shape[:-1]
    qc = [q[..., i] for i in range(q.shape[-1])]
    for _ in range(iterations):
        with numpy.errstate(all="ignore"):
            values = _fk_newton(*[study[..., i] for i in range(n)], *qc, *par)
            vals = [numpy.broadcast_to(numpy.asarray(v, dtype=float), shape) for v in values]
            m = len(vals) // (n + 1)
            f = numpy.stack(vals[:m], axis=-1)
            jac = numpy.stack(vals[m:], axis=-1).reshape(shape + (m, n))
            # Gauss-Newton: (J^T J) step = J^T f (the plain Newton step when J is square)
            jtj = numpy.swapaxes(jac, -1, -2) @ jac
            jtf = numpy.swapaxes(jac, -1, -2) @ f[..., None]
            ok = numpy.all(numpy.isfinite(jtj), axis=(-2, -1)) & numpy.all(
                numpy.isfinite(jtf), axis=(-2, -1))
            ok &= numpy.abs(numpy.linalg.det(numpy.where(ok[..., None, None], jtj,
                                                         numpy.eye(n)))) > 0.0
            safe = numpy.where(ok[..., None, None], jtj, numpy.eye(n))
            step = numpy.linalg.solve(safe, numpy.where(ok[..., None, None], jtf, 0.0))
        study = numpy.where(ok[..., None], study - step[..., 0], study)
    return study


def _fk_mode(q, mode, par, with_status):
    study, status = _backsubstitute(q, _FK_STEPS, _FK_INDEX, len(FK_UNKNOWNS), mode, par,
                                    with_status)
    study = _fk_polish(q, study, par)
    shape = q.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = _fk_pose(*[study[..., i] for i in range(len(FK_UNKNOWNS))], *par)
    pose = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                        for v in values], axis=-1)
    return pose, status


def fk(q, **params):
    """Forward kinematics, every assembly mode: array (..., FK_MODES, len(POSE)).

    Solved by back-substitution through a lexicographic Groebner basis of the constraint
    ideal over Q(joints, geometry), then polished by two Newton steps on the leg generators
    (the lex basis has large coefficients); a mode whose solution is not real is NaN
    (``fk_status`` says why).  Poses are in the coordinates of ``POSE``.
    """
    q, par = _fk_inputs("fk", q), _params("fk", params)
    return numpy.stack([_fk_mode(q, m, par, False)[0] for m in range(FK_MODES)], axis=-2)


def fk_status(q, **params):
    """Status per assembly mode for ``fk``: array (..., FK_MODES) of ``STATUS`` codes."""
    q, par = _fk_inputs("fk_status", q), _params("fk_status", params)
    return numpy.stack([_fk_mode(q, m, par, True)[1] for m in range(FK_MODES)], axis=-1)


def _pose_function(func, kern, pose, params):
    pose, par = _pose(func, pose), _params(func, params)
    shape = pose.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = kern(*[pose[..., i] for i in range(len(POSE))], *par)
    return numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                        for v in values], axis=-1)
'''
