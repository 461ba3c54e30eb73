"""The mobility from the ideal: the Krull dimension of a closure's variety at the declared
geometry (Cox-Little-O'Shea, Ch. 9 Sect. 3: the dimension from the leading monomials of a
Groebner basis).

The closure's ideal is the sum of its leg ideals, in the closure's coordinates and the
actuated joints; with the geometry at the declared parameter values (exact decimals), its
dimension is the number of independent motions of the closed mechanism over the complex
numbers: the mobility the counting formulas of the papers predict (002 eq. 3), without
their assumptions on generic joint axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..algebra import polyring as pr
from ..elimination.problem import EliminationProblem, EliminationResult
from ..errors import MechanismDefinitionError
from ..report.latex_util import latex, tex_escape


@dataclass(frozen=True)
class DimensionResult:
    result: EliminationResult
    variables: tuple[sp.Symbol, ...]

    @property
    def dimension(self) -> int:
        return self.result.dimension


def exact(value: float) -> sp.Rational:
    """A declared parameter value as the exact decimal it was written as."""
    return sp.Rational(repr(float(value)))


@dataclass(frozen=True)
class ClosureDimension:
    """Krull dimension of the ideal of closure ``closure`` (a point name) at the declared
    geometry, in (closure coordinates, actuated joints)."""

    name: str
    closure: str
    title: str = "Mobility from the ideal"

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")

    def run(self, d, algebra) -> DimensionResult:
        mech = d.mechanism
        closure = mech.closure(self.closure)
        values = {p.symbol: exact(p.value) for p in mech.parameters}
        eqs = pr.at_values(d.closure_generators(self.closure), values)
        used = set().union(*(e.free_symbols for e in eqs))
        stray = used - set(closure.pose) - set(mech.joints)
        if stray:
            raise MechanismDefinitionError(
                mech.name, f"analysis {self.name!r}: the ideal still has "
                f"{sorted(map(str, stray))} after the parameters are set")
        keep = tuple(closure.pose) + tuple(j for j in mech.joints if j in used)
        problem = EliminationProblem(
            f"mechanism {mech.name!r}, analysis {self.name!r}: the {closure.name}'s ideal at "
            "the declared geometry", eqs, (), keep)
        return DimensionResult(algebra.eliminate(problem), keep)

    def report(self, result: DimensionResult) -> list[str]:
        names = ", ".join(f"${latex(v)}$" for v in result.variables)
        return [rf"\section{{{tex_escape(self.title)}}}",
                f"The closure's ideal (the sum of its leg ideals) at the declared geometry, in "
                f"{names}: a Groebner basis of {len(result.result.basis)} generators, Krull "
                f"dimension {result.dimension}. That is the number of independent motions "
                "of the closed mechanism (over the complex numbers; a real configuration "
                "that is a smooth point of the variety has as many)."]
