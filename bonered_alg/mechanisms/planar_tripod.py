"""Hybrid planar-tripod mechanism (paper 000: Essomba & Phu, Mech. & Ind. 21, 403, 2020).

A 3-PRP double-triangular planar mechanism (base -> mobile platform MP1) carries a 3-RPS
tripod with an isosceles leg layout (MP1 -> end effector MP2); 6 DoF.  Pose
``(x, y, z, alpha, beta, gamma)`` of O2 in {Oxyz}, ``R = Rz(gamma) Ry(beta) Rx(alpha)``
(eq. 11), radians.  The paper's printed equations are checked in
:mod:`bonered_alg.papers.p000_planar_tripod`, the trajectories of eq. (43)-(44) in
:mod:`bonered_alg.studies.trajectories_000`.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_symbolic as ss
from ..analyses.parasitic import ParasiticMotion
from ..chains.double_triangle import prp_legs
from ..declaration import (
    Closure,
    Constant,
    Limit,
    Parameter,
    PoseFunction,
    PoseMap,
    Role,
    declare,
    joint,
    leg,
)

NAME = "planar_tripod"
R = {"real": True}
ra, rb = sp.symbols("ra rb", **R)
s3 = sp.Symbol("s3", positive=True)
q1, q2, q3, q4, q5, q6 = sp.symbols("q1:7", **R)
u1, u2, u3, l1, l2, l3 = sp.symbols("u1 u2 u3 l1 l2 l3", **R)
u4, u5, u6 = sp.symbols("u4 u5 u6", **R)
S1, S2, S3 = (sp.symbols(f"e{k}0:{k}4", **R) for k in (1, 2, 3))  # e10..e13, ...
# closure pose symbols: MP1 in {O} (planar) and MP2 in {O1} (chart x0 = 1)
g, v1, v2 = sp.symbols("g v1 v2", **R)
PX = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", **R)
x, y, z, alpha, beta, gamma = sp.symbols("x y z alpha beta gamma", **R)
POSE = (x, y, z, alpha, beta, gamma)
JOINTS = (q1, q2, q3, q4, q5, q6)
# MP2 relative to MP1 as T(x2, y2, z2) Rz(gamma2) Ry(beta) Rx(alpha), tan-half angles
ta, tb, tg2, x2, y2, z2 = sp.symbols("t_alpha t_beta t_gamma2 x2 y2 z2", **R)
MP1_STUDY = (1, 0, 0, g, 0, v1, v2, 0)
LIMITS = {"q_tripod": (175.0, 250.0), "revolute_deg": (-45.0, 45.0),  # 000 Table 1
          "spherical_deg": (-20.0, 20.0)}
_HALVES = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), z2: z}


def _tripod_legs():
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
            joint(NAME, "offset", f"{lab}.C", axis=c_ax, value=c_val,
                  description="revolute joint C_k on MP1 (eq. 18)"),
            joint(NAME, "revolute", f"{lab}.R", r_ax, uk, P,
                  "passive revolute: the leg turns in its plane (eq. 9)"),
            joint(NAME, "prismatic", f"{lab}.q", p_ax, p_val, A,
                  f"active leg length {qk} (eq. 13)"),
            joint(NAME, "spherical", f"{lab}.S", sph, P, "passive spherical joint D_k"),
            joint(NAME, "offset", f"{lab}.D", axis=d_ax, value=d_val,
                  description="from D_k to O2 (eq. 7)")))
    return tuple(legs)


def _parasitic(d) -> tuple:
    """x2, y2, t_gamma2 of MP2 in MP1 (000 eq. 10) as functions of the pose."""
    par = d.analyses["parasitic"].solved
    return tuple(sp.sympify(par[v]).subs(_HALVES) for v in (x2, y2, tg2))


def pose_to_study(d) -> dict:
    """Study coordinates of MP1 (planar) and of MP2 in MP1 from the pose: MP2 in MP1 =
    T(x2, y2, z) Rz(gamma2) Ry(beta) Rx(alpha) with the derived parasitic (x2, y2, gamma2);
    MP1 = MP2 * conj(MP2 in MP1).  Rational in the tan-half-angles."""
    par = d.analyses["parasitic"].solved
    t_g = sp.Symbol("t_gamma", **R)
    xp, yp, gp = (sp.sympify(par[v]).subs(z2, z) for v in (x2, y2, tg2))
    p2 = ss.product(ss.translation_vector((xp, yp, z)), ss.rotation("z", gp),
                    ss.rotation("y", tb), ss.rotation("x", ta))
    world = ss.product(ss.translation_vector((x, y, z)), ss.rotation("z", t_g),
                       ss.rotation("y", tb), ss.rotation("x", ta))
    p1 = ss.product(world, ss.conjugate(p2))
    halves = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), t_g: sp.tan(gamma / 2)}
    out = {}
    for sym, num, den in [(g, p1[3], p1[0]), (v1, p1[5], p1[0]), (v2, p1[6], p1[0])]:
        out[sym] = sp.factor(sp.cancel(num / den)).subs(halves)
    for i, s_ in enumerate(PX):
        out[s_] = sp.factor(sp.cancel(p2[i + 1] / p2[0])).subs(halves)
    return out


def limits(d) -> list[Limit]:
    """000 Table 1: strokes 175-250 mm (read as applying to all six actuators: the table
    gives one range for "q" and the home pose has q1 = q2 = q3 = 2 ra / sqrt(3) = 219 mm),
    revolute joints +-45 deg and spherical joints +-20 deg (eq. 45-46: the angle of each leg
    to the MP1 normal, and to the MP2 normal)."""
    xp, yp, gp = _parasitic(d)
    rot2 = sp.rot_axis3(-2 * sp.atan(gp)) * sp.rot_axis2(-beta) * sp.rot_axis1(-alpha)
    t2, normal2 = sp.Matrix([xp, yp, z]), rot2 * sp.Matrix([0, 0, 1])
    c_pts, d_pts = [(ra, 0, 0), (0, ra, 0), (-ra, 0, 0)], [(rb, 0, 0), (0, rb, 0), (-rb, 0, 0)]
    lo, hi = LIMITS["q_tripod"]
    out = [Limit(f"q{k}", q, lo, hi, "stroke", "mm", "000 Table 1 (q_min, q_max)")
           for k, q in enumerate(JOINTS, 1)]
    r_lo, r_hi = (sp.rad(v) for v in LIMITS["revolute_deg"])
    s_lo, s_hi = (sp.rad(v) for v in LIMITS["spherical_deg"])
    for k in range(3):
        leg_vec = t2 + rot2 * sp.Matrix(d_pts[k]) - sp.Matrix(c_pts[k])
        length = sp.sqrt(leg_vec.dot(leg_vec))
        out.append(Limit(f"phi_r{k + 1}", sp.acos(leg_vec[2] / length), r_lo, r_hi,
                         "passive", "rad", "000 eq. (45)-(46), Table 1: revolute joint C_k"))
        out.append(Limit(f"phi_s{k + 1}", sp.acos(normal2.dot(leg_vec) / length), s_lo, s_hi,
                         "passive", "rad", "000 eq. (45)-(46), Table 1: spherical joint D_k"))
    return out


def pose_functions(d) -> list[PoseFunction]:
    """``mp1_pose`` (x1, y1, gamma1 of MP1, 000 eq. 16) and ``parasitic_motion`` (x_par,
    y_par of O2 in {Oxyz} caused by the tripod, 000 eq. 42), both from the derivation."""
    gq, w1, w2 = (d.pose_to_study[s] for s in (g, v1, v2))
    tvec = cv.translation_times_norm((1, 0, 0, gq, 0, w1, w2, 0))
    x1e, y1e = (sp.simplify(c / (1 + gq**2)) for c in tvec[:2])
    xp, yp, _ = _parasitic(d)
    xpar, ypar = sp.rot_axis3(-gamma)[:2, :2] * sp.Matrix([xp, yp])
    return [
        PoseFunction("mp1_pose", ("x1", "y1", "gamma1"), (x1e, y1e, 2 * sp.atan(gq)),
                     "Pose of MP1 in {Oxyz} that compensates the tripod's parasitic motion "
                     "(000 eq. 16)."),
        PoseFunction("parasitic_motion", ("x_par", "y_par"),
                     (sp.simplify(xpar), sp.simplify(ypar)),
                     "Parasitic displacement of O2 generated by the tripod, in {Oxyz} "
                     "(000 eq. 42)."),
    ]


MECHANISM = declare(
    name=NAME,
    title="Hybrid planar-tripod mechanism (3-PRP + 3-RPS)",
    source="000_c0528de5aff00fc3.txt (Essomba & Phu, Mech. & Ind. 21, 403, 2020), Sect. 2-3, 5",
    summary="A 3-PRP double-triangular planar mechanism (base -> mobile platform MP1) carries "
            "a 3-RPS tripod with an isosceles leg layout (MP1 -> end effector MP2); 6 DoF. "
            "Frames, dimensions and the angle convention are the paper's (Sect. 2-3): pose "
            "(x, y, z, alpha, beta, gamma) of O2 in {Oxyz} with R = Rz(gamma) Ry(beta) "
            "Rx(alpha) (eq. 11), angles in radians.",
    parameters=(
        Parameter("ra", 190.0, "mm", "circumradius of A1A2A3, B1B2B3 and of the tripod base "
                  "C1C2C3", "000 Table 1", domain="positive"),
        Parameter("rb", 190.0, "mm", "circumradius of D1D2D3 (MP2)", "000 Table 1",
                  domain="positive")),
    constants=(Constant(s3, s3**2 - 3, sp.sqrt(3),
                        "sqrt(3) of the equilateral layouts (eq. 1-2)"),),
    joints=JOINTS,
    joint_units=("mm",) * 6,
    closures=(
        Closure("planar 3-PRP mechanism", "MP1",
                prp_legs(NAME, ra, s3, (q1, q2, q3), (u1, u2, u3), (l1, l2, l3)),
                MP1_STUDY, (g, v1, v2), motion="planar",
                note="MP1 moves in the base plane: a rotation g = tan(gamma1/2) about z and a "
                     "translation (x1, y1), v1 = -(x1 + g y1)/2, v2 = -(y1 - g x1)/2."),
        Closure("3-RPS tripod", "MP2", _tripod_legs(), (1, *PX), PX, base="MP1",
                note="MP2 relative to MP1 in the chart x0 = 1 (no half-turns)."),
    ),
    pose=PoseMap(POSE, ("mm", "mm", "mm", "rad", "rad", "rad"), pose_to_study,
                 from_study=dict(zip(POSE, ss.pose_from_study(ss.product(MP1_STUDY,
                                                                        (1, *PX))))),
                 end_effector=ss.study_from_pose(*POSE),
                 description="R = Rz(gamma) Ry(beta) Rx(alpha), 000 eq. 11; MP2 relative to "
                             "MP1 from the parasitic motion derived below; MP1 = MP2 * "
                             "conj(MP2 in MP1)"),
    analyses=(ParasiticMotion(
        "parasitic", "MP2", ss.product(ss.translation_vector((x2, y2, z2)),
                                       ss.rotation("z", tg2), ss.rotation("y", tb),
                                       ss.rotation("x", ta)),
        unknowns=(tg2, x2, y2), free=(ta, tb, z2),
        title="Parasitic motion of the tripod (000 eq. 9-10, 16, 42)",
        form=r"T(x_2, y_2, z_2) R_z(\gamma_2) R_y(\beta) R_x(\alpha)"),),
    limits=limits,
    pose_functions=pose_functions,
    reading_notes=(
        "Encoding: planar leg k is T(A_k) Rz(phi_k) Tx(q_k) Rz(-phi_k) (active prismatic "
        "along the base edge, eq. 1), Rz(u_k) (passive revolute), then back along the MP1 "
        "edge by the passive stroke l_k (eq. 2) and T(-B_k) to O1; the 120-degree layout "
        "needs sqrt(3), carried as the algebraic constant s3 with s3^2 = 3. Tripod leg k "
        "(eq. 13, 18) is T(C_k) R(u_k) T(-q_k) along the leg in the plane of its revolute "
        "joint, a spherical joint (Euler parameters), T(-d_k) back to O2 (eq. 7).",
        "000 eq. (2) places the MP1 corners at B1 = (sqrt(3)/2 ra, ra/2), B2 = (-sqrt(3)/2 "
        "ra, ra/2), B3 = (0, -ra), and the passive prismatic joints R'_k on the edges B1B2, "
        "B2B3, B3B1; the text calls MP1 \"the same size as A1A2A3\", so its circumradius is "
        "ra.",
        "The tripod parameters of 000 Table 1 (ra = rb = 190 mm, strokes 175-250 mm, revolute "
        "joints +-45 deg, spherical joints +-20 deg) are used; the planar strokes are not "
        "given.",
        "Eq. (17) reads \"substituting equation (16) into equation (6)\"; equation (5) is "
        "meant."),
    checks="bonered_alg.papers.p000_planar_tripod",
    studies=("bonered_alg.studies.trajectories_000",),
    # home: the platform 200 mm above the base, level; the tripod legs are then vertical
    # and as long as the height (000 eq. 18), the positive strokes
    home=(0.0, 0.0, 200.0, 0.0, 0.0, 0.0),
    home_joints={q: 200.0 for q in JOINTS[3:]},
)
