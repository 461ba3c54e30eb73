"""The 2-URRH remote-centre-of-motion manipulator (paper 002: Chen et al., Mech. Mach.
Theory 2020).

The paper derives everything by vector geometry (eq. 5-13) and a product of exponentials
(eq. 14-18); here every result comes from Study-parameter chains and the elimination and
is then held against those formulas (:mod:`bonered_alg.papers.p002_urrh_rcm`).

Frame {S} (002 Sect. 2.4, 4.1): O at the intersection of the fixed U-joint axes,
x = u1, y = u2, z completing; limb 1 pivots about x with its plane's normal
n1 = Rx(alpha1) v1, v1 = u2 = y; limb 2 about y with n2 = Ry(alpha2) v2, v2 = u1 = x.
Limb i: A_i = -l_oa,i u_i, B_i = A_i + l_ab,i exp(n_i^ beta_i) u_i (eq. 7), the coupler
B_i C_i of length l_bc,i, and the collar C_i on the shaft, C_i = d_i u (eq. 8).

The algebra's platform is the frame F of collar 1 (it carries the pin of joint C1, whose
axis is n1): F = Rx(theta1) Ry(theta2) Tz(-d1), so u = F (0, 0, -1) points from O towards
the collars (-z at home, eq. 5) and F's y axis is n1.  Collar 2 is the frame F spun about
the shaft (a passive angle k2, eliminated) and moved along it to d2: the closure's
coordinates are (w1, w2, d1, d2), w_k = tan(theta_k/2).  The virtual screw (eq. 9,
d = d1, gamma = (d1 - d2)/p) is linear in the angle, so it is not in the ideal: it is the
pose map d2 = d - p gamma (eq. 11).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_symbolic as ss
from ..analyses.closure_dimension import ClosureDimension
from ..analyses.remote_centre import RemoteCentre
from ..declaration import (
    Closure,
    InputFunction,
    Limit,
    Parameter,
    PoseFunction,
    PoseMap,
    Role,
    declare,
    joint,
    leg,
)

NAME = "urrh_rcm"
R = {"real": True}
loa1, lab1, lbc1, lae1, lef1 = sp.symbols("loa1 lab1 lbc1 lae1 lef1", **R)
loa2, lab2, lbc2, lae2, lef2 = sp.symbols("loa2 lab2 lbc2 lae2 lef2", **R)
p = sp.Symbol("p", **R)
a1, a2, b1, b2 = sp.symbols("a1 a2 b1 b2", **R)  # tan-halves of alpha_i, beta_i (actuated)
t1, s1, t2, s2, k2 = sp.symbols("t1 s1 t2 s2 k2", **R)  # passive: B_i, C_i, collar 2 spin
w1, w2, d1, d2 = sp.symbols("w1 w2 d1 d2", **R)  # the closure's coordinates
theta1, theta2, d, gamma = sp.symbols("theta1 theta2 d gamma", **R)
POSE = (theta1, theta2, d, gamma)
A, P = Role.ACTIVE, Role.PASSIVE

LIMB1 = leg(
    "1",
    joint(NAME, "revolute", "U1.1", "x", a1, A, "active alpha1 = 2 atan(a1) about u1 = x"),
    joint(NAME, "offset", "OA1", axis="x", value=-loa1, description="A1 = -l_oa1 u1"),
    joint(NAME, "revolute", "U1.2", "y", b1, A,
          "active beta1 = 2 atan(b1) about n1 (the limb plane's normal, eq. 7)"),
    joint(NAME, "offset", "AB1", axis="x", value=lab1, description="crank A1B1, l_ab1"),
    joint(NAME, "revolute", "B1", "y", t1, P, "passive revolute at B1 (axis n1)"),
    joint(NAME, "offset", "BC1", axis="x", value=lbc1, description="coupler B1C1, l_bc1"),
    joint(NAME, "revolute", "C1", "y", s1, P,
          "passive revolute at C1 (axis n1) into collar 1, whose frame is F"))
LIMB2 = leg(
    "2",
    joint(NAME, "revolute", "U2.1", "y", a2, A, "active alpha2 = 2 atan(a2) about u2 = y"),
    joint(NAME, "offset", "OA2", axis="y", value=-loa2, description="A2 = -l_oa2 u2"),
    joint(NAME, "revolute", "U2.2", "x", b2, A,
          "active beta2 = 2 atan(b2) about n2 (the limb plane's normal, eq. 7)"),
    joint(NAME, "offset", "AB2", axis="y", value=lab2, description="crank A2B2, l_ab2"),
    joint(NAME, "revolute", "B2", "x", t2, P, "passive revolute at B2 (axis n2)"),
    joint(NAME, "offset", "BC2", axis="y", value=lbc2, description="coupler B2C2, l_bc2"),
    joint(NAME, "revolute", "C2", "x", s2, P, "passive revolute at C2 (axis n2) into collar 2"),
    joint(NAME, "revolute", "K2", "z", k2, P,
          "collar 2's spin about the shaft relative to F (passive)"),
    joint(NAME, "offset", "E2", axis="z", value=d2 - d1,
          description="from collar 2 along the shaft to collar 1, by d1 - d2 along u (d1, "
                      "d2 are closure coordinates)"))

SHAFT = ss.product(ss.rotation("x", w1), ss.rotation("y", w2), ss.translation("z", -d1))

# the shaft direction u = Rx(theta1) Ry(theta2) (0, 0, -1) (002 eq. 5, 16)
U_OF_POSE = (-sp.sin(theta2), sp.cos(theta2) * sp.sin(theta1),
             -sp.cos(theta2) * sp.cos(theta1))
ux, uy, uz, c1, c2 = sp.symbols("ux uy uz d_1 d_2", **R)
beta1, beta2, q1, q2 = sp.symbols("beta1 beta2 q1 q2", **R)


def slider(lae, lef, beta):
    """002 eq. (13): the slider input q = |A F| of the crank A E (l_ae) and rod E F (l_ef)
    at the crank angle beta, the root q > 0 of the triangle A E F,
    q^2 + 2 l_ae cos(beta) q + l_ae^2 - l_ef^2 = 0 (the angle at A is pi - beta)."""
    return -lae * sp.cos(beta) + sp.sqrt(lef**2 - lae**2 * sp.sin(beta) ** 2)


def crank_angle(lae, lef, q):
    """002 eq. (7), second part: the crank angle from the same triangle,
    beta = pi - arccos((q^2 + l_ae^2 - l_ef^2) / (2 q l_ae)), in [0, pi]."""
    return sp.pi - sp.acos((q**2 + lae**2 - lef**2) / (2 * q * lae))




def plane_normal(fixed: str, normal: str, t: sp.Symbol) -> tuple[sp.Expr, ...]:
    """n_i (1 + t^2) = exp(u_i^ alpha_i) v_i with t = tan(alpha_i/2) (002 eq. 6): the
    normal of limb i's plane, the axis ``normal`` turned about the fixed axis ``fixed``."""
    rows = cv.rotation_matrix_times_norm(ss.rotation(fixed, t))
    k = "xyz".index(normal)
    return tuple(sp.expand(r[k]) for r in rows)


