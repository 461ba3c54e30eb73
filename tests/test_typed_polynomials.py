"""Typed polynomial arithmetic (bonered_alg/algebra/polyring.py; issue 15, item 4): every
fast path gives exactly what the plain sympy computation it replaces gives, which is what
keeps the derivations' outputs byte-identical."""

import math
import random
from fractions import Fraction

import pytest
import sympy as sp

from bonered_alg.algebra import polyring as pr
from bonered_alg.elimination import sphere_leg

S = sp.symbols("a b c x_1 y_0 z10 z9", real=True)


def _random_terms(rng: random.Random, n: int, nvars: int) -> dict:
    out = {}
    for _ in range(n):
        e = tuple(rng.choice((0, 0, 1, 2, 3)) for _ in range(nvars))
        out[e] = Fraction(rng.choice((-1, 1)) * rng.randint(1, 9), rng.choice((1, 1, 2, 7)))
    return out


def _plain(terms: dict, gens) -> sp.Expr:
    return sp.Add(*[sp.Rational(c.numerator, c.denominator) * sp.Mul(*[g**k for g, k in
                                                                        zip(gens, e)])
                    for e, c in terms.items()])


@pytest.mark.parametrize("seed", range(40))
def test_expression_is_the_expression_sympy_builds(seed):
    rng = random.Random(seed)
    terms = _random_terms(rng, rng.choice((1, 2, 5, 40)), len(S))
    if seed % 5 == 0:
        terms[(0,) * len(S)] = Fraction(-3, 2)  # a constant term
    built = pr.expression(terms.items(), S)
    plain = _plain(terms, S)
    assert built == plain
    assert sp.srepr(built) == sp.srepr(plain)
    assert pr.terms_of(plain, S) == {e: c for e, c in terms.items() if c}


def test_expression_of_nothing_is_zero():
    assert pr.expression([], S) == 0
    assert pr.expression([((0,) * len(S), 0)], S) == 0


@pytest.mark.parametrize("seed", range(12))
def test_factor_list_is_sympys(seed):
    """FLINT's factorization, normalized, against sympy.factor_list: products of random
    factors, some repeated, with a rational and negative constant."""
    rng = random.Random(100 + seed)
    gens = S[:4]
    expr = sp.Rational(rng.choice((-6, -1, 1, 4)), rng.choice((1, 3)))
    for _ in range(rng.randint(1, 3)):
        f = _plain(_random_terms(rng, rng.randint(1, 4), len(gens)), gens)
        if f.free_symbols:
            expr *= f ** rng.choice((1, 1, 2))
    expr = sp.expand(expr)
    constant, factors = pr.factor_list(expr)
    reference = sp.factor_list(expr)
    assert constant == reference[0]
    key = lambda t: sp.srepr(t)  # noqa: E731
    assert sorted(factors, key=key) == sorted(reference[1], key=key)
    assert [sp.srepr(f) for f, _ in sorted(factors, key=key)] == \
        [sp.srepr(f) for f, _ in sorted(reference[1], key=key)]


def test_factor_list_leaves_non_polynomials_to_sympy():
    x, y = S[:2]
    assert pr.factor_list(sp.Integer(6)) == sp.factor_list(sp.Integer(6))
    expr = sp.expand((x**2 - 2) * (x + sp.sqrt(3) * y))  # an irrational coefficient
    assert pr.terms_of(expr, (x, y)) is None
    assert pr.factor_list(expr) == sp.factor_list(expr)


def test_primitive_part_and_determinant():
    x, y, a, b = S[3], S[4], S[0], S[1]
    ring = pr.ring_over((x, y, a, b))
    p = pr.polynomial(ring, sp.expand(-(a**2 + 1) * (3 * x**2 * a - y * b + 2) / 5))
    prim = pr.primitive_in(p, (x, y))
    assert pr.as_expr(prim) == sp.expand(3 * x**2 * a - y * b + 2)
    m = sp.Matrix(3, 3, lambda i, j: (a + i) * x**j - b * y**i + i * j)
    det = pr.determinant([[pr.polynomial(ring, sp.expand(e)) for e in row]
                          for row in m.tolist()])
    assert sp.expand(pr.as_expr(det) - m.det(method="berkowitz")) == 0
    assert pr.polynomial(ring, 0) == ring.zero
    with pytest.raises(ValueError, match="not a polynomial"):
        pr.polynomial(ring, 1 / x)


