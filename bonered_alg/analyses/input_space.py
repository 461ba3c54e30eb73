"""Singularity factors in the actuated joints: the pose eliminated against the closure's
ideal, as the papers print them (004 eq. 24-27 give sg3-sg6 in t1, w1)."""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from ..algebra import polyring as pr
from ..elimination.problem import EliminationProblem
from ..errors import MechanismDefinitionError


@dataclass(frozen=True)
class InputSpaceSingularities:
    """Each factor (with a pose coordinate) of the named singularity polynomials, with the
    closure's pose coordinates eliminated against its ideal: ``{name: ((factor, its
    symbols), ...)}`` over the irreducible factors of the eliminants."""

    name: str
    closure: str
    singularities: tuple[str, ...]

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")

    def run(self, d, algebra):
        mech = d.mechanism
        closure = mech.closure(self.closure)
        gens = [g for r in d.legs if r.closure is closure for g in r.generators]
        pose = tuple(s for s in closure.pose if any(g.has(s) for g in gens))
        used = set().union(*(g.free_symbols for g in gens))
        keep = tuple(q for q in mech.joints if q in used) + tuple(
            s for s in mech.geometric if s in used)
        out = {}
        for poly in d.singularities:
            if poly.name not in self.singularities:
                continue
            facs = []
            for f, _ in poly.factors:
                if not f.free_symbols & set(pose):
                    continue
                problem = EliminationProblem(
                    f"mechanism {mech.name!r}: {poly.name} in the inputs "
                    f"({', '.join(str(q) for q in keep if q in mech.joints)})",
                    tuple(sp.expand(e) for e in (*gens, f)), pose, keep)
                res = algebra.eliminate(problem)
                for g in res.generators:
                    for ff, _k in pr.factor_list_as_sympy(g)[1]:
                        if ff.free_symbols & set(mech.joints):
                            facs.append((ff, frozenset(ff.free_symbols)))
            out[poly.name] = tuple(facs)
        missing = sorted(set(self.singularities) - set(out))
        if missing:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no derived "
                                                      f"singularity named {missing}")
        return MappingProxyType(out)

    def report(self, result) -> list[str]:
        return []
