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
from ..verification import Verdict, constant_ratio

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


def verify(d, gen, studies) -> list:
    """Verdicts for 000 eq. (5), (9), (10), (16), (17), (21), (24)-(26), (37)-(38), (42)."""
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
    d16 = [sp.simplify(sp.expand_trig(tvec[i] - pr16[i])) for i in range(2)]
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
        diff = sp.simplify(derived - printed_q)
        out.append(Verdict(
            f"000 eq. (5), q{k + 1}", f"planar IK q{k + 1}(x1, y1, gamma1)",
            "confirmed-symbolic" if diff == 0 else "erratum", None,
            f"derived generator solved for q{k + 1} minus the printed form = {sp.sstr(diff)}"))

    # eq. (17), (21): full IK, numerically (the printed forms involve sin/cos and sqrt)
    ik = deriv.ik_expressions()
    printed17, printed21 = _printed_eq17(), _printed_eq21()
    for k, qk in enumerate(JOINTS):
        pr = printed17[k] if k < 3 else printed21[k - 3]
        f_d = sp.lambdify(POSE, ik[qk].subs(geo), "mpmath")
        f_p = sp.lambdify(POSE, pr.subs(geo), "mpmath")
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
    jnum = sp.lambdify(POSE, (jb / ja).subs(q_sub).subs(geo), "mpmath")
    jder = sp.lambdify(POSE, sp.Matrix([ik[q] for q in (q1, q2, q3)]).jacobian(
        sp.Matrix(POSE)).subs(geo), "mpmath")
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
    out.append(Verdict("000 eq. (27)-(34)", "tripod velocity model J_C q' = J_D X'",
                       "not-checkable", None,
                       "eq. (34) uses a11, a12, a21, a22, which the paper never defines, and "
                       "'equation (35)' where (27) is meant; the derived dq/dX is checked "
                       "against finite differences of an independent model instead"))
    return out


def report_sections(d, studies) -> list[str]:
    """What the derived parasitic motion means for 000 eq. (10), (16), (42)."""
    return ["So $\\gamma_2 = 0$, $y_2 = 0$ and $x_2 = -r_b \\sin\\alpha\\sin\\beta$ "
            "(eq. 10). Hence $\\gamma_1 = \\gamma$, and MP1 = MP2 $\\cdot$ conj(MP2 in MP1) "
            "gives eq. (16); the generated module exposes both as \\texttt{mp1\\_pose} and "
            "\\texttt{parasitic\\_motion}."]