def _sphere_by_expressions(d, platform, minpolys):
    """The sphere condition the way the module computed it before the typed ring:
    expand, numerator over a common denominator, reduce modulo the minimal polynomials,
    primitive part in the platform's coordinates and the stroke."""
    m = sphere_leg.moved(d, platform)
    expr = d.stroke**2 * sum(c**2 for c in m[:4]) - 4 * sum(c**2 for c in m[4:])
    num = sp.expand(sp.fraction(sp.together(sp.expand(expr)))[0])
    for c, mp in minpolys.items():
        if num.has(c):
            gens = (c, *sorted(num.free_symbols - {c}, key=str))
            num = sp.Poly(num, *gens).rem(sp.Poly(mp, *gens)).as_expr()
    gens = sorted(set().union(*(sp.sympify(c).free_symbols for c in platform)) | {d.stroke},
                  key=str)
    _, prim = sp.Poly(num, *gens).primitive()
    return sp.expand(prim.as_expr())


def test_sphere_condition_equals_the_expression_computation():
    """A Stewart leg (layout rational in tan-half-angles, with sqrt(3) as a constant) and a
    layout of free symbols."""
    from bonered_alg.mechanisms import stewart
    from bonered_alg.pipeline import stages
    from bonered_alg.registry import load

    mech = stages.build(load("stewart"))
    closure = mech.closures[0]
    minpolys = sphere_leg.minimal_polynomials({c.symbol: c.value for c in mech.constants})
    d = sphere_leg.recognize(closure.legs[2])
    fast = sphere_leg.sphere_condition(d, closure.platform, minpolys)
    assert fast == _sphere_by_expressions(d, closure.platform, minpolys)
    assert fast.has(stewart.s3) and sp.degree(fast, stewart.s3) == 1
    x = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", real=True)
    a, b, q = sp.symbols("a1 a2 q", real=True)
    free = sphere_leg.DistanceLeg("L", (a, b / (1 + a**2), sp.Integer(0)),
                                  (b, sp.Integer(0), a), q)
    platform = (sp.Integer(1), *x)
    assert sphere_leg.sphere_condition(free, platform) == \
        _sphere_by_expressions(free, platform, {})


@pytest.mark.parametrize("seed", range(10))
def test_discriminant_is_sympys(seed):
    """FLINT's discriminant against sympy's, degrees 2 and 3 in q, rational coefficients and
    a negative leading coefficient included."""
    rng = random.Random(200 + seed)
    q, gens = S[6], S[:3]
    expr = sum(_plain(_random_terms(rng, rng.randint(1, 3), len(gens)), gens) * q**k
               for k in range(rng.randint(2, 3) + 1))
    expr = sp.expand(expr)
    fast = pr.discriminant(expr, q)
    reference = sp.expand(sp.discriminant(expr, q))
    assert fast == reference and sp.srepr(fast) == sp.srepr(reference)


@pytest.mark.parametrize("seed", range(20))
def test_canonical_key_orders_as_basic_compare(seed):
    """The key of :func:`polyring.canonical_key` sorts as ``cmp_to_key(Basic.compare)``
    (sympy's canonical order of arguments): monomials with rational coefficients of every
    sign and size, powers, symbols with and without assumptions, numbers."""
    from sympy.core.basic import _args_sortkey

    rng = random.Random(300 + seed)
    gens = (*S, *sp.symbols("u v w_2"))
    items = [_plain(_random_terms(rng, 1, len(gens)), gens) for _ in range(60)]
    items += [g ** rng.randint(1, 4) for g in rng.sample(gens, 5)]
    items += [sp.Rational(rng.randint(-9, 9), rng.randint(1, 4)) for _ in range(4)]
    rng.shuffle(items)
    memo: dict = {}
    ours = sorted(items, key=lambda e: pr.canonical_key(e, memo))
    theirs = sorted(items, key=_args_sortkey)
    assert [sp.srepr(e) for e in ours] == [sp.srepr(e) for e in theirs]


