"""Joints as ordered products of elementary Study-parameter factors (004 Tables 1-3).

Each :class:`Factor` is one row of a chain table: a label (``Pd1``), the elementary dual
quaternion, the role of its parameter (active, passive/free, geometric) and a description.
Rotations use tan-half-angle parameters, so every factor is polynomial (004 Sect. 2.1).
A :class:`Joint` groups the factors of one joint (its kind and degrees of freedom, which the
topology and the mobility count read); a :class:`Leg` is the ordered list of its joints.

============= ====================================================== ===================
type          factors                                                dof; parameters
============= ====================================================== ===================
revolute      ``R(axis, u)``                                          1; ``u = tan(t/2)``
prismatic     ``T(axis, s)``                                          1; ``s`` (mm)
cylindrical   ``R(axis, u) T(axis, s)``                               2; ``u``, ``s``
helical       ``R(axis, u) T(axis, s)`` with ``s = pitch * theta``    1; the coupling is
              (:class:`HelicalCoupling`)                              linear in the angle,
                                                                      not algebraic in
                                                                      ``u``: the ideal
                                                                      carries ``u``, ``s``
universal     ``R(axis1, u1) R(axis2, u2)``                           2; ``u1``, ``u2``
spherical     ``[q0:q1:q2:q3:0:0:0:0]`` (Euler parameters, no         3; ``q0..q3``
              parametrization singularity)
parallelogram ``R(axis, u) T(link) R(axis, -u)``: the far link        1; ``u``
              translates on a circle of radius ``|link|`` without
              turning (a circular translation, rational in ``u``)
offset        ``T(vector)`` or ``R(axis, u)`` with geometric entries  0; geometric
============= ====================================================== ===================
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum

import sympy as sp

from ..algebra import study_symbolic as ss
from ..errors import UnknownJointTypeError


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


@dataclass(frozen=True)
class HelicalCoupling:
    """``translation = pitch * theta`` with ``theta = 2 atan(rotation) (+ 2 k pi)``: the
    slide of a helical joint per radian of its turn.  Linear in the angle, transcendental in
    the tan-half-angle ``rotation``: the ideal carries both variables (a cylindrical joint)
    and the relation is a generated step applied to the recovered joint values."""

    rotation: sp.Symbol
    translation: sp.Symbol
    pitch: sp.Expr

    def residual_text(self) -> str:
        return f"{self.translation} - {self.pitch} * 2*atan({self.rotation})"


@dataclass(frozen=True)
class Joint:
    """The factors of one joint, its kind and its degrees of freedom."""

    label: str
    kind: str
    factors: tuple[Factor, ...]
    dof: int
    coupling: HelicalCoupling | None = None

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        return set().union(*(f.free_symbols for f in self.factors))

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        """Joint variables (non-geometric factors' symbols), in factor order."""
        out: list[sp.Symbol] = []
        for f in self.factors:
            if f.role is Role.GEOMETRIC:
                continue
            for s in sorted(f.free_symbols, key=str):
                if s not in out:
                    out.append(s)
        return tuple(out)


def _sym(x) -> sp.Expr:
    return sp.sympify(x) if not isinstance(x, sp.Basic) else x


def _factor(label, kind, args, axis, role, description) -> Factor:
    return Factor(label, kind, tuple(_sym(a) for a in args), axis, role, description)


def revolute(label: str, axis: str, u, role: Role = Role.PASSIVE, description: str = ""):
    """Revolute joint about a frame axis, tan-half-angle ``u``."""
    return Joint(label, "revolute", (_factor(label, "rotation", (u,), axis, role,
                                             description),), 1)


def prismatic(label: str, axis: str, s, role: Role = Role.PASSIVE, description: str = ""):
    """Prismatic joint along a frame axis, stroke ``s``."""
    return Joint(label, "prismatic", (_factor(label, "translation", (s,), axis, role,
                                              description),), 1)


def cylindrical(label: str, axis: str, u, s, role: Role = Role.PASSIVE, description: str = ""):
    """Cylindrical joint: rotation ``u`` and translation ``s`` about/along one axis."""
    return Joint(label, "cylindrical",
                 (_factor(f"{label}.R", "rotation", (u,), axis, role, description),
                  _factor(f"{label}.T", "translation", (s,), axis, role, description)), 2)


def helical(label: str, axis: str, u, s, pitch, role: Role = Role.PASSIVE,
            description: str = ""):
    """Helical joint: rotation ``u = tan(theta/2)`` and translation ``s = pitch * theta``
    (``pitch`` in length per radian; :class:`HelicalCoupling`)."""
    factors = (_factor(f"{label}.R", "rotation", (u,), axis, role, description),
               _factor(f"{label}.T", "translation", (s,), axis, role, description))
    return Joint(label, "helical", factors, 1, HelicalCoupling(_sym(u), _sym(s), _sym(pitch)))


def universal(label: str, axes: Sequence[str], u: Sequence, role: Role = Role.PASSIVE,
              description: str = ""):
    """Universal joint: two revolutes about ``axes[0]`` then ``axes[1]``."""
    if len(axes) != 2 or len(u) != 2:
        raise ValueError(f"universal joint {label}: needs two axes and two parameters")
    return Joint(label, "universal", tuple(
        _factor(f"{label}.{i + 1}", "rotation", (ui,), ax, role, description)
        for i, (ax, ui) in enumerate(zip(axes, u))), 2)


def spherical(label: str, q: Sequence, role: Role = Role.PASSIVE, description: str = ""):
    """Spherical joint as a rotation quaternion ``[q0:q1:q2:q3]`` (homogeneous)."""
    if len(q) != 4:
        raise ValueError(f"spherical joint {label}: needs four Euler parameters")
    return Joint(label, "spherical", (_factor(label, "quaternion", q, None, role,
                                              description),), 3)


def parallelogram(label: str, axis: str, u, link: Sequence, role: Role = Role.PASSIVE,
                  description: str = ""):
    """Parallelogram (a four-bar with equal opposite links) as one generalized joint: the
    far link is translated by ``R(axis, theta) link`` and keeps its orientation,
    ``R(axis, u) T(link) R(axis, -u)`` with ``u = tan(theta/2)``."""
    if len(link) != 3:
        raise ValueError(f"parallelogram joint {label}: the link needs three coordinates")
    return Joint(label, "parallelogram", (
        _factor(f"{label}.R", "rotation", (u,), axis, role, description),
        _factor(f"{label}.L", "translation", tuple(link), None, Role.GEOMETRIC,
                "link of the parallelogram"),
        _factor(f"{label}.R'", "rotation", (-_sym(u),), axis, role,
                "the far link keeps its orientation")), 1)


def offset(label: str, axis: str | None = None, value=None, vector: Sequence | None = None,
           rotation_u=None, description: str = ""):
    """Fixed (geometric) offset: a translation along an axis or by a vector, or a rotation."""
    if rotation_u is not None:
        f = _factor(label, "rotation", (rotation_u,), axis, Role.GEOMETRIC, description)
    elif vector is not None:
        f = _factor(label, "translation", tuple(vector), None, Role.GEOMETRIC, description)
    else:
        f = _factor(label, "translation", (value,), axis, Role.GEOMETRIC, description)
    return Joint(label, "offset", (f,), 0)


JOINT_TYPES = {
    "revolute": revolute,
    "prismatic": prismatic,
    "cylindrical": cylindrical,
    "helical": helical,
    "universal": universal,
    "spherical": spherical,
    "parallelogram": parallelogram,
    "offset": offset,
}

# degrees of freedom of each joint type, for the Kutzbach-Gruebler count
JOINT_DOF = {"revolute": 1, "prismatic": 1, "cylindrical": 2, "helical": 1, "universal": 2,
             "spherical": 3, "parallelogram": 1, "offset": 0}


def joint(mechanism: str, kind: str, *args, **kwargs) -> Joint:
    """A joint of type ``kind``; unknown types raise :class:`UnknownJointTypeError`."""
    try:
        make = JOINT_TYPES[kind]
    except KeyError:
        raise UnknownJointTypeError(
            mechanism, f"unknown joint type {kind!r}; expected one of {sorted(JOINT_TYPES)}"
        ) from None
    return make(*args, **kwargs)


@dataclass(frozen=True)
class Leg:
    """A leg: its joints base to platform.

    ``base`` names the body the leg stands on (the closure's base by default).  ``mount``
    is the Study point of the frame the leg starts from when that frame moves with other
    closures' outputs (a pure translation in the mechanism's pose coordinates, e.g. a chain
    of a mobile platform attached to another mechanism's end point): the leg is then
    eliminated in that frame and its ideal carried back by the linear change of
    coordinates ``X' = conj(mount) X``.
    """

    name: str
    joints: tuple[Joint, ...]
    base: str | None = None
    mount: tuple[sp.Expr, ...] | None = None

    @property
    def factors(self) -> tuple[Factor, ...]:
        return tuple(f for j in self.joints for f in j.factors)

    def product(self) -> tuple[sp.Expr, ...]:
        """The leg's Study point, ``F1 * F2 * ... * Fn`` (e.g. 004 eq. 14, 15), the mount
        included."""
        chain = [f.study() for f in self.factors]
        if self.mount is not None:
            chain.insert(0, tuple(self.mount))
        return ss.product(*chain)

    def local_product(self) -> tuple[sp.Expr, ...]:
        """The product of the leg's own factors (without the mount)."""
        return ss.product(*[f.study() for f in self.factors])

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        out = set().union(*(j.free_symbols for j in self.joints))
        if self.mount is not None:
            out |= set().union(*(sp.sympify(c).free_symbols for c in self.mount))
        return out

    @property
    def couplings(self) -> tuple[HelicalCoupling, ...]:
        return tuple(j.coupling for j in self.joints if j.coupling is not None)


def leg(name: str, *joints: Joint, base: str | None = None,
        mount: Sequence | None = None) -> Leg:
    """A leg from its joints, in base-to-platform order."""
    for j in joints:
        if not isinstance(j, Joint):
            raise TypeError(f"leg {name!r}: expected Joint objects (from joint(...)), got "
                            f"{type(j).__name__}")
    return Leg(name, tuple(joints), base,
               None if mount is None else tuple(sp.sympify(c) for c in mount))
