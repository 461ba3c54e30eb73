"""Forward kinematics of a 3-RPS closure, per configuration (``solvers/rps_eliminant``).

The three spherical centres run on circles; the eliminant of the circle-distance system
(degree 16 in the first revolute tan-half angle, certified by a Groebner basis during the
derivation) is formed per configuration as an iterated resultant sampled at roots of unity,
its roots by the companion matrix, the other two angles from the pairwise conditions, then
Newton steps, a residual test and de-duplication.  ``k`` is the generated module's kernel
table (``coefficients``, ``equations``, ``centres``, ``platform``, ``study``).
"""

from __future__ import annotations

import numpy

from .inputs import against_modes, broadcast
from .newton import kernel_system, newton_step
from .status import FORWARD_SINGULAR, NO_REAL_SOLUTION, OK, OUTSIDE_CHART

# u1 = (w + T) / (1 - T w) with T = tan(phi/2), phi = pi/2 + 0.1234: the eliminant is formed
# in w, so a leg that is exactly vertical (u1 = 0, mirror root u1 = infinity) costs no degree;
# w = infinity is leg 1 at phi - pi from the vertical (nearly horizontal).
T = 1.1317338234027953
DEGREE = 16
SAMPLES = DEGREE + 1
# candidates whose eliminant root has an imaginary part up to 1e-2 (relative) go to Newton:
# a cluster of roots (two modes sharing u1 at a symmetric configuration) blurs real roots
# by eps^(1/k); Newton, the residual test and de-duplication decide which are real
IMAG_TOL = 1e-2
RESIDUAL_TOL = 1e-9
MERGE_TOL = 1e-7
SINGULAR_TOL = 1e-6
STEP_TOL = 1e-10
# a Newton lane stops once its step is below this (rad)
STEP_STOP = 1e-14
# two roots of a leg's quadratic closer than this (chart w) get their midpoint as a start
PAIR_TOL = 0.2
NEWTON_STEPS = 16
MAX_STEP = 0.5
# displacements (rad) along the null direction in the search for a lost partner root
PARTNER_STEPS = (3e-4, 3e-3, 3e-2, 0.3)
# how many nearly singular modes (singular ratio below PARTNER_RATIO) are searched
PARTNER_MODES = 4
PARTNER_RATIO = 1e-2
# the chart x0 = 1 of the platform's Study coordinates, x_i = (R_kj - R_jk) / (1 + trace R):
# with 1 + trace R = 4 x0^2 (unit quaternion) below this, the rounding of R (about 1e-15)
# makes x_i wrong by more than 1e-9 relative, and on the 3-RPS's other operation mode (x0 =
# 0, the platform turned by a half-turn) numerator and denominator are both rounding noise:
# finite numbers with no meaning (measured on tripod_planar, q = (-532.24, 526.74, 309.13,
# -139.62, 525.94, 233.11): 1 + trace R of 1e-16 gave x = (-1, -2, -0.75) under OK).  Such
# a mode is OUTSIDE_CHART
CHART_TOL = 1e-6


def poly_mul(a, b):
    """Product of polynomials given by ascending coefficients along the last axis."""
    n = a.shape[-1] + b.shape[-1] - 1
    out = numpy.zeros(numpy.broadcast_shapes(a.shape[:-1], b.shape[:-1]) + (n,), dtype=complex)
    for i in range(a.shape[-1]):
        out[..., i:i + b.shape[-1]] += a[..., i:i + 1] * b
    return out


