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


def cofactor_determinant(m: sp.MatrixBase) -> sp.Expr:
    """``det m`` by Laplace (cofactor) expansion along the row or column with the most zero
    entries (the first such row, else column), not expanded: the same rational function as
    the expanded determinant, in the matrix's entries, whose common minors CSE shares."""
    n = m.rows
    if m.cols != n:
        raise ValueError(f"a determinant needs a square matrix, got {m.rows} x {m.cols}")
    if n == 1:
        return m[0, 0]
    if n == 2:
        return m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
    zeros = [sum(1 for j in range(n) if m[i, j] == 0) for i in range(n)]
    col_zeros = [sum(1 for i in range(n) if m[i, j] == 0) for j in range(n)]
    if max(col_zeros) > max(zeros):
        return cofactor_determinant(m.T)
    i = zeros.index(max(zeros))
    return sp.Add(*[(-1) ** (i + j) * m[i, j] * cofactor_determinant(m.minor_submatrix(i, j))
                    for j in range(n) if m[i, j] != 0])


def evaluation_form(expanded: sp.Expr, matrix: sp.MatrixBase) -> sp.Expr | None:
    """The determinant of ``matrix`` as the generated code should evaluate it: its cofactor
    expansion (:func:`cofactor_determinant`) where that counts fewer operations than
    ``expanded`` (urrh_rcm's 4 x 4 det Ji: 4,778 operations after CSE expanded, 129 from
    the entries), else None (the expansion)."""
    form = cofactor_determinant(matrix)
    return form if pr.count_ops(form) < pr.count_ops(expanded) else None


def factored(name: str, expr: sp.Expr, meaning: str = "",
             evaluate: sp.Expr | None = None,
             matrix: sp.MatrixBase | None = None) -> FactoredPolynomial:
    """Factor ``expr`` over the rationals (FLINT, :func:`..algebra.polyring.factor_list`);
    factors sorted for determinism.  An unevaluated
    product (``sp.Mul(..., evaluate=False)``, see :func:`large_product`) is factored factor
    by factor and kept unexpanded.  ``matrix``: the matrix whose determinant ``expr`` is;
    the generated code then evaluates :func:`evaluation_form`."""
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
    if evaluate is None and matrix is not None:
        evaluate = evaluation_form(expr, matrix)
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
