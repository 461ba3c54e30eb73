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
FORWARD_SINGULAR = 8
OUTSIDE_CHART = 9
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
    FORWARD_SINGULAR: "forward (output) singularity: two assembly modes (nearly) merge; the "
                      "pose of this mode is returned but not determined to working precision",
    OUTSIDE_CHART: "the platform is turned by a half-turn (x0 = 0), outside the chart x0 = 1 "
                   "in which the closure is written",
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


def ik_and_status(pose, mode=0, limits=True, **params):
    """``(ik(...), ik_status(...))`` from one solve: what a workspace scan needs."""
    return _solve(_pose("ik_and_status", pose), _mode("ik_and_status", mode),
                  _params("ik_and_status", params), True, limits)


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


def jacobian_and_status(pose, mode=0, limits=True, **params):
    """``(jacobian(...), jacobian_status(...))`` from one evaluation."""
    return _jacobian("jacobian_and_status", pose, mode, params, True, limits)


def _pivot_singular(pivots, scales, shape):
    """True where a pivot dG_k/dq_k of ``_jac`` vanishes relative to its row scale (or is not
    finite): an input singularity."""
    singular = numpy.zeros(shape, dtype=bool)
    for d, sc in zip(pivots, scales):
        singular |= ~(numpy.abs(d) > _DET_RTOL * sc)
    return singular