def eliminant(c12, c23, c31):
    """Ascending coefficients in w of Res_u3(Res_u2(e12, e23), e31), u1 = u1(w): its values
    at the roots of unity (exact resultant formulas), then a discrete Fourier transform."""
    n = SAMPLES
    w = numpy.exp(2j * numpy.pi * numpy.arange(n) / n)
    u = (w + T) / (1.0 - T * w)
    powers = numpy.stack([numpy.ones(n, dtype=complex), u, u * u], axis=-1)  # (n, 3)
    a = numpy.einsum("...ab,sa->...sb", c12, powers)  # e12 in u2: (..., n, 3)
    cc = numpy.einsum("...ab,sb->...sa", c31, powers)  # e31 in u3: (..., n, 3)
    b = c23[..., None, :, :].astype(complex)  # e23: u2^a times the polynomial C23[a] in u3
    a0, a1, a2 = (a[..., k:k + 1] for k in range(3))
    b0, b1, b2 = (b[..., k, :] for k in range(3))
    # Res_u2 of two quadratics: (a2 b0 - a0 b2)^2 - (a2 b1 - a1 b2)(a1 b0 - a0 b1)
    m1, m2, m3 = a2 * b0 - a0 * b2, a2 * b1 - a1 * b2, a1 * b0 - a0 * b1
    r = poly_mul(m1, m1) - poly_mul(m2, m3)  # quartic in u3: (..., n, 5)
    syl = numpy.zeros(r.shape[:-1] + (6, 6), dtype=complex)
    for i in range(2):
        syl[..., i, i:i + 5] = r[..., ::-1]
    for i in range(4):
        syl[..., 2 + i, i:i + 3] = cc[..., ::-1]
    values = numpy.linalg.det(syl) * (1.0 - T * w) ** DEGREE
    return numpy.fft.fft(values, axis=-1) / n


def roots(p):
    """Roots (..., 16) of the polynomials with ascending coefficients p; NaN where the
    eliminant is degenerate (all coefficients zero, or not finite)."""
    deg = DEGREE
    lead = p[..., deg]
    ok = numpy.isfinite(p).all(axis=-1) & (numpy.abs(lead) > 1e-14 * numpy.abs(p).max(axis=-1))
    comp = numpy.zeros(p.shape[:-1] + (deg, deg), dtype=complex)
    idx = numpy.arange(deg - 1)
    comp[..., idx + 1, idx] = 1.0
    comp[..., :, deg - 1] = -p[..., :deg] / numpy.where(ok, lead, 1.0)[..., None]
    comp = numpy.where(ok[..., None, None], comp, numpy.eye(deg))
    roots = numpy.linalg.eigvals(comp)
    return numpy.where(ok[..., None], roots, numpy.nan)


def quadratic_roots(c):
    """Both roots of c0 + c1 x + c2 x^2 (complex coefficients (..., 3)) and, third, the
    double root the pair tends to where the discriminant vanishes (..., 3).

    The third candidate is the midpoint of the pair in the chart w = (x - T)/(1 + T x), in
    which the roots are well scaled: near a forward singularity a leg's quadratic has a
    nearly double root that the roots of a slightly perturbed quadratic (u1 from a cluster
    of eliminant roots, accurate to eps^(1/k)) straddle by sqrt of the perturbation."""
    c0, c1, c2 = c[..., 0], c[..., 1], c[..., 2]
    sq = numpy.sqrt(c1 * c1 - 4.0 * c2 * c0)
    sq = numpy.where((numpy.conj(c1) * sq).real >= 0.0, sq, -sq)  # no cancellation
    big = -(c1 + sq) / 2.0
    r0, r1 = big / c2, c0 / big
    wm = ((r0 - T) / (1.0 + T * r0) + (r1 - T) / (1.0 + T * r1)) / 2.0
    return numpy.stack([r0, r1, (wm + T) / (1.0 - T * wm)], axis=-1)


def scaled(k, theta, qk, par, pair):
    """e_ij / ((1 + u_i^2)(1 + u_j^2)) at u = tan(theta/2) and its Jacobian in theta:
    d/dtheta_k = (de/du_k (1 + u_k^2) / 2 - e u_k) / ((1 + u_i^2)(1 + u_j^2)) for k in {i, j}."""
    u = numpy.tan(theta / 2.0)
    e, de = kernel_system(k.equations, [u[..., 0], u[..., 1], u[..., 2], *qk, *par],
                          u.shape[:-1], 3)
    w = 1.0 + u * u
    den = w[..., pair[:, 0]] * w[..., pair[:, 1]]
    jac = (de * (w / 2.0)[..., None, :] - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, :1]) - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, 1:]))
    return e / den, jac / den[..., None]


