"""Pro-Hep-LCT (paper 004: Vaida, Pisla et al., Symmetry 11, 1491, 2019) -- planar chains.

This module encodes the two planar mechanisms that position the points ``Pu`` and ``Pd``
(004 Sect. 3.2.1-3.2.2, eq. 14-16, Tables 1-2); the U-P-U mobile platform (eq. 17-18) follows
in a later issue.  It also transcribes the paper's printed results (:data:`PRINTED`) as
reference expressions for the verification section of the report.

Frames and conventions: Study parameters as in :mod:`bonered_alg.algebra.convention`;
both planar mechanisms move parallel to the XY plane; a point ``(X, Y, Z)`` with no rotation
is ``[1:0:0:0:0:-X/2:-Y/2:-Z/2]`` (004 eq. 13).  Units: mm; ``t1, w1`` are the tan-half-angles
of the active revolute joints ``q2, q3`` (004 Table 5 footnote).

Reading of the source text (the extraction is imperfect, see ``shared/seeds/README.md``):

* Table 1 lists ``lq4`` (Pu4) as the translation produced by the active joint ``q4``; eq. (14)
  gives ``lq4 = sqrt(ld4^2 - (q5 - q4)^2)``.  We model this linkage as the polynomial coupling
  ``lq4^2 + (q5 - q4)^2 - ld4^2 = 0`` with ``lq4`` a passive variable that is eliminated.
* Table 2 uses the name ``lq4`` for the base offset of the second lower chain (Pd7), a
  different quantity from Table 1's ``lq4``; it is called ``lq4d`` here.
* Table 2 as extracted lists six factors for the second lower chain but eq. (15) contains
  ``l4``; the chain needs the translation ``l4`` along X between ``w2`` and ``w3`` (a seventh
  row, called Pd11 here; the extraction's Pd11/Pd12 rows are scrambled), exactly mirroring
  the first chain Pd1-Pd6.
* Table 4 (the numeric parameter values) is missing from the source text; no value is
  invented here: :data:`PARAMETERS` holds ``None`` and the generated functions require the
  geometry as keyword arguments until the values are recovered (issue 5).
"""

from __future__ import annotations

import networkx as nx
import sympy as sp

from ..chains.joints import Role
from ..chains.mechanism import Closure, Coupling, Mechanism, Parameter, joint, leg

NAME = "pro_hep_lct"
SOURCE = "004_8bdb7fbbbd93924e.txt (Vaida, Pisla et al., Symmetry 11, 1491, 2019), Sect. 2, 3.1-3.2"

R = {"real": True}
# geometric parameters
Dz, lq5, ld4 = sp.symbols("Dz lq5 ld4", **R)
l1, l2, l3, l4, d, lq4d = sp.symbols("l1 l2 l3 l4 d lq4d", **R)
# joint variables
q4, q5, t1, w1 = sp.symbols("q4 q5 t1 w1", **R)
lq4, t2, t3, w2, w3 = sp.symbols("lq4 t2 t3 w2 w3", **R)
# pose (Study coordinates of the points Pu and Pd)
yu1, yu2, yu3, yd1, yd2 = sp.symbols("yu1 yu2 yu3 yd1 yd2", **R)

PARAMETERS: dict[str, Parameter] = {
    "Dz": Parameter("Dz", None, "mm", "height of the upper planar mechanism (Table 1, Pu1)",
                    "004 Table 4 (missing from the source text)"),
    "lq5": Parameter("lq5", None, "mm", "fixed X offset of the upper chain (Table 1, Pu3)",
                     "004 Table 4 (missing)"),
    "ld4": Parameter("ld4", None, "mm", "length of the rod driven by q4 (eq. 14)",
                     "004 Table 4 (missing)"),
    "l1": Parameter("l1", None, "mm", "first link of lower chain 1 (Table 2, Pd2)",
                    "004 Table 4 (missing)"),
    "l2": Parameter("l2", None, "mm", "second link of lower chain 1 (Table 2, Pd4)",
                    "004 Table 4 (missing)"),
    "l3": Parameter("l3", None, "mm", "first link of lower chain 2 (Table 2, Pd9)",
                    "004 Table 4 (missing)"),
    "l4": Parameter("l4", None, "mm", "second link of lower chain 2 (eq. 15-16)",
                    "004 Table 4 (missing)"),
    "d": Parameter("d", None, "mm", "length of link d; Pd is its midpoint (Table 2, Pd6)",
                   "004 Table 4 (missing)"),
    "lq4d": Parameter("lq4d", None, "mm",
                      "Y offset of the base joint of lower chain 2 (Table 2 Pd7, printed lq4)",
                      "004 Table 4 (missing)"),
}

