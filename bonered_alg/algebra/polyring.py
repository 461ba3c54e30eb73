"""Exact polynomial arithmetic on sympy's typed sparse polynomials (:mod:`sympy.polys.rings`).

Expanding products of Study tuples as sympy expressions (``sp.expand`` on ``Add``/``Mul``
trees) costs seconds per leg; the same arithmetic on ``PolyElement`` (dicts of exponent
tuples to gmpy2 rationals) costs milliseconds.  The functions here convert in and out and
compute the normal forms the symbolic stages need; the results are exact and independent of
how they were computed.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from fractions import Fraction
from functools import reduce

import sympy as sp
from sympy.core.basic import Basic, ordering_of_classes
from sympy.polys.polyutils import _sort_gens
from sympy.polys.rings import PolyElement, PolyRing

from . import convention as cv


def ring_over(symbols: Iterable[sp.Symbol]) -> PolyRing:
    """The ring Q[symbols], its variables in the given order (lex order on them)."""
    return PolyRing(tuple(symbols), sp.QQ)


def polynomial(ring: PolyRing, expr) -> PolyElement:
    """A polynomial expression with rational coefficients as an element of ``ring``;
    ValueError naming the expression when it is not one (a symbol outside the ring, a
    denominator, a function)."""
    try:
        return ring.from_expr(sp.sympify(expr))
    except (ValueError, sp.polys.polyerrors.PolynomialError, TypeError) as exc:
        raise ValueError(f"not a polynomial in {ring.symbols}: {expr}") from exc


def fraction(ring: PolyRing, expr) -> tuple[PolyElement, PolyElement]:
    """``(numerator, denominator)`` of a rational expression over a common denominator."""
    num, den = sp.fraction(sp.together(sp.sympify(expr)))
    return polynomial(ring, num), polynomial(ring, den)


def reduced_numerator(expr) -> sp.Expr:
    """The numerator of ``expr`` written as one reduced fraction: the numerator of
    ``sp.cancel(sp.together(expr))``, up to a constant factor, formed in the fraction field
    Z(symbols) (generators in ``sp.cancel``'s order), where each sum and product is cancelled
    as it is built instead of the whole expression being expanded at once (tripod_planar's
    3-RPS distance conditions: 1.36 s with ``cancel``, 0.13 s here, the same numerators)."""
    expr = sp.sympify(expr)
    field, *_ = sp.field(_sort_gens(expr.free_symbols), sp.ZZ)
    return field.from_expr(expr).numer.as_expr()


def lcm(polys: Sequence[PolyElement]) -> PolyElement:
    """Least common multiple (monic over Q) of non-zero polynomials."""
    return reduce(lambda a, b: a.lcm(b), polys, polys[0].ring.one)


def reduce_modulo(p: PolyElement, univariate: Iterable[PolyElement]) -> PolyElement:
    """Remainder of ``p`` by univariate polynomials in distinct variables (each a Groebner
    basis of its own ideal, so the remainder is unique): ``s3 -> `` degree < 2 for
    ``s3^2 - 3``."""
    for m in univariate:
        p = p.rem(m)
    return p


def _normalized_sign(p: PolyElement) -> PolyElement:
    """``p`` with integer coefficients of gcd 1 and a positive leading coefficient in the
    ring's lexicographic order."""
    _, p = p.clear_denoms()
    content = p.content()
    p = p.quo_ground(content) if content != 1 else p
    return -p if p.LC < 0 else p


def coefficients_in(p: PolyElement, variables: Sequence[sp.Symbol]
                    ) -> dict[tuple[int, ...], PolyElement]:
    """``p`` as a polynomial in ``variables``: exponents in them -> coefficient, an element
    of the same ring free of ``variables``."""
    ring = p.ring
    idx = [ring.symbols.index(v) for v in variables]
    grouped: dict[tuple[int, ...], dict] = {}
    for monom, c in p.items():
        key = tuple(monom[i] for i in idx)
        rest = list(monom)
        for i in idx:
            rest[i] = 0
        grouped.setdefault(key, {})[tuple(rest)] = c
    return {k: ring.from_dict(terms) for k, terms in grouped.items()}


def gcd(polys: Sequence[PolyElement]) -> PolyElement:
    """Greatest common divisor of polynomials (over Q: monic in the ring's order), from the
    shortest up; it stops at a constant, which every later gcd keeps."""
    ordered = sorted(polys, key=len)
    out = ordered[0]
    for p in ordered[1:]:
        if out.is_ground:
            break
        out = out.gcd(p)
    return out.ring.one if out.is_ground and out else out


def determinant(m: Sequence[Sequence[PolyElement]]) -> PolyElement:
    """Determinant of a small square matrix of ring elements, by cofactor expansion along
    the first row (exact, division-free)."""
    n = len(m)
    if n == 1:
        return m[0][0]
    out = m[0][0].ring.zero
    for j in range(n):
        if m[0][j]:
            minor = [row[:j] + row[j + 1:] for row in m[1:]]
            term = m[0][j] * determinant(minor)
            out = out - term if j % 2 else out + term
    return out


def jacobian(exprs: Sequence[sp.Expr], variables: Sequence[sp.Symbol]) -> sp.Matrix:
    """``sp.Matrix(exprs).jacobian(variables)``, the same expressions: each expanded
    polynomial with rational coefficients differentiated on its monomials and written back
    by :func:`expression` (sympy's ``diff`` of such a sum is the canonical sum of the
    differentiated monomials, which ``expression`` builds without flattening); any other
    expression differentiated by sympy."""
    exprs = [sp.sympify(e) for e in exprs]
    variables = list(variables)
    gens = tuple(_sort_gens(set().union(*(e.free_symbols for e in exprs)) | set(variables)))
    at = [gens.index(v) for v in variables]
    powers: dict = {}
    rows = []
    for e in exprs:
        terms = terms_of(e, gens)
        if terms is None:
            rows.append([sp.diff(e, v) for v in variables])
            continue
        row = []
        for i in at:
            rates = {}
            for ex, c in terms.items():
                if ex[i]:
                    rates[ex[:i] + (ex[i] - 1,) + ex[i + 1:]] = c * ex[i]
            row.append(expression(rates.items(), gens, powers))
        rows.append(row)
    return sp.Matrix(len(exprs), len(variables), [x for row in rows for x in row])


def jacobian_determinant(exprs: Sequence[sp.Expr], variables: Sequence[sp.Symbol]) -> sp.Expr:
    """``sp.expand(Matrix(exprs).jacobian(variables).det())`` of polynomials with rational
    coefficients, the same expression, differentiated and expanded in ``Q[symbols]`` (the
    expanded determinant is one canonical sum of monomials whichever way it is computed);
    anything else goes to sympy."""
    gens = tuple(_sort_gens(set().union(*(sp.sympify(e).free_symbols for e in exprs))
                            | set(variables)))
    if any(terms_of(e, gens) is None for e in exprs):
        return sp.expand(sp.Matrix(exprs).jacobian(list(variables)).det(method="berkowitz"))
    ring = ring_over(gens)
    polys = [polynomial(ring, e) for e in exprs]
    at = [ring.gens[gens.index(v)] for v in variables]
    det = determinant([[p.diff(v) for v in at] for p in polys])
    return expression(((e, Fraction(int(c.numerator), int(c.denominator)))
                       for e, c in det.terms()), gens)


def primitive_in(p: PolyElement, variables: Sequence[sp.Symbol]) -> PolyElement:
    """The primitive part of ``p`` as a polynomial in ``variables`` with coefficients in the
    ring's other symbols (Gauss's lemma: ``p`` divided by the gcd of those coefficients),
    with integer coefficients of gcd 1 and a positive leading coefficient (lex): the unique
    representative of ``p`` up to a factor free of ``variables``."""
    if not p:
        return p
    parts = [c for _, c in sorted(coefficients_in(p, variables).items())]
    content = gcd(parts)
    if not content.is_ground:
        p = p.exquo(content)
    return _normalized_sign(p)


def study_product(*factors: Sequence[PolyElement]) -> tuple[PolyElement, ...]:
    """Ordered dual-quaternion product of Study tuples of ring elements (004 eq. 6-7)."""
    acc = tuple(factors[0])
    for f in factors[1:]:
        acc = cv.study_product(acc, f)
    return acc


def as_expr(p: PolyElement) -> sp.Expr:
    """The polynomial as an expanded sympy expression."""
    return p.as_expr()


# ------------------------------------------------------------------ expressions
_CLASS_RANK: dict[type, tuple[int, str]] = {}


def _class_rank(cls: type) -> tuple[int, str]:
    """The position of ``cls`` in sympy's ``ordering_of_classes`` (unknown classes after
    the known ones, by name): ``sympy.core.basic._cmp_name`` as a key."""
    rank = _CLASS_RANK.get(cls)
    if rank is None:
        name = cls.__name__
        if name in ordering_of_classes:
            rank = (ordering_of_classes.index(name), "")
        else:
            rank = (len(ordering_of_classes) + 1, name)
        _CLASS_RANK[cls] = rank
    return rank


def canonical_key(expr: Basic, memo: dict | None = None, remember: bool = True) -> tuple:
    """A sort key with the order of ``Basic.compare`` (``sympy.core.basic._args_sortkey``,
    the order ``Mul`` and ``Add`` keep their arguments in): the class, the length of the
    hashable content, then its items, each a Basic's key or the raw value (a Basic before
    anything else, as ``compare`` has it).  Computed once per object (``memo``), not in
    every comparison of a sort: sorting thousands of terms took seconds with
    ``cmp_to_key(Basic.compare)``.  ``remember=False`` keeps ``expr``'s own key out of
    ``memo`` (its parts' keys go in), for objects sorted once."""
    if memo is not None:
        key = memo.get(expr)
        if key is not None:
            return key
    content = expr._hashable_content()
    items = []
    for item in content:
        if isinstance(item, Basic):
            items.append((0, canonical_key(item, memo)))
        elif isinstance(item, frozenset):
            items.append((0, canonical_key(Basic(*item), memo)))
        else:
            items.append((1, item))
    key = (_class_rank(type(expr)), len(content), tuple(items))
    if memo is not None and remember:
        memo[expr] = key
    return key


def expression(terms: Iterable[tuple[tuple[int, ...], Fraction | int]], gens: Sequence[sp.Symbol],
               powers: dict | None = None) -> sp.Expr:
    """A polynomial given as distinct monomials ``(exponents, coefficient)`` as the sympy
    expression ``sp.Add(*[c * sp.Mul(*[g**k ...]) ...])``, built from its canonical
    arguments without sympy's flattening (several times faster on thousands of terms): each
    product's factors and the sum's terms sorted by sympy's canonical key, the number first,
    as ``Mul.flatten`` and ``Add.flatten`` leave them (``tests/test_typed_polynomials.py``
    pins the two equal).  ``powers`` caches ``g**k`` and their sort keys across calls."""
    powers = {} if powers is None else powers
    keys = powers.setdefault("canonical keys", {})
    args, constant = [], None
    for e, c in terms:
        c = Fraction(c)
        coeff = sp.Rational(c.numerator, c.denominator)
        if coeff == 0:
            continue
        factors = []
        for g, k in zip(gens, e):
            if k:
                p = powers.get((g, k))
                if p is None:
                    p = powers[(g, k)] = g if k == 1 else sp.Pow(g, k)
                factors.append(p)
        if not factors:
            constant = coeff if constant is None else constant + coeff
            continue
        factors.sort(key=lambda f: canonical_key(f, keys))
        if coeff != 1:
            factors.insert(0, coeff)
        args.append(sp.Mul._from_args(factors) if len(factors) > 1 else factors[0])
    args.sort(key=lambda t: canonical_key(t, keys, remember=False))
    if constant is not None and constant != 0:
        args.insert(0, constant)
    if not args:
        return sp.Integer(0)
    return sp.Add._from_args(args) if len(args) > 1 else args[0]


def terms_of(expr: sp.Expr, gens: Sequence[sp.Symbol]) -> dict[tuple[int, ...], Fraction] | None:
    """An expanded polynomial expression with rational coefficients as exponents ->
    coefficient over ``gens``; None when it is not one (then the caller uses sympy)."""
    index = {g: i for i, g in enumerate(gens)}
    out: dict[tuple[int, ...], Fraction] = {}
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_coeff_Mul()
        if not coeff.is_Rational:
            return None
        e = [0] * len(gens)
        for f in sp.Mul.make_args(rest):
            if f is sp.S.One:  # rest of a bare number (as_coeff_Mul took every number out)
                continue
            base, k = f.as_base_exp()
            i = index.get(base)
            # k.p: the Python int (sympy's ``k > 0`` sympifies the 0 first)
            if i is None or not (k.is_Integer and k.p > 0):
                return None
            e[i] += int(k)
        key = tuple(e)
        out[key] = out.get(key, Fraction(0)) + Fraction(int(coeff.p), int(coeff.q))
    return {k: c for k, c in out.items() if c}


def _flint_poly(expr: sp.Expr, gens: Sequence[sp.Symbol]):
    """``(poly, den)``: FLINT's ``fmpz_mpoly`` of ``den * expr`` (lex on ``gens``, ``den``
    the least common denominator), or None when python-flint is missing or ``expr`` is not
    a polynomial with rational coefficients in ``gens``."""
    try:
        import flint
    except ImportError:  # pragma: no cover - python-flint is a dependency
        return None
    terms = terms_of(expr, gens) if gens else None
    if not terms:
        return None
    den = math.lcm(*(c.denominator for c in terms.values()))
    ctx = flint.fmpz_mpoly_ctx.get(tuple(f"v{i}" for i in range(len(gens))), "lex")
    return ctx.from_dict({e: int(c * den) for e, c in terms.items()}), den


def _from_flint(poly, gens, scale: Fraction = Fraction(1), powers: dict | None = None):
    return expression(((tuple(e), scale * int(c)) for e, c in poly.to_dict().items()), gens,
                      powers)


def discriminant(expr: sp.Expr, q: sp.Symbol) -> sp.Expr:
    """``sympy.discriminant(expr, q)``, expanded, of a polynomial with rational coefficients
    of degree >= 2 in ``q``, computed by FLINT (``(-1)^(n(n-1)/2) res(f, f') / lc(f)``, the
    same definition); anything else goes to sympy."""
    gens = tuple(_sort_gens(expr.free_symbols | {q}))
    flint_poly = _flint_poly(expr, gens)
    if flint_poly is None or int(flint_poly[0].degrees()[gens.index(q)]) < 2:
        return sp.expand(sp.discriminant(expr, q))
    poly, den = flint_poly
    n = int(poly.degrees()[gens.index(q)])
    disc = poly.discriminant(f"v{gens.index(q)}")
    return _from_flint(disc, gens, Fraction(1, den ** (2 * n - 2)))


def factor_list(expr: sp.Expr) -> tuple[sp.Expr, list[tuple[sp.Expr, int]]]:
    """``sympy.factor_list(expr)`` of an expanded polynomial with rational coefficients,
    computed by FLINT's multivariate factorization (python-flint) where it is installed:
    the same constant and the same irreducible factors, each primitive over Z with a
    positive leading coefficient in the lexicographic order of sympy's sorted generators
    (factors in FLINT's order; the callers sort them).  Anything else goes to sympy."""
    gens = tuple(_sort_gens(expr.free_symbols)) if expr.free_symbols else ()
    flint_poly = _flint_poly(expr, gens)
    if flint_poly is None:
        return sp.factor_list(expr)
    poly, den = flint_poly
    constant, factors = poly.factor()
    constant = sp.Rational(int(constant), den)
    out = []
    powers: dict = {}
    for f, k in factors:
        if int(f.leading_coefficient()) < 0:  # pragma: no cover - FLINT returns them positive
            f, constant = -f, constant * (-1) ** int(k)
        out.append((_from_flint(f, gens, powers=powers), int(k)))
    return constant, out



def factor_list_as_sympy(expr: sp.Expr) -> tuple[sp.Expr, list[tuple[sp.Expr, int]]]:
    """``sympy.factor_list(expr)``: the same constant, the same factors (to their srepr) in
    the same order, with each sum factored by FLINT (:func:`factor_list`).

    sympy's steps, followed here: ``together(expr).as_numer_denom()``; each argument of the
    numerator's product factored on its own generators (a number into the constant, a
    symbol as it is, a sum by FLINT); equal factors merged; the list sorted by sympy's key
    (``polytools._sorted_factors``: the dense representation's length in the factor's
    generators, their number, the multiplicity, the representation).  Anything else (a
    denominator with symbols, a power that is not a positive integer, a function) goes to
    sympy itself."""
    return _flint_factor_list(sp.sympify(expr)) or sp.factor_list(expr)


def factor(expr: sp.Expr) -> sp.Expr:
    """``sympy.factor(expr)`` of a polynomial, from :func:`factor_list_as_sympy`'s FLINT
    factors where it uses them (the constant kept as ``sympy.factor`` keeps it, times the
    product of the factors' powers); anything else by ``sympy.factor`` itself.  The same
    expression (``tests/test_typed_polynomials.py`` compares their srepr): IK plans factor
    their coefficients of up to 40 terms, 171 of them over the six mechanisms, in 0.7 s
    against 1.1 s."""
    from sympy.core.mul import _keep_coeff

    expr = sp.sympify(expr)
    found = _flint_factor_list(expr)
    if found is None:
        return sp.factor(expr)
    constant, factors = found
    return _keep_coeff(sp.sympify(constant), sp.Mul(*[f**k for f, k in factors]))


def _flint_factor_list(expr: sp.Expr) -> tuple[sp.Expr, list[tuple[sp.Expr, int]]] | None:
    """:func:`factor_list_as_sympy` where FLINT factors; None where it goes to sympy."""
    from sympy.polys.polytools import _sorted_factors

    numer, denom = sp.together(expr).as_numer_denom()
    if not denom.is_Number:
        return None
    constant = sp.S.One / denom
    merged: dict[sp.Poly, int] = {}
    for arg in sp.Mul.make_args(numer):
        if arg.is_Number:
            constant *= arg
            continue
        base, k = (arg.base, arg.exp) if arg.is_Pow else (arg, sp.S.One)
        if not (k.is_Integer and k > 0) or not (base.is_Symbol or base.is_Add):
            return None
        gens = tuple(_sort_gens(base.free_symbols))
        if base.is_Add and terms_of(base, gens) is None:  # sympy's generators differ
            return None  # (sqrt(3) would be one): its own order
        c, factors = factor_list(base) if base.is_Add else (sp.S.One, [(base, 1)])
        constant *= c ** k
        for f, m in factors:
            poly = sp.Poly(f, *gens)
            merged[poly] = merged.get(poly, 0) + int(m) * int(k)
    return constant, [(p.as_expr(), m) for p, m in _sorted_factors(list(merged.items()),
                                                                    "factor")]


def _symbol_power(f: sp.Expr) -> tuple[sp.Expr, sp.Expr] | None:
    """``(symbol, k)`` for a factor ``symbol**k`` (``k`` a positive integer), else None."""
    base, k = (f.base, f.exp) if f.is_Pow else (f, sp.S.One)
    # k.p: the Python int (sympy's ``k > 0`` sympifies the 0 first, a tenth of the call)
    return (base, k) if base.is_Symbol and k.is_Integer and k.p > 0 else None


def monomial_in(term: sp.Expr, v: sp.Symbol) -> tuple[sp.Expr, int] | None:
    """``(c, e)`` with ``term = c v^e`` for a monomial ``term`` (a rational times positive
    integer powers of symbols; ``c`` the canonical product of the rest), or None for
    anything else."""
    coeff, factors = term.as_coeff_mul()
    if not coeff.is_Rational:
        return None
    e, rest = 0, []
    for f in factors:
        power = _symbol_power(f)
        if power is None:
            return None
        if power[0] == v:
            e += int(power[1])
        else:
            rest.append(f)
    return sp.Mul(coeff, *rest), e


def coefficients_of_monomials(g: sp.Expr, v: sp.Symbol) -> dict[int, sp.Expr] | None:
    """``{k: coefficient of v^k}`` of ``g`` when ``g`` is a sum of monomials
    (:func:`monomial_in`), each coefficient the canonical sum of its monomials, as expanded
    as ``g``; None for anything else.  Reading the terms is many times faster than
    ``Poly(g, v)`` or ``as_coeff_exponent`` (which collects)."""
    by_power: dict[int, list[sp.Expr]] = {}
    for term in sp.Add.make_args(g):
        split = monomial_in(term, v)
        if split is None:
            return None
        by_power.setdefault(split[1], []).append(split[0])
    return {k: sp.Add(*cs) for k, cs in by_power.items()}


def coefficients(g: sp.Expr, v: sp.Symbol) -> dict[int, sp.Expr]:
    """``{k: coefficient of v^k}`` of the polynomial ``g`` in ``v`` (non-zero ones): off
    its monomials (:func:`coefficients_of_monomials`), through ``sympy.Poly`` where a term
    is not a monomial."""
    coeff = coefficients_of_monomials(g, v)
    if coeff is None:
        poly = sp.Poly(g, v)
        coeff = {m[0]: c for m, c in zip(poly.monoms(), poly.coeffs())}
    return coeff


def _simple_mul(a: sp.Expr):
    """``(coefficient, factors, powers)`` of a product of a leading number and factors that
    are symbols or symbols to positive integer powers; None for any other product."""
    args = a.args
    coeff = args[0] if args[0].is_Number else sp.S.One
    factors = args[1:] if args[0].is_Number else args
    if any(_symbol_power(f) is None for f in factors):
        return None
    return coeff, len(factors), sum(1 for f in factors if f.is_Pow)


def _simple_mul_ops(coeff: sp.Expr, r: int, powers: int) -> int:
    """``count_ops`` of ``coeff * factors`` (``coeff`` a positive number, ``r`` factors of
    which ``powers`` are powers): what sympy's ``fraction`` splits off and the products it
    leaves, counted without building them."""
    if coeff.is_Rational and coeff.q != 1:  # DIV, then the numerator p * factors
        k = r + (coeff.p != 1)
        return 1 + (k - 1 if k >= 2 else 0) + powers
    k = r + (coeff is not sp.S.One)
    return (k - 1 if k >= 2 else 0) + powers


def count_ops(expr) -> int:
    """``sympy.count_ops(expr)`` (visual=False), the same number: sympy's walk, counted
    in integers instead of symbolic operation names summed at the end, and a product of a
    number and symbol powers counted without rebuilding it through ``fraction`` and
    negation (the greater part of sympy's time on the kernels and long generators).
    Anything but a non-relational expression goes to sympy."""
    from sympy.core.function import _coeff_isneg
    from sympy.core.operations import LatticeOp
    from sympy.simplify.radsimp import fraction

    expr = sp.sympify(expr)
    if not isinstance(expr, sp.Expr) or expr.is_Relational:
        return int(sp.count_ops(expr))
    from sympy import Derivative, Integral, Sum

    n = 0
    todo: list = [(expr, False)]  # (expression, negate it first)
    while todo:
        a, negate = todo.pop()
        if a.is_Mul and (simple := _simple_mul(a)) is not None:
            coeff, r, powers = simple
            if coeff.is_extended_negative:
                n += not negate  # NEG, unless a sum's SUB stands for the sign
                coeff = -coeff
            n += _simple_mul_ops(coeff, r, powers)
            continue
        if negate:
            a = -a
        if a.is_Rational:
            if a is not sp.S.One:
                n += (a.p < 0) + (a.q != 1)
                continue
        elif a.is_Mul or a.is_MatMul:
            if _coeff_isneg(a):
                n += 1
                a = a.as_two_terms()[1] if a.args[0] is sp.S.NegativeOne else -a
            num, den = fraction(a)
            if num.is_Integer:
                n += 1 + (num.p < 0)
                todo.append((den, False))
                continue
            if den is not sp.S.One:
                if not den.is_Integer:
                    todo.append((den, False))
                n += 1
                todo.append((num, False))
                continue
        elif a.is_Add or a.is_MatAdd:
            terms = a.args
            negs = 0
            for i, t in enumerate(terms):
                neg = _coeff_isneg(t)
                negs += neg
                todo.append((t, neg))
                n += i > 0
            n += negs == len(terms)  # -x - y: NEG and SUB
            continue  # -x + y: SUB for the ADD counted
        if a.is_Pow and a.exp is sp.S.NegativeOne:
            n += 1
            todo.append((a.base, False))
            continue
        if a is sp.S.Exp1:
            n += 1
            continue
        if a.is_Pow and a.base is sp.S.Exp1:
            n += 1
            todo.append((a.exp, False))
            continue
        if a.is_Mul or isinstance(a, LatticeOp):
            n += len(a.args) - 1
        elif a.args and (a.is_Pow or a.is_Function
                         or isinstance(a, (Derivative, Integral, Sum))):
            n += 1
        if not a.is_Symbol:
            todo.extend((x, False) for x in a.args)
    return n


def expanded(expr: sp.Expr) -> sp.Expr:
    """``sympy.expand(expr)``, without the rebuild where ``expr`` is a sum of monomials
    with rational coefficients already (``expand`` returns it unchanged; on polynomials of
    thousands of terms it takes seconds to find that out)."""
    if expr.is_Add and all(_is_monomial(t) for t in expr.args):
        return expr
    return sp.expand(expr)


def at_values(exprs: Iterable[sp.Expr], values) -> tuple[sp.Expr, ...]:
    """``exprs`` with the numbers ``values`` (symbol -> number) put in for their symbols and
    expanded; results that are 0 or repeat an earlier one dropped.  By ``xreplace``, which,
    once expanded, gives ``subs``'s expression (the same srepr on all 188 calls of the
    solution-count and closure-dimension analyses over the six derivations, 0.34 s against
    1.70 s)."""
    values = {k: sp.sympify(v) for k, v in values.items()}
    return tuple(dict.fromkeys(e for e in (sp.expand(g.xreplace(values)) for g in exprs)
                               if e != 0))


def simplified(expr: sp.Expr) -> sp.Expr:
    """``sp.simplify(expr)``, with 0 at once where ``sp.cancel`` proves ``expr`` zero (a
    rational function of its symbols and function values that cancels): simplify's own
    candidates include that cancellation and 0 is the shortest, so the answer is the same;
    simplify spends a second on trigonometric or radical differences that cancel."""
    if sp.cancel(expr) == 0:
        return sp.S.Zero
    return sp.simplify(expr)


def _is_monomial(term: sp.Expr) -> bool:
    coeff, factors = term.as_coeff_mul()
    return coeff.is_Rational and all(_symbol_power(f) is not None for f in factors)


def text(expr: sp.Expr) -> str:
    """``str(expr)``, the same characters, for a sum of monomials with rational
    coefficients in distinct plain symbols; other expressions through sympy's printer.

    sympy's ``StrPrinter`` orders an Add's terms by ``as_ordered_terms`` (lex, descending,
    in the symbols sorted by name, which is their ``default_sort_key``), a term's factors by
    their sort key (the coefficient, then the symbols by name) and prints ``c x**k*y/q``
    with the sign and the rational coefficient split; for a polynomial of thousands of
    terms it takes seconds, most of them in the general machinery (``complex`` of every
    coefficient, the printer's dispatch).  Here the monomials are read off once and
    printed by those rules (checked against ``str`` in tests/test_typed_polynomials.py)."""
    parsed = []
    symbols: dict[str, sp.Symbol] = {}
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_coeff_Mul()
        if not coeff.is_Rational:
            return str(expr)
        powers = {}
        for f in sp.Mul.make_args(rest):
            if f is sp.S.One:
                continue
            power = _symbol_power(f)
            if power is None or type(power[0]) is not sp.Symbol:
                return str(expr)
            name = power[0].name
            if symbols.setdefault(name, power[0]) != power[0] or name in powers:
                return str(expr)  # two symbols of one name, or a repeated base
            powers[name] = int(power[1])
        parsed.append((coeff, powers))
    names = sorted(symbols)
    numbers = [t for t in parsed if not t[1]]
    if (len(parsed) == 2 and len(numbers) == 1 and numbers[0][0] > 0
            and [len(t[1]) for t in parsed if t[1]] == [1]
            and next(t for t in parsed if t[1])[0] < 0):
        # as_ordered_terms' special case: a positive number and -c*x**k, the number first
        parsed = [numbers[0], next(t for t in parsed if t[1])]
    elif len(parsed) > 1:
        keyed = [(tuple(p.get(n, 0) for n in names), c, p) for c, p in parsed]
        if len({k for k, _, _ in keyed}) != len(keyed):
            return str(expr)  # a repeated monomial: not a canonical sum
        keyed.sort(key=lambda t: t[0], reverse=True)
        parsed = [(c, p) for _, c, p in keyed]
    out = []
    for coeff, powers in parsed:
        p, q = int(coeff.p), int(coeff.q)
        sign = "-" if p < 0 else ""
        num = [str(abs(p))] if abs(p) != 1 else []
        num += [n if k == 1 else f"{n}**{k}" for n, k in sorted(powers.items())]
        t = "*".join(num) or "1"
        if q != 1:
            t += f"/{q}"
        out.append((sign, t))
    first_sign, first = out[0]
    return first_sign + first + "".join(
        f" {'-' if s else '+'} {t}" for s, t in out[1:])
