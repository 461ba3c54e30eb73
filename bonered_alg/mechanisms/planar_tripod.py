"""Hybrid planar-tripod mechanism (paper 000: Essomba & Phu, Mech. & Ind. 21, 403, 2020).

A 3-PRP double-triangular planar mechanism (base -> mobile platform MP1) carries a 3-RPS
tripod with an isosceles leg layout (MP1 -> end effector MP2); 6 DoF.  Frames, dimensions and
the angle convention are the paper's (Sect. 2-3): pose ``(x, y, z, alpha, beta, gamma)`` of
O2 in {Oxyz} with ``R = Rz(gamma) Ry(beta) Rx(alpha)`` (eq. 11), angles in radians.

Encoding (all factors are elementary Study points, see the report's tables):

* planar leg k: ``T(A_k) Rz(phi_k) Tx(q_k) Rz(-phi_k)`` (active prismatic along the base edge,
  eq. 1), ``Rz(u_k)`` (passive revolute), then back along the MP1 edge by the passive stroke
  ``l_k`` (eq. 2) and ``T(-B_k)`` to O1.  The 120-degree layout needs ``sqrt(3)``, carried as
  the algebraic constant ``s3`` with ``s3^2 = 3``.
* tripod leg k (eq. 13, 18): ``T(C_k) R(u_k) T(-q_k)`` along the leg in the plane of its
  revolute joint, a spherical joint (Euler parameters), ``T(-d_k)`` back to O2 (eq. 7).
* MP1 is a planar pose ``[1:0:0:g:0:v1:v2:0]`` (``g = tan(gamma1/2)``); MP2 relative to MP1 is
  a general Study point in the chart ``x0 = 1``.

Reading of the source text:

* 000 eq. (2) places the MP1 corners at B1 = (sqrt(3)/2 ra, ra/2), B2 = (-sqrt(3)/2 ra, ra/2),
  B3 = (0, -ra), and the passive prismatic joints R'_k on the edges B1B2, B2B3, B3B1; the text
  calls MP1 "the same size as A1A2A3", so its circumradius is ra.
* The tripod parameters of 000 Table 1 (ra = rb = 190 mm, strokes 175-250 mm, revolute
  joints +-45 deg, spherical joints +-20 deg) are used; the planar strokes are not given.
* Eq. (17) reads "substituting equation (16) into equation (6)"; equation (5) is meant.
"""

from __future__ import annotations

import networkx as nx
import sympy as sp

from ..algebra import study_symbolic as ss
from ..chains.double_triangle import prp_legs
from ..chains.joints import Role
from ..chains.mechanism import Closure, Constant, Mechanism, Parameter, joint, leg

NAME = "planar_tripod"
SOURCE = ("000_c0528de5aff00fc3.txt (Essomba & Phu, Mech. & Ind. 21, 403, 2020), "
          "Sect. 2-3, 5")

R = {"real": True}
ra, rb = sp.symbols("ra rb", **R)
s3 = sp.Symbol("s3", positive=True)
q1, q2, q3, q4, q5, q6 = sp.symbols("q1:7", **R)
u1, u2, u3, l1, l2, l3 = sp.symbols("u1 u2 u3 l1 l2 l3", **R)
u4, u5, u6 = sp.symbols("u4 u5 u6", **R)
S1 = sp.symbols("e10:14", **R)
S2 = sp.symbols("e20:24", **R)
S3 = sp.symbols("e30:34", **R)
# closure pose symbols: MP1 in {O} (planar) and MP2 in {O1} (chart x0 = 1)
g, v1, v2 = sp.symbols("g v1 v2", **R)
PX = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", **R)

PARAMETERS: dict[str, Parameter] = {
    "ra": Parameter("ra", 190.0, "mm", "circumradius of A1A2A3, B1B2B3 and of the tripod "
                    "base C1C2C3", "000 Table 1"),
    "rb": Parameter("rb", 190.0, "mm", "circumradius of D1D2D3 (MP2)", "000 Table 1"),
}
LIMITS = {  # 000 Table 1
    "q_tripod": (175.0, 250.0),
    "revolute_deg": (-45.0, 45.0),
    "spherical_deg": (-20.0, 20.0),
}

