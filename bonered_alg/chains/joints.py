"""Joints as ordered products of elementary Study-parameter factors (004 Tables 1-3).

Each :class:`Factor` is one row of a chain table: a label (``Pd1``), the elementary dual
quaternion, the role of its parameter (active, passive/free, geometric) and a description.
Rotations use tan-half-angle parameters, so every factor is polynomial (004 Sect. 2.1).

Joint constructors (:data:`JOINT_TYPES`) return lists of factors:

========== ======================================================== ======================
type       factors                                                  parameters
========== ======================================================== ======================
revolute   ``R(axis, u)``                                            ``u = tan(theta/2)``
prismatic  ``T(axis, s)``                                            ``s`` (mm)
cylindrical ``R(axis, u) T(axis, s)``                                ``u``, ``s``
helical    ``R(axis, u) T(axis, s)`` with ``s = pitch*theta/(2 pi)`` ``u``, ``s``; the
           coupling is transcendental in ``u`` and is recorded, not eliminated
universal  ``R(axis1, u1) R(axis2, u2)``                             ``u1``, ``u2``
spherical  ``[q0:q1:q2:q3:0:0:0:0]`` (Euler parameters; no           ``q0..q3``
           parametrization singularity)
offset     ``T(vector)`` or ``R(axis, u)`` with geometric entries    geometric
========== ======================================================== ======================
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import Enum

import sympy as sp

from ..algebra import study_symbolic as ss


class Role(str, Enum):
    """Role of a parameter in a chain, as in the 'Description' column of 004 Tables 1-3."""

    ACTIVE = "active"
    PASSIVE = "passive"
    GEOMETRIC = "geometric"


@dataclass(frozen=True)
class Factor:
    """One elementary dual quaternion of a chain (one row of 004 Tables 1-3)."""

    label: str
    kind: str  # "rotation" | "translation" | "quaternion"
    args: tuple[sp.Expr, ...]
    axis: str | None
    role: Role
    description: str = ""
    coupling: str | None = field(default=None)

    def study(self) -> tuple[sp.Expr, ...]:
        """The factor's Study point ``[x0:...:y3]``."""
        if self.kind == "rotation":
            return ss.rotation(self.axis, self.args[0])
        if self.kind == "translation":
            if self.axis is None:
                return ss.translation_vector(self.args)
            return ss.translation(self.axis, self.args[0])
        if self.kind == "quaternion":
            return ss.quaternion_rotation(self.args)
        raise ValueError(f"factor {self.label}: unknown elementary kind {self.kind!r}")

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        return set().union(*(sp.sympify(a).free_symbols for a in self.args))

    def motion(self) -> str:
        """Plain-language motion, e.g. 'rotation around OZ axis'."""
        if self.kind == "rotation":
            return f"rotation around O{self.axis.upper()} axis"
        if self.kind == "translation":
            return f"translation along O{self.axis.upper()} axis" if self.axis else "translation"
        return "spherical rotation (Euler parameters)"


def _sym(x) -> sp.Expr:
    return sp.sympify(x) if not isinstance(x, sp.Basic) else x


def revolute(label: str, axis: str, u, role: Role = Role.PASSIVE, description: str = ""):
    """Revolute joint about a frame axis, tan-half-angle ``u``."""
    return [Factor(label, "rotation", (_sym(u),), axis, role, description)]


def prismatic(label: str, axis: str, s, role: Role = Role.PASSIVE, description: str = ""):
    """Prismatic joint along a frame axis, stroke ``s``."""
    return [Factor(label, "translation", (_sym(s),), axis, role, description)]


def cylindrical(label: str, axis: str, u, s, role: Role = Role.PASSIVE, description: str = ""):
    """Cylindrical joint: rotation ``u`` and translation ``s`` about/along one axis."""
    return [Factor(f"{label}.R", "rotation", (_sym(u),), axis, role, description),
            Factor(f"{label}.T", "translation", (_sym(s),), axis, role, description)]


def helical(label: str, axis: str, u, s, pitch, role: Role = Role.PASSIVE,
            description: str = ""):
    """Helical joint: rotation ``u`` and translation ``s = pitch * theta / (2 pi)``.

    The coupling between ``s`` and ``u = tan(theta/2)`` is not algebraic; it is kept in
    ``Factor.coupling`` and must be imposed numerically (``s`` is a separate unknown here).
    """
    coupling = f"{s} = {pitch} * 2*atan({u}) / (2*pi)"
    return [Factor(f"{label}.R", "rotation", (_sym(u),), axis, role, description, coupling),
            Factor(f"{label}.T", "translation", (_sym(s),), axis, role, description, coupling)]


def universal(label: str, axes: Sequence[str], u: Sequence, role: Role = Role.PASSIVE,
              description: str = ""):
    """Universal joint: two revolutes about ``axes[0]`` then ``axes[1]``."""
    if len(axes) != 2 or len(u) != 2:
        raise ValueError(f"universal joint {label}: needs two axes and two parameters")
    return [Factor(f"{label}.{i + 1}", "rotation", (_sym(ui),), ax, role, description)
            for i, (ax, ui) in enumerate(zip(axes, u))]


def spherical(label: str, q: Sequence, role: Role = Role.PASSIVE, description: str = ""):
    """Spherical joint as a rotation quaternion ``[q0:q1:q2:q3]`` (homogeneous)."""
    if len(q) != 4:
        raise ValueError(f"spherical joint {label}: needs four Euler parameters")
    return [Factor(label, "quaternion", tuple(_sym(c) for c in q), None, role, description)]


def offset(label: str, axis: str | None = None, value=None, vector: Sequence | None = None,
           rotation_u=None, description: str = ""):
    """Fixed (geometric) offset: a translation along an axis or by a vector, or a rotation."""
    if rotation_u is not None:
        return [Factor(label, "rotation", (_sym(rotation_u),), axis, Role.GEOMETRIC,
                       description)]
    if vector is not None:
        return [Factor(label, "translation", tuple(_sym(c) for c in vector), None,
                       Role.GEOMETRIC, description)]
    return [Factor(label, "translation", (_sym(value),), axis, Role.GEOMETRIC, description)]


JOINT_TYPES = {
    "revolute": revolute,
    "prismatic": prismatic,
    "cylindrical": cylindrical,
    "helical": helical,
    "universal": universal,
    "spherical": spherical,
    "offset": offset,
}

# degrees of freedom of each joint type, for the Kutzbach-Gruebler count
JOINT_DOF = {"revolute": 1, "prismatic": 1, "cylindrical": 2, "helical": 1, "universal": 2,
             "spherical": 3, "offset": 0}


@dataclass(frozen=True)
class Leg:
    """A leg: the ordered product of its factors, base to platform."""

    name: str
    factors: tuple[Factor, ...]

    def product(self) -> tuple[sp.Expr, ...]:
        """The leg's Study point, ``F1 * F2 * ... * Fn`` (e.g. 004 eq. 14, 15)."""
        return ss.product(*[f.study() for f in self.factors])

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        return set().union(*(f.free_symbols for f in self.factors))
