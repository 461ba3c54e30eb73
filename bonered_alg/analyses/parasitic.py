"""Parasitic motion: what a closure's legs impose on coordinates the actuators do not drive.

The generators of a closure's leg ideals that contain no actuated joint are the constraints
of the legs alone (for a 3-RPS tripod: each spherical joint stays in the plane of its
revolute joint, 000 eq. 9, 001 eq. 9).  With the platform written in coordinates split into
free ones and parasitic ones (e.g. ``T(x2, y2, z2) Rz(g2) Ry(b) Rx(a)`` with tan-half
angles), the lex basis of these constraints in the parasitic coordinates over
Q(free coordinates, geometry) gives each parasitic coordinate as a function of the free ones
(Cox-Little-O'Shea, Ch. 3 Sect. 1; the basis is triangular and here linear).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from ..algebra import polyring as pr
from ..elimination.problem import ParametricProblem, ParametricResult
from ..errors import MechanismDefinitionError
from ..report.latex_util import broken_math, latex, tex_escape


def _numerator(g: sp.Expr, sub: dict) -> sp.Expr:
    """A numerator of ``g`` with ``sub`` substituted, expanded.  Where the substituted
    values are polynomials: the composition on typed polynomials with its denominators
    cleared (ten times faster than ``together`` and ``expand`` on the expression; for 001's
    conditions the same polynomials, in general the same up to a constant factor, which
    the lex basis does not see); through ``together`` where they are not."""
    syms = sorted(g.free_symbols.union(*(sp.sympify(v).free_symbols for v in sub.values())),
                  key=str)
    ring = pr.ring_over(syms)
    try:
        poly = pr.polynomial(ring, g)
        values = [(ring.gens[syms.index(s)], pr.polynomial(ring, v)) for s, v in sub.items()
                  if s in g.free_symbols]
    except ValueError:
        num, _ = sp.fraction(sp.together(g.subs(sub)))
        return sp.expand(num)
    _, poly = (poly.compose(values) if values else poly).clear_denoms()
    return poly.as_expr()


@dataclass(frozen=True)
class ParasiticResult:
    problem: ParametricProblem
    basis: ParametricResult
    solved: Mapping[sp.Symbol, sp.Expr]
    conditions: tuple[sp.Expr, ...]


@dataclass(frozen=True)
class ParasiticMotion:
    """The parasitic coordinates ``unknowns`` of the platform of closure ``closure`` (a
    point name), written as the Study point ``platform`` in ``unknowns`` and ``free``."""

    name: str
    closure: str
    platform: tuple[sp.Expr, ...]
    unknowns: tuple[sp.Symbol, ...]
    free: tuple[sp.Symbol, ...]
    title: str = "Parasitic motion"
    form: str = ""  # the platform's parametrization in LaTeX, for the report

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")
        if len(self.platform) != 8:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: the platform "
                                                      "needs 8 Study coordinates")
        allowed = set(self.unknowns) | set(self.free) | set(mech.geometric)
        stray = set().union(*(sp.sympify(c).free_symbols for c in self.platform)) - allowed
        if stray:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: the platform "
                                                      f"uses {sorted(map(str, stray))}")

    def run(self, d, algebra) -> ParasiticResult:
        mech = d.mechanism
        closure = mech.closure(self.closure)
        pose, joints = set(closure.pose), set(mech.joints)
        conditions = tuple(g for r in d.legs if r.closure is closure for g in r.generators
                           if not g.free_symbols & joints and g.free_symbols & pose)
        chart = closure.normalization
        point = chart.normalize(tuple(sp.sympify(c) for c in self.platform))
        sub = {s: point[i] for i, s in enumerate(closure.platform) if s in pose}
        eqs = []
        for g in conditions:
            num = _numerator(g, sub)
            if num != 0:
                eqs.append(num)
        consts = [c for c in mech.constants if any(e.has(c.symbol) for e in eqs)]
        eqs += [sp.expand(c.minimal_polynomial) for c in consts]
        eqs = list(dict.fromkeys(eqs))
        used = set().union(*(e.free_symbols for e in eqs))
        params = self.free + tuple(s for s in mech.geometric if s in used)
        problem = ParametricProblem(f"mechanism {mech.name!r}: {self.title.lower()} of the "
                                    f"{closure.name}", tuple(eqs),
                                    self.unknowns + tuple(c.symbol for c in consts), params)
        result = algebra.lex_basis(problem)
        values = {c.symbol: c.value for c in consts}
        solved = {}
        for gen in result.generators:
            gen = gen.subs(values)
            unknown = [u for u in self.unknowns if gen.has(u)]
            if len(unknown) == 1 and sp.degree(gen, unknown[0]) == 1:
                solved[unknown[0]] = sp.factor(sp.solve(gen, unknown[0])[0])
        missing = [str(u) for u in self.unknowns if u not in solved]
        if missing:
            raise MechanismDefinitionError(
                mech.name, f"analysis {self.name!r}: the lex basis does not give {missing} "
                "linearly in the free coordinates")
        return ParasiticResult(problem, result, MappingProxyType(solved), conditions)

    def report(self, result: ParasiticResult) -> list[str]:
        p = result.problem
        out = [rf"\section{{{tex_escape(self.title)}}}",
               "The generators of the leg ideals free of the actuated joints are the legs' own "
               f"constraints ({len(result.conditions)} of them). With the platform written as "
               + (f"${self.form}$" if self.form else
                  f"$[{':'.join(latex(c) for c in self.platform)}]$")
               + ", their lexicographic basis in "
               + ", ".join(f"${latex(u)}$" for u in p.unknowns) + r" over $\mathbb{Q}("
               + ", ".join(latex(s) for s in p.parameters) + ")$ is:"]
        for k, gen in enumerate(result.basis.generators, 1):
            out.append(broken_math(f"p_{{{k}}}", gen))
        out.append("Solved: " + ", ".join(f"${latex(k)} = {latex(v)}$"
                                          for k, v in result.solved.items()) + ".")
        return out
