"""The Study-parameter convention shared by the symbolic and numeric algebra.

Storage order: ``[x0, x1, x2, x3, y0, y1, y2, y3]`` (004 eq. 1), the dual quaternion
``x + eps*y`` with ``x = x0 + x1 i + x2 j + x3 k`` (Hamilton rules, 004 eq. 6).

* Rotation part: ``x`` is the unit quaternion of the rotation matrix ``R`` acting on column
  vectors, ``v' = x v conj(x)`` (004 eq. 4, first ratio: ``x1 ~ a32 - a23``).
* Translation part (Husty's convention, 004 eq. 13): ``y = -1/2 * t * x``; a translation by
  ``t`` along X is ``[1:0:0:0:0:-t/2:0:0]``, a rotation by ``phi`` about Z is
  ``[1:0:0:u:0:0:0:0]`` with ``u = tan(phi/2)``.
* Product: ``(x + eps y)(x' + eps y') = x x' + eps (x y' + y x')``.  With the convention
  above the map from homogeneous transforms is a homomorphism:
  ``study(T1 @ T2) = study(T1) * study(T2)``, so a chain is written base-to-tip in the order
  of its matrix product.  (It equals pytransform3d's dual quaternion with the dual part
  negated; ``tests/test_study_algebra.py`` pins this against pytransform3d.)

The formulas below are written once for any ring element type that supports ``+``, ``-``
and ``*`` (sympy expressions or numpy arrays), and are shared by both algebras.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

StudyLike = Sequence[Any]


def quaternion_product(a: StudyLike, b: StudyLike) -> tuple:
    """Hamilton product of quaternions ``a = a0 + a1 i + a2 j + a3 k`` and ``b``."""
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def study_product(a: StudyLike, b: StudyLike) -> tuple:
    """Dual quaternion product ``a * b`` of two Study points (004 eq. 6-7)."""
    xa, ya = a[:4], a[4:]
    xb, yb = b[:4], b[4:]
    x = quaternion_product(xa, xb)
    y1 = quaternion_product(xa, yb)
    y2 = quaternion_product(ya, xb)
    return x + tuple(p + q for p, q in zip(y1, y2))


def study_conjugate(a: StudyLike) -> tuple:
    """Quaternion conjugate of both parts (004 eq. 7): the inverse displacement."""
    x0, x1, x2, x3, y0, y1, y2, y3 = a
    return (x0, -x1, -x2, -x3, y0, -y1, -y2, -y3)


def study_quadric(a: StudyLike) -> Any:
    """Left side of the Study quadric ``x0 y0 + x1 y1 + x2 y2 + x3 y3`` (004 eq. 3)."""
    return a[0] * a[4] + a[1] * a[5] + a[2] * a[6] + a[3] * a[7]


def cross(a: Sequence[Any], b: Sequence[Any]) -> tuple:
    """The cross product ``a x b`` of two 3-vectors."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotation_norm(a: StudyLike) -> Any:
    """``x0^2 + x1^2 + x2^2 + x3^2`` (left side of 004 eq. 2)."""
    return a[0] ** 2 + a[1] ** 2 + a[2] ** 2 + a[3] ** 2


def translation_times_norm(a: StudyLike) -> tuple:
    """``|x|^2 * t``: translation scaled by the rotation norm (004 eq. 13 before dividing).

    ``t = -2 y conj(x) / |x|^2``.
    """
    x0, x1, x2, x3, y0, y1, y2, y3 = a
    return (
        -2 * (x0 * y1 - x1 * y0 + x2 * y3 - x3 * y2),
        -2 * (x0 * y2 - x1 * y3 - x2 * y0 + x3 * y1),
        -2 * (x0 * y3 + x1 * y2 - x2 * y1 - x3 * y0),
    )


def rotation_matrix_times_norm(a: StudyLike) -> tuple:
    """Rows of ``|x|^2 * R`` for the rotation quaternion ``x`` (active, column vectors)."""
    x0, x1, x2, x3 = a[:4]
    return (
        (x0**2 + x1**2 - x2**2 - x3**2, 2 * (x1 * x2 - x0 * x3), 2 * (x1 * x3 + x0 * x2)),
        (2 * (x1 * x2 + x0 * x3), x0**2 - x1**2 + x2**2 - x3**2, 2 * (x2 * x3 - x0 * x1)),
        (2 * (x1 * x3 - x0 * x2), 2 * (x2 * x3 + x0 * x1), x0**2 - x1**2 - x2**2 + x3**2),
    )


def rotation_ratios(a: Sequence[Sequence[Any]]) -> tuple:
    """The four ratios of 004 eq. (4) for ``x0:x1:x2:x3`` from a rotation matrix ``a``.

    Row ``k`` has pivot ``1 + 2 a_kk - trace`` style entry in position ``k``; at least one row
    is non-zero for every rotation, half-turns included.
    """
    a11, a12, a13 = a[0]
    a21, a22, a23 = a[1]
    a31, a32, a33 = a[2]
    return (
        (1 + a11 + a22 + a33, a32 - a23, a13 - a31, a21 - a12),
        (a32 - a23, 1 + a11 - a22 - a33, a12 + a21, a31 + a13),
        (a13 - a31, a12 + a21, 1 - a11 + a22 - a33, a23 + a32),
        (a21 - a12, a31 + a13, a23 + a32, 1 - a11 - a22 + a33),
    )


def dual_part_from_translation(t: Sequence[Any], x: StudyLike) -> tuple:
    """``y = -1/2 t x`` (corrected 004 eq. 5; see the erratum in the pro_hep_lct report)."""
    tx, ty, tz = t
    x0, x1, x2, x3 = x[:4]
    return (
        (tx * x1 + ty * x2 + tz * x3) / 2,
        -(tx * x0 + ty * x3 - tz * x2) / 2,
        -(-tx * x3 + ty * x0 + tz * x1) / 2,
        -(tx * x2 - ty * x1 + tz * x0) / 2,
    )