# user-facing pose: the Cartesian coordinates of Pu and Pd (004 eq. 17, 21), in mm
Xu, Yu, Xd, Yd = sp.symbols("Xu Yu Xd Yd", **R)
POSE = (Xu, Yu, Xd, Yd)
POSE_UNITS = ("mm", "mm", "mm", "mm")
# their Study coordinates, 004 eq. (13) with x = [1:0:0:0]
POSE_TO_STUDY = {yu1: -Xu / 2, yu2: -Yu / 2, yd1: -Xd / 2, yd2: -Yd / 2}
# and back (used by the forward kinematics)
STUDY_TO_POSE = {Xu: -2 * yu1, Yu: -2 * yu2, Xd: -2 * yd1, Yd: -2 * yd2}
JOINTS = (t1, w1, q4, q5)
JOINT_UNITS = ("1 (t1 = tan(q2/2))", "1 (w1 = tan(q3/2))", "mm", "mm")


def _upper_leg(name: str = NAME):
    A, P = Role.ACTIVE, Role.PASSIVE
    return leg(
        "U",
        joint(name, "offset", "Pu1", axis="z", value=Dz, description="geometric; height Dz"),
        joint(name, "prismatic", "Pu2", "y", q5, A, "active q5; translation along OY"),
        joint(name, "offset", "Pu3", axis="x", value=lq5, description="geometric; offset lq5"),
        joint(name, "prismatic", "Pu4", "x", lq4, P,
              "translation lq4 along OX produced by active q4 (eq. 14)"),
    )


def _lower_legs(name: str = NAME):
    A, P = Role.ACTIVE, Role.PASSIVE
    d1 = leg(
        "D1",
        joint(name, "revolute", "Pd1", "z", t1, A, "active q2 = 2 atan(t1)"),
        joint(name, "offset", "Pd2", axis="x", value=l1, description="geometric; link l1"),
        joint(name, "revolute", "Pd3", "z", t2, P, "free"),
        joint(name, "offset", "Pd4", axis="x", value=l2, description="geometric; link l2"),
        joint(name, "revolute", "Pd5", "z", t3, P, "free"),
        joint(name, "offset", "Pd6", axis="y", value=d / 2,
              description="geometric; half of link d, to its midpoint Pd"),
    )
    d2 = leg(
        "D2",
        joint(name, "offset", "Pd7", axis="y", value=lq4d,
              description="geometric; base offset (printed lq4)"),
        joint(name, "revolute", "Pd8", "z", w1, A, "active q3 = 2 atan(w1)"),
        joint(name, "offset", "Pd9", axis="x", value=l3, description="geometric; link l3"),
        joint(name, "revolute", "Pd10", "z", w2, P, "free"),
        joint(name, "offset", "Pd11", axis="x", value=l4,
              description="geometric; link l4 (row reconstructed, see module docstring)"),
        joint(name, "revolute", "Pd12", "z", w3, P, "free"),
        joint(name, "offset", "Pd13", axis="y", value=-d / 2,
              description="geometric; back along link d to its midpoint Pd"),
    )
    return d1, d2


def _topology() -> nx.MultiGraph:
    g = nx.MultiGraph()
    # upper planar mechanism (Table 1 and eq. 14): two sliders along Y, a rod of length ld4
    g.add_edge("base", "slider_q5", joint="prismatic", label="q5")
    g.add_edge("base", "slider_q4", joint="prismatic", label="q4")
    g.add_edge("slider_q5", "carriage_Pu", joint="prismatic", label="lq4")
    g.add_edge("slider_q4", "rod_ld4", joint="revolute", label="rod base")
    g.add_edge("rod_ld4", "carriage_Pu", joint="revolute", label="rod end")
    # lower RRR-RRR planar mechanism (Table 2)
    for a, b, lab in [("base", "link_l1", "t1"), ("link_l1", "link_l2", "t2"),
                      ("link_l2", "link_d", "t3"), ("base", "link_l3", "w1"),
                      ("link_l3", "link_l4", "w2"), ("link_l4", "link_d", "w3")]:
        g.add_edge(a, b, joint="revolute", label=lab)
    return g