x, y, z, alpha, beta, gamma = sp.symbols("x y z alpha beta gamma", **R)
POSE = (x, y, z, alpha, beta, gamma)
POSE_UNITS = ("mm", "mm", "mm", "rad", "rad", "rad")
JOINTS = (q1, q2, q3, q4, q5, q6)
JOINT_UNITS = ("mm",) * 6
POSE_TO_STUDY_SOURCE = ("R = Rz(gamma) Ry(beta) Rx(alpha), 000 eq. 11; MP2 relative to MP1 from "
                        "the parasitic motion derived below; MP1 = MP2 * conj(MP2 in MP1)")

# MP1 in the base (the planar closure's point) and the pose of MP2 from both closures' Study
# coordinates: MP2 = MP1 * (MP2 in MP1)
MP1_STUDY = (1, 0, 0, g, 0, v1, v2, 0)
STUDY_TO_POSE = dict(zip(POSE, ss.pose_from_study(ss.product(MP1_STUDY, (1, *PX)))))

SQRT3 = Constant(s3, s3**2 - 3, sp.sqrt(3), "sqrt(3) of the equilateral layouts (eq. 1-2)")


def _planar_legs(name: str = NAME):
    return prp_legs(name, ra, s3, (q1, q2, q3), (u1, u2, u3), (l1, l2, l3))


def _tripod_legs(name: str = NAME):
    A, P = Role.ACTIVE, Role.PASSIVE
    spec = [  # C_k (eq. 18), revolute axis, leg direction and sign, D_k (eq. 7), sphere
        ("T1", "x", ra, "y", u4, "x", -q4, "x", -rb, S1),
        ("T2", "y", ra, "x", u5, "y", -q5, "y", -rb, S2),
        ("T3", "x", -ra, "y", u6, "x", q6, "x", rb, S3),
    ]
    legs = []
    for lab, c_ax, c_val, r_ax, uk, p_ax, p_val, d_ax, d_val, sph in spec:
        qk = p_val if p_val.is_Symbol else -p_val
        legs.append(leg(
            lab,
            joint(name, "offset", f"{lab}.C", axis=c_ax, value=c_val,
                  description="revolute joint C_k on MP1 (eq. 18)"),
            joint(name, "revolute", f"{lab}.R", r_ax, uk, P,
                  "passive revolute: the leg turns in its plane (eq. 9)"),
            joint(name, "prismatic", f"{lab}.q", p_ax, p_val, A,
                  f"active leg length {qk} (eq. 13)"),
            joint(name, "spherical", f"{lab}.S", sph, P, "passive spherical joint D_k"),
            joint(name, "offset", f"{lab}.D", axis=d_ax, value=d_val,
                  description="from D_k to O2 (eq. 7)"),
        ))
    return legs


def _topology() -> nx.MultiGraph:
    gr = nx.MultiGraph()
    for k in (1, 2, 3):
        gr.add_edge("base", f"slider{k}", joint="prismatic", label=f"q{k}", subsystem="planar")
        gr.add_edge(f"slider{k}", f"rider{k}", joint="revolute", label=f"R{k}",
                    subsystem="planar")
        gr.add_edge(f"rider{k}", "MP1", joint="prismatic", label=f"l{k}", subsystem="planar")
        gr.add_edge("MP1", f"leg{k}", joint="revolute", label=f"C{k}", subsystem="tripod")
        gr.add_edge(f"leg{k}", f"rod{k}", joint="prismatic", label=f"q{k + 3}",
                    subsystem="tripod")
        gr.add_edge(f"rod{k}", "MP2", joint="spherical", label=f"D{k}", subsystem="tripod")
    return gr