# 002 Sect. 2.4, eq. (4): each limb moves in the plane through O normal to n_i
REMOTE_CENTRE = RemoteCentre("remote_centre", "shaft",
                             {"1": plane_normal("x", "y", a1), "2": plane_normal("y", "x", a2)},
                             title="Remote centre of motion from the ideal (002 Sect. 2.4)")

POSE_FUNCTIONS = (
    PoseFunction("shaft", ("ux", "uy", "uz", "d1", "d2"),
                 (*U_OF_POSE, d, d - p * gamma),
                 "The shaft: its unit direction u (from O towards the collars, 002 eq. 5) "
                 "and the collars' positions d1, d2 along it (mm, eq. 9, 11)."),
)
FUNCTIONS = (
    InputFunction("pose_from_shaft", (ux, uy, uz, c1, c2),
                  ("theta1", "theta2", "d", "gamma"),
                  (sp.atan2(uy, -uz), -sp.asin(ux / sp.sqrt(ux**2 + uy**2 + uz**2)), c1,
                   (c1 - c2) / p),
                  "The pose (theta1, theta2, d, gamma) from the shaft direction u (any "
                  "length) and the collars' positions d1, d2: theta1 = atan2(u_y, -u_z), "
                  "theta2 = phi1 - pi/2 = -asin(u_x / |u|) (002 eq. 16), d = d1, gamma = "
                  "(d1 - d2)/p (eq. 9)."),
    InputFunction("slider_inputs", (beta1, beta2), ("q1", "q2"),
                  (slider(lae1, lef1, beta1), slider(lae2, lef2, beta2)),
                  "The slider inputs q_i (mm) of the slider-cranks of 002 Fig. 5, 7 at the "
                  "crank angles beta_i (rad), eq. (13); NaN where the rod cannot reach.  "
                  "The crank angle is the one of eq. (7)'s second part, in [pi/2, pi] for "
                  "limb 1 (l_ae = l_ef): not the beta of eq. (7)'s first part (|beta1| <= "
                  "58.8 deg with Table 1), from which it differs by an offset the paper "
                  "does not give (see the verification)."),
    InputFunction("crank_angles", (q1, q2), ("beta1", "beta2"),
                  (crank_angle(lae1, lef1, q1), crank_angle(lae2, lef2, q2)),
                  "The slider-cranks' angles beta_i (rad, in [0, pi]) from the slider "
                  "inputs q_i (mm), 002 eq. (7) second part: the inverse of "
                  "slider_inputs; NaN outside the slider-crank's range."),
)


