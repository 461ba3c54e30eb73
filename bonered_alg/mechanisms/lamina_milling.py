"""The asymmetrical 3-DOF translational robot for spinal lamina milling (paper 003: Li, Gao,
Yu, Chen, Machines 10, 29, 2022).

The paper writes the kinematics as three distance equations (eq. 7-9) read off its
Fig. 6; here they come out of Study-parameter chains by elimination and are then held
against the printed (sign-restored) forms (:mod:`bonered_alg.papers.p003_lamina_milling`).

Base frame O-X0Y0Z0 (003 Sect. 2.2, Fig. 6): O at the common axis of the two actuated
revolute joints, Z0 along it and along the active prismatic joint.  The platform is the
frame at the tool point H; it is declared as a pure translation (chart x0 = 1,
x1 = x2 = x3 = 0), which the mobility study (screws at home, the closure's tangent space)
and the analysis ``pure_translation`` (every leg on a general platform) confirm.

* Upper chain (J11-J14 of 003 Fig. 5): the active slide L along Z0 carries D =
  (0, dy1, dD + L) and the rigid link DE along Y0 (E = D + (0, lDE, 0)); at E the top
  transverse link of the parallelogram turns about X0 (J12); the parallelogram (J13, its
  joint axes normal to the transverse link and to the long link EC) translates the bottom
  transverse link on a sphere of radius lEC; that link turns about X0 into the platform
  (J14) at C, and H = C + (0, dy2, 0).
* Bottom chains 1, 2 (J21-J23, J31-J33): the active revolute theta_i about Z0 at O, the
  link OA (OB) of length lOA (lOB), a passive revolute about Z0 at A (B), the link AF (BM)
  of length lAF (lBM), and a cylindrical joint along Z0 at F = M = (x, y, 0) into the
  platform's vertical shaft, which it meets a distance z below H.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import study_symbolic as ss
from ..analyses.closure_dimension import ClosureDimension
from ..analyses.pure_translation import PureTranslation
from ..declaration import (
    Closure,
    LinkWeight,
    Parameter,
    PoseMap,
    Role,
    WeightPoint,
    declare,
    joint,
    leg,
)

NAME = "lamina_milling"
R = {"real": True}
lOA, lAF, lOB, lBM = sp.symbols("lOA lAF lOB lBM", **R)
lDE, lEC, dy1, dy2, dD = sp.symbols("lDE lEC dy1 dy2 dD", **R)
L, t1, t2 = sp.symbols("L t1 t2", **R)  # actuated: the slide, tan(theta_i / 2)
e1, e2, e3 = sp.symbols("e1 e2 e3", **R)  # passive, upper chain: J12, J13, J14
b1, c1, s1 = sp.symbols("b1 c1 s1", **R)  # passive, bottom chain 1: J22, J23 (turn, slide)
b2, c2, s2 = sp.symbols("b2 c2 s2", **R)  # passive, bottom chain 2: J32, J33
x, y, z = sp.symbols("x y z", **R)  # H in the base frame (mm)
G = sp.symbols("G1:8", **R)  # link weights (N), 003 Table 1
l2, l4, l5, l8, l9 = sp.symbols("l2 l4 l5 l8 l9", **R)  # centres of gravity (mm)
POSE = (x, y, z)
A, P = Role.ACTIVE, Role.PASSIVE

UPPER = leg(
    "U",
    joint(NAME, "prismatic", "J11", "z", L, A, "active slide L along Z0 (carries D)"),
    joint(NAME, "offset", "D", vector=(0, dy1, dD),
          description="D = (0, dy1, dD + L), 003 Sect. 2.2"),
    joint(NAME, "offset", "DE", axis="y", value=lDE, description="the rigid link DE along Y0"),
    joint(NAME, "revolute", "J12", "x", e1, P,
          "passive: the parallelogram's top transverse link turns about X0 at E"),
    joint(NAME, "parallelogram", "J13", "y", e2, (0, 0, -lEC), P,
          "passive: the parallelogram E-C (its joint axes normal to the transverse link and "
          "to EC), the bottom transverse link translated by R(e2) (0, 0, -lEC)"),
    joint(NAME, "revolute", "J14", "x", e3, P,
          "passive: the bottom transverse link turns about X0 into the platform at C"),
    joint(NAME, "offset", "CH", axis="y", value=dy2, description="H = C + (0, dy2, 0)"))


def _bottom(k: int, t, loa, laf, b, c, s, names):
    o, a, f = names
    return leg(
        str(k),
        joint(NAME, "revolute", f"J{k + 1}1", "z", t, A,
              f"active theta{k} = 2 atan(t{k}) about Z0 at O, from X0 to O{a}"),
        joint(NAME, "offset", f"O{a}", axis="x", value=loa, description=f"link O{a}"),
        joint(NAME, "revolute", f"J{k + 1}2", "z", b, P, f"passive revolute about Z0 at {a}"),
        joint(NAME, "offset", f"{a}{f}", axis="x", value=laf, description=f"link {a}{f}"),
        joint(NAME, "cylindrical", f"J{k + 1}3", "z", c, s, P,
              f"passive cylindrical joint along Z0 at {f} = (x, y, 0) on the platform's "
              "vertical shaft (turn, then slide up to H)"))


BOTTOM1 = _bottom(1, t1, lOA, lAF, b1, c1, s1, ("O", "A", "F"))
BOTTOM2 = _bottom(2, t2, lOB, lBM, b2, c2, s2, ("O", "B", "M"))

PLATFORM = ss.translation_vector((x, y, z))


def _table1(name, value, what, source="003 Table 1"):
    return Parameter(name, value, "mm", what, source, domain="positive")


PARAMETERS = (
    _table1("lOA", 90.0, "l_OA = |O A|, bottom chain 1"),
    _table1("lAF", 90.0, "l_AF = |A F|, bottom chain 1"),
    _table1("lOB", 90.0, "l_OB = |O B|, bottom chain 2",
            "003 Table 1 (l_OA; Sect. 2.2: l_OB = l_OA)"),
    _table1("lBM", 90.0, "l_BM = |B M|, bottom chain 2",
            "003 Table 1 (l_AF; Sect. 2.2: l_BM = l_AF)"),
    _table1("lDE", 30.5, "l_DE = |D E|, the rigid link of the upper chain along Y0"),
    _table1("lEC", 90.0, "l_EC, the long links of the parallelogram"),
    _table1("dy1", 45.5, "Delta y1: D's offset along Y0"),
    _table1("dy2", 24.0, "Delta y2 = |C H| along Y0"),
    _table1("dD", 136.3, "Delta D: D's height at L = 0"),
    *(Parameter(f"G{k + 1}", v, "N", f"weight G{k + 1} of {what}", "003 Table 1",
                domain="nonnegative")
      for k, (v, what) in enumerate(((0.87, "the parallelogram's link EC"),
                                     (0.74, "the active link DE with its carriage"),
                                     (1.72, "link AF"), (1.87, "link OA (PA)"),
                                     (1.59, "link BM"), (2.52, "link OB"),
                                     (4.17, "the moving platform")))),
    _table1("l2", 45.0, "centre of gravity of EC from C along c_y (towards E)"),
    _table1("l4", 50.21, "centre of gravity of AF from F along f_y2 (towards A)"),
    _table1("l5", 39.096, "centre of gravity of OA from O (the paper's P)"),
    _table1("l8", 49.571, "centre of gravity of BM from M (chain 2's l4)"),
    _table1("l9", 29.139, "centre of gravity of OB from O (chain 2's l5)"),
)

_ORIGIN = (0, 0, 0)
# 003 Table 1 and Sect. 2.3 as read here (each reading in LinkWeight.reading); the bodies
# are the generated LINKS: U.1 the carriage with DE (frame at (0, 0, L)), U.2 the top
# transverse link (frame at E), U.3 the bottom transverse link (frame at C), 1.1 / 2.1 the
# links OA / OB (frame at O, x towards A / B), 1.2 / 2.2 the links AF / BM (frame at A / B,
# x towards F / M), "platform" the end effector's frame at H
LINK_WEIGHTS = (
    LinkWeight("G1", G[0], (WeightPoint("U.3", _ORIGIN, 1 - l2 / lEC),
                            WeightPoint("U.2", _ORIGIN, l2 / lEC)),
               "the parallelogram's long link EC (not a body of the chain: its centre of "
               "gravity is the point l2 from C towards E of the segment C E)",
               "l1 = 90 mm is |C E| = lEC and l2 = 45 mm the centre of gravity's distance "
               "from C (003 eq. 18: 'distances from point E and the center of gravity to the "
               "origin of the C coordinates'); 45 of 90 mm is the midpoint either way"),
    LinkWeight("G2", G[1], (WeightPoint("U.1", (0, dy1 + lDE / 2, dD)),),
               "the active link DE and its carriage (they only translate along Z0: the point "
               "does not matter)", "no distance printed: the middle of DE"),
    LinkWeight("G3", G[2], (WeightPoint("1.2", (lAF - l4, 0, 0)),),
               "link AF", "l4 from F along f_y2 towards A (003 eq. 37-38; l3 = 90 mm is "
               "|A F| = lAF)"),
    LinkWeight("G4", G[3], (WeightPoint("1.1", (l5, 0, 0)),),
               "link OA (the paper's PA)", "l5 from P = O (003 eq. 47; l6 = 90 mm is "
               "|P A| = lOA)"),
    LinkWeight("G5", G[4], (WeightPoint("2.2", (lBM - l8, 0, 0)),),
               "link BM", "l8 from M towards B, chain 2's l4 (l7 = 90 mm is |B M| = lBM)"),
    LinkWeight("G6", G[5], (WeightPoint("2.1", (l9, 0, 0)),),
               "link OB", "l9 from O, chain 2's l5 (l10 = 90 mm is |O B| = lOB)"),
    LinkWeight("G7", G[6], (WeightPoint("platform", _ORIGIN),),
               "the moving platform", "no centre of gravity printed: at H (the platform only "
               "translates, so every point of it moves alike)"),
)

MECHANISM = declare(
    name=NAME,
    title="3-DOF translational lamina-milling robot",
    source="003_8667f213c2f26c83.txt (Li, Gao, Yu, Chen, Machines 10, 29, 2022), Sect. 2",
    summary="One upper chain (an active slide L along Z0, the rigid link DE, a passive "
            "parallelogram between two revolute joints about X0) and two bottom chains (an "
            "active revolute theta_i about Z0 at O, a passive revolute, a cylindrical joint "
            "on the platform's vertical shaft) carry the tool point H = (x, y, z) in pure "
            "translation (003 Sect. 2.1-2.2, Fig. 4-6).",
    parameters=PARAMETERS,
    joints=(L, t1, t2),
    joint_units=("mm", "rad", "rad"),
    angle_joints={t1: "theta1", t2: "theta2"},
    closures=(
        Closure("one upper and two bottom chains", "platform", (UPPER, BOTTOM1, BOTTOM2),
                PLATFORM, POSE,
                note="H = (x, y, z) with the platform's orientation fixed (chart x0 = 1, "
                     "x1 = x2 = x3 = 0)."),),
    pose=PoseMap(POSE, ("mm", "mm", "mm"), {x: x, y: y, z: z},
                 from_study={x: x, y: y, z: z},
                 end_effector=PLATFORM,
                 description="H = (x, y, z) in the base frame (003 Sect. 2.2); the "
                             "platform's Study point is [1:0:0:0:0:-x/2:-y/2:-z/2]"),
    singularity_notes={
        "det_Ji_platform": "Input singularities, one factor per chain: z = dD + L where the "
                           "long link EC is horizontal (C at E's height) and L's two roots "
                           "merge (boundary_L); for bottom chain i the pivot of theta_i's "
                           "quadratic, zero where O A and A F are aligned (|F| = l_OA + l_AF "
                           "stretched, or |F| = |l_OA - l_AF| folded: with Table 1's lengths "
                           "F = O, where theta_i turns without moving F).",
        "det_Jo_platform": "Output singularities: z = dD + L (EC horizontal: H moves along "
                           "Z0 to first order with every actuator locked), and the second "
                           "factor, zero where the links A F and B M are parallel (F moves "
                           "normal to both with theta1, theta2 locked; e.g. theta1 = theta2, "
                           "A = B, where F turns about A).",
        "boundary_L": "x^2 + (y - dy2 - dy1 - lDE)^2 = lEC^2: EC horizontal, the edge of the "
                      "upper chain's reach in (x, y).",
        "boundary_t1": "|F| = l_OA +- l_AF: bottom chain 1 stretched or folded.",
        "boundary_t2": "|F| = l_OB +- l_BM: bottom chain 2 stretched or folded.",
    },
    reading_notes=(
        "The extraction drops every minus sign (the plus signs survive): C = (x, y - dy2, z) "
        "and eq. (7)-(9) are read with minus signs in every gap, e.g. eq. (7) x^2 + (y - dy2 "
        "- dy1 - lDE)^2 + (z - dD - L)^2 = lEC^2; the verification derives them from the "
        "chains.",
        "The parallelogram's transverse links lie along X0 (003 eq. 10: c_z = c_y x X0) and "
        "turn about X0 at E and at C (the torques about the transverse link vanish at both "
        "points, eq. 12): the chain is R_x(J12), the parallelogram (joint axes along c_z), "
        "R_x(J14).  The paper's generalized joints J12-J14 (eq. 3: a revolute about X0 and "
        "two translations) span the same twist system.",
        "Fig. 4-6 are not in the text.  Mode 0 of the IK hangs the parallelogram below E "
        "(z < dD + L) with the bottom elbows A, B outside the rhombus O A F B; the other "
        "branches are the other modes.",
        "With Table 1's lengths lOA = lAF = lOB = lBM, O lies on both circles of F: the "
        "second intersection of the bottom chains is always F = O, where both chains fold "
        "back and theta_1, theta_2 turn without moving F."),
    analyses=(PureTranslation("pure_translation", "platform",
                              title="Pure translation from the ideal (003 Sect. 2.1)"),
              ClosureDimension("mobility", "platform",
                               title="Mobility from the ideal (003 eq. 6)")),
    link_weights=LINK_WEIGHTS,
    checks="bonered_alg.papers.p003_lamina_milling",
    studies=("bonered_alg.studies.workspace_003", "bonered_alg.studies.statics_003"),
    # home: the middle of Table 2's ranges, theta1 = 38.75 deg, theta2 = 141.25 deg, L = 5 mm:
    # x = 0, y = 180 sin(38.75 deg), z from eq. (7) with C below E
    home=(0.0, 112.6662, 52.1958),
    home_joints={L: 5.0, t1: 0.67631, t2: 2.46528},
)