def build() -> Mechanism:
    planar = Closure("planar 3-PRP mechanism", "MP1", tuple(_planar_legs()), MP1_STUDY,
                     (g, v1, v2),
                     note="MP1 moves in the base plane: a rotation g = tan(gamma1/2) about z "
                          "and a translation (x1, y1), v1 = -(x1 + g y1)/2, "
                          "v2 = -(y1 - g x1)/2.")
    tripod = Closure("3-RPS tripod", "MP2", tuple(_tripod_legs()), (1, *PX), PX,
                     note="MP2 relative to MP1 in the chart x0 = 1 (no half-turns).")
    passive = (u1, u2, u3, l1, l2, l3, u4, u5, u6, *S1, *S2, *S3)
    return Mechanism(
        name=NAME, title="Hybrid planar-tripod mechanism (3-PRP + 3-RPS)", source=SOURCE,
        parameters=dict(PARAMETERS), active=JOINTS, passive=passive,
        closures=(planar, tripod), topology=_topology(), constants=(SQRT3,),
        subsystem_lambda={"planar": 3, "tripod": 6},
    )


# ------------------------------------------------------------------ analyses and pose map
ta, tb, tg2, x2, y2, z2 = sp.symbols("t_alpha t_beta t_gamma2 x2 y2 z2", **R)


def analyses(deriv, engine, budget_s, use_cache) -> dict:
    """Parasitic motion of the tripod (000 eq. 10), derived by elimination.

    The constraint generators of the tripod legs that do not contain the leg lengths are
    the revolute-plane conditions (eq. 9).  Writing MP2 in MP1 as
    ``T(x2, y2, z2) Rz(gamma2) Ry(beta) Rx(alpha)`` (tan-half-angles) and computing the lex
    basis over Q(t_alpha, t_beta, z2, rb, ra) in (t_gamma2, x2, y2) gives the parasitic
    components as functions of the three free coordinates.
    """
    from ..elimination.cache import lex_basis
    from ..elimination.problem import ParametricProblem

    tripod = [r for r in deriv.legs if r.closure.point == "MP2"]
    free = []
    for r in tripod:
        free += [gen for gen in r.result.generators
                 if not gen.free_symbols & set(JOINTS)]
    euler = ss.product(ss.translation_vector((x2, y2, z2)), ss.rotation("z", tg2),
                       ss.rotation("y", tb), ss.rotation("x", ta))
    sub = {s: euler[i + 1] / euler[0] for i, s in enumerate(PX)}
    eqs = []
    for gen in free:
        num, _ = sp.fraction(sp.together(gen.subs(sub)))
        if sp.expand(num) != 0:
            eqs.append(sp.expand(num))
    eqs = list(dict.fromkeys(eqs))
    problem = ParametricProblem(f"mechanism {NAME!r}: parasitic motion of the tripod",
                                tuple(eqs), (tg2, x2, y2), (ta, tb, z2, rb, ra))
    result = lex_basis(problem, engine, budget_s, use_cache)
    solved = {}
    for gen in result.generators:
        unknown = [u for u in (tg2, x2, y2) if gen.has(u)]
        if len(unknown) == 1 and sp.degree(gen, unknown[0]) == 1:
            solved[unknown[0]] = sp.factor(sp.solve(gen, unknown[0])[0])
    return {"parasitic_problem": problem, "parasitic_basis": result, "parasitic": solved,
            "plane_conditions": free}


def pose_to_study(deriv) -> dict:
    """Study coordinates of MP1 (planar) and of MP2 in MP1 from the pose (x..gamma).

    MP2 in MP1 = T(x2, y2, z) Rz(gamma2) Ry(beta) Rx(alpha) with the derived parasitic
    (x2, y2, gamma2); MP1 = MP2 * conj(MP2 in MP1)."""
    par = deriv.extra["parasitic"]
    t_g = sp.Symbol("t_gamma", **R)
    fill = {z2: z}
    xp, yp, gp = (sp.sympify(par[v]).subs(fill) for v in (x2, y2, tg2))
    p2 = ss.product(ss.translation_vector((xp, yp, z)), ss.rotation("z", gp),
                    ss.rotation("y", tb), ss.rotation("x", ta))
    world = ss.product(ss.translation_vector((x, y, z)), ss.rotation("z", t_g),
                       ss.rotation("y", tb), ss.rotation("x", ta))
    p1 = ss.product(world, ss.conjugate(p2))
    # rational in the tan-half-angles: the generated code evaluates three tangents only
    halves = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), t_g: sp.tan(gamma / 2)}
    out = {}
    for sym, num, den in [(g, p1[3], p1[0]), (v1, p1[5], p1[0]), (v2, p1[6], p1[0])]:
        out[sym] = sp.factor(sp.cancel(num / den)).subs(halves)
    for i, s_ in enumerate(PX):
        out[s_] = sp.factor(sp.cancel(p2[i + 1] / p2[0])).subs(halves)
    return out