def _table1(name, value, what, limb, domain="positive"):
    return Parameter(name, value, "mm", f"{what}, limb {limb}", "002 Table 1", domain=domain)


PARAMETERS = (
    _table1("loa1", 130.0, "l_oa = |O A_1|", 1),
    _table1("lab1", 90.0, "l_ab = |A_1 B_1|", 1),
    _table1("lbc1", 83.4, "l_bc = |B_1 C_1|", 1),
    _table1("lae1", 161.3, "l_ae = |A_1 E_1| (slider-crank)", 1),
    _table1("lef1", 161.3, "l_ef = |E_1 F_1| (slider-crank)", 1),
    _table1("loa2", 148.2, "l_oa = |O A_2|", 2),
    _table1("lab2", 85.0, "l_ab = |A_2 B_2|", 2),
    _table1("lbc2", 89.8, "l_bc = |B_2 C_2|", 2),
    _table1("lae2", 161.3, "l_ae = |A_2 E_2| (slider-crank)", 2),
    _table1("lef2", 160.3, "l_ef = |E_2 F_2| (slider-crank)", 2),
    Parameter("p", 10.0, "mm/rad", "pitch of the virtual screw (the pulley radius, eq. 9)",
              "assumed: 002 Sect. 5.1 says Table 1 gives the pulley radius, but the "
              "printed Table 1 has no such column", domain="positive"))


def _collar_limits() -> tuple[Limit, ...]:
    """The collars stay on their side of the RCM point, 0 <= d_i (u points from O towards
    them, 002 eq. 5; beyond O the shaft is inside the patient), and within the limb's reach
    d_i <= l_oa,i + l_ab,i + l_bc,i (Table 1; never binding).  No slider strokes or passive
    angle ranges are printed, so these are the only limits."""
    v = {q.name: q.value for q in PARAMETERS}
    reach = {i: v[f"loa{i}"] + v[f"lab{i}"] + v[f"lbc{i}"] for i in (1, 2)}
    src = ("assumed: the collar stays on its side of the RCM point (002 eq. 5); upper "
           "bound the limb's reach (Table 1)")
    return (Limit("d1", d, 0.0, reach[1], "passive", "mm", src),
            Limit("d2", d - p * gamma, 0.0, reach[2], "passive", "mm", src))


