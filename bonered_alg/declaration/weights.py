"""Link weights for the static model: where each weight acts, on which body of the legs.

A :class:`LinkWeight` is a weight ``G`` (a parameter, in N) acting downwards (along -Z of
the base frame) at a point fixed to one body.  The point is written as an affine
combination of points fixed to bodies of the legs, ``sum share_i * (g_i * c_i)`` with the
shares summing to 1: one point of one body, or a point on a link that is not a body of the
chains (the long link of a parallelogram, a generalized joint's inner link) written
between two body points it joins; the combination is a point of that link because the
link is rigid and both points are fixed to it.  Bodies are named as the generated
``LINKS`` (``<leg>.<k>``, the body after the leg's k-th moving joint) or ``"platform"``
(the end effector's frame of the pose map).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

PLATFORM = "platform"


@dataclass(frozen=True)
class WeightPoint:
    """A point ``local`` (body coordinates, mm) of body ``body`` carrying ``share`` of the
    weight."""

    body: str
    local: tuple[sp.Expr, sp.Expr, sp.Expr]
    share: sp.Expr = sp.Integer(1)


@dataclass(frozen=True)
class LinkWeight:
    """The weight ``weight`` (a parameter symbol, N) of a link, at the combination of
    ``points``; ``reading`` says how the paper's distances were read."""

    name: str
    weight: sp.Symbol
    points: tuple[WeightPoint, ...]
    description: str
    reading: str = ""


def body_names(mech) -> list[str]:
    """The bodies of the actuated closures' legs as the generated ``LINKS`` names them."""
    out = []
    for closure in mech.actuated_closures:
        for leg in closure.legs:
            moving = [j for j in leg.joints if j.kind != "offset"]
            out += [f"{leg.name}.{k}" for k in range(1, len(moving) + 1)]
    return out