# ------------------------------------------------------------------ printed results of 000
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


def verify(deriv) -> list:
    """Verdicts for 000 eq. (5), (9), (10), (16), (17), (21), (24)-(26), (37)-(38), (42)."""
    import mpmath

    with mpmath.workdps(40):  # independent of the caller's mpmath precision: deterministic
        return _verify(deriv)


def _verify(deriv) -> list:
    import numpy as np

    from ..verification import Verdict, constant_ratio

    out: list[Verdict] = []
    geo = {ra: 190, rb: 190}
    cs = deriv.constants
    poses = _random_poses(40)

    # eq. (10): parasitic motion
    par = deriv.extra["parasitic"]
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
            __import__("bonered_alg.algebra.convention", fromlist=["x"]).translation_times_norm(
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


def limits(deriv) -> list[tuple]:
    """Table 1 of 000: strokes 175-250 mm (read as applying to all six actuators: the table
    gives one range for "q" and the home pose has q1 = q2 = q3 = 2 ra / sqrt(3) = 219 mm),
    revolute joints +-45 deg and spherical joints +-20 deg (eq. 45-46: the angle of each leg
    to the MP1 normal, and to the MP2 normal)."""
    par = deriv.extra["parasitic"]
    fill = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), z2: z}
    xp, yp, gp = (sp.sympify(par[v]).subs(fill) for v in (x2, y2, tg2))
    rot2 = sp.rot_axis3(-2 * sp.atan(gp)) * sp.rot_axis2(-beta) * sp.rot_axis1(-alpha)
    t2 = sp.Matrix([xp, yp, z])
    normal2 = rot2 * sp.Matrix([0, 0, 1])
    c_pts = [(ra, 0, 0), (0, ra, 0), (-ra, 0, 0)]
    d_pts = [(rb, 0, 0), (0, rb, 0), (-rb, 0, 0)]
    lo, hi = LIMITS["q_tripod"]
    out = [(f"q{k}", q, lo, hi, "stroke", "mm", "000 Table 1 (q_min, q_max)")
           for k, q in enumerate(JOINTS, 1)]
    r_lo, r_hi = (sp.rad(v) for v in LIMITS["revolute_deg"])
    s_lo, s_hi = (sp.rad(v) for v in LIMITS["spherical_deg"])
    for k in range(3):
        leg_vec = t2 + rot2 * sp.Matrix(d_pts[k]) - sp.Matrix(c_pts[k])
        length = sp.sqrt(leg_vec.dot(leg_vec))
        out.append((f"phi_r{k + 1}", sp.acos(leg_vec[2] / length), r_lo, r_hi, "passive",
                    "rad", "000 eq. (45)-(46), Table 1: revolute joint C_k"))
        out.append((f"phi_s{k + 1}", sp.acos(normal2.dot(leg_vec) / length), s_lo, s_hi,
                    "passive", "rad", "000 eq. (45)-(46), Table 1: spherical joint D_k"))
    return out


