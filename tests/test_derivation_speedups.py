"""The derivation's speed-ups change no result: sympy's node counts and free symbols
remembered within a derivation (pipeline.sympy_memo), and mpmath evaluations that keep the
values of their elementary functions (verification.mpmath_function)."""

from __future__ import annotations

import mpmath
import sympy as sp
from sympy.core import sorting
from sympy.core.basic import Basic

from bonered_alg.pipeline.sympy_memo import remembered_structure
from bonered_alg.verification import _shared_subtrees, mpmath_function

x, y, z, a, b = sp.symbols("x y z a b", real=True)


def _deep(n=6):
    """A nested expression with repeated subtrees and Floats."""
    e = x * y + sp.Float("0.25") * z
    for k in range(n):
        e = sp.expand(e * (x + k * y)) + sp.tan(a / 2) * e / (1 + b ** 2)
    return e


def test_cse_and_derivatives_are_the_same_with_remembered_structure():
    exprs = [_deep(), sp.diff(_deep(4), x), sp.Derivative(sp.Function("f")(x), x) + x * y]
    plain_cse = sp.cse(exprs, order="canonical")
    plain_diff = [sp.diff(e, s) for e in exprs[:2] for s in (x, y, a)]
    plain_free = [e.free_symbols for e in exprs]
    with remembered_structure():
        cse = sp.cse(exprs, order="canonical")
        diff = [sp.diff(e, s) for e in exprs[:2] for s in (x, y, a)]
        free = [e.free_symbols for e in exprs]
        again = [e.free_symbols for e in exprs]
    assert sp.srepr(cse) == sp.srepr(plain_cse)
    assert [sp.srepr(d) for d in diff] == [sp.srepr(d) for d in plain_diff]
    assert free == plain_free == again


def test_free_symbols_is_a_new_set_each_time_and_sympy_is_restored():
    original_count = sorting._node_count
    original_free = Basic.__dict__["free_symbols"]
    e = x * y + z
    with remembered_structure():
        assert sorting._node_count is not original_count
        first = e.free_symbols
        first.add(a)  # a caller may change the set it gets
        assert e.free_symbols == {x, y, z}
        assert sorting._node_count(sp.Float(1.5) + x) == original_count(sp.Float(1.5) + x)
    assert sorting._node_count is original_count
    assert Basic.__dict__["free_symbols"] is original_free


def test_mpmath_function_gives_lambdify_s_numbers_bit_for_bit():
    expr = (sp.tan(a / 2) ** 3 * sp.sqrt(3) - sp.sin(b) * sp.tan(a / 2) / (1 + sp.cos(b))
            + sp.Rational(1, 3) * sp.atan(a * b) + sp.tan(a / 2))
    with mpmath.workdps(40):
        plain = sp.lambdify((a, b), [expr, sp.diff(expr, a)], "mpmath")
        kept = mpmath_function((a, b), [expr, sp.diff(expr, a)])
        for pa, pb in ((0.3, -0.2), (mpmath.mpf("0.1"), 2), (0.3, -0.2), (-0.0, 0.0)):
            want, got = plain(pa, pb), kept(pa, pb)
            assert all(isinstance(v, mpmath.mpf) for v in got)
            assert [mpmath.mpf(v) for v in want] == [mpmath.mpf(v) for v in got]


def test_mpmath_function_computes_repeated_subtrees_once_with_the_same_numbers():
    """Repeated subexpressions (as a term with a minus sign, a denominator, a power's base,
    a function's argument, in a matrix) are computed once, and every number is lambdify's
    to the last bit."""
    u = sp.tan(a / 2) * x + sp.Rational(2, 7) * y
    w = (1 + u**2) / (z - u)
    exprs = [x - 3 * u + w, u * y / (z + u) ** 2 - sp.sqrt(1 + u**2), sp.diff(w * u, x)]
    matrix = sp.Matrix([[w, -u], [sp.cos(u) * w, 1 / (1 + u**2)]])
    assert u in _shared_subtrees(exprs) and 1 + u**2 in _shared_subtrees(exprs)
    with mpmath.workdps(40):
        for expr in (exprs, matrix):
            plain = sp.lambdify((x, y, z, a), expr, "mpmath")
            shared = mpmath_function((x, y, z, a), expr)
            for point in ((0.3, -1.2, 5.0, 0.4), (mpmath.mpf("2.5"), 0.1, -3, -0.7)):
                want, got = plain(*point), shared(*point)
                assert [mpmath.mpf(v) for v in want] == [mpmath.mpf(v) for v in got]


