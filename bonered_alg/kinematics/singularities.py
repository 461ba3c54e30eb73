"""Singularity polynomials: factored determinants of the Jacobians and their projections.

``det Ji`` (input) and ``det Jo`` (output) are factored over Q; each irreducible factor is a
component of the singularity locus (004 Sect. 3.3).  For a quadratic IK step the discriminant
in the joint variable is the projection of ``dg/dq = 0`` onto the pose space: the boundary of
that leg's workspace (the links aligned, 004 eq. 36).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..algebra import polyring as pr


@dataclass(frozen=True)
class FactoredPolynomial:
    """``constant * prod(factor_i ** multiplicity_i)``; or, where ``expression`` is a square
    matrix (``is_determinant``), its determinant, not expanded (no factors)."""

    name: str
    expression: sp.Expr
    constant: sp.Expr
    factors: tuple[tuple[sp.Expr, int], ...]
    meaning: str = ""
    # the same quantity in the pose's Study coordinates and the joints, for the generated
    # code, when ``expression`` is written in other (e.g. passive joint) variables
    evaluate: sp.Expr | None = None

    @property
    def is_determinant(self) -> bool:
        return isinstance(self.expression, sp.MatrixBase)


# a product whose expansion would have more terms than this is factored factor by factor
# and kept as a product (the 6x6 det Ji of the Stewart platform: 16^6 terms expanded)
PRODUCT_LIMIT = 20_000


def _terms(e: sp.Expr) -> int:
    return len(sp.Add.make_args(pr.expanded(e)))


def large_product(factors: list[sp.Expr]) -> bool:
    """True when the expanded product of ``factors`` would exceed ``PRODUCT_LIMIT`` terms
    (estimated as the product of their term counts)."""
    n = 1
    for f in factors:
        n *= _terms(f)
    return n > PRODUCT_LIMIT


def factored(name: str, expr: sp.Expr, meaning: str = "",
             evaluate: sp.Expr | None = None) -> FactoredPolynomial:
    """Factor ``expr`` over the rationals (FLINT, :func:`..algebra.polyring.factor_list`);
    factors sorted for determinism.  An unevaluated
    product (``sp.Mul(..., evaluate=False)``, see :func:`large_product`) is factored factor
    by factor and kept unexpanded."""
    if isinstance(expr, sp.Mul) and large_product(list(expr.args)):
        c, merged = sp.Integer(1), {}
        for arg in expr.args:
            ca, fa = pr.factor_list(pr.expanded(arg))
            c *= ca
            for f, k in fa:
                f = pr.expanded(f)
                merged[f] = merged.get(f, 0) + int(k)
        fl = list(merged.items())
    else:
        expr = pr.expanded(expr)
        c, fl = pr.factor_list(expr)
    fl = sorted(((pr.expanded(f), int(k)) for f, k in fl), key=lambda t: (pr.count_ops(t[0]),
                                                                      sp.srepr(t[0])))
    return FactoredPolynomial(name, expr, c, tuple(fl), meaning, evaluate)


def discriminant(g: sp.Expr, q: sp.Symbol) -> sp.Expr:
    """Discriminant of ``g`` in ``q`` (degree 2: ``B^2 - 4AC``); ``-4 A C`` as an unevaluated
    product when ``B = 0`` and the product is large."""
    g = pr.expanded(g)
    coeff = pr.coefficients(g, q)
    if max(coeff, default=0) == 2 and 1 not in coeff:
        a, c = coeff[2], coeff.get(0, sp.S.Zero)
        if large_product([a, c]):
            return sp.Mul(-4, a, c, evaluate=False)
    return pr.discriminant(g, q)