def _jacobian(func, pose, mode, params, with_status, limits=True):
    pose, mode, par = _pose(func, pose), _mode(func, mode), _params(func, params)
    q, status = _solve(pose, mode, par, True, limits)
    shape = pose.shape[:-1]
    n, m = len(JOINTS), len(POSE)
    cols = [pose[..., i] for i in range(m)]
    qc = [q[..., i] for i in range(n)]
    with numpy.errstate(all="ignore"):
        values = _jac(*cols, *qc, *par)
        singular = _pivot_singular(values[:n], values[n:2 * n], shape)
        entries = values[2 * n:]
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
    with numpy.errstate(all="ignore"):
        study = _study(*[pose[..., i] for i in range(len(POSE))], *par)
        qc = [q[..., i] for i in range(len(JOINTS))]
        return {name: numpy.broadcast_to(numpy.asarray(kern(*study, *qc, *par)[0],
                                                       dtype=float), shape)
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


# ------------------------------------------- 3-RPS closure: eliminant per configuration
# u1 = (w + T) / (1 - T w) with T = tan(phi/2), phi = pi/2 + 0.1234: the eliminant is formed
# in w, so a leg that is exactly vertical (u1 = 0, mirror root u1 = infinity) costs no degree;
# w = infinity is leg 1 at phi - pi from the vertical (nearly horizontal).
_RPS_T = 1.1317338234027953
_RPS_DEGREE = 16
_RPS_SAMPLES = _RPS_DEGREE + 1
_RPS_IMAG_TOL = 1e-5
_RPS_RESIDUAL_TOL = 1e-9
_RPS_MERGE_TOL = 1e-7
_RPS_SINGULAR_TOL = 1e-8


def _rps_poly_mul(a, b):
    """Product of polynomials given by ascending coefficients along the last axis."""
    n = a.shape[-1] + b.shape[-1] - 1
    out = numpy.zeros(numpy.broadcast_shapes(a.shape[:-1], b.shape[:-1]) + (n,), dtype=complex)
    for i in range(a.shape[-1]):
        out[..., i:i + b.shape[-1]] += a[..., i:i + 1] * b
    return out


def _rps_eliminant(c12, c23, c31):
    """Ascending coefficients in w of Res_u3(Res_u2(e12, e23), e31), u1 = u1(w): its values
    at the roots of unity (exact resultant formulas), then a discrete Fourier transform."""
    n = _RPS_SAMPLES
    w = numpy.exp(2j * numpy.pi * numpy.arange(n) / n)
    u = (w + _RPS_T) / (1.0 - _RPS_T * w)
    powers = numpy.stack([numpy.ones(n, dtype=complex), u, u * u], axis=-1)  # (n, 3)
    a = numpy.einsum("...ab,sa->...sb", c12, powers)  # e12 in u2: (..., n, 3)
    cc = numpy.einsum("...ab,sb->...sa", c31, powers)  # e31 in u3: (..., n, 3)
    b = c23[..., None, :, :].astype(complex)  # e23: u2^a times the polynomial C23[a] in u3
    a0, a1, a2 = (a[..., k:k + 1] for k in range(3))
    b0, b1, b2 = (b[..., k, :] for k in range(3))
    # Res_u2 of two quadratics: (a2 b0 - a0 b2)^2 - (a2 b1 - a1 b2)(a1 b0 - a0 b1)
    m1, m2, m3 = a2 * b0 - a0 * b2, a2 * b1 - a1 * b2, a1 * b0 - a0 * b1
    r = _rps_poly_mul(m1, m1) - _rps_poly_mul(m2, m3)  # quartic in u3: (..., n, 5)
    syl = numpy.zeros(r.shape[:-1] + (6, 6), dtype=complex)
    for i in range(2):
        syl[..., i, i:i + 5] = r[..., ::-1]
    for i in range(4):
        syl[..., 2 + i, i:i + 3] = cc[..., ::-1]
    values = numpy.linalg.det(syl) * (1.0 - _RPS_T * w) ** _RPS_DEGREE
    return numpy.fft.fft(values, axis=-1) / n


def _rps_roots(p):
    """Roots (..., 16) of the polynomials with ascending coefficients p; NaN where the
    eliminant is degenerate (all coefficients zero, or not finite)."""
    deg = _RPS_DEGREE
    lead = p[..., deg]
    ok = numpy.isfinite(p).all(axis=-1) & (numpy.abs(lead) > 1e-14 * numpy.abs(p).max(axis=-1))
    comp = numpy.zeros(p.shape[:-1] + (deg, deg), dtype=complex)
    idx = numpy.arange(deg - 1)
    comp[..., idx + 1, idx] = 1.0
    comp[..., :, deg - 1] = -p[..., :deg] / numpy.where(ok, lead, 1.0)[..., None]
    comp = numpy.where(ok[..., None, None], comp, numpy.eye(deg))
    roots = numpy.linalg.eigvals(comp)
    return numpy.where(ok[..., None], roots, numpy.nan)


def _rps_quadratic_roots(c):
    """Both roots (..., 2) of c0 + c1 x + c2 x^2 (complex coefficients (..., 3))."""
    c0, c1, c2 = c[..., 0], c[..., 1], c[..., 2]
    sq = numpy.sqrt(c1 * c1 - 4.0 * c2 * c0)
    sq = numpy.where((numpy.conj(c1) * sq).real >= 0.0, sq, -sq)  # no cancellation
    big = -(c1 + sq) / 2.0
    return numpy.stack([big / c2, c0 / big], axis=-1)


def _rps_scaled(theta, qk, par, pair):
    """e_ij / ((1 + u_i^2)(1 + u_j^2)) at u = tan(theta/2) and its Jacobian in theta:
    d/dtheta_k = (de/du_k (1 + u_k^2) / 2 - e u_k) / ((1 + u_i^2)(1 + u_j^2)) for k in {i, j}."""
    u = numpy.tan(theta / 2.0)
    vals = [numpy.broadcast_to(numpy.asarray(v, dtype=float), u.shape[:-1])
            for v in _rps_equations(u[..., 0], u[..., 1], u[..., 2], *qk, *par)]
    e = numpy.stack(vals[:3], axis=-1)
    de = numpy.stack(vals[3:], axis=-1).reshape(u.shape[:-1] + (3, 3))
    w = 1.0 + u * u
    den = w[..., pair[:, 0]] * w[..., pair[:, 1]]
    jac = (de * (w / 2.0)[..., None, :] - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, :1]) - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, 1:]))
    return e / den, jac / den[..., None]


