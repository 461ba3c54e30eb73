"""Jacobian rows of distance legs from the leg's line, not from its sphere polynomial.

A distance leg (:mod:`..elimination.sphere_leg`) keeps the platform point ``B`` at distance
``|q|`` from the base point ``A``: with the platform at ``(R, t)`` the leg vector is
``l = R B + t - A`` and ``q^2 = |l|^2``.  Differentiating, ``q dq/dX_m = l . dl/dX_m``, and
with ``dl/dX_m = omega_m x R B + t'_m`` (``omega_m`` the angular velocity of ``R`` per unit
rate of the pose coordinate ``X_m``, ``t'_m = dt/dX_m``)

    q dq/dX_m = omega_m . (R B x l) + t'_m . l,

the leg's line in Plucker coordinates paired with the platform's velocity (the classical
inverse Jacobian of a Gough-Stewart platform).  The frame
``R, t, omega_m, t'_m`` of a platform is shared by all its legs; per leg the row costs a
few dozen operations, where the chain rule through the eight linear forms of the sphere
condition in the Study coordinates costs a few hundred (a Stewart leg: 290).

The row holds for either sign of ``q`` (both roots of the leg's quadratic), and its pivot
and row scale are those of the sphere generator ``g = q^2 R - 4 D`` divided by ``2 R`` on
the solution: ``dg/dq = 2 q |x|^2`` and ``dg/dX_m = -2 |x|^2 l . dl/dX_m``, so the ratio
``|pivot| / scale`` that decides an input singularity is unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from ..algebra import convention as cv


def _rational(e: sp.Expr) -> sp.Expr:
    """``e`` as one reduced fraction, numerator and denominator factored: the frame of a
    pose map in tan-half-angles reduces to products of ``1 +- t^2`` and ``t`` (Z-Y-X angles:
    the entries of R are products of sines and cosines)."""
    return sp.factor(sp.cancel(sp.together(e)))


@dataclass(frozen=True)
class LegLine:
    """A leg whose stroke is the distance from the base point ``base`` (A, in the frame the
    platform moves in) to the platform point ``point`` (B, platform frame), with the
    platform's Study point ``platform`` (in the Study coordinates)."""

    base: tuple
    point: tuple
    platform: tuple


@dataclass(frozen=True)
class PlatformFrame:
    """A platform's rotation ``R`` (rows), translation ``t``, and per pose coordinate the
    angular velocity ``omega_m`` and ``t'_m``, as functions of the pose coordinates."""

    rotation: tuple[tuple[sp.Expr, ...], ...]
    translation: tuple[sp.Expr, ...]
    omega: tuple[tuple[sp.Expr, ...], ...]
    translation_rate: tuple[tuple[sp.Expr, ...], ...]


def platform_frame(point: Sequence[sp.Expr], pose: Sequence[sp.Symbol]) -> PlatformFrame:
    """The frame of the Study point ``point`` (any scale, in the pose coordinates):
    ``R = rows of |x|^2 R / |x|^2``, ``t = -2 vec(y conj(x)) / |x|^2`` (004 eq. 13) and
    ``omega_m = 2 vec(x'_m conj(x)) / |x|^2`` (``R'_m R^T = [omega_m]x``, as
    :mod:`.twist`), each entry reduced (:func:`_rational`)."""
    point = tuple(sp.sympify(c) for c in point)
    n = cv.rotation_norm(point)
    rot = tuple(tuple(_rational(c / n) for c in row)
                for row in cv.rotation_matrix_times_norm(point))
    t = tuple(_rational(c / n) for c in cv.translation_times_norm(point))
    x = point[:4]
    conj = (x[0], -x[1], -x[2], -x[3])
    omega, rate = [], []
    for p in pose:
        dx = tuple(sp.diff(c, p) for c in x)
        omega.append(tuple(_rational(2 * c / n) for c in cv.quaternion_product(dx, conj)[1:]))
        rate.append(tuple(_rational(sp.diff(c, p)) for c in t))
    return PlatformFrame(rot, t, tuple(omega), tuple(rate))


def distance_row(frame: PlatformFrame, base: Sequence[sp.Expr], point: Sequence[sp.Expr],
                 stroke: sp.Symbol) -> tuple[sp.Expr, sp.Expr, list[sp.Expr]]:
    """``(pivot, row scale, dq/dX)`` of the distance leg from ``base`` (A, base frame) to
    ``point`` (B, platform frame) with stroke ``q``: pivot ``q``, scale ``|q| + sum_m |q
    dq/dX_m|``, ``dq/dX_m = (omega_m . (R B x l) + t'_m . l) / q`` (module docstring)."""
    rb = [sp.Add(*[r * b for r, b in zip(row, point)]) for row in frame.rotation]
    leg = [rb[i] + frame.translation[i] - base[i] for i in range(3)]
    moment = cv.cross(rb, leg)
    numer = [sp.Add(*[w * c for w, c in zip(om, moment)])
             + sp.Add(*[r * c for r, c in zip(rate, leg)])
             for om, rate in zip(frame.omega, frame.translation_rate)]
    scale = sp.Abs(stroke, evaluate=False) + sum((sp.Abs(e, evaluate=False) for e in numer
                                                  if e != 0), sp.Integer(0))
    return stroke, scale, [e / stroke for e in numer]
