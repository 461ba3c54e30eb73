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
SINGULAR_TOL = 1e-8


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
    """Both roots (..., 2) of c0 + c1 x + c2 x^2 (complex coefficients (..., 3))."""
    c0, c1, c2 = c[..., 0], c[..., 1], c[..., 2]
    sq = numpy.sqrt(c1 * c1 - 4.0 * c2 * c0)
    sq = numpy.where((numpy.conj(c1) * sq).real >= 0.0, sq, -sq)  # no cancellation
    big = -(c1 + sq) / 2.0
    return numpy.stack([big / c2, c0 / big], axis=-1)


def scaled(k, theta, qk, par, pair):
    """e_ij / ((1 + u_i^2)(1 + u_j^2)) at u = tan(theta/2) and its Jacobian in theta:
    d/dtheta_k = (de/du_k (1 + u_k^2) / 2 - e u_k) / ((1 + u_i^2)(1 + u_j^2)) for k in {i, j}."""
    u = numpy.tan(theta / 2.0)
    vals = [numpy.broadcast_to(numpy.asarray(v, dtype=float), u.shape[:-1])
            for v in k.equations(u[..., 0], u[..., 1], u[..., 2], *qk, *par)]
    e = numpy.stack(vals[:3], axis=-1)
    de = numpy.stack(vals[3:], axis=-1).reshape(u.shape[:-1] + (3, 3))
    w = 1.0 + u * u
    den = w[..., pair[:, 0]] * w[..., pair[:, 1]]
    jac = (de * (w / 2.0)[..., None, :] - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, :1]) - e[..., :, None] * u[..., None, :]
           * (numpy.arange(3)[None, :] == pair[:, 1:]))
    return e / den, jac / den[..., None]


def candidates(c, w):
    """(u1, u2, u3) candidates (..., 64, 3) over the eliminant's roots w: each root with each
    pair of roots of e12 (in u2) and e31 (in u3) that satisfies e23 nearly as well as the best
    pair.  More than one pair survives where two solutions share u1 (symmetric
    configurations, e.g. all legs equal); Newton and de-duplication sort them out."""
    u1 = (w + T) / (1.0 - T * w)
    pw = numpy.stack([numpy.ones_like(u1), u1, u1 * u1], axis=-1)  # (..., 16, 3)
    u2 = quadratic_roots(numpy.einsum("...ab,...ka->...kb", c[..., 0, :, :], pw))
    u3 = quadratic_roots(numpy.einsum("...ab,...kb->...ka", c[..., 2, :, :], pw))
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
    s1 = numpy.broadcast_to(((w1 + T) / (1.0 - T * w1))[..., None], v2.shape)
    u = numpy.stack([numpy.broadcast_to(u1[..., None], v2.shape), v2, v3], axis=-1)
    # realness is judged in w = (u - T)/(1 + T u), where the roots are well scaled (u is not:
    # u -> infinity for a leg turned to theta = pi)
    wu = (u - T) / (1.0 + T * u)
    real = keep & (numpy.abs(wu.imag) <= IMAG_TOL * (1.0 + numpy.abs(wu))).all(axis=-1)
    start = numpy.stack([s1, v2.real, v3.real], axis=-1)
    start = numpy.where(real[..., None], start, numpy.nan)
    n = 4 * DEGREE
    return start.reshape(start.shape[:-3] + (n, 3)), real.reshape(real.shape[:-2] + (n,))


