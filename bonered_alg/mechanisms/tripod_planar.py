"""Hybrid tripod-planar mechanism (paper 001: Essomba et al., Mechanical Sciences).

A 3-RPS tripod (base A -> platform B) carries a double-triangular 3-PRP planar mechanism
(B -> end effector C, centre O2); 6 DoF (001 Sect. 2, Fig. 3-4).  The generated functions
take ``(x, y, z, alpha, beta, gamma)``: O2 in {O,x,y,z} and the end effector's rotation
``R = Rz(gamma) Ry(beta) Rx(alpha)`` (DESIGN.md section 3); the paper's own angles are
mechanism coordinates (``paper_coordinates`` converts, see
:mod:`bonered_alg.papers.p001_tripod_planar`, which checks the printed equations).
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
from ..kinematics.symmetry import turned_generators

NAME = "tripod_planar"
R = {"real": True}
ra, rb, d = sp.symbols("ra rb d", **R)
s3 = sp.Symbol("s3", positive=True)
q1, q2, q3, q4, q5, q6 = sp.symbols("q1:7", **R)
u1, u2, u3, u4, u5, u6 = sp.symbols("u1:7", **R)
l4, l5, l6 = sp.symbols("l4 l5 l6", **R)
S1, S2, S3 = (sp.symbols(f"e{k}0:{k}4", **R) for k in (1, 2, 3))  # e10..e13, ...
# closure pose symbols: B in {O} (chart x0 = 1) and C relative to B (planar, height d)
PX = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", **R)
g, v1, v2 = sp.symbols("g v1 v2", **R)
x, y, z, alpha, beta, gamma = sp.symbols("x y z alpha beta gamma", **R)
POSE = (x, y, z, alpha, beta, gamma)
JOINTS = (q1, q2, q3, q4, q5, q6)
LIMITS = {"q_tripod": (160.0, 320.0), "q_planar": (120.0, 325.0),  # 001 Sect. 3
          "spherical_deg": (-20.0, 20.0)}
C_IN_B = (1, 0, 0, g, d * g / 2, v1, v2, -d / 2)  # T(x2, y2, d) Rz(gamma_p), eq. 7, 19
# base corners A_k (eq. 1) and spherical joints O1B_k (eq. 2): -30, 90, 210 degrees
_A = [(s3 / 2 * ra, -ra / 2, 0), (0, ra, 0), (-s3 / 2 * ra, -ra / 2, 0)]
_B = [(s3 / 2 * rb, -rb / 2, 0), (0, rb, 0), (-s3 / 2 * rb, -rb / 2, 0)]
_PSI = [s3 / 3, None, -s3 / 3]  # tan(psi/2): x axis to the tangent of the base circle
# B = T(x1, y1, z1) [1:b1:b2:b3] for the parasitic motion; tan-half angles of the pose
b1, b2, b3, x1, y1, z1 = sp.symbols("b1 b2 b3 x1 y1 z1", **R)
ta, tb, tg = sp.symbols("t_alpha t_beta t_gamma", **R)
_HALVES = {ta: sp.tan(alpha / 2), tb: sp.tan(beta / 2), tg: sp.tan(gamma / 2)}


def _tripod_legs():
    legs = []
    for k, (qk, uk, sph) in enumerate([(q1, u1, S1), (q2, u2, S2), (q3, u3, S3)]):
        lab = f"T{k + 1}"
        f = [joint(NAME, "offset", f"{lab}.A", vector=_A[k], description=f"base corner A{k + 1} "
                   "(eq. 1)")]
        if _PSI[k] is not None:
            f.append(joint(NAME, "offset", f"{lab}.t", axis="z", rotation_u=_PSI[k],
                           description="x axis to the tangent of the base circle"))
        f += [joint(NAME, "revolute", f"{lab}.R", "x", uk, Role.PASSIVE,
                    "passive revolute: the leg turns in the plane through A_k and z (eq. 9)"),
              joint(NAME, "prismatic", f"{lab}.q", "z", qk, Role.ACTIVE,
                    f"active leg length {qk} (eq. 4, 13)"),
              joint(NAME, "spherical", f"{lab}.S", sph, Role.PASSIVE,
                    f"passive spherical joint B{k + 1}"),
              joint(NAME, "offset", f"{lab}.B", vector=tuple(-c for c in _B[k]),
                    description=f"from B{k + 1} to O1 (eq. 2)")]
        legs.append(leg(lab, *f))
    return tuple(legs)


def _pose_pieces(d_) -> dict:
    """B's rotation (b1, b2), B's origin (x1, y1, z1), C in B (g, x2, y2), from the pose.

    The end effector's rotation quaternion e = Rz(gamma) Ry(beta) Rx(alpha) splits as
    e = b * Rz(gamma_p) with b = [b0:b1:b2:0] (the derived zero torsion, eq. 10):
    tan(gamma_p/2) = e3/e0 and b = e * conj(Rz(gamma_p)) = [e0^2+e3^2 : e0 e1 - e2 e3 :
    e0 e2 + e1 e3 : 0].  (x1, y1) follow from the derived parasitic motion (eq. 11-12);
    z1 and (x2, y2) from O2 = O1 + R_B (x2, y2, d) (eq. 8).  In the tan-half-angles.
    """
    par = d_.analyses["parasitic"].solved
    e = ss.product(ss.rotation("z", tg), ss.rotation("y", tb), ss.rotation("x", ta))
    e0, e1, e2, e3 = e[:4]
    bq0 = e0**2 + e3**2
    bb1, bb2 = (e0 * e1 - e2 * e3) / bq0, (e0 * e2 + e1 * e3) / bq0
    xb, yb = (sp.sympify(par[v]).subs({b1: bb1, b2: bb2}) for v in (x1, y1))
    rot = sp.Matrix(cv.rotation_matrix_times_norm((1, bb1, bb2, 0))) / (1 + bb1**2 + bb2**2)
    normal = rot[:, 2]
    zb = (normal[0] * (x - xb) + normal[1] * (y - yb) + normal[2] * z - d) / normal[2]
    rel = rot.T * sp.Matrix([x - xb, y - yb, z - zb])
    return {"b1": bb1, "b2": bb2, "x1": xb, "y1": yb, "z1": zb, "rot": rot, "g": e3 / e0,
            "x2": rel[0], "y2": rel[1]}


def pose_to_study(d_) -> dict:
    """Study coordinates of B (chart x0 = 1) and of C in B (g, v1, v2) from the pose."""
    p = _pose_pieces(d_)
    xq = (1, p["b1"], p["b2"], 0)
    bst = xq + cv.dual_part_from_translation((p["x1"], p["y1"], p["z1"]), xq)  # not expanded
    out = {s: bst[i + 1] for i, s in enumerate(PX)}
    out[g] = p["g"]
    out[v1] = -(p["x2"] + p["g"] * p["y2"]) / 2
    out[v2] = -(p["y2"] - p["g"] * p["x2"]) / 2
    return {k: sp.sympify(v).subs(_HALVES) for k, v in out.items()}


def ik_generators(d_):
    """Leg T2's sphere generator turned to legs T1 and T3 by the three-fold symmetry: the
    grevlex bases of legs T1 and T3 contain no quadratic in q with a leading coefficient
    that cannot vanish; the turned one has one (q^2 (1 + x_1'^2) - ...)."""
    return turned_generators(
        d_.leg("T2"), q2, (("T1", q1, s3), ("T3", q3, -s3)), (1, *PX), ((s3, sp.sqrt(3)),),
        select=lambda gen: sp.degree(gen, q2) == 2
        and sp.Poly(gen, q2).coeff_monomial(q2**2) == PX[0] ** 2 + 1,
        note="leg T2's sphere generator pulled back by the symmetry")


def limits(d_) -> list[Limit]:
    """001 Sect. 3: strokes 160-320 mm (tripod) and 120-325 mm (planar); spherical joints
    +-20 deg, read as the angle between leg k and the normal of platform B (as 000 eq. 46).
    No revolute range is given for 001."""
    p = _pose_pieces(d_)
    rot, o1 = p["rot"], sp.Matrix([p["x1"], p["y1"], p["z1"]])
    out = []
    for key, joints_ in (("q_tripod", (q1, q2, q3)), ("q_planar", (q4, q5, q6))):
        lo, hi = LIMITS[key]
        out += [Limit(str(q), q, lo, hi, "stroke", "mm", "001 Sect. 3") for q in joints_]
    s_lo, s_hi = (sp.rad(v) for v in LIMITS["spherical_deg"])
    for k in range(3):
        a_k, b_k = (sp.Matrix(pt[k]).subs(s3, sp.sqrt(3)) for pt in (_A, _B))
        leg_vec = o1 + rot * b_k - a_k
        ang = sp.acos(rot[:, 2].dot(leg_vec) / sp.sqrt(leg_vec.dot(leg_vec)))
        out.append(Limit(f"phi_s{k + 1}", ang.subs(_HALVES), s_lo, s_hi, "passive", "rad",
                         "001 Sect. 3: spherical joint B_k"))
    return out


def pose_functions(d_) -> list[PoseFunction]:
    """``paper_coordinates`` (the paper's mechanism coordinates of a pose) and
    ``pose_from_paper_coordinates`` (the inverse), from the derived split."""
    p = _pose_pieces(d_)
    rot = p["rot"]
    paper = [sp.atan2(rot[2, 1], rot[2, 2]),
             sp.atan2(-rot[2, 0], sp.sqrt(rot[0, 0] ** 2 + rot[1, 0] ** 2)),
             2 * sp.atan(p["g"]), sp.atan2(rot[1, 0], rot[0, 0]),
             p["x1"], p["y1"], p["z1"], p["x2"], p["y2"]]
    # inverse: R = Rz(phi) Ry(beta_p) Rx(alpha_p) Rz(gamma_p), tan(phi/2) = t_a t_b (eq. 10)
    q_e = ss.product(ss.rotation("z", ta * tb), ss.rotation("y", tb), ss.rotation("x", ta),
                     ss.rotation("z", tg))
    r_n = sp.Matrix(cv.rotation_matrix_times_norm(q_e))
    back = [x, y, z, sp.atan2(r_n[2, 1], r_n[2, 2]),
            sp.atan2(-r_n[2, 0], sp.sqrt(r_n[0, 0] ** 2 + r_n[1, 0] ** 2)),
            sp.atan2(r_n[1, 0], r_n[0, 0])]
    return [
        PoseFunction("paper_coordinates",
                     ("alpha_p", "beta_p", "gamma_p", "phi", "x1", "y1", "z1", "x2", "y2"),
                     tuple(sp.sympify(e).subs(_HALVES) for e in paper),
                     "The paper's coordinates of a pose (001 eq. 6-8, 10-12, 19): roll alpha_p "
                     "and pitch beta_p of platform B, the planar rotation gamma_p, the "
                     "parasitic yaw phi, B's origin (x1, y1, z1) and O2 in B (x2, y2) (rad, mm)."),
        PoseFunction("pose_from_paper_coordinates", tuple(str(s) for s in POSE),
                     tuple(sp.sympify(e).subs(_HALVES) for e in back),
                     "The pose (R = Rz(gamma) Ry(beta) Rx(alpha) of the end effector) from the "
                     "paper's coordinates given in the pose slots as (x, y, z, alpha_p, beta_p, "
                     "gamma_p)."),
    ]


MECHANISM = declare(
    name=NAME,
    title="Hybrid tripod-planar mechanism (3-RPS + 3-PRP)",
    source="001_5ecc975eb69feb79.txt (Essomba et al., hybrid tripod-planar bone-reduction "
           "mechanism, Mechanical Sciences), Sect. 2-3",
    summary="A 3-RPS tripod (base A -> platform B) carries a double-triangular 3-PRP planar "
            "mechanism (B -> end effector C, centre O2); 6 DoF (001 Sect. 2, Fig. 3-4).",
    parameters=(
        Parameter("ra", 200.0, "mm", "circumradius of the base A1A2A3",
                  "001 Sect. 3: rings of 400 mm diameter", domain="positive"),
        Parameter("rb", 200.0, "mm", "circumradius of B1B2B3 and of the planar triangles",
                  "001 Sect. 3: rings of 400 mm diameter", domain="positive"),
        Parameter("d", 0.0, "mm", "height of O2 above platform B (eq. 7)",
                  "not given in 001; 0 as in 000 (flat planar stage)")),
    constants=(Constant(s3, s3**2 - 3, sp.sqrt(3),
                        "sqrt(3) of the equilateral layouts (eq. 1-3)"),),
    joints=JOINTS,
    joint_units=("mm",) * 6,
    closures=(
        Closure("3-RPS tripod", "B", _tripod_legs(), (1, *PX), PX,
                note="B in {O} in the chart x0 = 1 (no half-turns)."),
        Closure("planar 3-PRP mechanism", "C",
                prp_legs(NAME, rb, s3, (q4, q5, q6), (u4, u5, u6), (l4, l5, l6),
                         names=("P1", "P2", "P3"), height=d, upper="C", corner="C"),
                C_IN_B, (g, v1, v2), base="B", motion="planar",
                note="C relative to B: T(x2, y2, d) Rz(gamma_p) with g = tan(gamma_p/2), "
                     "v1 = -(x2 + g y2)/2, v2 = -(y2 - g x2)/2 (eq. 7, 19)."),
    ),
    pose=PoseMap(POSE, ("mm", "mm", "mm", "rad", "rad", "rad"), pose_to_study,
                 from_study=dict(zip(POSE, ss.pose_from_study(ss.product((1, *PX), C_IN_B)))),
                 end_effector=ss.study_from_pose(*POSE),
                 description="R = Rz(gamma) Ry(beta) Rx(alpha) of the end effector; "
                             "tan(gamma_p/2) = x3/x0, B's rotation = end effector * "
                             "Rz(-gamma_p), B's translation from the derived parasitic motion"),
    analyses=(ParasiticMotion(
        "parasitic", "B", ss.product(ss.translation_vector((x1, y1, z1)),
                                     ss.quaternion_rotation((1, b1, b2, b3))),
        unknowns=(b3, x1, y1), free=(b1, b2, z1),
        title="Parasitic motion of the tripod (001 eq. 9-12)",
        form=r"B = T(x_1, y_1, z_1)\,[1:b_1:b_2:b_3]"),),
    ik_generators=ik_generators,
    limits=limits,
    pose_functions=pose_functions,
    reading_notes=(
        "Encoding: tripod leg k is T(A_k) Rz(psi_k) Rx(u_k) Tz(q_k) (the revolute axis is "
        "tangent to the base circle, the leg is vertical at u_k = 0), a spherical joint "
        "(Euler parameters) and T(-O1B_k) to O1 (eq. 1-2, 4-5); B is a general Study point in "
        "the chart x0 = 1. Planar leg k is the double-triangular PRP leg with circumradius rb "
        "and the height d of C above B (eq. 7, 17-20); C relative to B is "
        "T(x2, y2, d) Rz(gamma_p).",
        "eq. (17) prints O1R1 = (sqrt3/2 rb - q4/2, rb/2 + sqrt3/2 q4); that point is not on "
        "an edge of the lower triangle. The chain uses -rb/2 (as 000 eq. 1); the report shows "
        "that only this reading reproduces eq. (21).",
        "eq. (3) prints O2C3 as \"(- 0, rb, 0)\"; (0, -rb, 0) is meant (the triangle "
        "C1C2C3).",
        "Dimensions (001 Sect. 3): rings of 400 mm diameter, so ra = rb = 200 mm; strokes "
        "160-320 mm (tripod) and 120-325 mm (planar); spherical joints +-20 deg. The height d "
        "of C above B is not given; 0 is used (the planar stage is flat, as in 000), and every "
        "function takes it."),
    checks="bonered_alg.papers.p001_tripod_planar",
    # home: 001 Table 1's homing height, level; the 3-RPS legs vertical, positive strokes
    home=(0.0, 0.0, 210.0, 0.0, 0.0, 0.0),
    home_joints={q: 210.0 for q in JOINTS[:3]},
)