def candidates(c, w):
    """(u1, u2, u3) starts (..., 144, 3) over the eliminant's roots w and which are real.

    Each root u1 with each root of e12 (in u2) and of e31 (in u3) that satisfies e23 nearly
    as well as the best pair; where a leg's two roots nearly coincide (a nearly double
    root: a forward singularity), also with their midpoint (``quadratic_roots``).  More
    than one pair survives where two solutions share u1 (symmetric configurations, e.g. all
    legs equal); Newton and de-duplication sort them out."""
    u1 = (w + T) / (1.0 - T * w)
    pw = numpy.stack([numpy.ones_like(u1), u1, u1 * u1], axis=-1)  # (..., 16, 3)
    u2 = quadratic_roots(numpy.einsum("...ab,...ka->...kb", c[..., 0, :, :], pw))
    u3 = quadratic_roots(numpy.einsum("...ab,...kb->...ka", c[..., 2, :, :], pw))

    def close(r):  # the two roots nearly coincide (in the well-scaled chart w)
        wr = (r[..., :2] - T) / (1.0 + T * r[..., :2])
        return numpy.abs(wr[..., 0] - wr[..., 1]) <= PAIR_TOL * (1.0 + numpy.abs(wr[..., 0]))

    close2, close3 = close(u2), close(u3)
    p2 = u2[..., :, None] ** numpy.arange(3)  # (..., 16, 3, 3)
    p3 = u3[..., :, None] ** numpy.arange(3)
    combos = [(i, j) for i in range(3) for j in range(3)]  # combo (i, j) -> 3 i + j
    v2 = numpy.stack([u2[..., i] for i, _ in combos], axis=-1)  # (..., 16, 9)
    v3 = numpy.stack([u3[..., j] for _, j in combos], axis=-1)
    res = numpy.stack([numpy.abs((p2[..., i, :] * numpy.einsum(
        "...ab,...kb->...ka", c[..., 1, :, :], p3[..., j, :])).sum(axis=-1)) / (
        (1.0 + numpy.abs(u2[..., i]) ** 2) * (1.0 + numpy.abs(u3[..., j]) ** 2))
        for i, j in combos], axis=-1)
    exact = numpy.array([i < 2 and j < 2 for i, j in combos])
    best = numpy.where(exact, res, numpy.inf).min(axis=-1, keepdims=True)
    keep = numpy.where(exact, res <= numpy.maximum(1e3 * best, 1e-7), True)
    ones = numpy.ones_like(close2)
    keep &= numpy.stack([(close2 if i == 2 else ones) & (close3 if j == 2 else ones)
                         for i, j in combos], axis=-1)
    # Newton starts: the two members of a nearly real pair start apart (Re w +- Im w), so
    # two close real roots that the eigenvalues blurred into a pair are both found
    w1 = w.real + w.imag
    s1 = numpy.broadcast_to(((w1 + T) / (1.0 - T * w1))[..., None], v2.shape)
    # realness is judged in w, where the roots are well scaled (u is not: u -> infinity for
    # a leg turned to theta = pi), and only for u1: near a forward singularity u1 from a
    # cluster of eliminant roots is slightly complex, and a leg's quadratic with a nearly
    # double root turns that into roots u2, u3 with large imaginary parts; their real parts
    # are still good starts, and Newton with the residual test decides what is real
    real = keep & (numpy.abs(w.imag) <= IMAG_TOL * (1.0 + numpy.abs(w)))[..., None]
    start = numpy.stack([s1, v2.real, v3.real], axis=-1)
    start = numpy.where(real[..., None], start, numpy.nan)
    n = len(combos) * DEGREE
    return start.reshape(start.shape[:-3] + (n, 3)), real.reshape(real.shape[:-2] + (n,))