def build() -> Mechanism:
    """The Pro-Hep-LCT planar chains as a :class:`Mechanism` (004 Sect. 3.2.1-3.2.2)."""
    upper = Closure(
        name="upper planar mechanism", point="Pu", legs=(_upper_leg(),),
        platform=(1, 0, 0, 0, 0, yu1, yu2, yu3), pose=(yu1, yu2, yu3),
        couplings=(Coupling(lq4**2 + (q5 - q4) ** 2 - ld4**2,
                            "rod of length ld4 between slider q4 and the carriage",
                            "004 eq. (14): lq4 = sqrt(ld4^2 - (q5 - q4)^2)"),),
        note="Pu has no rotation: x = [1:0:0:0].",
    )
    d1, d2 = _lower_legs()
    lower = Closure(
        name="lower planar mechanism", point="Pd", legs=(d1, d2),
        platform=(1, 0, 0, 0, 0, yd1, yd2, 0), pose=(yd1, yd2),
        note="Link d keeps its orientation (parallelograms Par1, Par2): x0 = 1, x3 = 0 (004 "
             "Sect. 3.2.2).",
    )
    return Mechanism(
        name=NAME,
        title="Pro-Hep-LCT planar chains",
        source=SOURCE,
        parameters=dict(PARAMETERS),
        active=(t1, w1, q4, q5),
        passive=(lq4, t2, t3, w2, w3),
        closures=(upper, lower),
        topology=_topology(),
        planar=True,
        extra_constraints=1,
        extra_constraints_note="the parallelograms Par1, Par2 keep link d's orientation "
        "constant (x3 = 0), removing one degree of freedom of the six-bar",
    )


# ------------------------------------------------------------------ printed results of 004
lq3_printed, q4_printed = sp.symbols("lq3 q4", **R)


def _printed_eq15():
    """004 eq. (15) as printed (x0, x3, y1, y2 of both chains; the second chain's y2 is
    printed with the label 'y1').  Symbols printed as ``lq3`` and ``q4`` in the second chain
    are kept literally; ``lq4`` there is Table 2's base offset (``lq4d`` here)."""
    c1 = {
        "x0": 4 * (t1 * t2 + t1 * t3 + t2 * t3 - 1),
        "x3": 4 * (t1 * t2 * t3 + t1 + t2 - t3),
        "y1": t1 * t2 * (d * t3 + 2 * l1 - 2 * l2) + t1 * t3 * (2 * l1 + 2 * l2)
        + t2 * t3 * (-2 * l1 + 2 * l2) - d * (t1 + t2 + t3) + 2 * (l1 + l2),
        "y2": 2 * t1 * t2 * t3 * (l2 - l1) - d * (t1 * t2 + t2 * t3 + t1 * t3)
        + 2 * l1 * (t1 - t2 - t3) + 2 * l2 * (t1 + t2 - t3) + d,
    }
    c2 = {
        "x0": 4 * (w1 * w2 + w1 * w3 + w2 * w3 - 1),
        "x3": 4 * (w1 * w2 * w3 + w1 + w2 - w3),
        "y1": w1 * w2 * w3 * (d + 2 * lq3_printed) + 2 * w1 * w2 * (l3 - l4)
        + 2 * w1 * w3 * (l3 + l4) + 2 * w2 * w3 * (-l3 + l4) - d * (w1 + w2 + w3)
        + 2 * lq4d * (w1 + w2 + w3) + 2 * (l3 + l4),
        "y2": w1 * w2 * w3 * (2 * l4 - 2 * l3) - w1 * w2 * (d + 2 * lq4d)
        - w1 * w3 * (d + 2 * lq4d) - 2 * w2 * w3 * (d + 2 * lq4d) + l3 * (w1 - w2 - w3)
        + 2 * l4 * (w1 + w2 - w3) + d + 2 * q4_printed,
    }
    return {"D1": c1, "D2": c2}