@pytest.mark.parametrize("seed", range(12))
def test_coefficients_and_expanded_read_off_monomials_as_sympy(seed):
    """coefficients_of_monomials is Poly(g, v)'s coefficients, expanded() is sp.expand,
    each as the same expression; neither takes a term that is not a monomial."""
    rng = random.Random(700 + seed)
    g = _plain(_random_terms(rng, rng.choice((1, 3, 30)), len(S)), S)
    v = rng.choice(S)
    poly = sp.Poly(g, v)
    got = pr.coefficients_of_monomials(g, v)
    assert {k: sp.srepr(c) for k, c in got.items()} == {
        m[0]: sp.srepr(sp.expand(c)) for m, c in zip(poly.monoms(), poly.coeffs())}
    assert sp.srepr(pr.expanded(g)) == sp.srepr(sp.expand(g))
    x, y = S[:2]
    unexpanded = g + (x + y) ** 2
    assert pr.coefficients_of_monomials(unexpanded, v) is None
    assert sp.srepr(pr.expanded(unexpanded)) == sp.srepr(sp.expand(unexpanded))
    assert pr.coefficients_of_monomials(g + sp.sqrt(3) * x, v) is None


def test_parasitic_numerator_is_the_together_numerator_up_to_a_constant():
    """The conditions' numerators from typed composition (analyses.parasitic) against
    sympy's together: the same polynomial up to a rational factor; the same one where the
    substitution leaves no cancelling products."""
    from bonered_alg.analyses.parasitic import _numerator

    a, b, c, x, y = S[:5]
    sub = {x: a / 2 + c, y: a**2 / 4 + b / 3}
    for g in (x * y + 3 * y - x**2, (x - a) ** 2 - y, x**2 - y):
        reference = sp.expand(sp.fraction(sp.together(g.subs(sub)))[0])
        got = _numerator(g, sub)
        ratio = sp.cancel(got / reference)
        assert ratio.is_Rational and ratio != 0
    g = x * y + 3 * y
    assert _numerator(g, sub) == sp.expand(sp.fraction(sp.together(g.subs(sub)))[0])
    assert _numerator(x - 1, {x: 1 / (a + 1)}) == sp.expand(-a)  # not a polynomial: together


@pytest.mark.parametrize("seed", range(60))
def test_text_is_str(seed):
    """polyring.text prints what str prints (the algebra records are written with it),
    for random sums of monomials, the two-term case sympy orders number first (1 - 2*x),
    symbols whose names sort otherwise than their indices (z10 before z9), and for
    what it leaves to sympy (non-polynomial terms, two symbols of one name)."""
    rng = random.Random(seed)
    terms = _random_terms(rng, rng.choice((1, 2, 2, 3, 6, 40)), len(S))
    if seed % 4 == 0:
        terms[(0,) * len(S)] = Fraction(rng.choice((-5, -1, 1, 3)), rng.choice((1, 2)))
    e = _plain(terms, S)
    assert pr.text(e) == str(e)
    x = S[3]
    special = [1 - 2 * x**3, sp.Rational(1, 2) - x, 1 - 2 * x * S[0], -1 + x, 2 + x,
               sp.Integer(0), sp.Rational(-7, 3), -x, x / 7 - S[6] * S[5],
               sp.sqrt(2) * x + 1, x**-1 + x, sp.Symbol("a") + S[0], 0.5 * x + 1]
    for e in special:
        assert pr.text(e) == str(e), e


@pytest.mark.parametrize("seed", range(20))
def test_report_degrees_are_polys(seed):
    """The reports' degree summaries read off the monomials are Poly's degree_list, also
    for what is left to Poly (a non-rational coefficient, zero once expanded)."""
    from bonered_alg.report.algebra_record import degrees

    rng = random.Random(seed)
    e = _plain(_random_terms(rng, rng.choice((1, 3, 12)), len(S)), S)
    cases = [e, sp.sqrt(2) * e + S[0], (S[0] + 1) ** 2 - S[0] ** 2 - 2 * S[0] - 1]
    for c in cases:
        free = sorted(c.free_symbols, key=str)
        want = list(zip(free, sp.Poly(sp.expand(c), *free).degree_list())) if free else []
        assert degrees(c) == want


