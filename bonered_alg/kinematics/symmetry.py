"""Generators carried from one leg to a congruent one by a symmetry of the mechanism.

If leg B is leg A conjugated by a rotation ``rho`` about the base normal (the spherical or
universal joints absorb the turn), then B's ideal is A's ideal pulled back by
``X -> conj(rho) X rho``: a generator of A with A's joint renamed to B's, composed with that
linear map, lies in B's ideal.  The pipeline proves each one by its normal form modulo B's
basis before the planner may use it (``pipeline.stages.plan``).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import study_symbolic as ss
from ..declaration.mechanism import ExtraGenerator


def turned_generators(source, joint: sp.Symbol, targets, platform, constants=(),
                      select=None, note: str = "") -> list[ExtraGenerator]:
    """``source`` (a leg ideal) generators in ``joint`` (those ``select`` keeps) carried to
    each ``(leg name, its joint, tan(theta/2) of its turn about z)`` of ``targets``;
    ``platform`` is the closure's Study point (chart x0 = 1), ``constants`` the algebraic
    constants ``(symbol, value)`` to reduce with."""
    gens = [g for g in source.generators if select is None or select(g)]
    pose = [s for s in platform[1:]]
    out = []
    for name, qk, w in targets:
        rho = ss.product(ss.rotation("z", w), tuple(platform), ss.rotation("z", -w))
        sub = {s: rho[i + 1] / rho[0] for i, s in enumerate(pose)}
        for gen in gens:
            num = sp.fraction(sp.together(gen.subs(joint, qk).xreplace(sub)))[0]
            for sym, value in constants:
                num = sp.expand(num.subs(sym, value)).subs(value, sym)
            out.append(ExtraGenerator(name, sp.expand(num), note))
    return out
