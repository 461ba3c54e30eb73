"""Input/output Jacobians of a constraint system ``G(q, X) = 0`` and ``dq/dX`` (004 eq. 19-21).

With ``Ji = dG/dq`` and ``Jo = dG/dX`` the velocity relation is ``Ji q' + Jo X' = 0``
(004 eq. 19-21), hence ``dq/dX = -Ji^{-1} Jo`` wherever ``det Ji != 0``.  ``det Ji = 0`` are
the input (type I) singularities and ``det Jo = 0`` the output (type II) singularities.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp


@dataclass(frozen=True)
class VelocityModel:
    """Ji, Jo of generators ``G`` with respect to joints ``q`` and pose coordinates ``X``."""

    generators: tuple[sp.Expr, ...]
    joints: tuple[sp.Symbol, ...]
    pose: tuple[sp.Symbol, ...]

    @property
    def input_jacobian(self) -> sp.Matrix:
        return sp.Matrix(self.generators).jacobian(sp.Matrix(self.joints))

    @property
    def output_jacobian(self) -> sp.Matrix:
        return sp.Matrix(self.generators).jacobian(sp.Matrix(self.pose))


def velocity_model(generators: Sequence[sp.Expr], joints: Sequence[sp.Symbol],
                   pose: Sequence[sp.Symbol]) -> VelocityModel:
    return VelocityModel(tuple(generators), tuple(joints), tuple(pose))