# ------------------------------------------------------------------ generated extras
def pose_functions(deriv) -> list[tuple]:
    """``mp1_pose`` (x1, y1, gamma1 of MP1, 000 eq. 16) and ``parasitic_motion`` (x_par,
    y_par of O2 in {Oxyz} caused by the tripod, 000 eq. 42), both from the derivation."""
    from ..algebra import convention as cv

    p2s = deriv.pose_to_study
    gq, w1, w2 = (p2s[s] for s in (g, v1, v2))
    tvec = cv.translation_times_norm((1, 0, 0, gq, 0, w1, w2, 0))
    x1e, y1e = (sp.simplify(c / (1 + gq**2)) for c in tvec[:2])
    par = deriv.extra["parasitic"]
    fill = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), z2: z}
    xp, yp = (sp.sympify(par[v]).subs(fill) for v in (x2, y2))
    rz = sp.rot_axis3(-gamma)[:2, :2]
    xpar, ypar = (rz * sp.Matrix([xp, yp]))
    return [
        ("mp1_pose", ("x1", "y1", "gamma1"), [x1e, y1e, 2 * sp.atan(gq)],
         "Pose of MP1 in {Oxyz} that compensates the tripod's parasitic motion (000 eq. 16)."),
        ("parasitic_motion", ("x_par", "y_par"), [sp.simplify(xpar), sp.simplify(ypar)],
         "Parasitic displacement of O2 generated by the tripod, in {Oxyz} (000 eq. 42)."),
    ]


# 000 eq. (43)-(44) give z(t) near 0, where the tripod legs would have zero length; the
# paper's z must be measured from a home height it does not state.  We add the mid-stroke
# height of Table 1, z0 = (175 + 250) / 2 mm (at alpha = beta = 0 the legs have length z).
Z_HOME = 212.5


def trajectory_eq43(t):
    """000 eq. (43): pure rotation, parasitic compensation test (Fig. 6), z about Z_HOME."""
    import numpy as np

    zero = np.zeros_like(t)
    pose = np.stack([zero, zero, zero + Z_HOME, np.pi / 12 * np.sin(t), np.pi / 15 * np.sin(t),
                     np.pi / 6 * np.cos(2 * t)], axis=-1)
    rate = np.stack([zero, zero, zero, np.pi / 12 * np.cos(t), np.pi / 15 * np.cos(t),
                     -np.pi / 3 * np.sin(2 * t)], axis=-1)
    return pose, rate


def trajectory_eq44(t):
    """000 eq. (44): the 6-DoF test trajectory (Figs. 7-8), z about Z_HOME."""
    import numpy as np

    pose = np.stack([20 * np.sin(t), 20 * np.sin(t), Z_HOME + 50 * np.cos(2 * t),
                     2 * np.pi / 45 * np.sin(t), np.pi / 18 * np.sin(t),
                     np.pi / 12 * np.cos(2 * t)], axis=-1)
    rate = np.stack([20 * np.cos(t), 20 * np.cos(t), -100 * np.sin(2 * t),
                     2 * np.pi / 45 * np.cos(t), np.pi / 18 * np.cos(t),
                     -np.pi / 6 * np.sin(2 * t)], axis=-1)
    return pose, rate


def _csv(header, rows) -> str:
    lines = [",".join(header)]
    lines += [",".join(f"{v:.10g}" for v in row) for row in rows]
    return "\n".join(lines) + "\n"