def _rps_candidates(c, w):
    """(u1, u2, u3) candidates (..., 64, 3) over the eliminant's roots w: each root with each
    pair of roots of e12 (in u2) and e31 (in u3) that satisfies e23 nearly as well as the best
    pair.  More than one pair survives where two solutions share u1 (symmetric
    configurations, e.g. all legs equal); Newton and de-duplication sort them out."""
    u1 = (w + _RPS_T) / (1.0 - _RPS_T * w)
    pw = numpy.stack([numpy.ones_like(u1), u1, u1 * u1], axis=-1)  # (..., 16, 3)
    u2 = _rps_quadratic_roots(numpy.einsum("...ab,...ka->...kb", c[..., 0, :, :], pw))
    u3 = _rps_quadratic_roots(numpy.einsum("...ab,...kb->...ka", c[..., 2, :, :], pw))
    p2 = u2[..., :, None] ** numpy.arange(3)  # (..., 16, 2, 3)
    p3 = u3[..., :, None] ** numpy.arange(3)
    v2 = numpy.repeat(u2, 2, axis=-1)  # combos (i, j) -> 2 i + j: (..., 16, 4)
    v3 = numpy.tile(u3, 2)
    res = numpy.stack([numpy.abs((p2[..., i, :] * numpy.einsum(
        "...ab,...kb->...ka", c[..., 1, :, :], p3[..., j, :])).sum(axis=-1)) / (
        (1.0 + numpy.abs(u2[..., i]) ** 2) * (1.0 + numpy.abs(u3[..., j]) ** 2))
        for i in range(2) for j in range(2)], axis=-1)
    keep = res <= numpy.maximum(1e3 * res.min(axis=-1, keepdims=True), 1e-7)
    # Newton starts: the two members of a nearly real pair start apart (Re w +- Im w), so
    # two close real roots that the eigenvalues blurred into a pair are both found
    w1 = w.real + w.imag
    s1 = numpy.broadcast_to(((w1 + _RPS_T) / (1.0 - _RPS_T * w1))[..., None], v2.shape)
    u = numpy.stack([numpy.broadcast_to(u1[..., None], v2.shape), v2, v3], axis=-1)
    # realness is judged in w = (u - T)/(1 + T u), where the roots are well scaled (u is not:
    # u -> infinity for a leg turned to theta = pi)
    wu = (u - _RPS_T) / (1.0 + _RPS_T * u)
    real = keep & (numpy.abs(wu.imag) <= _RPS_IMAG_TOL * (1.0 + numpy.abs(wu))).all(axis=-1)
    start = numpy.stack([s1, v2.real, v3.real], axis=-1)
    start = numpy.where(real[..., None], start, numpy.nan)
    n = 4 * _RPS_DEGREE
    return start.reshape(start.shape[:-3] + (n, 3)), real.reshape(real.shape[:-2] + (n,))


