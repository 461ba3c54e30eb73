"""The ideal of one leg: the first method in :data:`LEG_METHODS` that applies.

* :class:`DistanceLeg`: a leg that only fixes a distance (U-P-S, S-P-S) has the pulled-back
  sphere condition as its ideal, certified instead of eliminated
  (:mod:`bonered_alg.elimination.sphere_leg`);
* :class:`Elimination`: any leg, by a Groebner basis for an elimination order
  (:mod:`bonered_alg.elimination.closure`); a mounted leg is eliminated in its mount's frame.
"""

from __future__ import annotations

import sympy as sp

from ..algebra.study_symbolic import quadric
from ..declaration.closures import UnitCoordinate
from ..elimination import sphere_leg
from ..elimination.closure import leg_problem, leg_variables, moved_platform
from ..elimination.problem import EliminationProblem
from ..errors import NonClosingMechanismError
from ..pipeline.results import LegIdeal


class DistanceLeg:
    """``<Study quadric, sphere condition>`` of a leg ``T(A) R.. T(q) R.. T(-B)``."""

    name = "distance leg (closed-form ideal, certified)"

    def derive(self, mech, closure, leg, algebra) -> LegIdeal | None:
        d = sphere_leg.recognize(leg)
        if d is None or leg.mount is not None:
            return None
        chart = closure.normalization
        if not (isinstance(chart, UnitCoordinate) and chart.index == 0):
            return None  # the certificate is written in the chart x0 = 1
        full = leg_variables(mech, closure, leg)
        passive = tuple(s for s in full.eliminate if s != closure.normalization.scale)
        params = {p.symbol: sp.nsimplify(p.value) for p in mech.parameters}
        consts = {c.symbol: c.value for c in mech.constants}
        try:
            note = sphere_leg.certify(leg, d, closure.platform, passive, params, consts)
        except sphere_leg.NotADistanceLeg:
            return None
        eqs = (quadric(closure.platform),
               sphere_leg.sphere_condition(d, closure.platform,
                                           sphere_leg.minimal_polynomials(consts)))
        eqs += tuple(sp.expand(c.minimal_polynomial) for c in mech.constants
                     if c.symbol in full.keep)
        problem = EliminationProblem(full.context + " (closed-form distance-leg ideal)", eqs,
                                     (), full.keep)
        result = algebra.eliminate(problem)
        return LegIdeal(closure, leg, leg.product(), problem, result,
                        tuple(result.generators), problem.keep, self.name, note)


class Elimination:
    """The passive joint variables and the chart's scale eliminated by a Groebner basis."""

    name = "Groebner elimination"

    def derive(self, mech, closure, leg, algebra) -> LegIdeal:
        problem = leg_problem(mech, closure, leg)
        result = algebra.eliminate(problem)
        if result.is_unit_ideal:
            raise NonClosingMechanismError(
                mech.name, f"leg {leg.name!r} cannot close on the platform point "
                f"{closure.point} of the {closure.name}: its elimination ideal is <1> "
                "(no pose satisfies the closure equations)")
        gens = tuple(result.generators)
        keep = problem.keep
        if leg.mount is not None:
            sub = moved_platform(closure, leg)
            gens = tuple(g for g in (sp.expand(g.xreplace(sub)) for g in gens) if g != 0)
            moved = set(sub)
            keep = tuple(closure.pose) + tuple(closure.inputs) + tuple(
                s for s in problem.keep if s not in moved)
        return LegIdeal(closure, leg, leg.product(), problem, result, gens, keep, self.name)


LEG_METHODS = (DistanceLeg(), Elimination())


def leg_ideal(mech, closure, leg, algebra) -> LegIdeal:
    """The ideal of ``leg`` from the first method of :data:`LEG_METHODS` that applies."""
    for method in LEG_METHODS:
        out = method.derive(mech, closure, leg, algebra)
        if out is not None:
            return out
    raise AssertionError("Elimination applies to every leg")  # pragma: no cover