PRINTED = {
    # 004 eq. (14): Pu = [1:0:0:0:0:-(lq5+lq4)/2:-q5/2:0], lq4 = sqrt(ld4^2-(q5-q4)^2)
    "eq14": (1, 0, 0, 0, 0, -(lq5 + lq4) / 2, -q5 / 2, 0),
    "eq14_lq4": sp.sqrt(ld4**2 - (q5 - q4) ** 2),
    "eq15": _printed_eq15(),
    # 004 eq. (16), the two generators of Gd, in the Study coordinates (y1, y2) of Pd
    "eq16": {
        "D1": 16 * (t1**2 + 1) * yd1**2 - 16 * l1 * (t1**2 - 1) * yd1 + 16 * (t1**2 + 1) * yd2**2
        + 8 * (d * t1**2 + 4 * l1 * t1 + d) * yd2 + (d**2 + 4 * l1**2 - 4 * l2**2) * t1**2
        + 8 * d * l1 * t1 + d**2 + 4 * (l1**2 - l2**2),
        "D2": 16 * (w1**2 + 1) * yd1**2 - 16 * l3 * (w1**2 - 1) * yd1 + 16 * (w1**2 + 1) * yd2**2
        + 8 * ((2 * lq4d + d) * w1**2 + 4 * l3 * w1 + 2 * lq4d + d) * yd2
        + (d**2 + 4 * (d * lq4d + l3**2 - l4**2 + lq4d**2)) * w1**2
        + 8 * l3 * (d + 2 * lq4d) * w1 + d**2 + 4 * (d * lq4d + l3**2 - l4**2 + lq4d**2),
    },
    # 004 eq. (37): input singularity of the upper mechanism
    "eq37": (q4 - q5) / sp.sqrt((q4 - q5 + ld4) * (-q4 + q5 + ld4)),
}