MECHANISM = declare(
    name=NAME,
    title="2-URRH remote-centre-of-motion manipulator",
    source="002_7cf28ec01450fa69.txt (Chen et al., Mech. Mach. Theory 2020), Sect. 2, 4",
    summary="Two URRH limbs: an actuated universal joint at the base (alpha_i about the "
            "fixed axis u_i, beta_i about the limb plane's normal n_i), passive revolute "
            "joints at B_i and C_i, and a collar on the common shaft; the collars' "
            "positions along the shaft drive its translation and, through the virtual "
            "screw, its spin (002 eq. 9).  3R1T with a remote centre of motion at O.",
    parameters=PARAMETERS,
    joints=(a1, a2, b1, b2),
    joint_units=("rad",) * 4,
    angle_joints={a1: "alpha1", a2: "alpha2", b1: "beta1", b2: "beta2"},
    closures=(
        Closure("two URRH limbs on the shaft", "shaft", (LIMB1, LIMB2), SHAFT,
                (w1, w2, d1, d2),
                note="F = Rx(theta1) Ry(theta2) Tz(-d1), the frame of collar 1 (chart x0 = 1: "
                     "no half-turn of theta1 or theta2); d1, d2 are the collars' positions "
                     "along u."),),
    pose=PoseMap(POSE, ("rad", "rad", "mm", "rad"),
                 {w1: sp.tan(theta1 / 2), w2: sp.tan(theta2 / 2), d1: d, d2: d - p * gamma},
                 from_study={theta1: 2 * sp.atan(w1), theta2: 2 * sp.atan(w2), d: d1,
                             gamma: (d1 - d2) / p},
                 end_effector=ss.product(ss.rotation("x", sp.tan(theta1 / 2)),
                                         ss.rotation("y", sp.tan(theta2 / 2)),
                                         ss.translation("z", -d),
                                         ss.rotation("z", -sp.tan(gamma / 2))),
                 description="the virtual chain of 002 eq. (14)-(16): theta1 = alpha1, "
                             "theta2 = phi1 - pi/2, d = d1, gamma the spin about u; "
                             "F = Rx(theta1) Ry(theta2) Tz(-d), d1 = d, d2 = d - p gamma "
                             "(eq. 9, 11)"),
    # home: the shaft along -z (theta1 = theta2 = 0, eq. 16), both collars 80 mm from O;
    # the physical branch has each crank near its fixed axis and the coupler at a small
    # angle to the shaft (002 Sect. 4.4: "the angle between the coupler link and the
    # central shaft in a range of small values"): beta1 = 4.44 deg, beta2 = -12.38 deg
    # (v2 = u1 turns B2 towards +z for beta2 > 0), alpha2 = 0 rather than the half-turn
    limits=_collar_limits(),
    analyses=(ClosureDimension("mobility", "shaft", title="Mobility from the ideal "
                                                          "(002 eq. 3)"),
              REMOTE_CENTRE),
    pose_functions=POSE_FUNCTIONS,
    functions=FUNCTIONS,
    singularity_notes={
        "det_Ji_shaft": "Input singularities, one factor per IK step: the pivot of alpha2's "
                        "quadratic vanishes where its two roots (alpha2 and the half-turn) "
                        "merge, the shaft along limb 2's fixed axis u2 (boundary_a2; 002 "
                        "Sect. 4.4's alpha1 = +-pi/2, Fig. 8a); the "
                        "pivots of beta1, beta2 vanish where crank A_iB_i and coupler B_iC_i "
                        "are aligned and the two elbows merge at the edge of limb i's reach "
                        "(boundary_b1, boundary_b2; the limb's analogue of 002 Fig. 8d).",
        "det_Jo_shaft": "Output singularities: one factor per limb where the coupler B_iC_i "
                        "is perpendicular to the shaft, so collar i slides along it with the "
                        "joints locked (l_cd,i = 0, 002 Fig. 8c). The first factor, dG/dw2 of "
                        "alpha2's generator, vanishes at no real configuration (with the "
                        "generator it forces tan^2(theta2/2) = -1).",
        "boundary_a2": "The shaft along u2 (u = +-y): limb 2's plane turns about the shaft "
                       "without moving it, and alpha2's two roots merge.",
        "boundary_b1": "|C1 - A1| = l_ab1 +- l_bc1: limb 1 stretched or folded, the edge of "
                       "collar 1's reach.",
        "boundary_b2": "|C2 - A2| = l_ab2 +- l_bc2: limb 2 stretched or folded, the edge of "
                       "collar 2's reach (written with alpha2's tan-half, hence one factor).",
    },
    reading_notes=(
        "Frame and normals as Sect. 2.4 and 4.1 print them: x = u1, y = u2, v1 = u2, v2 = u1, "
        "so n1 = Rx(alpha1) y and n2 = Ry(alpha2) x. With these, a positive beta2 turns limb "
        "2's crank towards +z, away from the collars: the working beta2 are negative, while "
        "eq. (7)'s slider formula gives angles in [0, pi] (see the verification).",
        "The shaft direction u points from O towards the collars (-z at home), as eq. (5) and "
        "the issue's convention have it; eq. (6), (8) and (10) hold for the opposite "
        "direction, and each verdict says which.",
        "The virtual screw is not algebraic in the tan-half-angle of the spin: the algebra "
        "carries the collars' positions d1, d2 along the shaft as closure coordinates, and eq. "
        "(9) is the pose map d1 = d, d2 = d - p gamma. Sect. 3.2 says the end effector is "
        "attached to collar 2 (which would make d follow d2); eq. (9) is used as printed.",
        "The pitch p of the virtual screw is not in Table 1, though the text says the table "
        "gives the pulley radius: p = 10 mm is assumed, and the workspace's spin ranges "
        "scale with 1/p.",
        "Collar 1's frame is the platform F; collar 2 is F spun about the shaft by a passive "
        "angle k2 and moved along it, so limb 2's ideal has alpha2 and its half-turn "
        "alpha2 + pi as the two roots of a quadratic (the IK's alpha2 mode bit), while limb "
        "1's gives alpha1 = theta1 directly. The RCM property is built into F (its origin is "
        "d1 u); that a 2-URRH must have one is proved separately, each limb closing on a "
        "general platform (the section on the remote centre): it holds wherever the limb "
        "planes differ, and fails where they coincide (alpha1 = alpha2 = +-pi/2, far outside "
        "the workspace), configurations this pose map cannot describe.",
        "Fig. 5, 7, 8 and 10-13 are not in the text: the slider-crank's geometry beyond eq. "
        "(7) and (13), the singular configurations of Fig. 8 and the five orientations of "
        "Table 2 are read from the equations only."),
    checks="bonered_alg.papers.p002_urrh_rcm",
    studies=("bonered_alg.studies.workspace_002",),
    home=(0.0, 0.0, 80.0, 0.0),
    home_joints={a2: 0.0, b1: 0.0775, b2: -0.216},
)