def solve(k, q, par):
    """Every assembly mode of the 3-RPS closure: its Study coordinates RPS_UNKNOWNS
    (..., 16, 7) and status (..., 16), real modes first, by decreasing platform height.

    The eliminant in u1 is formed per configuration (see ``eliminant``), its roots by
    the companion matrix; u2 and u3 from e12 and e31 (``candidates``); then Newton steps
    on (e12, e23, e31) in the joint angles, a residual test, and de-duplication.  A mode
    where the Jacobian of (e12, e23, e31) is nearly singular (two modes merge: a forward
    singularity) has the status FORWARD_SINGULAR.
    """
    shape = q.shape[:-1]
    qc = [q[..., i] for i in range(q.shape[-1])]
    deg = DEGREE
    with numpy.errstate(all="ignore"):
        c = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                         for v in k.coefficients(*qc, *par)], axis=-1)
        raw = numpy.abs(c.reshape(shape + (3, 9))).max(axis=-1)[..., None, :]
        c = c.reshape(shape + (3, 3, 3)) / raw[..., 0, :, None, None]  # each eq. to scale 1
        w = roots(eliminant(c[..., 0, :, :], c[..., 1, :, :], c[..., 2, :, :]))
        u, real = candidates(c, w)
        qk = [numpy.asarray(v)[..., None] for v in qc]
        # Newton in the joint angles theta = 2 atan(u) on e_ij / ((1 + u_i^2)(1 + u_j^2)),
        # bounded functions of the angles: well conditioned also for legs near theta = pi
        # (the mirror images below the base, u large)
        theta = 2.0 * numpy.arctan(u)
        pair = numpy.array([[0, 1], [1, 2], [2, 0]])
        for _ in range(5):
            f, jac = scaled(k, theta, qk, par, pair)
            good = numpy.isfinite(jac).all(axis=(-2, -1)) & numpy.isfinite(f).all(axis=-1)
            good &= numpy.abs(numpy.linalg.det(numpy.where(good[..., None, None], jac,
                                                           numpy.eye(3)))) > 0.0
            step = numpy.linalg.solve(numpy.where(good[..., None, None], jac, numpy.eye(3)),
                                      numpy.where(good[..., None], f, 0.0)[..., None])[..., 0]
            theta = numpy.where(good[..., None], theta - step, theta)
        f, jac = scaled(k, theta, qk, par, pair)
        # residuals relative to the largest coefficient of each equation
        converged = real & (numpy.abs(f) <= RESIDUAL_TOL * raw).all(axis=-1)
        # a root polished twice (the eigenvalues of a double projection, a blurred pair)
        # (compared on the unit circle: -pi and pi are one angle)
        theta = numpy.where(converged[..., None], theta, numpy.nan)
        point = numpy.exp(1j * theta)
        for j in range(1, theta.shape[-2]):
            same = (numpy.abs(point[..., j:j + 1, :] - point[..., :j, :])
                    <= MERGE_TOL).all(axis=-1).any(axis=-1)
            converged[..., j] &= ~same
        theta = numpy.where(converged[..., None], theta, numpy.nan)
        rows = numpy.linalg.norm(jac, axis=-1).prod(axis=-1)
        singular = converged & ~(numpy.abs(numpy.linalg.det(
            numpy.where(converged[..., None, None], jac, numpy.eye(3)))) > SINGULAR_TOL
            * rows)
        status = numpy.where(converged, numpy.where(singular, FORWARD_SINGULAR, OK),
                             NO_REAL_SOLUTION)
        # the 16 modes: solved ones first (by decreasing platform height), then failures
        u = numpy.tan(theta / 2.0)
        cen = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), u.shape[:-1])
                           for v in k.centres(u[..., 0], u[..., 1], u[..., 2], *qk, *par)],
                          axis=-1).reshape(u.shape[:-1] + (3, 3))
        height = cen[..., 2].mean(axis=-1)
        key = numpy.where(converged, -height, numpy.inf)
        order = numpy.argsort(key, axis=-1, kind="stable")[..., :deg]
        cen = numpy.take_along_axis(cen, order[..., None, None], axis=-3)
        status = numpy.take_along_axis(status, order, axis=-1).astype(numpy.int8)
        plat = numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
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
        out = [numpy.broadcast_to(numpy.asarray(v, dtype=float), status.shape)
               for v in k.study(*[rot[..., i, j] for i in range(3) for j in range(3)],
                                   *[trans[..., i] for i in range(3)])]
        study = numpy.where(valid[..., None], numpy.stack(out, axis=-1), numpy.nan)
        half_turn = valid & ~numpy.isfinite(study).all(axis=-1)
        status = numpy.where(half_turn, OUTSIDE_CHART, status).astype(numpy.int8)
    return study, status
