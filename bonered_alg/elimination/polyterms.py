"""Exact term lists: the engine-independent form of polynomials, and their normal form.

A polynomial is a tuple of terms ``(exponents, coefficient)`` with integer exponent tuples and
``fractions.Fraction`` coefficients.  Both engines return term lists; the normal form here
(primitive integer coefficients, positive leading coefficient, terms and generators sorted by
the degree-reverse-lexicographic order) makes a reduced Groebner basis unique and
byte-for-byte deterministic.  No strings are ever evaluated: coefficients are parsed as
rationals only.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from fractions import Fraction
from itertools import combinations

Exponents = tuple[int, ...]
Term = tuple[Exponents, Fraction]
PolyTerms = tuple[Term, ...]


def grevlex_key(e: Exponents) -> tuple:
    """Sort key of the degree-reverse-lexicographic order (larger key = larger monomial)."""
    return (sum(e), tuple(-x for x in reversed(e)))


def parse_rational(text: str) -> Fraction:
    """Parse ``'-3/4'`` or ``'12'`` strictly (no evaluation of arbitrary expressions)."""
    text = text.strip()
    num, _, den = text.partition("/")
    if not num.lstrip("-+").isdigit() or (den and not den.isdigit()):
        raise ValueError(f"not a rational number: {text!r}")
    return Fraction(int(num), int(den) if den else 1)


def normal_form(terms: Iterable[Term]) -> PolyTerms:
    """Primitive integer polynomial with positive grevlex-leading coefficient.  (Integer
    arithmetic on numerators where the denominators are cleared: ``c * den`` is
    ``numerator * (den // denominator)`` exactly; a Fraction is added only to a repeated
    monomial.)"""
    merged: dict[Exponents, Fraction] = {}
    for e, c in terms:
        e = tuple(e)
        c = c if type(c) is Fraction else Fraction(c)
        merged[e] = merged[e] + c if e in merged else c
    items = sorted(((e, c) for e, c in merged.items() if c != 0), key=lambda t: grevlex_key(t[0]),
                   reverse=True)
    if not items:
        return ()
    den = math.lcm(*(c.denominator for _, c in items))
    ints = [c.numerator * (den // c.denominator) for _, c in items]
    g = math.gcd(*ints)
    sign = 1 if ints[0] > 0 else -1
    return tuple((e, Fraction(sign * i // g)) for (e, _), i in zip(items, ints))


def normal_basis(polys: Iterable[Iterable[Term]]) -> tuple[PolyTerms, ...]:
    """Normal forms of all non-zero generators, sorted by leading monomial (ascending)."""
    nfs = [p for p in (normal_form(t) for t in polys) if p]
    return tuple(sorted(set(nfs), key=lambda p: [grevlex_key(e) for e, _ in p]))


def dimension_from_leading_monomials(leading: Sequence[Exponents], nvars: int) -> int:
    """Krull (Hilbert) dimension of ``k[x]/I`` from the leading monomials of a Groebner basis of I.

    The dimension is the size of the largest set of variables that contains the support of
    no leading monomial (Cox, Little, O'Shea, *Ideals, Varieties, and Algorithms*, 4th ed.,
    Ch. 9 Sect. 3, Prop. 3 and Thm. 8).  Returns -1 for the unit ideal.
    """
    supports = [frozenset(i for i, x in enumerate(e) if x) for e in leading]
    if any(not s for s in supports):
        return -1
    for size in range(nvars, -1, -1):
        for subset in combinations(range(nvars), size):
            free = frozenset(subset)
            if not any(s <= free for s in supports):
                return size
    return 0


def count_standard_monomials(leading: Sequence[Exponents], nvars: int) -> int | None:
    """Number of monomials outside the leading-term ideal (the number of solutions counted
    with multiplicity of a zero-dimensional ideal; Cox-Little-O'Shea Ch. 5 Sect. 3, Thm. 6).
    None when the ideal is not zero-dimensional."""
    bounds = []
    for i in range(nvars):
        pure = [e[i] for e in leading if e[i] and all(x == 0 for j, x in enumerate(e) if j != i)]
        if not pure:
            return None
        bounds.append(min(pure))
    count = 0
    for mono in _box(bounds):
        if not any(all(m >= x for m, x in zip(mono, e)) for e in leading):
            count += 1
    return count


def _box(bounds):
    if not bounds:
        yield ()
        return
    for head in range(bounds[0]):
        for tail in _box(bounds[1:]):
            yield (head, *tail)


def to_json(basis: Sequence[PolyTerms]) -> list:
    """JSON-safe form: ``[[[exponents], "num/den"], ...]`` per generator."""
    return [[[list(e), str(c)] for e, c in p] for p in basis]


def from_json(data: list) -> tuple[PolyTerms, ...]:
    """Inverse of :func:`to_json`, validating every entry."""
    out = []
    for p in data:
        out.append(tuple((tuple(int(x) for x in e), parse_rational(c)) for e, c in p))
    return tuple(out)


def canonical_text(basis: Sequence[PolyTerms]) -> str:
    """Deterministic text of a basis, for hashing."""
    return ";".join(",".join(f"{c}*{list(e)}" for e, c in p) for p in basis)