def solve(k, q, par):
    """Every assembly mode of the 3-RPS closure: its Study coordinates RPS_UNKNOWNS
    (..., 16, 7) and status (..., 16), real modes first, by decreasing platform height.

    The eliminant in u1 is formed per configuration (see ``eliminant``), its roots by
    the companion matrix; u2 and u3 from e12 and e31 (``candidates``); then clipped Newton
    steps on (e12, e23, e31) in the joint angles (``newton``), a residual test and
    de-duplication (``distinct``).  Real solutions are even in number: an odd count sends
    the nearly singular modes to a search for their lost partner (``partners``).  A mode is
    OK only where its last Newton step is below STEP_TOL rad and the Jacobian of (e12, e23,
    e31) is not nearly singular; otherwise (two modes merge: a forward singularity, where
    the pose is determined only to about sqrt(eps)) it is FORWARD_SINGULAR.
    """
    shape = q.shape[:-1]
    qc = [q[..., i] for i in range(q.shape[-1])]
    deg = DEGREE
    with numpy.errstate(all="ignore"):
        c = numpy.stack([broadcast(v, shape)
                         for v in k.coefficients(*qc, *par)], axis=-1)
        raw = numpy.abs(c.reshape(shape + (3, 9))).max(axis=-1)[..., None, :]
        c = c.reshape(shape + (3, 3, 3)) / raw[..., 0, :, None, None]  # each eq. to scale 1
        w = roots(eliminant(c[..., 0, :, :], c[..., 1, :, :], c[..., 2, :, :]))
        u, real = candidates(c, w)
        qk = [numpy.asarray(v)[..., None] for v in qc]
        # the geometry alike, where it is given per configuration: against the modes' axis
        pk = against_modes(par)
        # Newton in the joint angles theta = 2 atan(u) on e_ij / ((1 + u_i^2)(1 + u_j^2)),
        # bounded functions of the angles: well conditioned also for legs near theta = pi
        # (the mirror images below the base, u large)
        theta = 2.0 * numpy.arctan(u)
        pair = numpy.array([[0, 1], [1, 2], [2, 0]])
        theta, f, jac, converged = newton(k, theta, qk, par, pair, raw, real)
        theta, jac, converged = compact(theta, jac, converged)
        theta, converged = distinct(theta, converged)
        ratio = singular_ratio(jac)
        # real solutions come in even number (conjugate pairs; 16 in all): an odd count has
        # lost the partner of a nearly double root, sought along the Jacobian's null
        # direction of the most singular mode; still odd, that mode is FORWARD_SINGULAR
        odd = converged.sum(axis=-1) % 2 == 1
        if odd.any():
            theta, converged, ratio, unpaired = partners(k, theta, converged, ratio, jac, qk,
                                                       par, pair, raw, odd)
        else:
            unpaired = numpy.zeros_like(converged)
        # a mode is OK only where the angles are known to STEP_TOL rad: the last Newton
        # step is that small (quadratic convergence, a regular root)
        theta, size = last_step(k, theta, qk, par, pair)
        singular = converged & ((ratio <= SINGULAR_TOL) | unpaired | ~(size <= STEP_TOL))
        status = numpy.where(converged, numpy.where(singular, FORWARD_SINGULAR, OK),
                             NO_REAL_SOLUTION)
        # the 16 modes: solved ones first (by decreasing platform height), then failures
        u = numpy.tan(theta / 2.0)
        cen = numpy.stack([broadcast(v, u.shape[:-1])
                           for v in k.centres(u[..., 0], u[..., 1], u[..., 2], *qk, *pk)],
                          axis=-1).reshape(u.shape[:-1] + (3, 3))
        height = cen[..., 2].mean(axis=-1)
        key = numpy.where(converged, -height, numpy.inf)
        order = numpy.argsort(key, axis=-1, kind="stable")[..., :deg]
        cen = numpy.take_along_axis(cen, order[..., None, None], axis=-3)
        status = numpy.take_along_axis(status, order, axis=-1).astype(numpy.int8)
        plat = numpy.stack([broadcast(v, shape)
                            for v in k.platform(*par)], axis=-1)
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
        out = [broadcast(v, status.shape)
               for v in k.study(*[rot[..., i, j] for i in range(3) for j in range(3)],
                                *[trans[..., i] for i in range(3)])]
        study = numpy.where(valid[..., None], numpy.stack(out, axis=-1), numpy.nan)
        chart = 1.0 + numpy.trace(rot, axis1=-2, axis2=-1)  # 4 x0^2
        half_turn = valid & (~numpy.isfinite(study).all(axis=-1) | ~(chart > CHART_TOL))
        study = numpy.where(half_turn[..., None], numpy.nan, study)
        status = numpy.where(half_turn, OUTSIDE_CHART, status).astype(numpy.int8)
    return study, status


def lanes(theta, qk, par):
    """The starts (..., n, 3) as a flat list of lanes (L, 3), with the joints and
    parameters of each lane (the solver works on the lanes still running only)."""
    shape = theta.shape[:-1]
    qf = [numpy.broadcast_to(v, shape).reshape(-1) for v in qk]
    pf = [p if numpy.ndim(p) == 0 else numpy.broadcast_to(numpy.asarray(p)[..., None],
                                                          shape).reshape(-1) for p in par]
    return theta.reshape(-1, 3).copy(), qf, pf


