"""Closure equations of a leg and the elimination problem that removes its passive joints.

The closure's chart (:mod:`bonered_alg.declaration.closures`) gives the equations of
``C = lambda X``; the passive joint variables and the chart's scale variable are eliminated
(Cox-Little-O'Shea, Ch. 3 Sect. 1, Elimination Theorem).

A leg with a ``mount`` (a pure translation ``T`` in other closures' outputs) is eliminated
in the mount's frame: its local chain closes on ``X' = conj(T) X``, whose rotation part is
that of ``X`` (so the chart is unchanged), and the ideal is carried back by substituting
``X'`` -- a linear change of coordinates, so the substituted generators generate the leg's
ideal in ``X`` and the inputs.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import study_symbolic as ss
from ..declaration.closures import MU, Closure
from .problem import EliminationProblem

__all__ = ["MU", "closure_equations", "leg_problem", "leg_variables", "moved_symbols",
           "moved_platform"]


def closure_equations(chain, platform, chart) -> list[sp.Expr]:
    """The chart's equations of ``chain = lambda * platform``."""
    return chart.equations(chain, platform)


def moved_symbols(closure: Closure) -> tuple[sp.Symbol, ...]:
    """The platform coordinates in a leg's mount frame (one symbol per Study coordinate)."""
    return tuple(sp.Symbol(f"m_{k}", real=True)
                 for k in ("x0", "x1", "x2", "x3", "y0", "y1", "y2", "y3"))


def moved_platform(closure: Closure, leg) -> dict[sp.Symbol, sp.Expr]:
    """``X' = conj(mount) X``: each moved coordinate as a linear form in the platform's."""
    moved = ss.product(ss.conjugate(tuple(leg.mount)), tuple(closure.platform))
    return dict(zip(moved_symbols(closure), moved))


def _leg_frame(closure: Closure, leg):
    """``(chain, platform, pose, symbols)`` of the leg in its own frame (the mount's, if
    any); ``chain`` is computed only when called."""
    if leg.mount is None:
        return leg.product, tuple(closure.platform), tuple(closure.pose), leg.free_symbols
    syms = set().union(*(f.free_symbols for f in leg.factors))
    pose = moved_symbols(closure)
    return leg.local_product, pose, pose, syms


def leg_variables(mech, closure: Closure, leg) -> EliminationProblem:
    """``leg_problem`` without its equations: the variables it eliminates and keeps, and
    its context, for a caller that writes the leg's ideal another way."""
    _, _, pose, syms = _leg_frame(closure, leg)
    couplings = [c.equation for c in closure.couplings if c.equation.free_symbols & syms]
    syms = syms.union(*(c.free_symbols for c in couplings))
    passive = tuple(s for s in mech.passive if s in syms)
    active = tuple(s for s in mech.active if s in syms)
    geometric = tuple(s for s in mech.geometric if s in syms)
    constants = tuple(c for c in mech.constants if c.symbol in syms)
    frame = "" if leg.mount is None else " (in the frame of its mount)"
    return EliminationProblem(
        context=f"mechanism {mech.name!r}, closure {closure.name!r}, leg {leg.name!r}{frame}",
        equations=tuple(couplings) + tuple(c.minimal_polynomial for c in constants),
        eliminate=passive + (closure.normalization.scale,),
        keep=pose + active + geometric + tuple(c.symbol for c in constants),
    )


def leg_problem(mech, closure: Closure, leg) -> EliminationProblem:
    """The problem eliminating ``leg``'s passive variables (and the chart's scale)."""
    chain, platform, _, _ = _leg_frame(closure, leg)
    shape = leg_variables(mech, closure, leg)
    eqs = closure_equations(chain(), platform, closure.normalization)
    eqs += [sp.expand(c) for c in shape.equations]
    return EliminationProblem(shape.context, tuple(eqs), shape.eliminate, shape.keep)