def test_no_shared_subtrees_across_the_branches_of_a_piecewise():
    u = x * y + 1
    assert _shared_subtrees([sp.Piecewise((1 / u, x > 0), (u, True)), u**2]) == []


def test_pose_map_rates_are_the_derivatives():
    """codegen.module.pose_map_rates (forward mode through the outputs' CSE program, every
    temporary and rate a named value of a Program) gives the values and the derivatives
    sympy's diff gives, exactly (cancel of the difference, the program written out), on a
    rational map with shared factors like a Study map's (a rotation's half-angle tangents,
    the translation through them), including outputs that do not depend on every
    coordinate."""
    from bonered_alg.codegen.kernels import Program
    from bonered_alg.codegen.module import pose_map_rates

    x, y, a, b = sp.symbols("x y alpha beta", real=True)
    ta, tb = sp.tan(a / 2), sp.tan(b / 2)
    n = (1 + ta**2) * (1 + tb**2)
    outputs = [ta * tb / n, (x * (1 - ta**2) - 2 * y * ta) / n, (x + y * tb) / (1 + ta * tb),
               sp.Integer(3), y**2 * tb, x]
    pose = [x, y, a, b]
    program = Program()
    values, rates = pose_map_rates(outputs, pose, program)
    assert program.entries  # the shared factors are named, not multiplied out
    for out, value, row in zip(outputs, program.written_out(values), rates):
        assert sp.cancel(sp.expand_trig(value - out)) == 0
        assert len(row) == len(pose)
        for p, r in zip(pose, program.written_out(row)):
            assert sp.cancel(sp.expand_trig(r - sp.diff(out, p))) == 0


def test_a_kernel_with_a_program_computes_what_the_written_out_outputs_do():
    """codegen.kernels.kernel with ``program`` (named values the outputs read, in
    dependency order): the entries the outputs need are computed once each, before their
    readers, an entry that is a number or a symbol is put in its readers' places, one that
    no output reads is not computed, and the numbers are those of the kernel of the
    outputs written out."""
    import numpy as np

    from bonered_alg.codegen.kernels import Program, kernel

    prog = Program()
    u = prog.name(x * y + 1)
    v = prog.name(u * u - z)
    w = prog.name(x)  # an atom: no entry
    prog.name(sp.sin(z) * u)  # read by no output
    outs = [v / u + w, u * v * sp.tan(z), sp.Integer(2) * w]
    k = kernel("_k", [x, y, z], outs, "test", c=True, program=prog.entries)
    ref = kernel("_ref", [x, y, z], prog.written_out(outs), "test")
    assert "sin" not in k.source and "sin" not in k.c_source
    space: dict = {"numpy": np}
    exec(k.source, space)
    exec(ref.source, space)
    rng = np.random.default_rng(3)
    args = [rng.uniform(-2, 2, 50) for _ in range(3)]
    for got, want in zip(space["_k"](*args), space["_ref"](*args)):
        np.testing.assert_allclose(got, want, rtol=1e-13)
    # every temporary assigned once, before any line that reads it
    assigned = []
    for line in k.source.splitlines()[2:]:
        if " = " in line:
            name, rhs = line.strip().split(" = ", 1)
            assert all(t in assigned for t in
                       {s for s in rhs.replace("(", " ").replace(")", " ").replace("*", " ")
                        .replace("+", " ").replace("-", " ").replace("/", " ").split()
                        if s.startswith("_c")})
            assert name not in assigned
            assigned.append(name)