@pytest.mark.parametrize("seed", range(30))
def test_normal_parametric_basis_is_the_sympy_form(seed):
    """The lex bases' normal form (primitive over Z[parameters], signed, sorted) by FLINT's
    gcd and exact division equals the one by sympy's together/gcd_list/cancel: generators
    with a content in the parameters (a product with a random polynomial in them), an
    integer content, rational coefficients, a zero and a repeated generator."""
    from bonered_alg.elimination.problem import (
        normal_parametric_basis,
        normal_parametric_basis_sympy,
    )

    rng = random.Random(1000 + seed)
    unknowns, parameters = S[3:], S[:3]
    gens = unknowns + parameters
    basis = []
    for _ in range(rng.randint(1, 4)):
        p = sp.expand(_plain(_random_terms(rng, rng.choice((1, 3, 8)), len(gens)), gens))
        if p == 0:
            continue
        content = _plain(_random_terms(rng, rng.choice((1, 2)), 3), parameters)
        scaled = sp.expand(p * content * sp.Rational(rng.choice((1, -6, 4)),
                                                     rng.choice((1, 3))))
        if scaled == 0:
            continue
        poly = sp.Poly(scaled, *gens)
        basis.append(tuple((e, Fraction(int(c.p), int(c.q))) for e, c in poly.terms()))
    basis += [(), basis[0]] if basis else [()]
    got = normal_parametric_basis(basis, unknowns, parameters)
    assert got == normal_parametric_basis_sympy(basis, unknowns, parameters)
    for terms in got:  # primitive: no integer content left
        assert terms and math.gcd(*(int(c) for _, c in terms)) == 1


@pytest.mark.parametrize("seed", range(16))
def test_factor_list_as_sympy_is_sympys_factor_list(seed):
    """pr.factor_list_as_sympy (FLINT's factors in sympy's order) is sympy.factor_list, to
    the srepr of each factor and the order of the list: products of random polynomials
    (some repeated, some of equal size), expanded; a product and a number go to sympy."""
    rng = random.Random(2000 + seed)
    parts = []
    for _ in range(rng.randint(1, 4)):
        f = _plain(_random_terms(rng, rng.choice((1, 2, 3, 4)), len(S)), S)
        if f.free_symbols:
            parts.append(f ** rng.choice((1, 1, 2)))
    expr = sp.expand(sp.Rational(rng.choice((1, -3, 5)), rng.choice((1, 2))) * sp.Mul(*parts)
                     + (0 if parts else S[0] + 2 * S[1]))
    want = sp.factor_list(expr)
    got = pr.factor_list_as_sympy(expr)
    assert got[0] == want[0]
    assert [(sp.srepr(f), k) for f, k in got[1]] == [(sp.srepr(f), k) for f, k in want[1]]
    for other in (sp.Mul(*parts[:2]) if len(parts) > 1 else S[2] ** 2, sp.Integer(6),
                  sp.expand((sp.sqrt(3) * S[0] + S[1]) * (S[0] - 2 * S[2]))):
        assert pr.factor_list_as_sympy(other) == sp.factor_list(other)
    # pr.factor is sympy.factor, to the srepr, on what the IK plans factor (sums of at most
    # 40 terms: sympy takes tens of seconds on some of the larger products here)
    small = [expr] if len(sp.Add.make_args(expr)) <= 40 else []
    for e in small + [sp.Integer(6), S[2], sp.expand((S[0] + 2 * S[1]) * (S[2] - S[3]) / 7),
                      sp.expand((sp.sqrt(3) * S[0] + S[1]) * (S[0] - 2 * S[2]))]:
        assert sp.srepr(pr.factor(e)) == sp.srepr(sp.factor(e))