# ------------------------------------------------------------------ verification against 004
def verify(deriv) -> list:
    """Verdicts for 004 eq. (14)-(16), (19), (37) and Tables 1-2 (DESIGN.md section 5)."""
    from ..verification import Verdict, constant_ratio, in_ideal, term_difference

    out: list[Verdict] = []
    names = ["x0", "x1", "x2", "x3", "y0", "y1", "y2", "y3"]

    # Tables 1-2: the rows are the input of the derivation
    for r in deriv.legs:
        table = "Table 1" if r.closure.point == "Pu" else "Table 2"
        for f in r.leg.factors:
            recon = "reconstructed" in f.description
            out.append(Verdict(
                f"004 {table}, {f.label}", f"{f.role.value} factor: {f.motion()}",
                "not-checkable", None,
                ("row reconstructed from eq. (15)-(16): the extracted table omits it; "
                 if recon else "input of the derivation; ")
                + "[" + ":".join(sp.sstr(c) for c in f.study()) + "]"))

    # eq. (14): Pu = Pu1 Pu2 Pu3 Pu4
    pu = deriv.leg("U").product
    printed = PRINTED["eq14"]
    diffs = [(n, sp.sstr(p), sp.sstr(c)) for n, p, c in zip(names, printed, pu)
             if sp.expand(sp.sympify(p) - c) != 0]
    out.append(Verdict(
        "004 eq. (14)", "Pu = Pu1 Pu2 Pu3 Pu4 (upper chain, Table 1)",
        "erratum" if diffs else "confirmed-symbolic", None,
        ("printed " + "; ".join(f"{n} = {p}, product of Table 1 gives {n} = {c}"
                                 for n, p, c in diffs)
         + ": the printed Pu drops the translation Pu1 by Dz along OZ (Pu lies in the plane "
         "Z = Dz, which the mobile platform of eq. 17 uses as P5 = [..:-Dz/2])")
        if diffs else "the product of Table 1 equals the printed Pu",
        evidence=r"P_{u1}P_{u2}P_{u3}P_{u4} = [" + ":".join(sp.latex(c) for c in pu) + "]"))
    ubasis = deriv.leg("U").result
    coupling_ok = in_ideal(
        (lq5 + 2 * yu1) ** 2 - (ld4**2 - (q5 - q4) ** 2), ubasis.generators, ubasis.problem.keep)
    out.append(Verdict(
        "004 eq. (14), lq4", "lq4 = sqrt(ld4^2 - (q5 - q4)^2)",
        "confirmed-symbolic" if coupling_ok else "erratum", None,
        "with -2 yu1 = lq5 + lq4 (the X coordinate of Pu) the squared relation lies in the "
        "upper ideal; the sign of the square root (lq4 >= 0) is one of the two working modes "
        "of the upper mechanism"))

    # eq. (15): both lower chains, component by component (projectively)
    for legname in ("D1", "D2"):
        prod = deriv.leg(legname).product
        pr = PRINTED["eq15"][legname]
        lam = constant_ratio(pr["x0"], prod[0])
        for comp in ("x0", "x3", "y1", "y2"):
            derived = prod[names.index(comp)]
            ref = f"004 eq. (15), chain {legname[-1]}, {comp}"
            if lam is None:
                out.append(Verdict(ref, f"{comp} of Pd", "erratum", None,
                                   "printed x0 is not a constant multiple of the product's "
                                   f"x0 = {sp.sstr(derived)}"))
                continue
            diff = sp.expand(pr[comp] - lam * derived)
            extra = sorted(map(str, sp.sympify(pr[comp]).free_symbols
                               - deriv.mechanism.declared()))
            if diff == 0:
                out.append(Verdict(ref, f"{comp} of Pd", "confirmed-symbolic", None,
                                   f"printed = {sp.sstr(lam)} * (product of Table 2)"))
            else:
                flipped = sp.expand(pr[comp] - lam * derived.subs(d, -d))
                hint = ""
                if legname == "D2" and comp.startswith("y") and flipped != diff:
                    hint = ("; with d -> -d in the derived product (Pd at +d/2 from the last "
                            "joint, the reading eq. 16 also implies) the difference becomes "
                            f"{sp.sstr(sp.factor(flipped))}")
                out.append(Verdict(
                    ref, f"{comp} of Pd", "erratum", None,
                    f"with the scale {sp.sstr(lam)} fixed by x0, printed - scale*derived = "
                    f"{sp.sstr(sp.factor(diff))}; derived {comp} = "
                    f"{sp.sstr(sp.factor(lam * derived))}"
                    + (f"; the printed form uses symbols {extra} that the chain does not have"
                       if extra else "") + hint,
                    evidence=sp.latex(sp.factor(diff))))
    # x0 = 1, x3 = 0 on the closure: Pd moves in a plane with 2 degrees of freedom per leg
    for legname in ("D1", "D2"):
        res = deriv.leg(legname).result
        ngeo = sum(1 for s in res.problem.keep if s in set(deriv.mechanism.geometric))
        free = res.dimension - ngeo
        out.append(Verdict(
            "004 Sect. 3.2.2", f"chain {legname[-1]} with x0 = 1, x3 = 0: Pd moves in a plane",
            "confirmed-symbolic" if free == 2 else "erratum", None,
            f"Hilbert dimension of the chain's elimination ideal = {res.dimension} = "
            f"{ngeo} geometric parameters + {free} (the pose (y1, y2) of Pd is free and the "
            "active joint follows from it)"))

    # eq. (16): the generators of Gd
    for legname in ("D1", "D2"):
        res = deriv.leg(legname).result
        gens = res.generators
        pr = PRINTED["eq16"][legname]
        keep = res.problem.keep
        ref = f"004 eq. (16), generator {legname[-1]}"
        match = [g for g in gens if constant_ratio(pr, g) is not None]
        member = in_ideal(pr, gens, keep)
        if match:
            out.append(Verdict(ref, f"Gd generator of chain {legname[-1]}", "confirmed-symbolic",
                               None, f"printed = {sp.sstr(constant_ratio(pr, match[0]))} * "
                               "derived generator (the elimination ideal is principal)"))
            continue
        diff = term_difference(pr, gens[0], keep)
        detail = (f"not a multiple of the derived generator and {'' if member else 'not '}"
                  f"in the elimination ideal; printed - lambda*derived = {sp.sstr(diff)}")
        if legname == "D2" and constant_ratio(pr, gens[0].subs(d, -d)) is not None:
            detail += (". The printed generator is exactly the derived one with d -> -d, i.e. "
                       "Pd placed at +d/2 from the last joint of chain 2; with Table 2's last "
                       "factor [..:d/4:..] (translation -d/2), Pd is the midpoint of link d "
                       "only with the derived sign; the printed sign would put both ends of "
                       "link d at the same point. Corrected generator: "
                       + sp.sstr(sp.factor(gens[0])))
        out.append(Verdict(ref, f"Gd generator of chain {legname[-1]}", "erratum", None, detail,
                           evidence=sp.latex(diff)))

    # eq. (19)/(20): Ji,2 printed as d(Gu)/d(q4,q5)
    gd = [g for r in (deriv.leg("D1"), deriv.leg("D2")) for g in r.result.generators]
    wrong = sp.Matrix(gd).jacobian(sp.Matrix([q4, q5]))
    right = sp.Matrix(gd).jacobian(sp.Matrix([t1, w1]))
    out.append(Verdict(
        "004 eq. (20)", "Ji,2 of the lower mechanism",
        "erratum" if wrong.is_zero_matrix and not right.is_zero_matrix else "not-checkable",
        None,
        "printed Ji,2 = d(Gu[1],Gu[2])/d(q4,q5) repeats Ji,1; with qd = [t1, w1] (as printed "
        "in the same equation) it must be d(Gd[1],Gd[2])/d(t1,w1): d(Gd)/d(q4,q5) is the zero "
        "matrix, which would make the lower mechanism singular everywhere"))

    # Sect. 3.4: working modes (IK branches) of the two planar mechanisms
    branches = {}
    for st in deriv.steps:
        point = "Pu" if st.joint in (q4, q5) else "Pd"
        branches[point] = branches.get(point, 1) * st.branches
    ok34 = branches == {"Pu": 2, "Pd": 4}
    out.append(Verdict(
        "004 Sect. 3.4", "four working modes of the lower, two of the upper planar mechanism",
        "confirmed-symbolic" if ok34 else "erratum", None,
        f"IK branches from the ideals: upper {branches.get('Pu')}, lower {branches.get('Pd')} "
        "(one quadratic generator per RRR chain, one for the rod ld4); the forward kinematics "
        "has " + " x ".join(str(f.solutions) for f in deriv.fk) + " assembly modes"))

    # eq. (37): input singularity of the upper mechanism
    det_u = next(s for s in deriv.singularities if s.name == "det_Ji_Pu")
    facs = [f for f, _ in det_u.factors]
    ok37 = len(facs) == 1 and constant_ratio(q4 - q5, facs[0]) is not None
    out.append(Verdict(
        "004 eq. (37)", "sg16, input singularity of the upper mechanism",
        "confirmed-symbolic" if ok37 else "erratum", None,
        f"det Ji,1 = {sp.sstr(sp.factor(det_u.expression))}; printed sg16 = (q4 - q5)/lq4 "
        "with lq4 = sqrt((q4-q5+ld4)(-q4+q5+ld4)) > 0 inside the workspace, so the zero sets "
        "agree: q4 = q5 (the rod ld4 parallel to OX)"))
    return out


