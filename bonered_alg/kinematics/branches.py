"""Working mode 0 as the physical branch the mechanism declares.

A quadratic IK step ``A q^2 + B q + C = 0`` has two roots; mode bit 0 takes the ``+sqrt``
one of the generator as the elimination normalized it, which may be the unphysical branch
(a negative stroke).  Negating the generator swaps which root is ``+sqrt`` and changes
nothing else (its zero set, the Jacobian ``-Ji^{-1} Jo``).  With the declared home pose and
the joint values of the physical branch there (``Mechanism.home``, ``home_joints``), each
quadratic step whose ``+sqrt`` root is farther from the declared value than its ``-sqrt``
root is negated, so that mode 0 reproduces the declared values.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import mpmath
import sympy as sp

from ..errors import MechanismDefinitionError
from .ik_plan import IKStep

PRECISION = 30  # decimal digits of the evaluation at home


@dataclass(frozen=True)
class Branch:
    """How mode 0 of the quadratic step in ``joint`` was chosen at the home pose."""

    joint: sp.Symbol
    declared: float
    roots: tuple[float, float]  # (+sqrt, -sqrt) roots of the generator as eliminated
    negated: bool  # the generator was negated, so mode 0 takes the former -sqrt root

    @property
    def mode0(self) -> float:
        return self.roots[1] if self.negated else self.roots[0]


def orient(name: str, steps: Sequence[IKStep], to_study: Mapping, pose: Sequence[sp.Symbol],
           home: Sequence[float], home_joints: Mapping[sp.Symbol, float],
           values: Mapping[sp.Symbol, float]) -> tuple[tuple[IKStep, ...], tuple[Branch, ...]]:
    """The steps with the generators negated where needed, and the record per declared
    joint.  ``values`` are the geometric parameters and constants."""
    if not home_joints:
        return tuple(steps), ()
    mpmath.mp.dps = PRECISION
    at = {s: sp.Float(v, PRECISION) for s, v in zip(pose, home)}
    at.update({s: sp.Float(v, PRECISION) if not isinstance(v, sp.Expr) else v
               for s, v in values.items()})
    sub = {k: sp.sympify(v).xreplace(at).evalf(PRECISION) for k, v in to_study.items()}
    out, records = [], []
    for st in steps:
        def value(e):
            return sp.sympify(e).xreplace(sub).xreplace(at).evalf(PRECISION)

        a, b, c = value(st.A), value(st.B), value(st.C)
        if st.degree == 1:
            root = -c / b
            at[st.joint] = root
            out.append(st)
            continue
        disc = b * b - 4 * a * c
        if st.joint in home_joints and a == 0 and b != 0:
            # the leading coefficient vanishes at home: one root is -C/B, the other at
            # infinity (a tan-half-angle at a half-turn).  The runtime's +sqrt root tends
            # to the finite one where B > 0 (backsubstitution's stable form), so mode 0
            # keeps the finite root, the nearer to any declared value, when the generator
            # is oriented with B > 0 at home
            finite = float(-c / b)
            want = home_joints[st.joint]
            negate = b < 0
            roots = (finite, math.inf) if b > 0 else (math.inf, finite)
            records.append(Branch(st.joint, float(want), roots, bool(negate)))
            at[st.joint] = -c / b
            out.append(replace(st, generator=-st.generator, A=-st.A, B=-st.B, C=-st.C)
                       if negate else st)
            continue
        if st.joint in home_joints and not (disc.is_real and disc >= 0 and a != 0):
            raise MechanismDefinitionError(
                name, f"home_joints[{st.joint}]: at the home pose {tuple(home)} the quadratic "
                      f"step of {st.joint} has no real roots (discriminant {float(disc):.6g});"
                      " declare a home pose inside the workspace")
        roots = [(-b + sgn * sp.sqrt(disc)) / (2 * a) for sgn in (1, -1)] if disc >= 0 else [
            sp.nan, sp.nan]
        negate = False
        if st.joint in home_joints:
            want = home_joints[st.joint]
            far = [abs(float(r) - want) for r in roots]
            if abs(far[0] - far[1]) <= 1e-9 * (1 + abs(want)):
                raise MechanismDefinitionError(
                    name, f"home_joints[{st.joint}] = {want} is as near the one root "
                          f"({float(roots[0]):.6g}) as the other ({float(roots[1]):.6g}) at "
                          "the home pose: it does not choose a branch")
            negate = far[1] < far[0]
            records.append(Branch(st.joint, float(want), (float(roots[0]), float(roots[1])),
                                  negate))
        at[st.joint] = roots[1] if negate else roots[0]
        out.append(replace(st, generator=-st.generator, A=-st.A, B=-st.B, C=-st.C)
                   if negate else st)
    missing = [str(q) for q in home_joints if q not in {r.joint for r in records}]
    if missing:
        raise MechanismDefinitionError(
            name, f"home_joints names {missing}, whose IK steps are linear (one root, no "
                  "branch to choose); leave them out")
    return tuple(out), tuple(records)


def negate_rows(matrix: sp.ImmutableMatrix, rows: Sequence[int]) -> sp.ImmutableMatrix:
    """``matrix`` with the given rows negated (the Jacobian rows of negated generators)."""
    m = sp.Matrix(matrix)
    for i in rows:
        m[i, :] = -m[i, :]
    return sp.ImmutableMatrix(m)
