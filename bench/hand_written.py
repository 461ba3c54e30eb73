"""Hand-written numpy IK and IK + Jacobian, from the papers' closed forms and plain geometry:
what a user would write instead of importing the generated module (issue 15's baseline).

Written from the papers and the layouts, not from generated code: planar_tripod from 000
eq. (17) and (21) with their derivatives; stewart from the leg vectors |t + R b_k - a_k|;
pro_hep_lct from the two-link and slider-rod geometry of 004 eq. (14)-(16) (test geometry of
tests/independent_pro_hep_lct.py); tripod_planar from 001 eq. (8), (10)-(13), (21)-(23) and
their derivatives.  Each returns joints in the generated module's order and dq/dX with X as
in its POSE, except tripod_planar, which works in 001's own coordinates (the bench converts).
"""

from __future__ import annotations

import numpy as np
from independent_stewart import corners as stewart_corners  # tests/: the layout, once

S3 = np.sqrt(3.0)


# ------------------------------------------------------------------ planar_tripod (000)
def planar_tripod(p, ra=190.0, rb=190.0, jacobian=False):
    """000 eq. (17) (q1..q3, the planar stage) and eq. (21) (q4..q6, the tripod legs)."""
    x, y, z, a, b, g = (p[:, i] for i in range(6))
    sa, ca, sb, cb, sg, cg = np.sin(a), np.cos(a), np.sin(b), np.cos(b), np.sin(g), np.cos(g)
    den = sg + S3 * cg
    k = S3 * rb * sa * sb
    n1 = ra + ra * cg + 2 * y * cg - 2 * x * sg + S3 * ra * sg
    n2 = ra + ra * cg + S3 * ra * sg - y * cg + x * sg - S3 * y * sg - S3 * x * cg - k
    n3 = ra + ra * cg + S3 * ra * sg - y * cg + x * sg + S3 * y * sg + S3 * x * cg + k
    u4, w4 = z - rb * sb, ra - rb * cb + rb * sa * sb
    u5, w5 = z + rb * sa * cb, ra - rb * ca
    u6, w6 = z + rb * sb, ra - rb * cb - rb * sa * sb
    q = np.empty((len(x), 6))
    q[:, 0], q[:, 1], q[:, 2] = n1 / den, n2 / den, n3 / den
    q4 = q[:, 3] = np.sqrt(u4 * u4 + w4 * w4)
    q5 = q[:, 4] = np.sqrt(u5 * u5 + w5 * w5)
    q6 = q[:, 5] = np.sqrt(u6 * u6 + w6 * w6)
    if not jacobian:
        return q
    jac = np.zeros((len(x), 6, 6))
    dden = cg - S3 * sg  # d den / d gamma
    dk_a, dk_b = S3 * rb * ca * sb, S3 * rb * sa * cb
    inv, inv2 = 1.0 / den, 1.0 / (den * den)
    # d n_i / d(x, y, gamma) and the quotient rule for gamma
    dn1 = (-2 * sg, 2 * cg, -ra * sg - 2 * y * sg - 2 * x * cg + S3 * ra * cg)
    dn2 = (sg - S3 * cg, -cg - S3 * sg,
           -ra * sg + S3 * ra * cg + y * sg + x * cg - S3 * y * cg + S3 * x * sg)
    dn3 = (sg + S3 * cg, -cg + S3 * sg,
           -ra * sg + S3 * ra * cg + y * sg + x * cg + S3 * y * cg - S3 * x * sg)
    for i, (n, dn, sign) in enumerate(((n1, dn1, 0.0), (n2, dn2, -1.0), (n3, dn3, 1.0))):
        jac[:, i, 0], jac[:, i, 1] = dn[0] * inv, dn[1] * inv
        if sign:
            jac[:, i, 3], jac[:, i, 4] = sign * dk_a * inv, sign * dk_b * inv
        jac[:, i, 5] = (dn[2] * den - n * dden) * inv2
    # q = sqrt(u^2 + w^2): dq = (u du + w dw) / q
    for i, (qq, u, w, du, dw) in enumerate((
            (q4, u4, w4, (0, -rb * cb), (rb * ca * sb, rb * sb + rb * sa * cb)),
            (q5, u5, w5, (rb * ca * cb, -rb * sa * sb), (rb * sa, 0)),
            (q6, u6, w6, (0, rb * cb), (-rb * ca * sb, rb * sb - rb * sa * cb))), start=3):
        iq = 1.0 / qq
        jac[:, i, 2] = u * iq
        jac[:, i, 3] = (u * du[0] + w * dw[0]) * iq
        jac[:, i, 4] = (u * du[1] + w * dw[1]) * iq
    return q, jac


