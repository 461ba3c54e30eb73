"""Pro-Hep-LCT (paper 004: Vaida, Pisla et al., Symmetry 11, 1491, 2019).

Two planar mechanisms position the points ``Pu`` and ``Pd`` (004 Sect. 3.2.1-3.2.2, eq.
14-16, Tables 1-2); the U-P-U mobile platform (eq. 17-18, Table 3) is a closure driven by
them, in the chart ``|x|^2 = 1``, with its two chains mounted on ``Pd`` and ``Pu``.  The
printed equations are checked in :mod:`bonered_alg.papers.p004_pro_hep_lct`; Table 5, the
RCM deviation and the workspace in :mod:`bonered_alg.studies`; the tool's numeric side
(tool IK with the redundant insertion ``n``, FK of the whole robot) is
:mod:`bonered_alg.surgical.pro_hep_lct_tool`.  A point ``(X, Y, Z)`` with no rotation is
``[1:0:0:0:0:-X/2:-Y/2:-Z/2]`` (004 eq. 13); ``t1, w1`` are the tan-half-angles of the
active revolute joints ``q2, q3`` (004 Table 5 footnote); mm.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import study_symbolic as ss
from ..analyses.input_space import InputSpaceSingularities
from ..analyses.solution_counts import SolutionCounts
from ..declaration import (
    Closure,
    Coupling,
    Parameter,
    PoseMap,
    Role,
    UnitRotation,
    declare,
    joint,
    leg,
)

NAME = "pro_hep_lct"
R = {"real": True}
Dz, lq5, ld4 = sp.symbols("Dz lq5 ld4", **R)
l1, l2, l3, l4, d, lq4d = sp.symbols("l1 l2 l3 l4 d lq4d", **R)
c_off, Dn = sp.symbols("c Dn", **R)
q4, q5, t1, w1 = sp.symbols("q4 q5 t1 w1", **R)  # actuated
lq4, t2, t3, w2, w3 = sp.symbols("lq4 t2 t3 w2 w3", **R)  # passive, planar mechanisms
u1, u2, v1, v2, p_free = sp.symbols("u1 u2 v1 v2 p", **R)  # passive, mobile platform
yu1, yu2, yu3, yd1, yd2 = sp.symbols("yu1 yu2 yu3 yd1 yd2", **R)  # Study coords of Pu, Pd
PX = sp.symbols("x0:4", **R) + sp.symbols("y0:4", **R)  # the platform's Study point
Xu, Yu, Xd, Yd = sp.symbols("Xu Yu Xd Yd", **R)  # the pose: Pu and Pd in mm (eq. 17, 21)
A, P = Role.ACTIVE, Role.PASSIVE

_FIT = ("recovered from 004 Table 5: least-squares fit of the lower mechanism's two dyads to the "
        "printed t1, w1 of all 13 rows but B 5 deg (t1) and B 10 deg (w1), four equal links "
        "(a free fit gives 168.0 +- 0.06 for all four); max residual 0.027 mm "
        "(tests/test_pro_hep_lct_platform.py::test_geometry_recovered_from_table5)")

UPPER = leg(  # Table 1, eq. (14)
    "U",
    joint(NAME, "offset", "Pu1", axis="z", value=Dz, description="geometric; height Dz"),
    joint(NAME, "prismatic", "Pu2", "y", q5, A, "active q5; translation along OY"),
    joint(NAME, "offset", "Pu3", axis="x", value=lq5, description="geometric; offset lq5"),
    joint(NAME, "prismatic", "Pu4", "x", lq4, P,
          "translation lq4 along OX produced by active q4 (eq. 14)"))
LOWER = (  # Table 2, eq. (15)
    leg("D1",
        joint(NAME, "revolute", "Pd1", "z", t1, A, "active q2 = 2 atan(t1)"),
        joint(NAME, "offset", "Pd2", axis="x", value=l1, description="geometric; link l1"),
        joint(NAME, "revolute", "Pd3", "z", t2, P, "free"),
        joint(NAME, "offset", "Pd4", axis="x", value=l2, description="geometric; link l2"),
        joint(NAME, "revolute", "Pd5", "z", t3, P, "free"),
        joint(NAME, "offset", "Pd6", axis="y", value=d / 2,
              description="geometric; half of link d, to its midpoint Pd")),
    leg("D2",
        joint(NAME, "offset", "Pd7", axis="y", value=lq4d,
              description="geometric; base offset (printed lq4)"),
        joint(NAME, "revolute", "Pd8", "z", w1, A, "active q3 = 2 atan(w1)"),
        joint(NAME, "offset", "Pd9", axis="x", value=l3, description="geometric; link l3"),
        joint(NAME, "revolute", "Pd10", "z", w2, P, "free"),
        joint(NAME, "offset", "Pd11", axis="x", value=l4,
              description="geometric; link l4 (row reconstructed, see the reading notes)"),
        joint(NAME, "revolute", "Pd12", "z", w3, P, "free"),
        joint(NAME, "offset", "Pd13", axis="y", value=-d / 2,
              description="geometric; back along link d to its midpoint Pd")))
# Table 3 as read here (eq. 17): chain 1 from the lower universal joint Ud = Pd + (c, 0, 0),
# chain 2 from the upper one Uu = (Xu, Yu, Dz).  Table 3 prints P1 = [..:(Xd+c)/2:Yd/2:0], a
# translation by -(Xd + c, Yd, 0) in 004's own convention (eq. 5); eq. (17) and Table 5
# need +(Xd + c, Yd, 0).  P2/P3 are the two axes of a universal joint (X then Y; the
# extracted table names OY, OZ), P8 the free prismatic joint along the tool axis.
PLATFORM = (
    leg("1",
        joint(NAME, "universal", "Ud", ("x", "y"), (u1, u2), P,
              "free; universal joint Ud (P2, P3)"),
        joint(NAME, "offset", "P4", axis="z", value=-Dn, description="geometric; -Dn along Z'"),
        base="Pd", mount=ss.translation_vector((Xd + c_off, Yd, 0))),
    leg("2",
        joint(NAME, "universal", "Uu", ("x", "y"), (v1, v2), P,
              "free; universal joint Uu (P6, P7)"),
        joint(NAME, "prismatic", "P8", "z", -p_free, P, "free prismatic joint p along -Z'"),
        base="Pu", mount=ss.translation_vector((Xu, Yu, Dz))),
)
# configurations at which the solution count of G is computed exactly (Groebner basis over Q)
_GEO = {Dz: 108, c_off: sp.Rational(6091, 100), Dn: 110}
_VERT = 300 - sp.Rational(6091, 100)
PLATFORM_CONFIGS = {
    "generic": {Xu: 317, Yu: 191, Xd: 233, Yd: 172, **_GEO},
    "tool vertical (sg7 and sg8: Yd = Yu, Xd + c = Xu)": {Xu: 300, Yu: 180, Xd: _VERT, Yd: 180,
                                                          **_GEO},
    "sg7 only (Yd = Yu)": {Xu: 317, Yu: 180, Xd: 233, Yd: 180, **_GEO},
    "sg8 only (Xd - Xu + c = 0)": {Xu: 300, Yu: 191, Xd: _VERT, Yd: 172, **_GEO},
    "sg9 (Dz = 0)": {Xu: 317, Yu: 191, Xd: 233, Yd: 172, **_GEO, Dz: 0},
    "Dz = 0 and Uu = Ud": {Xu: 300, Yu: 180, Xd: _VERT, Yd: 180, **_GEO, Dz: 0},
}

MECHANISM = declare(
    name=NAME,
    title="Pro-Hep-LCT",
    source="004_8bdb7fbbbd93924e.txt (Vaida, Pisla et al., Symmetry 11, 1491, 2019), Sect. 2, "
           "3.1-3.2",
    summary="The two planar mechanisms that position the points Pu and Pd (004 Sect. "
            "3.2.1-3.2.2, eq. 14-16, Tables 1-2) are the actuated closures (IK, FK, Jacobians "
            "and singularities are generated from them); the U-P-U mobile platform (eq. 17-18, "
            "Table 3) is a closure they drive, whose ideal G is generated as functions.",
    parameters=(
        Parameter("Dz", 108.0, "mm", "height of the upper planar mechanism (Table 1, Pu1)",
                  "recovered from 004 Table 5 path A: q5 = Yu = 180 + (Dz + Dn) tan(phi), "
                  "rows A 5-30 deg give Dz + Dn = 218.00 (004 Table 4 is missing)",
                  domain="positive"),
        Parameter("lq5", 284.0, "mm", "fixed X offset of the upper chain (Table 1, Pu3)",
                  "recovered from 004 Table 5: Xu = lq5 + lq4 = 300 at O with lq4 = 16"),
        Parameter("ld4", 160.0, "mm", "length of the rod driven by q4 (eq. 14)",
                  "recovered from 004 Table 5 path B: q4 with (q5 - q4)^2 + lq4^2 = ld4^2 "
                  "and Xu = 300 + 218 tan(theta) gives lq4(O) = 16.0, ld4 = 160.0",
                  domain="positive"),
        Parameter("l1", 168.05, "mm", "first link of lower chain 1 (Table 2, Pd2)", _FIT,
                  domain="positive"),
        Parameter("l2", 168.05, "mm", "second link of lower chain 1 (Table 2, Pd4)", _FIT,
                  domain="positive"),
        Parameter("l3", 168.05, "mm", "first link of lower chain 2 (Table 2, Pd9)", _FIT,
                  domain="positive"),
        Parameter("l4", 168.05, "mm", "second link of lower chain 2 (eq. 15-16)", _FIT,
                  domain="positive"),
        Parameter("d", 149.94, "mm", "length of link d; Pd is its midpoint (Table 2, Pd6)",
                  _FIT, domain="positive"),
        Parameter("lq4d", 400.0, "mm",
                  "Y offset of the base joint of lower chain 2 (Table 2 Pd7, printed lq4)", _FIT),
        Parameter("c", 60.91, "mm", "X offset of the lower universal joint from Pd (Table 3, "
                  "P1: Ud = (Xd + c, Yd, 0))", _FIT),
        Parameter("Dn", 110.0, "mm", "distance from the lower universal joint to the platform "
                  "frame along -Z' (Table 3, P4)",
                  "recovered from 004 Sect. 4 / Table 5: O = [1:0:0:0:0:-150:-90:55] is 110 mm "
                  "below the plane of Pd, and n = 110/cos(angle) - 10 on both paths",
                  domain="positive")),
    joints=(t1, w1, q4, q5),
    joint_units=("1 (t1 = tan(q2/2))", "1 (w1 = tan(q3/2))", "mm", "mm"),
    closures=(
        Closure("upper planar mechanism", "Pu", (UPPER,), (1, 0, 0, 0, 0, yu1, yu2, yu3),
                (yu1, yu2, yu3), motion="planar", note="Pu has no rotation: x = [1:0:0:0].",
                couplings=(Coupling(
                    lq4**2 + (q5 - q4) ** 2 - ld4**2,
                    "rod of length ld4 between slider q4 and the carriage",
                    "004 eq. (14): lq4 = sqrt(ld4^2 - (q5 - q4)^2)",
                    linkage=(("base", "slider_q4", "prismatic", "q4"),
                             ("slider_q4", "rod_ld4", "revolute", "rod base"),
                             ("rod_ld4", "Pu", "revolute", "rod end"))),)),
        Closure("lower planar mechanism", "Pd", LOWER, (1, 0, 0, 0, 0, yd1, yd2, 0),
                (yd1, yd2), motion="planar", extra_constraints=1,
                constraints_note="the parallelograms Par1, Par2 keep link d's orientation "
                                 "constant (x3 = 0), removing one degree of freedom of the "
                                 "six-bar",
                note="Link d keeps its orientation (parallelograms Par1, Par2): x0 = 1, x3 = 0 "
                     "(004 Sect. 3.2.2)."),
        Closure("mobile platform", "platform", PLATFORM, PX, PX, chart=UnitRotation(),
                inputs=(Xu, Yu, Xd, Yd), source="004 eq. 17-18, 21",
                note="The platform frame in the base frame, |x|^2 = 1 (004 eq. 2): chain 1 "
                     "T(Ud) Rx(u1) Ry(u2) Tz(-Dn), chain 2 T(Uu) Rx(v1) Ry(v2) Tz(-p)."),
    ),
    pose=PoseMap((Xu, Yu, Xd, Yd), ("mm",) * 4,
                 {yu1: -Xu / 2, yu2: -Yu / 2, yd1: -Xd / 2, yd2: -Yd / 2},
                 from_study={Xu: -2 * yu1, Yu: -2 * yu2, Xd: -2 * yd1, Yd: -2 * yd2}),
    analyses=(
        SolutionCounts("G_counts", "platform", PLATFORM_CONFIGS,
                       title="Mobile platform: solution counts of G (004 eq. 18, 28-31)"),
        InputSpaceSingularities("input_space_singularities", "Pd", ("det_Jo_Pd", "det_Ji_Pd")),
    ),
    singularity_notes={
        "det_Ji_Pu": "Input singularity q4 = q5: the rod ld4 is parallel to OX, the carriage "
                     "is at its largest reach Xu = lq5 + ld4 and the two modes of q4 merge "
                     "(004 eq. 37, sg16; the paper's form divides by lq4).",
        "det_Jo_Pu": "Output singularity lq5 + 2 yu1 = 0, i.e. Xu = lq5 and lq4 = 0: the rod "
                     "lies along OY, so the carriage can move along OX to first order with q4 "
                     "and q5 locked. Not listed in the paper's sg1-sg16.",
        "boundary_q4": "Same locus as det_Ji_Pu seen from the pose side: (Xu - lq5)^2 = ld4^2.",
        "det_Ji_Pd": "Input singularities of the lower mechanism: one factor per chain, "
                     "vanishing where l1 and l2 (resp. l3 and l4) are aligned, the boundary of "
                     "that chain's reach (004 eq. 36, Fig. 3c).",
        "det_Jo_Pd": "Output singularity of the lower mechanism: vanishes where the links l2 "
                     "and l4 are parallel, where link d (kept at constant orientation) can "
                     "translate with t1 and w1 locked: the self-motion of 004 Fig. 3b (which "
                     "the paper attributes to its input polynomial eq. 34).",
        "boundary_t1": "Circles |Pd - (0, d/2)| = l1 +- l2: chain 1 stretched or folded "
                       "(004 eq. 36).",
        "boundary_w1": "Circles |Pd + (0, d/2) - (0, lq4d)| = l3 +- l4: chain 2 stretched or "
                       "folded (004 eq. 36).",
    },
    reading_notes=(
        "Table 1 lists lq4 (Pu4) as the translation produced by the active joint q4; eq. (14) "
        "gives lq4 = sqrt(ld4^2 - (q5 - q4)^2). We model this linkage as the polynomial "
        "coupling lq4^2 + (q5 - q4)^2 - ld4^2 = 0 with lq4 a passive variable that is "
        "eliminated.",
        "Table 2 uses the name lq4 for the base offset of the second lower chain (Pd7), a "
        "different quantity from Table 1's lq4; it is called lq4d here.",
        "Table 2 as extracted lists six factors for the second lower chain but eq. (15) "
        "contains l4; the chain needs the translation l4 along X between w2 and w3 (a seventh "
        "row, called Pd11 here; the extraction's Pd11/Pd12 rows are scrambled), exactly "
        "mirroring the first chain Pd1-Pd6.",
        "Table 4 (the numeric parameter values) is missing from the source text. The values "
        "are recovered from the printed Table 5 (each with its derivation in its source); "
        "nothing is taken from elsewhere.",
        "Table 3's P1 is read with the opposite sign (see the verification), and the mobile "
        "platform's chains are eliminated in the frames of their first factors, the "
        "translations to the universal joints Ud and Uu."),
    checks="bonered_alg.papers.p004_pro_hep_lct",
    studies=("bonered_alg.studies.rcm_paths_004", "bonered_alg.studies.workspace_004"),
    # home: the tool vertical at the entry point O of 004 Sect. 4; the physical branch is
    # the paper's working mode, the joints of Table 5 row O (t1, w1, q4; q5 is linear)
    home=(300.0, 180.0, 239.09, 180.0),
    home_joints={t1: -0.1343, w1: 0.0214, q4: 20.802},
)
