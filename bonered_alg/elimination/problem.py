"""An elimination problem and its result, independent of the engine that solves it."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

import sympy as sp

from . import polyterms as pt


@dataclass(frozen=True)
class EliminationProblem:
    """Eliminate ``eliminate`` from the ideal of ``equations``; keep ``keep``.

    The answer is the reduced Groebner basis of the elimination ideal
    ``<equations> ∩ Q[keep]`` in the grevlex order on ``keep`` (in the given order), normalized by
    :func:`polyterms.normal_basis` (Cox-Little-O'Shea, Ch. 3 Sect. 1, Elimination Theorem).
    ``context`` names the mechanism and step for error messages.
    """

    context: str
    equations: tuple[sp.Expr, ...]
    eliminate: tuple[sp.Symbol, ...]
    keep: tuple[sp.Symbol, ...]

    @property
    def gens(self) -> tuple[sp.Symbol, ...]:
        return self.eliminate + self.keep

    def equation_terms(self) -> list[pt.PolyTerms]:
        """Equations as exact term lists over ``gens`` (rational coefficients only)."""
        out = []
        for eq in self.equations:
            poly = sp.Poly(sp.expand(eq), *self.gens, domain=sp.QQ)
            out.append(
                tuple((e, pt.parse_rational(str(c))) for e, c in poly.terms())
            )
        return out

    def canonical_text(self) -> str:
        names = ",".join(map(str, self.gens))
        eqs = pt.canonical_text([pt.normal_form(t) for t in self.equation_terms()])
        return f"elim={len(self.eliminate)};vars={names};eqs={eqs}"

    def key(self, engine: str) -> str:
        return hashlib.sha256(f"{engine}|{self.canonical_text()}".encode()).hexdigest()


@dataclass
class EliminationResult:
    """Normalized reduced Groebner basis of the elimination ideal, with provenance."""

    problem: EliminationProblem
    basis: tuple[pt.PolyTerms, ...]
    dimension: int
    engine: str
    seconds: float
    cached: bool = field(default=False)

    @property
    def generators(self) -> list[sp.Expr]:
        """The generators as sympy expressions in ``problem.keep``."""
        keep = self.problem.keep
        return [
            sp.Add(*[sp.Rational(c.numerator, c.denominator) * sp.Mul(
                *[v**k for v, k in zip(keep, e)]) for e, c in p])
            for p in self.basis
        ]

    @property
    def is_unit_ideal(self) -> bool:
        return self.dimension == -1
