"""Closure equations of a leg and the elimination problem that removes its passive joints.

A leg closes on the platform when its chain product ``C`` and the platform's Study point ``X``
are the same projective point: ``C = lambda X`` with ``lambda != 0``.  With the normalization
``X_p = 1`` this is ``C_k - C_p X_k = 0`` for ``k != p``, and ``C_p != 0`` is imposed by the
Rabinowitsch variable ``mu``: ``1 - mu C_p = 0`` (Cox-Little-O'Shea, Ch. 4 Sect. 4, saturation).
"""

from __future__ import annotations

import sympy as sp

from ..chains.joints import Leg
from ..chains.mechanism import Closure, Mechanism
from .problem import EliminationProblem

MU = sp.Symbol("mu_sat")


def closure_equations(chain: tuple[sp.Expr, ...], platform: tuple[sp.Expr, ...]) -> list[sp.Expr]:
    """``C_k - C_p X_k`` for ``k != p`` and ``1 - mu C_p``, where ``X_p = 1``."""
    p = next(i for i, c in enumerate(platform) if sp.sympify(c) == 1)
    eqs = [sp.expand(chain[k] - chain[p] * platform[k]) for k in range(8) if k != p]
    eqs.append(sp.expand(1 - MU * chain[p]))
    return [e for e in eqs if e != 0]


def leg_problem(mech: Mechanism, closure: Closure, leg: Leg) -> EliminationProblem:
    """The problem eliminating ``leg``'s passive variables (and ``mu``) from its closure."""
    eqs = closure_equations(leg.product(), closure.platform)
    syms = leg.free_symbols
    couplings = [c.equation for c in closure.couplings if c.equation.free_symbols & syms]
    eqs += [sp.expand(c) for c in couplings]
    syms = syms.union(*(c.free_symbols for c in couplings))
    passive = tuple(s for s in mech.passive if s in syms)
    active = tuple(s for s in mech.active if s in syms)
    geometric = tuple(s for s in mech.geometric if s in syms)
    constants = tuple(c for c in mech.constants if c.symbol in syms)
    eqs += [sp.expand(c.minimal_polynomial) for c in constants]
    pose = tuple(closure.pose)
    return EliminationProblem(
        context=f"mechanism {mech.name!r}, closure {closure.name!r}, leg {leg.name!r}",
        equations=tuple(eqs),
        eliminate=passive + (MU,),
        keep=pose + active + geometric + tuple(c.symbol for c in constants),
    )
