"""Singularity polynomials: factored determinants of the Jacobians and their projections.

``det Ji`` (input) and ``det Jo`` (output) are factored over Q; each irreducible factor is a
component of the singularity locus (004 Sect. 3.3).  For a quadratic IK step the discriminant
in the joint variable is the projection of ``dg/dq = 0`` onto the pose space: the boundary of
that leg's workspace (the links aligned, 004 eq. 36).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp


@dataclass(frozen=True)
class FactoredPolynomial:
    """``constant * prod(factor_i ** multiplicity_i)``."""

    name: str
    expression: sp.Expr
    constant: sp.Expr
    factors: tuple[tuple[sp.Expr, int], ...]
    meaning: str = ""
    # the same quantity in the pose's Study coordinates and the joints, for the generated
    # code, when ``expression`` is written in other (e.g. passive joint) variables
    evaluate: sp.Expr | None = None


def factored(name: str, expr: sp.Expr, meaning: str = "",
             evaluate: sp.Expr | None = None) -> FactoredPolynomial:
    """Factor ``expr`` over the rationals; factors sorted for determinism."""
    expr = sp.expand(expr)
    c, fl = sp.factor_list(expr)
    fl = sorted(((sp.expand(f), int(k)) for f, k in fl), key=lambda t: (sp.count_ops(t[0]),
                                                                      sp.srepr(t[0])))
    return FactoredPolynomial(name, expr, c, tuple(fl), meaning, evaluate)


def discriminant(g: sp.Expr, q: sp.Symbol) -> sp.Expr:
    """Discriminant of ``g`` in ``q`` (degree 2: ``B^2 - 4AC``)."""
    return sp.expand(sp.discriminant(sp.expand(g), q))