# ------------------------------------------------------------------ stewart
def stewart(p, jacobian=False, corners=None):
    """q_k = |t + R b_k - a_k|, R = Rz(gamma) Ry(beta) Rx(alpha); dq_k/dX = v_k^T dv_k/dX
    / q_k."""
    base, plat = corners or stewart_corners()
    x, y, z, a, b, g = (p[:, i] for i in range(6))
    sa, ca, sb, cb, sg, cg = np.sin(a), np.cos(a), np.sin(b), np.cos(b), np.sin(g), np.cos(g)
    # rows of R (each an array over poses): R = Rz Ry Rx
    r = ((cg * cb, cg * sb * sa - sg * ca, cg * sb * ca + sg * sa),
         (sg * cb, sg * sb * sa + cg * ca, sg * sb * ca - cg * sa),
         (-sb, cb * sa, cb * ca))
    q = np.empty((len(x), 6))
    jac = np.empty((len(x), 6, 6)) if jacobian else None
    if jacobian:  # dR/d alpha, d beta, d gamma: the columns that multiply b_x and b_y
        d = {"a": ((0.0, cg * sb * ca + sg * sa), (0.0, sg * sb * ca - cg * sa), (0.0, cb * ca)),
             "b": ((-cg * sb, cg * cb * sa), (-sg * sb, sg * cb * sa), (-cb, -sb * sa)),
             "g": ((-sg * cb, -(sg * sb * sa + cg * ca)), (cg * cb, cg * sb * sa - sg * ca),
                   (0.0, 0.0))}
    for k, ((ax, ay, _), (bx, by, _)) in enumerate(zip(base, plat)):
        vx = x + r[0][0] * bx + r[0][1] * by - ax
        vy = y + r[1][0] * bx + r[1][1] * by - ay
        vz = z + r[2][0] * bx + r[2][1] * by
        qk = q[:, k] = np.sqrt(vx * vx + vy * vy + vz * vz)
        if jacobian:
            inv = 1.0 / qk
            ux, uy, uz = vx * inv, vy * inv, vz * inv
            jac[:, k, 0], jac[:, k, 1], jac[:, k, 2] = ux, uy, uz
            for col, key in ((3, "a"), (4, "b"), (5, "g")):
                (x0, y0), (x1, y1), (x2, y2) = d[key]
                jac[:, k, col] = (ux * (x0 * bx + y0 * by) + uy * (x1 * bx + y1 * by)
                                  + uz * (x2 * bx + y2 * by))
    return q if not jacobian else (q, jac)