def artifacts(deriv, gen) -> dict:
    """Trajectories of 000 eq. (43) and (44) through the generated IK and Jacobian: joint
    positions and velocities (q' = J X') over t in [0, 2 pi], as CSV and PNG, with z offset
    by Z_HOME.  Limits are not applied (``limits=False``) so the curves are complete; the
    CSV has a column ``within_limits`` from the generated ``ik_status``."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    t = np.linspace(0.0, 2 * np.pi, 361)
    out = {}
    for label, traj in (("eq43", trajectory_eq43), ("eq44", trajectory_eq44)):
        pose, rate = traj(t)
        q = gen.ik(pose, limits=False)
        jac = gen.jacobian(pose, limits=False)
        qdot = np.einsum("nij,nj->ni", jac, rate)
        par = gen.parasitic_motion(pose)
        mp1 = gen.mp1_pose(pose)
        inside = (gen.ik_status(pose) == gen.OK).astype(float)
        header = (["t"] + [str(s) for s in POSE] + [f"q{k}" for k in range(1, 7)]
                  + [f"q{k}dot" for k in range(1, 7)] + ["x_par", "y_par", "x1", "y1",
                                                         "gamma1", "within_limits"])
        rows = np.column_stack([t, pose, q, qdot, par, mp1, inside])
        out[f"{NAME}.trajectory_{label}.csv"] = _csv(header, rows)
        fig, axes = plt.subplots(1, 3 if label == "eq43" else 2, figsize=(11, 3.4))
        for k in range(6):
            axes[0].plot(t, q[:, k], label=f"q{k + 1}")
            axes[1].plot(t, qdot[:, k], label=f"q{k + 1}'")
        axes[0].set(xlabel="t", ylabel="joint position (mm)")
        axes[1].set(xlabel="t", ylabel="joint velocity (mm per unit t)")
        axes[0].legend(fontsize=7, ncol=2)
        if label == "eq43":
            axes[2].plot(t, par[:, 0], label="x_par (eq. 42)")
            axes[2].plot(t, par[:, 1], label="y_par (eq. 42)")
            axes[2].plot(t, mp1[:, 0], "--", label="MP1 x1 (eq. 16)")
            axes[2].plot(t, mp1[:, 1], "--", label="MP1 y1 (eq. 16)")
            axes[2].set(xlabel="t", ylabel="mm")
            axes[2].legend(fontsize=7)
        fig.suptitle(f"000 eq. ({label[2:]}) through generated/{NAME}.py")
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
        plt.close(fig)
        out[f"{NAME}.trajectory_{label}.png"] = buf.getvalue()
    return out


def report_sections(deriv) -> list[str]:
    """The parasitic-motion derivation and the trajectory figures."""
    from ..report.latex_util import broken_math, tex_escape

    res = deriv.extra["parasitic_basis"]
    out = [r"\section{Parasitic motion of the tripod (000 eq. 9-10, 16, 42)}",
           "The leg ideals of the tripod contain, besides the sphere conditions that fix the "
           "leg lengths, generators free of $q_4, q_5, q_6$: the revolute-plane conditions "
           "(eq. 9). With MP2 in MP1 written as $T(x_2, y_2, z_2) R_z(\\gamma_2) R_y(\\beta) "
           "R_x(\\alpha)$ (tan-half-angles $t_\\alpha, t_\\beta, t_{\\gamma_2}$), their "
           "lexicographic basis over $\\mathbb{Q}(t_\\alpha, t_\\beta, z_2, r_a, r_b)$ is:"]
    for k, gen in enumerate(res.generators, 1):
        out.append(broken_math(f"p_{{{k}}}", gen))
    out.append("so $\\gamma_2 = 0$, $y_2 = 0$ and $x_2 = -r_b \\sin\\alpha\\sin\\beta$ "
               "(eq. 10). Hence $\\gamma_1 = \\gamma$, and MP1 = MP2 $\\cdot$ conj(MP2 in MP1) "
               "gives eq. (16); the generated module exposes both as \\texttt{mp1\\_pose} and "
               "\\texttt{parasitic\\_motion}.")
    out += [r"\section{Trajectories (000 eq. 43-44)}",
            tex_escape("Joint positions and velocities along the paper's test trajectories, "
                       "computed by the generated functions (files "
                       f"{NAME}.trajectory_eq43.csv and {NAME}.trajectory_eq44.csv). "
                       "Eq. (43)-(44) put z near 0, where the legs would have zero length, so "
                       "the paper's z must be measured from a home height it does not state; "
                       f"z(t) is offset here by the mid-stroke height {Z_HOME} mm of Table 1. "
                       "Limits are not applied to the curves; the CSV column within_limits "
                       "marks the samples inside the strokes and joint ranges of Table 1."),
            r"\begin{center}\includegraphics[width=\textwidth]{" + NAME
            + r".trajectory_eq43.png}\end{center}",
            r"\begin{center}\includegraphics[width=0.75\textwidth]{" + NAME
            + r".trajectory_eq44.png}\end{center}"]
    return out