def test_spurious_factors_are_removed_as_sympy_s_factor_list_removes_them():
    """passive._without_spurious_factors (FLINT's factors) gives the polynomial that
    sympy's factor_list gives: without the factors free of v and the factors v^2 + 1."""
    from bonered_alg.kinematics.passive import _without_spurious_factors

    v = sp.Symbol("v", real=True)
    cases = [sp.expand(-6 * (v**2 + 1) * (x * v - 2 * y) ** 2 * (3 * z + 1) * (v - x * y)),
             sp.expand(sp.Rational(1, 4) * x**2 * (v**2 + 1) ** 2 * (2 * v**2 - z * v + 1)),
             sp.expand((y - 1) * (v + x) * (v - x))]
    for g in cases:
        _, factors = sp.factor_list(g)
        keep = [f**k for f, k in factors if f.has(v) and sp.expand(f - (v**2 + 1)) != 0]
        assert _without_spurious_factors(g, v) == sp.expand(sp.Mul(*keep))


def test_jacobian_determinant_is_sympy_s_expanded_determinant_term_for_term():
    """polyring.jacobian_determinant (typed polynomials) builds the expression that sympy's
    expanded Berkowitz determinant of the Jacobian is, the same tree; sympy's own route for
    anything that is not a polynomial with rational coefficients."""
    from bonered_alg.algebra.polyring import jacobian_determinant

    u1, u2, u3 = sp.symbols("u1 u2 u3", real=True)
    eqs = [sp.expand((1 + u1**2) * (1 + u2**2) * x - 4 * u1 * u2 * y + sp.Rational(3, 2) * z),
           sp.expand(u2**2 * u3 - x * y * u3 + 7 * u2 - sp.Rational(1, 3)),
           sp.expand((u3 - u1) ** 2 * z - x**2 * u1 * u3)]
    for exprs in (eqs, [eqs[0], eqs[1], eqs[2] + sp.sqrt(3) * u1]):
        want = sp.expand(sp.Matrix(exprs).jacobian([u1, u2, u3]).det(method="berkowitz"))
        got = jacobian_determinant(exprs, (u1, u2, u3))
        assert sp.srepr(got) == sp.srepr(want)


def test_numeric_coordinates_are_subs_of_the_whole_configuration_bit_for_bit():
    """mobility.chains._numeric gives each coordinate only its own symbols' values: the
    same floats as ``subs`` of the whole configuration (subs puts them in one after another
    in one sorted order, in which the others are no-ops)."""
    import numpy as np

    from bonered_alg.mobility.chains import _numeric

    syms = sp.symbols("s0:12", real=True)
    rng = np.random.default_rng(3)
    vals = {s: float(v) for s, v in zip(syms, rng.uniform(-2, 2, len(syms)))}
    point = [(1 + syms[0] ** 2) * syms[3] / 7 - sp.Rational(2, 3) * syms[5] * syms[0],
             syms[11] * (syms[2] - syms[7]) ** 3 + 0.1 * syms[2], sp.Integer(4),
             sp.sqrt(3) * syms[4] * syms[9] / (1 + syms[9] ** 2)]
    want = np.array([float(sp.sympify(c).subs(vals)) for c in point])
    assert np.array_equal(_numeric(point, vals), want)


def test_cofactor_determinant_is_the_determinant():
    """kinematics.singularities.cofactor_determinant expands along the row or column with
    the most zeros, unexpanded; expanded, it is sympy's Bareiss determinant, for matrices of
    sizes 1-4 with zeros in rows, in columns and nowhere."""
    import random

    from bonered_alg.kinematics.singularities import cofactor_determinant

    rng = random.Random(7)
    syms = (x, y, z, a, b)
    for n in (1, 2, 3, 4):
        for zero_col in (False, True):
            entries = [[sp.Integer(rng.randint(-3, 3)) * rng.choice(syms)
                        + sp.Rational(rng.randint(-5, 5), rng.randint(1, 4))
                        * rng.choice(syms) ** rng.randint(0, 2)
                        for _ in range(n)] for _ in range(n)]
            for _ in range(n):  # a few zeros anywhere
                entries[rng.randrange(n)][rng.randrange(n)] = sp.Integer(0)
            if zero_col and n > 2:  # a column with more zeros than any row
                for i in range(n - 1):
                    entries[i][1] = sp.Integer(0)
            m = sp.Matrix(entries)
            got = cofactor_determinant(m)
            assert sp.expand(got - m.det(method="bareiss")) == 0