@pytest.mark.parametrize("seed", range(25))
def test_jacobian_is_sympys_jacobian(seed):
    """pr.jacobian (each expanded polynomial differentiated on its monomials) gives the
    expressions of sympy's Matrix.jacobian, to their srepr: random polynomials with rational
    coefficients and a constant term, a variable absent from a row, and a row sympy keeps
    (a product, a square root)."""
    rng = random.Random(3000 + seed)
    exprs = [_plain(_random_terms(rng, rng.choice((1, 2, 6, 20)), len(S)), S)
             for _ in range(rng.randint(1, 3))]
    exprs.append(sp.Integer(rng.choice((0, 5))) + S[0] ** 3 / 3)
    if seed % 4 == 0:
        exprs.append(S[1] * (S[2] + 1) + sp.sqrt(3) * S[3])
    variables = [S[k] for k in rng.sample(range(len(S)), 3)] + [sp.Symbol("absent")]
    want = sp.Matrix(exprs).jacobian(variables)
    got = pr.jacobian(exprs, variables)
    assert got.shape == want.shape
    assert [sp.srepr(x) for x in got] == [sp.srepr(x) for x in want]


def test_count_ops_is_sympys():
    """polyring.count_ops against sympy.count_ops on random expressions (sums, products,
    powers, functions, negations, rational and float numbers) and on polynomials."""
    xs = sp.symbols("a b c d")
    rng = random.Random(3)

    def rnd(depth=0):
        r = rng.random()
        if depth > 3 or r < 0.25:
            return rng.choice([*xs, sp.Integer(rng.randint(-3, 3)),
                               sp.Rational(rng.randint(-5, 5), rng.randint(1, 4)),
                               sp.Float(rng.choice([-1.0, 1.0, 2.5, -0.5]))])
        k = rng.random()
        if k < 0.3:
            return sp.Add(*[rnd(depth + 1) for _ in range(rng.randint(2, 4))])
        if k < 0.6:
            return sp.Mul(*[rnd(depth + 1) for _ in range(rng.randint(2, 3))])
        if k < 0.75:
            return sp.Pow(rnd(depth + 1), rng.choice([2, 3, -1, -2, sp.Rational(1, 2),
                                                      sp.Rational(-1, 2)]))
        if k < 0.85:
            return rng.choice([sp.sin, sp.atan, sp.exp, sp.sqrt, sp.Abs])(rnd(depth + 1))
        return -rnd(depth + 1)

    for _ in range(1500):
        e = rnd()
        assert pr.count_ops(e) == int(sp.count_ops(e)), e
    for _ in range(100):
        e = sp.Add(*[sp.Rational(rng.randint(-9, 9), rng.choice([1, 1, 2, 3]))
                     * sp.Mul(*[x ** rng.randint(0, 3) for x in xs])
                     for _ in range(rng.randint(1, 30))])
        assert pr.count_ops(e) == int(sp.count_ops(e)), e
    assert pr.count_ops(sp.Eq(xs[0], xs[1] + 1)) == int(sp.count_ops(sp.Eq(xs[0], xs[1] + 1)))


@pytest.mark.parametrize("seed", range(30))
def test_reduced_numerator_is_cancels_numerator(seed):
    """The fraction-field numerator (pr.reduced_numerator, behind the 3-RPS distance
    conditions) against sympy's cancel: the same polynomial up to a non-zero rational
    factor, and the same one where every coefficient is an integer (the conditions' case:
    the same generator order and the same cancellation, so the same normalisation)."""
    rng = random.Random(seed)
    a, b, c, u, v = S[:5]
    integer = seed % 2 == 0

    def poly(vars_, n):
        terms = _random_terms(rng, n, len(vars_))
        if integer:
            terms = {e: Fraction(int(k.numerator)) for e, k in terms.items()}
        return _plain(terms, vars_)

    cu, cv = (1 - u**2) / (1 + u**2), (1 - v**2) / (1 + v**2)
    su, sv = 2 * u / (1 + u**2), 2 * v / (1 + v**2)
    expr = ((poly((a, b), 3) * cu - poly((b, c), 2) * cv) ** 2
            + (poly((a, c), 2) * su - sv * b) ** 2 - poly((a, b, c), 4))
    if seed % 3 == 0:
        expr += poly((a, u), 3) / (a + 2 * b + 1)  # a denominator that does not cancel
    reference = sp.fraction(sp.cancel(sp.together(expr)))[0]
    got = pr.reduced_numerator(expr)
    ratio = sp.cancel(got / reference)
    assert ratio.is_Rational and ratio != 0
    if integer:
        assert sp.expand(got - reference) == 0