# ------------------------------------------------------------------ pro_hep_lct (004)
def _two_link(px, py, l1, l2, elbow):
    """theta1 of a two-link chain from its base to (px, py), the elbow on side ``elbow``
    (+-1), and d theta1 / d(px, py)."""
    r2 = px * px + py * py
    c2 = (r2 - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    s2 = elbow * np.sqrt(1 - c2 * c2)
    k1, k2 = l1 + l2 * c2, l2 * s2
    th1 = np.arctan2(py, px) - np.arctan2(k2, k1)
    # the inverse of the chain's Jacobian: d theta1 = (c12 dpx + s12 dpy) / (l1 s2)
    c12, s12 = np.cos(th1 + np.arctan2(s2, c2)), np.sin(th1 + np.arctan2(s2, c2))
    return th1, c12 / (l1 * s2), s12 / (l1 * s2)


def pro_hep_lct(p, g, signs=(1.0, 1.0, -1.0), jacobian=False):
    """(t1, w1, q4, q5) from (Xu, Yu, Xd, Yd): the lower chains as two-link chains to Pd
    (chain 1 from the origin, +d/2; chain 2 from (0, lq4d), -d/2), t = tan(theta/2); the
    upper chain q5 = Yu, q4 = q5 - s sqrt(ld4^2 - (Xu - lq5)^2).  ``signs``: the elbow sides
    of the two lower chains and s of the upper one (the working mode)."""
    xu, yu, xd, yd = (p[:, i] for i in range(4))
    th1, d1x, d1y = _two_link(xd, yd - g["d"] / 2, g["l1"], g["l2"], signs[0])
    th3, d3x, d3y = _two_link(xd, yd - g["lq4d"] + g["d"] / 2, g["l3"], g["l4"], signs[1])
    t1, w1 = np.tan(th1 / 2), np.tan(th3 / 2)
    root = np.sqrt(g["ld4"] ** 2 - (xu - g["lq5"]) ** 2)
    q4 = yu - signs[2] * root
    q = np.stack([t1, w1, q4, yu], axis=-1)
    if not jacobian:
        return q
    jac = np.zeros((len(xu), 4, 4))
    h1, h3 = (1 + t1 * t1) / 2, (1 + w1 * w1) / 2  # dt = (1 + t^2)/2 dtheta
    jac[:, 0, 2], jac[:, 0, 3] = h1 * d1x, h1 * d1y
    jac[:, 1, 2], jac[:, 1, 3] = h3 * d3x, h3 * d3y
    jac[:, 2, 0], jac[:, 2, 1] = signs[2] * (xu - g["lq5"]) / root, 1.0
    jac[:, 3, 1] = 1.0
    return q, jac


# ------------------------------------------------------------------ urrh_rcm (002)
def _unit_rows(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def urrh_rcm(p, g, jacobian=False):
    """(alpha1, alpha2, beta1, beta2) from (theta1, theta2, d, gamma) by 002's vector
    geometry: u of the virtual chain (eq. 5, 16), the limb planes (eq. 4: tan alpha1 =
    -u_y/u_z, tan alpha2 = u_x/u_z), the triangles of eq. (12) at the collars d1 = d,
    d2 = d - p gamma (eq. 11) on the physical elbows (beta1 = b11 - b12, beta2 = b22 - b21,
    see the verification of eq. 12); with ``jacobian``, dq/dX as the inverse of eq. (18)'s
    J_q (its two corrections: a12 negated, l_cd,i = u^T r_B - d_i)."""
    t1, t2, d, gm = (p[:, i] for i in range(4))
    s1, c1, s2, c2 = np.sin(t1), np.cos(t1), np.sin(t2), np.cos(t2)
    u = np.stack([-s2, c2 * s1, -c2 * c1], axis=-1)
    a1 = np.arctan(-u[:, 1] / u[:, 2])
    a2 = np.arctan(u[:, 0] / u[:, 2])
    out = [a1, a2]
    for k, di, sign in ((1, d, 1.0), (2, d - g["p"] * gm, -1.0)):
        loa, lab, lbc = g[f"loa{k}"], g[f"lab{k}"], g[f"lbc{k}"]
        # |C - A|^2 with C = d u, A = -loa u_k: d^2 + loa^2 + 2 d loa u_k . u
        ac2 = di * di + loa * loa + 2 * di * loa * u[:, k - 1]
        ac = np.sqrt(ac2)
        b_1 = np.arccos((loa * loa + ac2 - di * di) / (2 * loa * ac))
        b_2 = np.arccos((lab * lab + ac2 - lbc * lbc) / (2 * lab * ac))
        out.append(sign * (b_1 - b_2))
    q = np.stack(out, axis=-1)
    if not jacobian:
        return q
    return q, np.linalg.inv(_urrh_jq(u, q, d, d - g["p"] * gm, g))


def _urrh_jq(u, q, d1, d2, g):
    """002 Sect. 4.3's J_q, vectorized, with the two corrections of the verification."""
    n = len(q)
    x, y = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    ca, sa = np.cos(q[:, :2]), np.sin(q[:, :2])
    n1 = np.stack([np.zeros(n), ca[:, 0], sa[:, 0]], axis=-1)
    n2 = np.stack([ca[:, 1], np.zeros(n), -sa[:, 1]], axis=-1)
    cb, sb = np.cos(q[:, 2:]), np.sin(q[:, 2:])
    # B_i - A_i = l_ab Rx(a1) Ry(b1) x, l_ab Ry(a2) Rx(b2) y
    ab1 = g["lab1"] * np.stack([cb[:, 0], -sa[:, 0] * -sb[:, 0], ca[:, 0] * -sb[:, 0]], -1)
    ab2 = g["lab2"] * np.stack([sa[:, 1] * sb[:, 1], cb[:, 1], ca[:, 1] * sb[:, 1]], -1)
    rb1, rb2 = ab1 - g["loa1"] * x, ab2 - g["loa2"] * y
    cross = np.cross(n2, n1)
    nn = np.linalg.norm(cross, axis=-1)

    def proj(v):  # (I - u u^T) v
        return v - np.sum(u * v, -1, keepdims=True) * u

    a01 = -x[None, :] / np.sqrt(1 - u[:, :1] ** 2)
    a11 = proj(np.cross(n2, np.cross(n1, np.broadcast_to(x, (n, 3))))) / nn[:, None]
    a12 = -proj(np.cross(n1, np.cross(n2, np.broadcast_to(y, (n, 3))))) / nn[:, None]
    dots = [np.sum(u * r, -1) for r in (rb1, rb2)]
    lcd = [dot - di for di, dot in zip((d1, d2), dots)]  # -(the root of the collar)
    a21, a22 = ((1 - dot / lc)[:, None] * r for dot, lc, r in zip(dots, lcd, (rb1, rb2)))
    a31, a32 = ((1 - dot / lc)[:, None] * u + r / lc[:, None]
                for dot, lc, r in zip(dots, lcd, (rb1, rb2)))
    a41, a43 = np.cross(x, ab1), np.cross(n1, ab1)
    a42, a44 = np.cross(y, ab2), np.cross(n2, ab2)

    def dot(a, b):
        return np.sum(a * b, -1)

    p = g["p"]
    j = np.zeros((n, 4, 4))
    j[:, 0, 0] = 1.0
    j[:, 1, 0], j[:, 1, 1] = dot(a01, a11), dot(a01, a12)
    j[:, 2, 0] = dot(a21, a11) + dot(a31, a41)
    j[:, 2, 1], j[:, 2, 2] = dot(a21, a12), dot(a31, a43)
    j[:, 3, 0] = (dot(a21 - a22, a11) + dot(a31, a41)) / p
    j[:, 3, 1] = (dot(a21 - a22, a12) - dot(a32, a42)) / p
    j[:, 3, 2], j[:, 3, 3] = dot(a31, a43) / p, -dot(a32, a44) / p
    return j


def urrh_rcm_fk(q, g):
    """Every pose of (alpha1, alpha2, beta1, beta2) by 002 eq. (6)-(9): u = n1 x n2 (towards
    the collars), theta1 = atan2(u_y, -u_z), theta2 = -asin(u_x), both roots of eq. (8) per
    limb: (..., 4 modes, 4)."""
    a1, a2, b1, b2 = (q[:, i] for i in range(4))
    n1 = np.stack([np.zeros_like(a1), np.cos(a1), np.sin(a1)], -1)
    n2 = np.stack([np.cos(a2), np.zeros_like(a2), -np.sin(a2)], -1)
    u = _unit_rows(np.cross(n1, n2))
    th1, th2 = np.arctan2(u[:, 1], -u[:, 2]), -np.arcsin(u[:, 0])
    rb1 = np.stack([-g["loa1"] + g["lab1"] * np.cos(b1), g["lab1"] * np.sin(a1) * np.sin(b1),
                    -g["lab1"] * np.cos(a1) * np.sin(b1)], -1)
    rb2 = np.stack([g["lab2"] * np.sin(a2) * np.sin(b2), -g["loa2"] + g["lab2"] * np.cos(b2),
                    g["lab2"] * np.cos(a2) * np.sin(b2)], -1)
    roots = []
    for rb, lbc in ((rb1, g["lbc1"]), (rb2, g["lbc2"])):
        along = np.sum(u * rb, -1)
        sq = np.sqrt(lbc * lbc - (np.sum(rb * rb, -1) - along * along))
        roots.append((along + sq, along - sq))
    out = [np.stack([th1, th2, e1, (e1 - e2) / g["p"]], -1)
           for e1 in roots[0] for e2 in roots[1]]
    return np.stack(out, axis=-2)


# ------------------------------------------------------------------ lamina_milling (003)
def lamina_milling(p, g, jacobian=False):
    """(L, theta1, theta2) from H = (x, y, z) by 003 eq. (7)-(8) solved by hand: L = z - dD
    + sqrt(lEC^2 - x^2 - (y - dy2 - dy1 - lDE)^2) (C below E), theta_i = phi -+ alpha_i with
    phi the direction of F = (x, y) and alpha_i the angle at O of the triangle O A F; with
    ``jacobian``, their derivatives."""
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    yo = y - (g["dy2"] + g["dy1"] + g["lDE"])
    r = np.sqrt(g["lEC"] ** 2 - x * x - yo * yo)
    rho2 = x * x + y * y
    rho = np.sqrt(rho2)
    phi = np.arctan2(y, x)
    c1 = (rho2 + g["lOA"] ** 2 - g["lAF"] ** 2) / (2 * g["lOA"] * rho)
    c2 = (rho2 + g["lOB"] ** 2 - g["lBM"] ** 2) / (2 * g["lOB"] * rho)
    a1, a2 = np.arccos(c1), np.arccos(c2)
    q = np.stack([z - g["dD"] + r, phi - a1, phi + a2], axis=-1)
    if not jacobian:
        return q
    # d alpha / d rho = -(dc/d rho) / sin(alpha), dc/d rho = (1 - (a^2 - b^2)/rho^2) / (2a)
    da1 = -(1 - (g["lOA"] ** 2 - g["lAF"] ** 2) / rho2) / (2 * g["lOA"]) / np.sin(a1)
    da2 = -(1 - (g["lOB"] ** 2 - g["lBM"] ** 2) / rho2) / (2 * g["lOB"]) / np.sin(a2)
    dphi = np.stack([-y / rho2, x / rho2], axis=-1)
    drho = np.stack([x / rho, y / rho], axis=-1)
    J = np.zeros((len(p), 3, 3))
    J[:, 0, 0], J[:, 0, 1], J[:, 0, 2] = -x / r, -yo / r, 1.0
    J[:, 1, :2] = dphi - da1[:, None] * drho
    J[:, 2, :2] = dphi + da2[:, None] * drho
    return q, J


def lamina_milling_statics(p, load, g):
    """003's efforts (f, T1, T2) by hand: J^T tau = grad V - F with the weights' potential
    V = (lam G1 + G2) L + ((1 - lam) G1 + G7) z + const (lam = l2 / lEC; the bottom links
    stay at height 0, so G3-G6 do not enter)."""
    _, J = lamina_milling(p, g, jacobian=True)
    lam = g["l2"] / g["lEC"]
    grad = (lam * g["G1"] + g["G2"]) * J[:, 0, :]
    grad[:, 2] += (1 - lam) * g["G1"] + g["G7"]
    return np.linalg.solve(np.swapaxes(J, -1, -2), (grad - load)[..., None])[..., 0]


# ------------------------------------------------------------------ tripod_planar (001)
def tripod_planar(p, ra=200.0, rb=200.0, d=0.0, jacobian=False):
    """001 eq. (10)-(13), (8) and (21)-(23) in the paper's own coordinates p = (x, y, z,
    alpha_p, beta_p, gamma_p): the legs q1..q3 of the 3-RPS tripod, then the planar stage's
    q4..q6.  With ``jacobian``, dq/dp by the chain rule written out: the parasitic yaw phi
    (eq. 10), B's origin (x1, y1) (eq. 11-12) and R depend on (alpha_p, beta_p) only, O2's
    coordinates (x2, y2) in B and z1 (eq. 8) on (x, y, z, alpha_p, beta_p) too."""
    x, y, z, a, b, g = (p[:, i] for i in range(6))
    sa, ca, sb, cb = np.sin(a), np.cos(a), np.sin(b), np.cos(b)
    u, w = sa * sb, ca + cb
    f = np.arctan(u / w)
    sf, cf = np.sin(f), np.cos(f)
    x1 = -rb * cb * sf
    y1 = rb * (ca * cf + sa * sb * sf - cb * cf) / 2
    r00, r01, r02 = cb * cf, sa * sb * cf - ca * sf, ca * sb * cf + sa * sf
    r10, r11, r12 = cb * sf, sa * sb * sf + ca * cf, ca * sb * sf - sa * cf
    r20, r21, r22 = -sb, sa * cb, ca * cb
    # eq. (8) for (x2, y2, z1): 2x2 system in x2, y2, then z1
    ex, ey = x - x1 - d * r02, y - y1 - d * r12
    det = r00 * r11 - r01 * r10
    x2 = (ex * r11 - ey * r01) / det
    y2 = (r00 * ey - r10 * ex) / det
    z1 = z - d * r22 - r20 * x2 - r21 * y2
    corners = [(np.cos(t), np.sin(t)) for t in (-np.pi / 6, np.pi / 2, 7 * np.pi / 6)]
    q = np.empty((len(x), 6))
    legs = []
    for k, (kx, ky) in enumerate(corners):
        bx = x1 + (r00 * kx + r01 * ky) * rb - ra * kx
        by = y1 + (r10 * kx + r11 * ky) * rb - ra * ky
        bz = z1 + (r20 * kx + r21 * ky) * rb
        q[:, k] = np.sqrt(bx * bx + by * by + bz * bz)
        legs.append((bx, by, bz))
    sg, cg = np.sin(g), np.cos(g)
    den = sg + S3 * cg
    inv = 1.0 / den
    m4, n4 = S3 * rb - 2 * x2, rb + 2 * y2
    m5, n5 = S3 * rb + x2 - S3 * y2, rb - S3 * x2 - y2
    m6, n6 = S3 * rb + x2 + S3 * y2, rb + S3 * x2 - y2
    planar = ((m4, n4), (m5, n5), (m6, n6))
    for k, (mk, nk) in enumerate(planar, start=3):
        q[:, k] = (rb + mk * sg + nk * cg) * inv
    if not jacobian:
        return q
    # d/d alpha_p and d/d beta_p of phi, sin/cos phi, x1, y1 and R
    uu = 1.0 / (u * u + w * w)
    fa, fb = (w * ca * sb + u * sa) * uu, (w * sa * cb + u * sb) * uu
    sfa, sfb, cfa, cfb = cf * fa, cf * fb, -sf * fa, -sf * fb
    x1a, x1b = -rb * cb * sfa, rb * sb * sf - rb * cb * sfb
    y1a = rb * (-sa * cf + ca * cfa + ca * sb * sf + sa * sb * sfa - cb * cfa) / 2
    y1b = rb * (ca * cfb + sa * cb * sf + sa * sb * sfb + sb * cf - cb * cfb) / 2
    r00a, r00b = cb * cfa, -sb * cf + cb * cfb
    r01a = ca * sb * cf + sa * sb * cfa + sa * sf - ca * sfa
    r01b = sa * cb * cf + sa * sb * cfb - ca * sfb
    r02a = -sa * sb * cf + ca * sb * cfa + ca * sf + sa * sfa
    r02b = ca * cb * cf + ca * sb * cfb + sa * sfb
    r10a, r10b = cb * sfa, -sb * sf + cb * sfb
    r11a = ca * sb * sf + sa * sb * sfa - sa * cf + ca * cfa
    r11b = sa * cb * sf + sa * sb * sfb + ca * cfb
    r12a = -sa * sb * sf + ca * sb * sfa - ca * cf - sa * cfa
    r12b = ca * cb * sf + ca * sb * sfb - sa * cfb
    r20b = -cb
    r21a, r21b = ca * cb, -sa * sb
    r22a, r22b = -sa * cb, -ca * sb
    # (x2, y2, z1): d/dx, d/dy (ex_x = ey_y = 1), d/dz (z1 only), d/d alpha_p, d/d beta_p
    ida = 1.0 / det
    exa, exb = -x1a - d * r02a, -x1b - d * r02b
    eya, eyb = -y1a - d * r12a, -y1b - d * r12b
    deta = r00a * r11 + r00 * r11a - r01a * r10 - r01 * r10a
    detb = r00b * r11 + r00 * r11b - r01b * r10 - r01 * r10b
    x2x, x2y = r11 * ida, -r01 * ida
    x2a = (exa * r11 + ex * r11a - eya * r01 - ey * r01a - x2 * deta) * ida
    x2b = (exb * r11 + ex * r11b - eyb * r01 - ey * r01b - x2 * detb) * ida
    y2x, y2y = -r10 * ida, r00 * ida
    y2a = (r00a * ey + r00 * eya - r10a * ex - r10 * exa - y2 * deta) * ida
    y2b = (r00b * ey + r00 * eyb - r10b * ex - r10 * exb - y2 * detb) * ida
    z1x, z1y = -r20 * x2x - r21 * y2x, -r20 * x2y - r21 * y2y
    z1a = -d * r22a - r20 * x2a - r21a * y2 - r21 * y2a
    z1b = -d * r22b - r20b * x2 - r20 * x2b - r21b * y2 - r21 * y2b
    jac = np.empty((len(x), 6, 6))
    for k, ((kx, ky), (bx, by, bz)) in enumerate(zip(corners, legs)):
        iq = 1.0 / q[:, k]
        bxa, bxb = x1a + (r00a * kx + r01a * ky) * rb, x1b + (r00b * kx + r01b * ky) * rb
        bya, byb = y1a + (r10a * kx + r11a * ky) * rb, y1b + (r10b * kx + r11b * ky) * rb
        bza, bzb = z1a + r21a * ky * rb, z1b + (r20b * kx + r21b * ky) * rb
        bzq = bz * iq
        jac[:, k, 0], jac[:, k, 1], jac[:, k, 2] = bzq * z1x, bzq * z1y, bzq
        jac[:, k, 3] = (bx * bxa + by * bya + bz * bza) * iq
        jac[:, k, 4] = (bx * bxb + by * byb + bz * bzb) * iq
        jac[:, k, 5] = 0.0
    dden = cg - S3 * sg
    partials = (((-2 * sg), 2 * cg), (sg - S3 * cg, -S3 * sg - cg), (sg + S3 * cg, S3 * sg - cg))
    for k, ((mk, nk), (px, py)) in enumerate(zip(planar, partials), start=3):
        px, py = px * inv, py * inv  # dq/dx2, dq/dy2
        jac[:, k, 0], jac[:, k, 1] = px * x2x + py * y2x, px * x2y + py * y2y
        jac[:, k, 2] = 0.0
        jac[:, k, 3], jac[:, k, 4] = px * x2a + py * y2a, px * x2b + py * y2b
        jac[:, k, 5] = (mk * cg - nk * sg - q[:, k] * dden) * inv
    return q, jac