def test_evaluation_form_is_the_shorter_of_the_two():
    """The generated code evaluates a determinant from its matrix's entries only where
    that counts fewer operations than the expanded determinant."""
    from bonered_alg.algebra.polyring import count_ops
    from bonered_alg.kinematics.singularities import cofactor_determinant, evaluation_form

    wide = sp.Matrix([[(x + y + 1) ** 3, a + b], [z - a, (x - b) ** 3]])
    expanded = sp.expand(wide.det())
    form = evaluation_form(expanded, wide)
    assert form is not None and count_ops(form) < count_ops(expanded)
    assert sp.expand(form - expanded) == 0
    plain = sp.Matrix([[x, y], [z, a]])  # x a - y z: the same length either way
    assert count_ops(cofactor_determinant(plain)) >= count_ops(x * a - y * z)
    assert evaluation_form(sp.expand(plain.det()), plain) is None


def test_simplified_is_simplify_with_zero_taken_early():
    """polyring.simplified gives sp.simplify's result: 0 where the difference cancels (a
    trigonometric and a radical identity, a rational one), simplify's own answer where it
    does not."""
    from bonered_alg.algebra.polyring import simplified

    t = sp.Symbol("t", real=True)
    zero = [sp.sin(a) ** 2 + sp.cos(a) ** 2 - 1 - (sp.sin(a) ** 2 + sp.cos(a) ** 2 - 1),
            2 * t / (1 + t**2) - 2 * t * (1 - t**2) / (1 - t**4),
            sp.sqrt(3) * x / (1 + sp.sqrt(3)) - sp.sqrt(3) * x * (sp.sqrt(3) - 1) / 2]
    other = [sp.sin(a) ** 2 + sp.cos(a) ** 2, (x**2 - 1) / (x - 1) - y,
             sp.tan(a / 2) - sp.sin(a) / (1 + sp.cos(a)) + x]
    for e in zero:
        assert simplified(e) == 0 and sp.simplify(e) == 0
    for e in other:
        assert sp.srepr(simplified(e)) == sp.srepr(sp.simplify(e))
        assert simplified(e) != 0


def test_normal_form_is_the_primitive_polynomial_by_fraction_arithmetic():
    """polyterms.normal_form (integer arithmetic on the numerators) equals the plain
    Fraction computation: merged monomials, grevlex order descending, denominators
    cleared, content removed, positive leading coefficient; on random term lists with
    repeated monomials, zero sums, integer and rational coefficients."""
    import math
    import random
    from fractions import Fraction

    from bonered_alg.elimination.polyterms import grevlex_key, normal_form

    def plain(terms):
        merged = {}
        for e, c in terms:
            merged[tuple(e)] = merged.get(tuple(e), Fraction(0)) + Fraction(c)
        items = sorted(((e, c) for e, c in merged.items() if c != 0),
                       key=lambda t: grevlex_key(t[0]), reverse=True)
        if not items:
            return ()
        den = math.lcm(*(c.denominator for _, c in items))
        ints = [int(c * den) for _, c in items]
        g = math.gcd(*ints) * (1 if ints[0] > 0 else -1)
        return tuple((e, Fraction(i // g)) for (e, _), i in zip(items, ints))

    rng = random.Random(3)
    for _ in range(2000):
        terms = [(tuple(rng.randint(0, 2) for _ in range(3)),
                  rng.choice([rng.randint(-9, 9), Fraction(rng.randint(-9, 9), rng.randint(1, 7))]))
                 for _ in range(rng.randint(0, 12))]
        got = normal_form(terms)
        assert got == plain(terms) and all(type(c) is Fraction for _, c in got)