def _rps_solve(q, par):
    """Every assembly mode of the 3-RPS closure: its Study coordinates RPS_UNKNOWNS
    (..., 16, 7) and status (..., 16), real modes first, by decreasing platform height.

    The eliminant in u1 is formed per configuration (see ``_rps_eliminant``), its roots by
    the companion matrix; u2 and u3 from e12 and e31 (``_rps_candidates``); then Newton steps
    on (e12, e23, e31) in the joint angles, a residual test, and de-duplication.  A mode
    where the Jacobian of (e12, e23, e31) is nearly singular (two modes merge: a forward
    singularity) has the status FORWARD_SINGULAR.
    """
    shape = q.shape[:-1]
    qc = [q[..., i] for i in range(q.shape[-1])]
    deg = _RPS_DEGREE
    with numpy.errstate(all="ignore"):
        c = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                         for v in _rps_coefficients(*qc, *par)], axis=-1)
        raw = numpy.abs(c.reshape(shape + (3, 9))).max(axis=-1)[..., None, :]
        c = c.reshape(shape + (3, 3, 3)) / raw[..., 0, :, None, None]  # each eq. to scale 1
        w = _rps_roots(_rps_eliminant(c[..., 0, :, :], c[..., 1, :, :], c[..., 2, :, :]))
        u, real = _rps_candidates(c, w)
        qk = [numpy.asarray(v)[..., None] for v in qc]
        # Newton in the joint angles theta = 2 atan(u) on e_ij / ((1 + u_i^2)(1 + u_j^2)),
        # bounded functions of the angles: well conditioned also for legs near theta = pi
        # (the mirror images below the base, u large)
        theta = 2.0 * numpy.arctan(u)
        pair = numpy.array([[0, 1], [1, 2], [2, 0]])
        for _ in range(5):
            f, jac = _rps_scaled(theta, qk, par, pair)
            good = numpy.isfinite(jac).all(axis=(-2, -1)) & numpy.isfinite(f).all(axis=-1)
            good &= numpy.abs(numpy.linalg.det(numpy.where(good[..., None, None], jac,
                                                           numpy.eye(3)))) > 0.0
            step = numpy.linalg.solve(numpy.where(good[..., None, None], jac, numpy.eye(3)),
                                      numpy.where(good[..., None], f, 0.0)[..., None])[..., 0]
            theta = numpy.where(good[..., None], theta - step, theta)
        f, jac = _rps_scaled(theta, qk, par, pair)
        # residuals relative to the largest coefficient of each equation
        converged = real & (numpy.abs(f) <= _RPS_RESIDUAL_TOL * raw).all(axis=-1)
        # a root polished twice (the eigenvalues of a double projection, a blurred pair)
        # (compared on the unit circle: -pi and pi are one angle)
        theta = numpy.where(converged[..., None], theta, numpy.nan)
        point = numpy.exp(1j * theta)
        for k in range(1, theta.shape[-2]):
            same = (numpy.abs(point[..., k:k + 1, :] - point[..., :k, :])
                    <= _RPS_MERGE_TOL).all(axis=-1).any(axis=-1)
            converged[..., k] &= ~same
        theta = numpy.where(converged[..., None], theta, numpy.nan)
        rows = numpy.linalg.norm(jac, axis=-1).prod(axis=-1)
        singular = converged & ~(numpy.abs(numpy.linalg.det(
            numpy.where(converged[..., None, None], jac, numpy.eye(3)))) > _RPS_SINGULAR_TOL
            * rows)
        status = numpy.where(converged, numpy.where(singular, FORWARD_SINGULAR, OK),
                             NO_REAL_SOLUTION)
        # the 16 modes: solved ones first (by decreasing platform height), then failures
        u = numpy.tan(theta / 2.0)
        cen = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), u.shape[:-1])
                           for v in _rps_centres(u[..., 0], u[..., 1], u[..., 2], *qk, *par)],
                          axis=-1).reshape(u.shape[:-1] + (3, 3))
        height = cen[..., 2].mean(axis=-1)
        key = numpy.where(converged, -height, numpy.inf)
        order = numpy.argsort(key, axis=-1, kind="stable")[..., :deg]
        cen = numpy.take_along_axis(cen, order[..., None, None], axis=-3)
        status = numpy.take_along_axis(status, order, axis=-1).astype(numpy.int8)
        plat = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                            for v in _rps_platform(*par)], axis=-1)
        plat = plat.reshape(shape + (1, 3, 3))

        def frame(pts):
            e1, e2 = pts[..., 1, :] - pts[..., 0, :], pts[..., 2, :] - pts[..., 0, :]
            return numpy.stack([e1, e2, numpy.cross(e1, e2)], axis=-1)

        # R W = V for the edge frames W (platform) and V (solved centres)
        vmat, wmat = frame(cen), frame(plat)
        valid = numpy.isfinite(vmat).all(axis=(-2, -1))
        rot = numpy.swapaxes(numpy.linalg.solve(
            numpy.swapaxes(numpy.broadcast_to(wmat, vmat.shape), -1, -2),
            numpy.swapaxes(numpy.where(valid[..., None, None], vmat, 0.0), -1, -2)), -1, -2)
        trans = cen[..., 0, :] - numpy.einsum("...ij,...j->...i", rot, plat[..., 0, :])
        out = [numpy.broadcast_to(numpy.asarray(v, dtype=float), status.shape)
               for v in _rps_study(*[rot[..., i, j] for i in range(3) for j in range(3)],
                                   *[trans[..., i] for i in range(3)])]
        study = numpy.where(valid[..., None], numpy.stack(out, axis=-1), numpy.nan)
        half_turn = valid & ~numpy.isfinite(study).all(axis=-1)
        status = numpy.where(half_turn, OUTSIDE_CHART, status).astype(numpy.int8)
    return study, status


