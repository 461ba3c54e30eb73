"""The spatial twist of a body from its Study point: ``(omega; v) = (g' g^-1)^vee``.

For a Study point ``Q = x + eps y`` (any scale, 004 eq. 1) of the transform ``g = (R, t)``
with ``y = -1/2 t x`` (004 eq. 13): ``omega = 2 vec(x' conj(x)) / |x|^2`` (the angular
velocity of ``R``, ``R' R^T = [omega]x``) and ``v = t' - omega x t``, the velocity of the
point of the body at the origin of the base frame.  The columns of :func:`pose_twist` map
the rates of the pose coordinates to the twist.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from ..algebra import convention as cv


def pose_twist(point: Sequence[sp.Expr], pose: Sequence[sp.Symbol]) -> sp.Matrix:
    """6 x len(pose): column i is the spatial twist per unit rate of ``pose[i]``."""
    x = tuple(sp.sympify(c) for c in point[:4])
    n = cv.rotation_norm(point)
    t = [c / n for c in cv.translation_times_norm(point)]
    conj = (x[0], -x[1], -x[2], -x[3])
    cols = []
    for p in pose:
        dx = tuple(sp.diff(c, p) for c in x)
        w = [2 * c / n for c in cv.quaternion_product(dx, conj)[1:]]
        dt = [sp.diff(c, p) for c in t]
        v = [dt[0] - (w[1] * t[2] - w[2] * t[1]), dt[1] - (w[2] * t[0] - w[0] * t[2]),
             dt[2] - (w[0] * t[1] - w[1] * t[0])]
        cols.append(w + v)
    return sp.Matrix(cols).T