def scaled_at(k, th, qf, pf, pair, idx):
    """``scaled`` on the lanes ``idx`` only."""
    return scaled(k, th[idx], [v[idx] for v in qf],
                  [p if numpy.ndim(p) == 0 else p[idx] for p in pf], pair)


def newton(k, theta, qk, par, pair, raw, active):
    """Newton steps on (e12, e23, e31) in the joint angles from ``theta`` (..., n, 3);
    returns the angles, residuals, Jacobian and which starts converged (residual test).

    At a forward singularity Newton converges only linearly (the error halves per step)
    from starts that clustered eliminant roots place far off: up to NEWTON_STEPS steps,
    each clipped to MAX_STEP rad so that a nearly singular Jacobian cannot throw a start
    into another mode's basin.  Each step works on the lanes still running: those active,
    finite, with an invertible Jacobian and a last step above STEP_STOP rad (converged
    quadratically; a lane near a fold keeps going)."""
    shape = theta.shape[:-1]
    th, qf, pf = lanes(theta, qk, par)
    rawf = numpy.broadcast_to(raw, shape + (3,)).reshape(-1, 3)
    act = numpy.broadcast_to(active, shape).reshape(-1) & numpy.isfinite(th).all(axis=-1)
    idx = numpy.flatnonzero(act)
    for _ in range(NEWTON_STEPS):
        if not idx.size:
            break
        f, jac = scaled_at(k, th, qf, pf, pair, idx)
        good = numpy.isfinite(jac).all(axis=(-2, -1)) & numpy.isfinite(f).all(axis=-1)
        step, good = newton_step(f, jac, good)
        size = numpy.abs(step).max(axis=-1, keepdims=True)
        step = step * numpy.minimum(1.0, MAX_STEP / numpy.maximum(size, 1e-300))
        th[idx] -= numpy.where(good[..., None], step, 0.0)
        idx = idx[good & (size[..., 0] > STEP_STOP)]
    idx = numpy.flatnonzero(act)
    f = numpy.full(th.shape, numpy.nan)
    jac = numpy.full(th.shape + (3,), numpy.nan)
    f[idx], jac[idx] = scaled_at(k, th, qf, pf, pair, idx)
    # residuals relative to the largest coefficient of each equation
    converged = act & (numpy.abs(f) <= RESIDUAL_TOL * rawf).all(axis=-1)
    return (th.reshape(theta.shape), f.reshape(shape + (3,)), jac.reshape(shape + (3, 3)),
            converged.reshape(shape))


def last_step(k, theta, qk, par, pair):
    """One more (unclipped) Newton step on the finite lanes: the angles after it and its
    size, the estimate of the error of the angles before it (large where the Jacobian is
    nearly singular; infinite where no step was taken)."""
    shape = theta.shape[:-1]
    th, qf, pf = lanes(theta, qk, par)
    idx = numpy.flatnonzero(numpy.isfinite(th).all(axis=-1))
    size = numpy.full(th.shape[0], numpy.inf)
    if idx.size:
        f, jac = scaled_at(k, th, qf, pf, pair, idx)
        good = numpy.isfinite(jac).all(axis=(-2, -1)) & numpy.isfinite(f).all(axis=-1)
        step, good = newton_step(f, jac, good)
        th[idx] -= numpy.where(good[..., None], step, 0.0)
        size[idx] = numpy.where(good, numpy.abs(step).max(axis=-1), numpy.inf)
    return th.reshape(theta.shape), size.reshape(shape)


def compact(theta, jac, converged):
    """The converged lanes of each sample moved to the front (in their order), the lanes
    cut to the largest count in the batch (at least DEGREE + 1: free slots for ``partners``
    and 16 modes to return): de-duplication then compares a few lanes, not 144."""
    order = numpy.argsort(~converged, axis=-1, kind="stable")
    keep = max(int(converged.sum(axis=-1).max(initial=0)), DEGREE + 1)
    order = order[..., :keep]
    return (numpy.take_along_axis(theta, order[..., None], axis=-2),
            numpy.take_along_axis(jac, order[..., None, None], axis=-3),
            numpy.take_along_axis(converged, order, axis=-1))


