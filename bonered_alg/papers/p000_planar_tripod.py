"""Paper 000 (Essomba & Phu, Mech. & Ind. 21, 403, 2020): its printed equations and the
verdicts of the derivation of ``planar_tripod`` against them (DESIGN.md section 5).

Each ``_printed_*`` function transcribes a printed equation as a reference (layer 1 of
DESIGN.md section 6); :func:`verify` compares the derivation with it, symbolically where the
identity can be proved and numerically (40 random poses, 40-digit mpmath) otherwise.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_symbolic as ss
from ..algebra.polyring import simplified
from ..mechanisms.planar_tripod import (
    JOINTS,
    POSE,
    PX,
    alpha,
    beta,
    g,
    gamma,
    q1,
    q2,
    q3,
    q4,
    q5,
    q6,
    ra,
    rb,
    ta,
    tb,
    tg2,
    v1,
    v2,
    x,
    x2,
    y,
    y2,
    z,
    z2,
)
from ..verification import Verdict, constant_ratio, mpmath_function, noise_bound, rounded
from .planar_stage import output_determinant_with_ik

R = {"real": True}


x1p, y1p, gam1 = sp.symbols("x1 y1 gamma1", **R)
_SQ3 = sp.sqrt(3)


def _printed_eq5():
    """000 eq. (5): (s g1 + sqrt3 c g1) q_k = rhs_k in the MP1 pose (x1, y1, gamma1)."""
    s_, c_ = sp.sin(gam1), sp.cos(gam1)
    return [
        ra + (_SQ3 * ra - 2 * x1p) * s_ + (ra + 2 * y1p) * c_,
        ra + (_SQ3 * ra + x1p - _SQ3 * y1p) * s_ + (ra - _SQ3 * x1p - y1p) * c_,
        ra + (_SQ3 * ra + x1p + _SQ3 * y1p) * s_ + (ra + _SQ3 * x1p - y1p) * c_,
    ], s_ + _SQ3 * c_


def _printed_eq17():
    sa, sb, sgm, cgm = sp.sin(alpha), sp.sin(beta), sp.sin(gamma), sp.cos(gamma)
    den = sgm + _SQ3 * cgm
    return [
        (ra + ra * cgm + 2 * y * cgm - 2 * x * sgm + _SQ3 * ra * sgm) / den,
        (ra + ra * cgm + _SQ3 * ra * sgm - y * cgm + x * sgm - _SQ3 * y * sgm - _SQ3 * x * cgm
         - _SQ3 * rb * sa * sb) / den,
        (ra + ra * cgm + _SQ3 * ra * sgm - y * cgm + x * sgm + _SQ3 * y * sgm + _SQ3 * x * cgm
         + _SQ3 * rb * sa * sb) / den,
    ]


def _printed_eq21():
    sa, ca, sb, cb = sp.sin(alpha), sp.cos(alpha), sp.sin(beta), sp.cos(beta)
    return [
        sp.sqrt((z - rb * sb) ** 2 + (ra - rb * cb + rb * sa * sb) ** 2),
        sp.sqrt((z + rb * sa * cb) ** 2 + (ra - rb * ca) ** 2),
        sp.sqrt((z + rb * sb) ** 2 + (ra - rb * cb - rb * sa * sb) ** 2),
    ]


def _printed_eq26():
    """000 eq. (24)-(26): J_A = (s g + sqrt3 c g) I, J_B (columns x, y, z, alpha, beta, gamma)."""
    sa, ca, sb, cb = sp.sin(alpha), sp.cos(alpha), sp.sin(beta), sp.cos(beta)
    sg_, cg_ = sp.sin(gamma), sp.cos(gamma)
    jb16 = (-ra * sg_ - 2 * y * sg_ - 2 * x * cg_ + _SQ3 * ra * cg_ - q1 * (cg_ - _SQ3 * sg_))
    jb26 = (-ra * sg_ + y * sg_ + x * cg_ - _SQ3 * y * cg_ + _SQ3 * x * sg_ + _SQ3 * ra * cg_
            - q2 * (cg_ - _SQ3 * sg_))
    jb36 = (-ra * sg_ + y * sg_ + x * cg_ + _SQ3 * y * cg_ - _SQ3 * x * sg_ + _SQ3 * ra * cg_
            - q3 * (cg_ - _SQ3 * sg_))
    jb = sp.Matrix([
        [-2 * sg_, 2 * cg_, 0, 0, 0, jb16],
        [sg_ - _SQ3 * cg_, -cg_ - _SQ3 * sg_, 0, -_SQ3 * rb * ca * sb, -_SQ3 * rb * sa * cb, jb26],
        [sg_ + _SQ3 * cg_, -cg_ + _SQ3 * sg_, 0, _SQ3 * rb * ca * sb, _SQ3 * rb * sa * cb, jb36],
    ])
    return (sg_ + _SQ3 * cg_), jb


def _tan_half(expr):
    """Trigonometric functions of alpha, beta, gamma(1) as rational functions of tan-halves."""
    return ss.tan_half_substitution(expr, ((alpha, ta), (beta, tb),
                                           (gamma, sp.Symbol("t_gamma", **R)),
                                           (gam1, sp.Symbol("t_gamma1", **R))))


def _random_poses(n, seed=3):
    import numpy as np

    rng = np.random.default_rng(seed)
    return [dict(zip(POSE, (rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(150, 230),
                            rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3),
                            rng.uniform(-0.8, 0.8)))) for _ in range(n)]


def _printed_tripod_velocity(p, ra_: float, rb_: float) -> dict:
    """The quantities of 000 eq. (27)-(34) at the pose ``p``, from the printed geometry: o1
    of eq. (16), d_k = o2 + R 2d_k (eq. 7, 11, 13), c_k = o1 + Rz 1c_k (eq. 18-19), rho_k and
    the cross products of eq. (28); v1 (eq. 30), omega (Euler rates of eq. 11) and omega1 =
    gamma' z as 3 x 6 maps of X' = (x', y', z', alpha', beta', gamma').

    ``jd`` is the printed J_D of eq. (33)-(34), the undefined a_ij read as the coefficients of
    alpha', beta' in eq. (30): a11 = rb ca sb cg, a12 = rb sa cb cg, a21 = rb ca sb sg,
    a22 = rb sa cb sg.
    """
    import numpy as np

    xx, yy, zz, a, b, gm = (float(p[s]) for s in POSE)
    sa, ca, sb, cb = np.sin(a), np.cos(a), np.sin(b), np.cos(b)
    sg_, cg_ = np.sin(gm), np.cos(gm)
    rz = np.array([[cg_, -sg_, 0], [sg_, cg_, 0], [0, 0, 1.0]])
    rot = rz @ np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]]) @ np.array(
        [[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    o2 = np.array([xx, yy, zz])
    o1 = np.array([xx + rb_ * sa * sb * cg_, yy + rb_ * sa * sb * sg_, 0.0])
    axes = np.array([(1.0, 0, 0), (0, 1.0, 0), (-1.0, 0, 0)])
    a11, a12, a21, a22 = (rb_ * ca * sb * cg_, rb_ * sa * cb * cg_, rb_ * ca * sb * sg_,
                          rb_ * sa * cb * sg_)
    v1 = np.array([[1, 0, 0, a11, a12, -rb_ * sa * sb * sg_],
                   [0, 1, 0, a21, a22, rb_ * sa * sb * cg_], [0, 0, 0, 0, 0, 0]])
    omega = np.zeros((3, 6))
    omega[:, 3:] = [[cg_ * cb, -sg_, 0.0], [sg_ * cb, cg_, 0.0], [-sb, 0.0, 1.0]]
    omega1 = np.zeros((3, 6))
    omega1[2, 5] = 1.0
    rho = np.array([o2 + rot @ (rb_ * e) - o1 - rz @ (ra_ * e) for e in axes])  # eq. (20)
    ck = np.array([np.cross(rz @ (ra_ * e), r_) for e, r_ in zip(axes, rho)])
    dk = np.array([np.cross(rot @ (rb_ * e), r_) for e, r_ in zip(axes, rho)])
    jd = np.zeros((3, 6))
    jd[:, 2] = rho[:, 2]
    jd[:, 3] = (-(rho[:, 0] * a11 + rho[:, 1] * a21) + dk[:, 0] * cg_ * cb + dk[:, 1] * sg_ * cb
                - sb * (dk[:, 2] - ck[:, 2]))
    jd[:, 4] = -(rho[:, 0] * a12 + rho[:, 1] * a22) - dk[:, 0] * sg_ + dk[:, 1] * cg_
    return {"rho": rho, "c": ck, "d": dk, "q": np.linalg.norm(rho, axis=1), "jd": jd,
            "v1": v1, "omega": omega, "omega1": omega1}


def _verify_tripod_velocity(ik, poses, geo) -> list:
    """000 eq. (27)-(35): the tripod's velocity model and the assembled one, each against the
    derivative of the derived IK (40 poses, random velocities)."""
    import numpy as np

    ra_, rb_ = float(geo[ra]), float(geo[rb])
    jac = mpmath_function(POSE, sp.Matrix([ik[q] for q in JOINTS]).jacobian(
        sp.Matrix(POSE)).xreplace(geo))
    ja_s, jb_s = _printed_eq26()
    q17 = dict(zip((q1, q2, q3), _printed_eq17()))
    eq26 = sp.lambdify(POSE, [ja_s.xreplace(geo), jb_s.subs(q17).xreplace(geo)], "numpy")
    rng = np.random.default_rng(11)
    err = dict.fromkeys(("27", "29", "34", "35"), 0.0)
    ckz = 0.0
    for p in poses:
        at = [p[s] for s in POSE]
        jder = np.array(jac(*at).tolist(), dtype=float)
        pv = _printed_tripod_velocity(p, ra_, rb_)
        xdot = rng.uniform(-1, 1, 6)
        o2dot, w, w1, v1 = xdot[:3], pv["omega"] @ xdot, pv["omega1"] @ xdot, pv["v1"] @ xdot
        for k in range(3):
            qdot, qk = float(jder[3 + k] @ xdot), pv["q"][k]
            rho, ck, dk = pv["rho"][k], pv["c"][k], pv["d"][k]
            rhs = rho @ o2dot + dk @ w - rho @ v1 - ck @ w1   # eq. (29); eq. (27) literally
            err["27"] = max(err["27"], abs(rhs / qk - qdot))  # c_k d_k as the unit vector
            err["29"] = max(err["29"], abs(rhs - qk * qdot) / qk)
            ckz = max(ckz, abs(ck[2]))
        err["34"] = max(err["34"], float(np.abs(pv["jd"] / pv["q"][:, None] - jder[3:]).max()))
        ja, jb = eq26(*map(float, at))
        a_full = np.diag([float(ja)] * 3 + list(pv["q"]))
        b_full = np.vstack([np.array(jb, dtype=float), pv["jd"]])
        err["35"] = max(err["35"], float(np.abs(np.linalg.solve(a_full, b_full) - jder).max()))

    def verdict(key):
        return "confirmed-numeric" if err[key] < 1e-9 else "erratum"

    return [
        Verdict("000 eq. (27)", "leg velocity q'_{k+3} of the tripod", verdict("27"),
                noise_bound(err["27"]),
                "printed right side with o1 (eq. 16), v1 (eq. 30), omega from the Euler rates "
                "of eq. (11) and omega1 = gamma' z, at 40 poses and random velocities, vs the "
                "derived dq/dX X'. It holds reading c_k d_k in eq. (27) as the unit vector of "
                "C_k D_k; read as the vector C_k D_k itself (as eq. (28) defines rho_k) the "
                "right side is q_k q'_k, which is eq. (29)"),
        Verdict("000 eq. (28)", "rho_k, c_k, d_k", "not-checkable", None,
                "definitions used by eq. (29)-(34); c_k and d_k also name the joint positions "
                "of eq. (14), (19)"),
        Verdict("000 eq. (29)", "q_k q'_k = rho_k^T o2' + d_k^T omega - rho_k^T v1 - c_k^T "
                "omega1", verdict("29"), noise_bound(err["29"]),
                "at the same poses and velocities, error divided by q_k; the sentence before it "
                "says 'equation (35)' where eq. (27) is meant"),
        Verdict("000 eq. (34)", "J_C^-1 J_D of the tripod (J_C of eq. 32, J_D of eq. 33-34)",
                verdict("34"), noise_bound(err["34"]),
                "a11, a12, a21, a22 are never defined; read as the coefficients of alpha', "
                "beta' in eq. (30) (a11 = rb ca sb cg, a12 = rb sa cb cg, a21 = rb ca sb sg, "
                "a22 = rb sa cb sg), J_C^-1 J_D equals the derivative of the derived q4..q6 at "
                "40 poses. The c_kz in J_Dk4 is zero on the closure (largest |c_kz| "
                f"{noise_bound(ckz, 1e-6)} mm^2): each leg moves in the vertical plane of its "
                "revolute joint, which contains Rz 1c_k"),
        Verdict("000 eq. (35)", "blkdiag(J_A, J_C) q' = [J_B; J_D] X'", verdict("35"),
                noise_bound(err["35"]),
                "the printed blocks (eq. 24-26 with q1..q3 of eq. 17; eq. 32-34 with a_ij as "
                "for eq. 34) solved for q', vs the derived 6 x 6 dq/dX at 40 poses"),
    ]


def _verify_eq30(pr16) -> Verdict:
    """000 eq. (30): v1 is the time derivative of eq. (16) (confirmed against the derivation)."""
    sa, ca, sb, cb = sp.sin(alpha), sp.cos(alpha), sp.sin(beta), sp.cos(beta)
    sgm, cgm = sp.sin(gamma), sp.cos(gamma)
    # the printed "- r_b s(alpha s beta s gamma)" read as - rb s alpha s beta s gamma
    printed = sp.Matrix([[1, 0, 0, rb * ca * sb * cgm, rb * sa * cb * cgm, -rb * sa * sb * sgm],
                         [0, 1, 0, rb * ca * sb * sgm, rb * sa * cb * sgm, rb * sa * sb * cgm]])
    diff = (sp.Matrix(pr16).jacobian(sp.Matrix(POSE)) - printed).applyfunc(sp.simplify)
    return Verdict("000 eq. (30)", "linear velocity v1 of MP1",
                   "confirmed-symbolic" if diff.is_zero_matrix else "erratum", None,
                   "the time derivative of eq. (16), which the derived MP1 position confirms; "
                   "the printed '- r_b s(alpha s beta s gamma)' read as - rb sa sb sg")


def _verify_eq31_33(ik) -> Verdict:
    free = sorted(str(s) for q in (q4, q5, q6) for s in ik[q].free_symbols & {x, y, gamma})
    return Verdict("000 eq. (31)-(33)", "J_C = diag(q4, q5, q6), J_D zero in x', y', gamma'",
                   "confirmed-symbolic" if not free else "erratum", None,
                   "the derived q4, q5, q6 do not depend on x, y, gamma"
                   + (f" (they depend on {free})" if free else "")
                   + ", so the columns 1, 2, 6 of J_D are zero; J_C = diag(q_k) is the left "
                   "side of eq. (29)")


def _tripod_det_crossing(f, lo: float = 5.0, hi: float = 300.0) -> float | None:
    """The smallest z in [lo, hi] where ``f(z)`` changes sign (a 60-point scan, then
    bisection to 1e-9 mm), None if it does not."""
    import numpy as np

    zs = np.linspace(lo, hi, 60)
    vals = [f(z) for z in zs]
    for i in range(59):
        if vals[i] * vals[i + 1] < 0:
            a, b, fa = zs[i], zs[i + 1], vals[i]
            while b - a > 1e-9:
                m = (a + b) / 2
                fm = f(m)
                a, b, fa = (m, b, fm) if fa * fm > 0 else (a, m, fa)
            return float((a + b) / 2)
    return None


def _verify_planar_singularity(deriv, ik, geo) -> list:
    """000 eq. (39)-(41): det B, its printed expansion and its value with eq. (17)."""
    import numpy as np

    # eq. (39): B = [J_B; J_D] of eq. (25), (33) with generic entries
    b_ = {(i, j): sp.Symbol(f"b{i}{j}") for i in range(1, 4) for j in (1, 2, 4, 5, 6)
          if not (i == 1 and j in (4, 5))}
    d_ = {(i, j): sp.Symbol(f"d{i}{j}") for i in range(1, 4) for j in (3, 4, 5)}
    bmat = sp.Matrix(6, 6, lambda r, c: b_.get((r + 1, c + 1), 0) if r < 3
                     else d_.get((r - 2, c + 1), 0))
    det_b = sp.expand(bmat.det(method="laplace"))
    planar = bmat[:3, [0, 1, 5]].det()
    tripod = bmat[3:, [2, 3, 4]].det()
    sign = next((s for s in (1, -1) if sp.expand(det_b - s * planar * tripod) == 0), None)
    printed40 = (b_[1, 1] * (b_[2, 6] * b_[3, 2] - b_[2, 2] * b_[3, 6])
                 + b_[1, 2] * (b_[2, 1] * b_[3, 6] - b_[2, 6] * b_[3, 1])
                 + b_[1, 6] * (b_[2, 2] * b_[3, 1] - b_[2, 1] * b_[3, 2]))
    ok40 = sp.expand(printed40 + planar) == 0
    # the tripod factor vanishes: derived and printed det d(q4..q6)/d(z, alpha, beta)
    jac = mpmath_function(POSE, sp.Matrix([ik[q] for q in (q4, q5, q6)]).jacobian(
        sp.Matrix([z, alpha, beta])).xreplace(geo))
    a0 = 0.2

    def derived_det(zz):
        return float(np.linalg.det(np.array(jac(0, 0, zz, a0, a0, 0).tolist(), dtype=float)))

    def printed_det(zz):
        pv = _printed_tripod_velocity(dict(zip(POSE, (0, 0, zz, a0, a0, 0))),
                                      float(geo[ra]), float(geo[rb]))
        return float(np.linalg.det(pv["jd"][:, 2:5]))

    z_der, z_pr = _tripod_det_crossing(derived_det), _tripod_det_crossing(printed_det)
    found = z_der is not None and z_pr is not None and abs(z_der - z_pr) < 1e-6
    out = [
        Verdict("000 eq. (39)", "det B = 0, B = [J_B; J_D] of eq. (35)",
                "confirmed-symbolic" if sign is not None else "erratum", None,
                "with the zero pattern of eq. (25), (33): det B = "
                f"{'-' if sign == -1 else ''}det J_B[x, y, gamma] det J_D[z, alpha, beta] "
                "(expanded symbolically with generic entries)"),
        Verdict("000 eq. (40)", "det B = 0 written out",
                "erratum" if found or not ok40 else "confirmed-symbolic", None,
                ("the printed expression is -det J_B[x, y, gamma] (cofactor expansion, checked "
                 "symbolically), " if ok40 else "the printed expression is not the cofactor "
                 "expansion of det J_B[x, y, gamma]; it is ")
                + "only the planar factor of det B: the tripod factor "
                "det J_D[z, alpha, beta] (its forward singularity) is left out. It vanishes: at "
                f"x = y = gamma = 0, alpha = beta = {a0} rad, det d(q4, q5, q6)/d(z, alpha, "
                f"beta) of the derived IK changes sign at z = {rounded(z_der or 0, 6)} mm, "
                f"the printed J_D[z, alpha, beta] at z = {rounded(z_pr or 0, 6)} mm "
                "(below the 175 mm of Table 1's leg stroke, so outside the workspace)"),
    ]
    # eq. (41): sum of J_Bk6 with eq. (17); det J_B[x, y, gamma] = 2 sqrt3 sum
    ja, jb = _printed_eq26()
    jb6 = sp.symbols("J_B16 J_B26 J_B36")
    sym = jb.copy()
    for i in range(3):
        sym[i, 5] = jb6[i]
    ok_sum = simplified(sym[:, [0, 1, 5]].det() - 2 * _SQ3 * sum(jb6)) == 0
    q17 = dict(zip((q1, q2, q3), _printed_eq17()))
    got = sp.simplify(sum(jb[i, 5] for i in range(3)).subs(q17))
    th = gamma + sp.pi / 3
    correct = 3 * ra * (1 - sp.cos(th)) / sp.sin(th)
    printed41 = (1 - sp.cos(th)) / sp.sin(th)
    ok_correct = simplified(sp.expand_trig(got - correct)) == 0
    ok41 = sp.simplify(sp.expand_trig(got - printed41)) == 0
    fwd, fwd_roots = output_determinant_with_ik(deriv, "det_Jo_MP1", (q1, q2, q3), g)
    out.append(Verdict(
        "000 eq. (41)", "J_B16 + J_B26 + J_B36 with eq. (17) inserted",
        "confirmed-symbolic" if ok41 else "erratum", None,
        ("det J_B[x, y, gamma] = 2 sqrt3 (J_B16 + J_B26 + J_B36) (the rows of J_B's columns "
         "x, y sum to zero; checked symbolically). " if ok_sum else "")
        + f"With eq. (17) inserted the sum is {sp.sstr(got)}"
        + (" = 3 ra (1 - c(gamma + pi/3))/s(gamma + pi/3)" if ok_correct else "")
        + ", the printed right side without the factor 3 ra; the conclusion stands: it is "
        "3 ra tan((gamma + pi/3)/2), zero only at gamma = -pi/3 + 2 m pi, where J_A is "
        "singular too (eq. 38). The derived output Jacobian of the planar closure (Study "
        f"coordinates) with the derived IK inserted factors as {sp.sstr(fwd)}, vanishing only "
        f"at gamma in {fwd_roots}"))
    return out


def verify(d, gen, studies) -> list:
    """Verdicts for 000 eq. (5), (9), (10), (16), (17), (21), (24)-(35), (37)-(42)."""
    import mpmath

    with mpmath.workdps(40):  # independent of the caller's mpmath precision: deterministic
        return _verify(d)


def _verify(deriv) -> list:
    import numpy as np


    out: list[Verdict] = []
    geo = {ra: 190, rb: 190}
    cs = deriv.constants
    poses = _random_poses(40)

    # eq. (10): parasitic motion
    par = deriv.analyses["parasitic"].solved
    sa2, sb2 = 2 * ta / (1 + ta**2), 2 * tb / (1 + tb**2)
    printed = {tg2: 0, x2: -rb * sa2 * sb2, y2: 0}
    diffs = {str(k): sp.simplify(par.get(k, sp.nan) - v) for k, v in printed.items()}
    ok10 = all(v == 0 for v in diffs.values())
    out.append(Verdict(
        "000 eq. (10)", "parasitic motion of the tripod: gamma2, x2, y2",
        "confirmed-symbolic" if ok10 else "erratum", None,
        "lex basis of the revolute-plane conditions with MP2 = T(x2,y2,z2)Rz(g2)Ry(b)Rx(a): "
        + ", ".join(f"{k} = {sp.sstr(v)}" for k, v in par.items())
        + " (tan-half-angles), i.e. gamma2 = 0, y2 = 0, x2 = -rb sin(alpha) sin(beta)"))

    # eq. (9): the q-free generators are the plane conditions d1y = d2x = d3y = 0
    euler = ss.product(ss.translation_vector((x2, y2, z2)), ss.rotation("z", tg2),
                       ss.rotation("y", tb), ss.rotation("x", ta))
    m = ss.transform_from_study(euler)
    d_pts = {"T1": (rb, 0, 0), "T2": (0, rb, 0), "T3": (-rb, 0, 0)}
    comp = {"T1": 1, "T2": 0, "T3": 1}
    sub = {s: euler[i + 1] / euler[0] for i, s in enumerate(PX)}
    ok9 = True
    for r in (r for r in deriv.legs if r.closure.point == "MP2"):
        dk = m[:3, :3] * sp.Matrix(d_pts[r.leg.name]) + m[:3, 3]
        plane = [gen for gen in r.result.generators
                 if not gen.free_symbols & set(JOINTS) and sp.Poly(gen, *PX).total_degree() == 2
                 and gen.has(rb)]
        target = sp.together(dk[comp[r.leg.name]])
        ok9 &= any(sp.simplify(sp.together(gen.subs(sub)) / target).free_symbols
                   <= {ta, tb, tg2} for gen in plane)
    out.append(Verdict(
        "000 eq. (9)", "revolute-joint constraints d1y = d2x = d3y = 0",
        "confirmed-symbolic" if ok9 else "erratum", None,
        "each tripod leg ideal contains a generator free of the leg length that equals the "
        "printed coordinate of D_k times a non-vanishing factor of the rotation"))

    # eq. (16) and (42): MP1 position and the parasitic motion seen from the base
    p2s = deriv.pose_to_study
    gq, w1, w2 = (p2s[s] for s in (g, v1, v2))
    tvec = [sp.simplify(c / (1 + gq**2)) for c in
            cv.translation_times_norm(
                (1, 0, 0, gq, 0, w1, w2, 0))]
    sa, sb, sgm, cgm = sp.sin(alpha), sp.sin(beta), sp.sin(gamma), sp.cos(gamma)
    pr16 = [x + rb * sa * sb * cgm, y + rb * sa * sb * sgm]
    d16 = [simplified(sp.expand_trig(tvec[i] - pr16[i])) for i in range(2)]
    ok16 = all(v == 0 for v in d16)
    out.append(Verdict("000 eq. (16)", "MP1 position compensating the parasitic motion",
                       "confirmed-symbolic" if ok16 else "erratum", None,
                       f"MP1 = MP2 conj(MP2 in MP1): x1 - printed = {sp.sstr(d16[0])}, "
                       f"y1 - printed = {sp.sstr(d16[1])}; gamma1 = gamma "
                       f"({sp.sstr(gq)} = tan(gamma1/2))"))
    out.append(Verdict("000 eq. (42)", "parasitic motion projected on {Oxyz}",
                       "confirmed-symbolic" if ok16 and ok10 else "erratum", None,
                       "x_par = -rb sa sb cg, y_par = -rb sa sb sg is Rz(gamma) (x2, y2) with "
                       "the derived x2, y2 (eq. 10), i.e. minus the compensation of eq. (16)"))

    # eq. (5): planar IK in the MP1 pose
    rhs, lhs = _printed_eq5()
    tg1 = sp.Symbol("t_gamma1", **R)
    mp1 = {g: tg1, v1: -(x1p + tg1 * y1p) / 2, v2: -(y1p - tg1 * x1p) / 2}
    for k, qk in enumerate((q1, q2, q3)):
        st = next(s for s in deriv.steps if s.joint == qk)
        derived = sp.cancel((-st.C / st.B).subs(cs).subs(mp1))
        printed_q = sp.cancel(_tan_half(rhs[k] / lhs))
        diff = simplified(derived - printed_q)
        out.append(Verdict(
            f"000 eq. (5), q{k + 1}", f"planar IK q{k + 1}(x1, y1, gamma1)",
            "confirmed-symbolic" if diff == 0 else "erratum", None,
            f"derived generator solved for q{k + 1} minus the printed form = {sp.sstr(diff)}"))

    # eq. (17), (21): full IK, numerically (the printed forms involve sin/cos and sqrt)
    ik = deriv.ik_expressions()
    printed17, printed21 = _printed_eq17(), _printed_eq21()
    for k, qk in enumerate(JOINTS):
        pr = printed17[k] if k < 3 else printed21[k - 3]
        f_d = mpmath_function(POSE, ik[qk].xreplace(geo))
        f_p = mpmath_function(POSE, pr.xreplace(geo))
        errs = [abs(float(f_d(*[p[s] for s in POSE])) - float(f_p(*[p[s] for s in POSE])))
                for p in poses]
        err = max(errs)
        ref = f"000 eq. ({17 if k < 3 else 21}), q{k + 1}"
        out.append(Verdict(ref, f"IK of q{k + 1} in the pose (x, y, z, alpha, beta, gamma)",
                           "confirmed-numeric" if err < 1e-9 else "erratum", float(f"{err:.2e}"),
                           "derived IK vs printed formula at 40 random poses "
                           "(|x|,|y| < 40 mm, z in [150, 230] mm, |alpha|,|beta| < 0.3, "
                           "|gamma| < 0.8 rad; ra = rb = 190 mm)"))

    # eq. (24)-(26): J_A^-1 J_B against the derived dq/dX for q1..q3
    ja, jb = _printed_eq26()
    q_sub = {q1: ik[q1], q2: ik[q2], q3: ik[q3]}
    jnum = mpmath_function(POSE, (jb / ja).subs(q_sub).xreplace(geo))
    jder = mpmath_function(POSE, sp.Matrix([ik[q] for q in (q1, q2, q3)]).jacobian(
        sp.Matrix(POSE)).xreplace(geo))
    err26 = 0.0
    worst_entry = None
    for p in poses:
        a = np.array(jnum(*[p[s] for s in POSE]).tolist(), dtype=float)
        b = np.array(jder(*[p[s] for s in POSE]).tolist(), dtype=float)
        e = np.abs(a - b)
        if e.max() > err26:
            err26, worst_entry = float(e.max()), np.unravel_index(np.argmax(e), e.shape)
    cols = ["x", "y", "z", "alpha", "beta", "gamma"]
    out.append(Verdict(
        "000 eq. (24)-(26)", "planar velocity model J_A q' = J_B X'",
        "confirmed-numeric" if err26 < 1e-9 else "erratum", float(f"{err26:.2e}"),
        "J_A^-1 J_B (q1..q3 from the derived IK) vs the derivative of the derived IK at 40 "
        "poses" + ("" if err26 < 1e-9 else
                   f"; largest difference in row q{worst_entry[0] + 1}, column "
                   f"{cols[worst_entry[1]]}")))
    velocity = _verify_tripod_velocity(ik, poses, geo)  # eq. (27)-(29), (34), (35)
    out.extend([*velocity[:3], _verify_eq30(pr16), _verify_eq31_33(ik), *velocity[3:]])

    # eq. (37)-(38): det A of the planar part
    det_p = next(s for s in deriv.singularities if s.name == "det_Ji_MP1")
    roots = set()
    for f, _ in det_p.factors:
        f = sp.expand(f.subs(cs))
        if f.free_symbols == {g}:
            roots |= {sp.nsimplify(2 * sp.atan(r)) for r in sp.solve(f, g)}
    ok38 = roots == {2 * sp.pi / 3, -sp.pi / 3}
    out.append(Verdict(
        "000 eq. (37)-(38)", "planar input singularity det A = 0",
        "confirmed-symbolic" if ok38 else "erratum", None,
        "derived det Ji of the planar closure = "
        f"{sp.sstr(sp.factor(det_p.expression.subs(cs), extension=sp.sqrt(3)))}"
        f"; its roots in g = tan(gamma1/2) give gamma1 in {sorted(map(str, roots))}"))
    out.extend(_verify_planar_singularity(deriv, ik, geo))
    det_t = next(s for s in deriv.singularities if s.name == "det_Ji_MP2")
    lead = sp.factor(det_t.expression)
    ok37 = constant_ratio(det_t.expression, q4 * q5 * q6 * (1 + PX[0] ** 2) * (1 + PX[1] ** 2)**2)
    out.append(Verdict(
        "000 eq. (37)", "tripod factor L4 L5 L6 of det A",
        "confirmed-symbolic" if ok37 is not None else "erratum", None,
        f"derived det Ji of the tripod = {sp.sstr(lead)}: the leg lengths q4 q5 q6 times "
        "factors 1 + x_i^2 that never vanish"))

    # inputs of the derivation
    for ref, what in [("000 eq. (1)", "active prismatic joints R_k on the base edges"),
                      ("000 eq. (2)", "passive prismatic joints R'_k on the MP1 edges"),
                      ("000 eq. (7), (18)", "D_k and C_k of the tripod"),
                      ("000 eq. (6), (11)", "R = Rz Ry Rx")]:
        out.append(Verdict(ref, what, "not-checkable", None, "input of the derivation"))
    return out


def report_sections(d, studies) -> list[str]:
    """What the derived parasitic motion means for 000 eq. (10), (16), (42)."""
    return ["So $\\gamma_2 = 0$, $y_2 = 0$ and $x_2 = -r_b \\sin\\alpha\\sin\\beta$ "
            "(eq. 10). Hence $\\gamma_1 = \\gamma$, and MP1 = MP2 $\\cdot$ conj(MP2 in MP1) "
            "gives eq. (16); the generated module exposes both as \\texttt{mp1\\_pose} and "
            "\\texttt{parasitic\\_motion}."]