# interpretation of the singularity polynomials (checked in tests/test_singularities_pro_hep_lct.py)
SINGULARITY_NOTES = {
    "det_Ji_Pu": "Input singularity q4 = q5: the rod ld4 is parallel to OX, the carriage is at "
                 "its largest reach Xu = lq5 + ld4 and the two modes of q4 merge (004 eq. 37, "
                 "sg16; the paper's form divides by lq4).",
    "det_Jo_Pu": "Output singularity lq5 + 2 yu1 = 0, i.e. Xu = lq5 and lq4 = 0: the rod lies "
                 "along OY, so the carriage can move along OX to first order with q4 and q5 "
                 "locked. Not listed in the paper's sg1-sg16.",
    "boundary_q4": "Same locus as det_Ji_Pu seen from the pose side: (Xu - lq5)^2 = ld4^2.",
    "det_Ji_Pd": "Input singularities of the lower mechanism: one factor per chain, vanishing "
                 "where l1 and l2 (resp. l3 and l4) are aligned, the boundary of that chain's "
                 "reach (004 eq. 36, Fig. 3c).",
    "det_Jo_Pd": "Output singularity of the lower mechanism: vanishes where the links l2 and l4 "
                 "are parallel, where link d (kept at constant orientation) can translate with "
                 "t1 and w1 locked: the self-motion of 004 Fig. 3b (which the paper attributes "
                 "to its input polynomial eq. 34).",
    "boundary_t1": "Circles |Pd - (0, d/2)| = l1 +- l2: chain 1 stretched or folded (004 eq. 36).",
    "boundary_w1": "Circles |Pd + (0, d/2) - (0, lq4d)| = l3 +- l4: chain 2 stretched or folded "
                   "(004 eq. 36).",
}
