"""Insertion, retraction and remote-centre-of-motion manipulation as Study products.

004 Sect. 2.1, eq. (8)-(12), numeric and vectorized over leading axes.  Study points are
arrays ``(..., 8)`` in the order ``[x0..x3, y0..y3]`` (:mod:`bonered_alg.algebra.study_numeric`).

* eq. (8): ``P_ins = P * P_l`` with ``P_l`` the translation by ``l`` along a tool axis, which
  004 writes ``[1:0:0:0:0:0:0:-l/2]`` for Z' (so ``l > 0`` moves along +Z');
* eq. (9): ``P = P_ins * conj(P_l)``;
* eq. (10): ``P_RCM = P * P_o * P_l``: rotate about the frame of ``P`` (the entry point), then
  insert along the rotated axis;
* eq. (11): ``P = P_RCM * conj(P_l) * conj(P_o)``;
* eq. (12): a sequence of RCM steps, each undone before the next is applied, i.e. the same as
  one eq. (10) step from the entry-point pose with the step's orientation and depth.
"""

from __future__ import annotations

import numpy as np

from ..algebra import study_numeric as sn

AXES = ("x", "y", "z")


def _axis(axis: str) -> int:
    if axis not in AXES:
        raise ValueError(f"tool axis must be one of {AXES}, not {axis!r}")
    return AXES.index(axis)


def insertion_factor(length, axis: str = "z") -> np.ndarray:
    """``P_l``: translation by ``length`` (mm) along the tool axis (004 Sect. 2.1)."""
    length = np.asarray(length, dtype=float)
    t = np.zeros(length.shape + (3,))
    t[..., _axis(axis)] = length
    return sn.translation(t)


def insert(pose, length, axis: str = "z") -> np.ndarray:
    """004 eq. (8): ``P_ins = P * P_l``."""
    return sn.product(pose, insertion_factor(length, axis))


def retract(pose_inserted, length, axis: str = "z") -> np.ndarray:
    """004 eq. (9): ``P = P_ins * conj(P_l)``."""
    return sn.product(pose_inserted, sn.conjugate(insertion_factor(length, axis)))


def orientation_factor(u, axis: str) -> np.ndarray:
    """``P_o = [1:u e_axis:0:0:0:0]``, a rotation by ``2 atan(u)`` about a tool axis."""
    _axis(axis)
    return sn.rotation(axis, u)


def rcm(pose, u, axis: str, length, insert_axis: str = "z") -> np.ndarray:
    """004 eq. (10): ``P_RCM = P * P_o * P_l`` (rotation about the entry point, then
    insertion by ``length`` along the rotated tool axis)."""
    return sn.product(sn.product(pose, orientation_factor(u, axis)),
                      insertion_factor(length, insert_axis))


def rcm_inverse(pose_rcm, u, axis: str, length, insert_axis: str = "z") -> np.ndarray:
    """004 eq. (11): ``P = P_RCM * conj(P_l) * conj(P_o)``."""
    back = sn.product(pose_rcm, sn.conjugate(insertion_factor(length, insert_axis)))
    return sn.product(back, sn.conjugate(orientation_factor(u, axis)))


def rcm_sequence(pose, steps, insert_axis: str = "z") -> list[np.ndarray]:
    """004 eq. (12): the poses of a sequence of RCM steps ``[(u, axis, length), ...]``.

    Each step undoes the previous one (eq. 11) before applying its own (eq. 10), so every
    pose keeps the entry point of ``pose`` on the tool axis."""
    out, current, previous = [], np.asarray(pose, dtype=float), None
    for u, axis, length in steps:
        base = current if previous is None else rcm_inverse(current, *previous, insert_axis)
        current = rcm(base, u, axis, length, insert_axis)
        previous = (u, axis, length)
        out.append(current)
    return out


def point(pose) -> np.ndarray:
    """Origin of the frame ``pose`` in the fixed frame (004 eq. 13), shape (..., 3)."""
    return sn.transform_from_study(pose)[..., :3, 3]
