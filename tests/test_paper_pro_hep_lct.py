"""Pro-Hep-LCT planar chains against the equations printed in 004 (layer 1).

Reference values are the paper's printed equations, transcribed in
``bonered_alg.papers.p004_pro_hep_lct.PRINTED`` (eq. 14, 15, 16, 37).  Where the derivation
disagrees, the test pins the *derived* form and the exact printed discrepancy.
"""

import json

import sympy as sp
from conftest import ROOT

from bonered_alg.mechanisms import pro_hep_lct as m
from bonered_alg.papers import p004_pro_hep_lct as paper
from bonered_alg.papers import study_algebra
from bonered_alg.verification import constant_ratio


def by_ref(verification, ref):
    return [v for v in verification if v.ref == ref]


def test_eq16_generator_1_confirmed(derivation):
    """004 eq. (16), first generator of Gd: equal to the derived chain-1 ideal generator."""
    gens = derivation.leg("D1").result.generators
    assert len(gens) == 1
    assert constant_ratio(paper.PRINTED["eq16"]["D1"], gens[0]) == 1


def test_eq16_generator_2_is_the_d_sign_erratum(derivation, verification):
    """004 eq. (16), second generator: printed = derived with d -> -d (Pd not the midpoint)."""
    (g,) = derivation.leg("D2").result.generators
    printed = paper.PRINTED["eq16"]["D2"]
    assert constant_ratio(printed, g) is None
    assert constant_ratio(printed, g.subs(m.d, -m.d)) == 1
    (v,) = by_ref(verification, "004 eq. (16), generator 2")
    assert v.verdict == "erratum" and "d -> -d" in v.detail


def test_geometric_meaning_of_generator_2(derivation):
    """The derived chain-2 generator is |Pd + (0, d/2) - (0, lq4d) - l3 e(w1)|^2 = l4^2."""
    (g,) = derivation.leg("D2").result.generators
    th = sp.Symbol("th", real=True)
    X, Y = -2 * m.yd1, -2 * m.yd2
    circle = ((X - m.l3 * sp.cos(th)) ** 2 + (Y + m.d / 2 - m.lq4d - m.l3 * sp.sin(th)) ** 2
              - m.l4**2)
    on = {m.w1: sp.tan(th / 2)}
    assert sp.simplify(g.subs(on) * sp.cos(th / 2) ** 2 / 4 - circle) == 0


def test_eq14_pu_drops_dz(derivation, verification):
    """004 eq. (14): the printed Pu has y3 = 0; the product of Table 1 has y3 = -Dz/2."""
    pu = derivation.leg("U").product
    assert sp.expand(pu[7] + m.Dz / 2) == 0
    assert all(sp.expand(sp.sympify(p) - c) == 0 for p, c in zip(paper.PRINTED["eq14"][:7], pu[:7]))
    (v,) = by_ref(verification, "004 eq. (14)")
    assert v.verdict == "erratum"


def test_eq15_components(derivation, verification):
    """004 eq. (15): x0, y1, y2 of chain 1 confirmed (scale -4); x3 has the t1, t2 signs wrong."""
    got = {v.ref: v.verdict for v in verification if v.ref.startswith("004 eq. (15)")}
    assert got == {
        "004 eq. (15), chain 1, x0": "confirmed-symbolic",
        "004 eq. (15), chain 1, x3": "erratum",
        "004 eq. (15), chain 1, y1": "confirmed-symbolic",
        "004 eq. (15), chain 1, y2": "confirmed-symbolic",
        "004 eq. (15), chain 2, x0": "confirmed-symbolic",
        "004 eq. (15), chain 2, x3": "erratum",
        "004 eq. (15), chain 2, y1": "erratum",
        "004 eq. (15), chain 2, y2": "erratum",
    }
    prod = derivation.leg("D1").product
    # derived x3 = t1 + t2 + t3 - t1 t2 t3 (x3/x0 = tan of half the summed angles); the
    # printed 4(t1 t2 t3 + t1 + t2 - t3) has the signs of t1, t2 flipped
    assert sp.expand(prod[3] - (m.t1 + m.t2 + m.t3 - m.t1 * m.t2 * m.t3)) == 0


def test_eq37_upper_input_singularity(derivation, verification):
    (v,) = by_ref(verification, "004 eq. (37)")
    assert v.verdict == "confirmed-symbolic"


def test_lower_boundary_is_links_aligned(derivation):
    """004 eq. (36): the discriminant in t1 vanishes where l1 and l2 are aligned."""
    b = next(s for s in derivation.singularities if s.name == "boundary_t1")
    X, Y = sp.symbols("X Y", real=True)
    radius2 = {(m.l1 + m.l2) ** 2, (m.l1 - m.l2) ** 2}
    found = set()
    for f, _ in b.factors:
        f_xy = sp.expand(f.subs({m.yd1: -X / 2, m.yd2: -Y / 2}))
        for r2 in radius2:
            if constant_ratio(f_xy, X**2 + (Y - m.d / 2) ** 2 - r2) is not None:
                found.add(sp.expand(r2))
    assert found == {sp.expand(r) for r in radius2}


def test_study_eq5_erratum_and_eq13():
    """004 Sect. 2 has its own record: the framework, not a mechanism."""
    got = {v.ref: v for v in study_algebra.algebra_verdicts()}
    assert got["004 eq. (5)"].verdict == "erratum"
    assert got["004 eq. (13)"].verdict == "confirmed-symbolic"
    num = got["004 eq. (4)+(13)"]
    assert num.verdict == "confirmed-numeric" and num.max_error <= 1e-9  # noise: the bound 1e-9
    committed = json.loads((ROOT / "derivations" / "study_algebra.verification.json")
                           .read_text())
    assert [e["ref"] for e in committed] == list(got)


def test_verification_json_schema():
    data = json.loads((ROOT / "derivations" / "pro_hep_lct.verification.json").read_text())
    assert {e["verdict"] for e in data} <= {"confirmed-symbolic", "confirmed-numeric",
                                            "erratum", "not-checkable"}
    for e in data:
        assert set(e) == {"ref", "quantity", "verdict", "max_error", "detail"}
    refs = {e["ref"] for e in data}
    for needed in ("004 eq. (14)", "004 eq. (16), generator 1", "004 eq. (16), generator 2",
                   "004 Table 2, Pd1", "004 Table 1, Pu4"):
        assert needed in refs
    # the Study-parameter framework's verdicts are in their own record, not a mechanism's
    for name in ("pro_hep_lct", "planar_tripod", "tripod_planar", "stewart"):
        data = json.loads((ROOT / "derivations" / f"{name}.verification.json").read_text())
        assert "004 eq. (5)" not in {e["ref"] for e in data}, name