def distinct(theta, converged):
    """Drop a root polished twice (the eigenvalues of a double projection, a blurred pair),
    compared on the unit circle (-pi and pi are one angle); NaN where not converged."""
    theta = numpy.where(converged[..., None], theta, numpy.nan)
    point = numpy.exp(1j * theta)
    converged = converged.copy()
    for j in range(1, theta.shape[-2]):
        same = (numpy.abs(point[..., j:j + 1, :] - point[..., :j, :])
                <= MERGE_TOL).all(axis=-1).any(axis=-1)
        converged[..., j] &= ~same
    return numpy.where(converged[..., None], theta, numpy.nan), converged


def singular_ratio(jac):
    """|det J| over the product of its row norms: 0 at a forward singularity, 1 at best."""
    ok = numpy.isfinite(jac).all(axis=(-2, -1))
    safe = numpy.where(ok[..., None, None], jac, numpy.eye(3))
    rows = numpy.linalg.norm(safe, axis=-1).prod(axis=-1)
    return numpy.where(ok, numpy.abs(numpy.linalg.det(safe)) / numpy.where(rows > 0, rows, 1.0),
                       0.0)


def partners(k, theta, converged, ratio, jac, qk, par, pair, raw, odd):
    """For the samples with an odd number of real modes: Newton from each of their
    PARTNER_MODES most singular modes (singular ratio below PARTNER_RATIO) displaced along
    the null direction of its Jacobian (PARTNER_STEPS rad either way); each new root is
    added in a free slot.  Returns the updated angles, converged flags, ratios, and the
    modes to flag FORWARD_SINGULAR: the most singular one of a sample still odd."""
    shape, n = odd.shape, theta.shape[-2]
    idx = numpy.flatnonzero(odd)
    th = theta.reshape(-1, n, 3)[idx]
    conv, rat = converged.reshape(-1, n)[idx], ratio.reshape(-1, n)[idx]
    jc = jac.reshape(-1, n, 3, 3)[idx]
    q_sub = [numpy.broadcast_to(v, shape + (1,)).reshape(-1, 1)[idx] for v in qk]
    # the geometry of those samples, where it is given per configuration
    par_sub = [p if numpy.ndim(p) == 0 else numpy.broadcast_to(p, shape).reshape(-1)[idx]
               for p in par]
    raw_sub = numpy.broadcast_to(raw, shape + (1, 3)).reshape(-1, 1, 3)[idx]
    rows = numpy.arange(len(idx))
    order = numpy.argsort(numpy.where(conv, rat, numpy.inf), axis=-1, kind="stable")
    worst = order[:, 0]
    t = numpy.array([sign * d for d in PARTNER_STEPS for sign in (1.0, -1.0)])
    for r in range(PARTNER_MODES):
        mode = order[:, r]
        near = conv[rows, mode] & (rat[rows, mode] < PARTNER_RATIO)
        if not near.any():
            break
        x0, j0 = th[rows, mode], jc[rows, mode]
        _, _, vt = numpy.linalg.svd(numpy.where(numpy.isfinite(j0), j0, 0.0))
        starts = x0[:, None, :] + t[None, :, None] * vt[:, -1, None, :]
        active = numpy.broadcast_to(near[:, None], starts.shape[:-1])
        new, _, new_jac, ok = newton(k, starts, q_sub, par_sub, pair, raw_sub, active)
        for s in range(len(t)):  # each start's root, if new, into a free slot
            point, old = numpy.exp(1j * new[:, s]), numpy.exp(1j * th)
            seen = ((numpy.abs(point[:, None, :] - old) <= MERGE_TOL).all(axis=-1)
                    & conv).any(axis=-1)
            free = numpy.argmin(conv, axis=-1)
            add = ok[:, s] & ~seen & ~conv[rows, free]
            th[rows[add], free[add]] = new[rows[add], s]
            conv[rows[add], free[add]] = True
            rat[rows[add], free[add]] = singular_ratio(new_jac[rows[add], s])
    still = conv.sum(axis=-1) % 2 == 1
    unpaired = numpy.zeros_like(conv)
    unpaired[rows[still], worst[still]] = True
    theta, converged = theta.reshape(-1, n, 3).copy(), converged.reshape(-1, n).copy()
    ratio, flag = ratio.reshape(-1, n).copy(), numpy.zeros((odd.size, n), dtype=bool)
    theta[idx], converged[idx], ratio[idx], flag[idx] = th, conv, rat, unpaired
    return (theta.reshape(shape + (n, 3)), converged.reshape(shape + (n,)),
            ratio.reshape(shape + (n,)), flag.reshape(shape + (n,)))
