"""The two Groebner engines give the same normalized reduced basis (DESIGN.md section 6),
on every leg of the pilot with symbolic geometry and on the lower legs with numeric geometry."""

import pytest
import sympy as sp

from bonered_alg.elimination.closure import leg_problem
from bonered_alg.elimination.engines import SingularEngine, SympyEngine
from bonered_alg.elimination.polyterms import dimension_from_leading_monomials
from bonered_alg.elimination.problem import EliminationProblem
from bonered_alg.mechanisms import planar_tripod
from bonered_alg.mechanisms import pro_hep_lct as MOD

pytestmark = pytest.mark.skipif(not SingularEngine().available(), reason="Singular missing")

MECH = MOD.MECHANISM


def problems():
    upper, lower, platform = MECH.closures
    yield leg_problem(MECH, platform, platform.legs[0])  # a mounted leg, chart |x|^2 = 1
    yield leg_problem(MECH, upper, upper.legs[0])
    for leg in lower.legs:
        yield leg_problem(MECH, lower, leg)
    vals = {MOD.l1: 180, MOD.l2: 160, MOD.d: 60, MOD.l3: 170, MOD.l4: 150, MOD.lq4d: 250}
    for leg in lower.legs:
        p = leg_problem(MECH, lower, leg)
        yield EliminationProblem(p.context + " (numeric geometry)",
                                 tuple(sp.expand(e.subs(vals)) for e in p.equations),
                                 p.eliminate, tuple(s for s in p.keep if s not in vals))


@pytest.mark.parametrize("problem", list(problems()), ids=lambda p: p.context[-40:])
def test_sympy_and_singular_agree(problem):
    a = SympyEngine().eliminate(problem, 120)
    b = SingularEngine().eliminate(problem, 120)
    assert a == b
    assert len(a) >= 1


def test_dimension_matches_singular():
    """Our dimension from leading monomials vs. Singular's dim() on the same basis."""
    import subprocess

    x, y, z = sp.symbols("x y z")
    cases = [([x * y, x * z], 3, 2), ([x**2, y**3], 3, 1), ([sp.Integer(1)], 3, -1)]
    for gens, n, expected in cases:
        lms = [sp.Poly(g, x, y, z).monoms()[0] for g in gens]
        ours = dimension_from_leading_monomials(lms, n)
        script = f"ring r=0,(x,y,z),dp; print(dim(std(ideal({','.join(map(str, gens))}))));quit;"
        out = subprocess.run(["Singular", "-q", "--no-rc"], input=script, capture_output=True,
                             text=True, timeout=30).stdout.split()
        assert ours == expected == int(out[0])


def test_lex_bases_agree(derivation):
    """The forward-kinematics lex bases over Q(joints, geometry) agree between engines."""
    assert derivation.fk, "forward kinematics was derived"
    for f in derivation.fk:
        assert SympyEngine().lex_basis(f.problem, 120) == SingularEngine().lex_basis(
            f.problem, 120)


def test_algebraic_constant_runs_over_the_extension_field():
    """A kept constant with an irreducible minimal polynomial (s3^2 = 3) is handed to
    Singular as ``minpoly``; the answer is the same ideal as sympy's, where s3 is a variable.
    The planar leg of 000 exercises it with a real chain."""
    mech = planar_tripod.MECHANISM
    planar = mech.closures[0]
    problem = leg_problem(mech, planar, planar.legs[0])
    assert "minpoly" in SingularEngine().script(problem)
    assert SympyEngine().eliminate(problem, 120) == SingularEngine().eliminate(problem, 120)
    x, u, s3 = sp.symbols("x u s3")
    toy = EliminationProblem("toy", (s3**2 - 3, x - s3 * u, u**2 - 2), (u,), (x, s3))
    got = SingularEngine().eliminate(toy, 60)
    assert got == SympyEngine().eliminate(toy, 60)
    # <x^2 - 6, s3^2 - 3>: the only relation between x and s3 is none beyond these
    assert len(got) == 2


def test_saturation_variable_eliminated_first():
    """A Rabinowitsch variable (one equation ``w d - 1``) is removed in a stage of its own;
    the basis is the one sympy's single elimination gives: the unit circle, from its
    tan-half-angle parametrization x = (1 - t^2)/(1 + t^2), y = 2t/(1 + t^2)."""
    from bonered_alg.elimination.engines import _elimination_stages

    t, w, x, y = sp.symbols("t w x y")
    problem = EliminationProblem("circle (test)", (x * (1 + t**2) - (1 - t**2),
                                                   y * (1 + t**2) - 2 * t,
                                                   w * (1 + t**2) - 1), (t, w), (x, y))
    assert _elimination_stages(problem.equation_terms(), 2) == [[1], [0]]
    assert SingularEngine().script(problem).count("eliminate(") == 2
    a = SympyEngine().eliminate(problem, 120)
    assert a == SingularEngine().eliminate(problem, 120)
    # the one generator, as written independently here: x^2 + y^2 - 1 up to sign
    assert len(a) == 1
    got = {e: c for e, c in a[0]}
    assert got in ({(2, 0): 1, (0, 2): 1, (0, 0): -1}, {(2, 0): -1, (0, 2): -1, (0, 0): 1})
