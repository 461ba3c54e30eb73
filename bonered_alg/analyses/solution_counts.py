"""Dimension and solution count of a closure's ideal at rational configurations.

At each configuration (values of the closure's inputs and the geometry) the exact lex
Groebner basis of the closure's ideal in its Study coordinates gives the Krull dimension
and, for a zero-dimensional ideal, the number of solutions counted with multiplicity (the
standard monomials; Cox-Little-O'Shea, Ch. 5 Sect. 3, Thm. 6).  A configuration where a
printed basis divides by zero but the count does not drop is regular (004 eq. 28-29).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from ..algebra import polyring as pr
from ..elimination import polyterms as pt
from ..elimination.problem import ParametricProblem
from ..errors import MechanismDefinitionError
from ..report.latex_util import tex_escape


@dataclass(frozen=True)
class SolutionCounts:
    """Counts of the ideal of the closure on ``closure`` at each of ``configurations``."""

    name: str
    closure: str
    configurations: Mapping[str, Mapping[sp.Symbol, sp.Expr]]
    title: str = "Solution counts"

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")

    def run(self, d, algebra) -> Mapping[str, dict]:
        mech = d.mechanism
        closure = mech.closure(self.closure)
        unknowns = tuple(closure.pose)
        gens = d.closure_generators(self.closure)
        out = {}
        for label, values in self.configurations.items():
            eqs = pr.at_values(gens, values)
            problem = ParametricProblem(f"mechanism {mech.name!r}: ideal of the "
                                        f"{closure.name} at {label}", eqs, unknowns, ())
            res = algebra.lex_basis(problem)
            n = len(unknowns)
            leading = [max(e[:n] for e, _ in poly) for poly in res.basis]
            dim = pt.dimension_from_leading_monomials(leading, n)
            count = pt.count_standard_monomials(leading, n) if dim == 0 else None
            degrees = sorted(sp.Poly(g, *unknowns).total_degree() for g in res.generators)
            out[label] = {"dimension": dim, "count": count, "degrees": degrees}
        return MappingProxyType(out)

    def report(self, result) -> list[str]:
        out = [rf"\section{{{tex_escape(self.title)}}}",
               tex_escape("Exact Groebner bases of the closure's ideal at rational "
                          "configurations:"),
               r"\begin{center}\begin{tabular}{lrr}\hline configuration & dimension & "
               r"solutions\\\hline"]
        for label, cnt in result.items():
            out.append(f"{tex_escape(label)} & {cnt['dimension']} & "
                       f"{cnt['count'] if cnt['count'] is not None else '--'}\\\\")
        out.append(r"\hline\end{tabular}\end{center}")
        return out