def _fk_input_singular(pose, q, par, status):
    """INPUT_SINGULAR for a real mode at which a pivot of Ji vanishes: the pose solves the
    closure equations, but the joints do not determine it (e.g. a planar 3-PRP stage turned
    to its input singularity assembles for any strokes)."""
    n = len(JOINTS)
    with numpy.errstate(all="ignore"):
        values = _jac(*[pose[..., i] for i in range(len(POSE))],
                      *[q[..., i] for i in range(n)], *par)
        singular = _pivot_singular(values[:n], values[n:2 * n], status.shape)
    return numpy.where((status == OK) & singular, INPUT_SINGULAR, status).astype(numpy.int8)


def _fk_all(q, par, with_status):
    """Poses (..., FK_MODES, len(POSE)) and statuses (..., FK_MODES) of every mode:
    mode = r * 2**len(FK_MODE_BITS) + m for RPS mode r and back-substitution mode m."""
    shape = q.shape[:-1]
    if RPS_MODES:
        rps, rps_status = _rps_solve(q, par)
    else:
        rps = numpy.zeros(shape + (1, 0))
        rps_status = numpy.zeros(shape + (1,), dtype=numpy.int8)
    solved = []  # the back-substitution modes do not depend on the RPS mode
    for m in range(2 ** len(FK_MODE_BITS)):
        if _FK_STEPS:
            study, status = _backsubstitute(q, _FK_STEPS, _FK_INDEX, len(FK_UNKNOWNS), m, par,
                                            with_status)
            solved.append((_fk_polish(q, study, par), status))
        else:
            solved.append((numpy.zeros(shape + (0,)),
                           numpy.zeros(shape, dtype=numpy.int8) if with_status else None))
    poses, statuses = [], []
    for r in range(rps.shape[-2]):
        for study, status in solved:
            with numpy.errstate(all="ignore"):
                values = _fk_pose(*[rps[..., r, i] for i in range(rps.shape[-1])],
                                  *[study[..., i] for i in range(study.shape[-1])], *par)
            poses.append(numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                                      for v in values], axis=-1))
            if with_status:
                status = numpy.where(rps_status[..., r] != OK, rps_status[..., r], status)
                statuses.append(_fk_input_singular(poses[-1], q, par, status))
    return (numpy.stack(poses, axis=-2),
            numpy.stack(statuses, axis=-1) if with_status else None)


def fk(q, **params):
    """Forward kinematics, every assembly mode: array (..., FK_MODES, len(POSE)).

    Closures with a triangular lex basis over Q(joints, geometry) are solved by
    back-substitution, polished by two Newton steps on the leg generators; a 3-RPS closure
    through its eliminant of degree 16, formed per configuration (``_rps_solve``).  A mode
    whose solution is not real is NaN (``fk_status`` says why).  Poses are in the
    coordinates of ``POSE``.  A real mode at an input singularity (the joints do not
    determine it) is returned with the status INPUT_SINGULAR.
    """
    q, par = _fk_inputs("fk", q), _params("fk", params)
    return _fk_all(q, par, False)[0]


def fk_status(q, **params):
    """Status per assembly mode for ``fk``: array (..., FK_MODES) of ``STATUS`` codes."""
    q, par = _fk_inputs("fk_status", q), _params("fk_status", params)
    return _fk_all(q, par, True)[1]


def _pose_function(func, kern, pose, params):
    pose, par = _pose(func, pose), _params(func, params)
    shape = pose.shape[:-1]
    with numpy.errstate(all="ignore"):
        values = kern(*[pose[..., i] for i in range(len(POSE))], *par)
    return numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                        for v in values], axis=-1)
'''
