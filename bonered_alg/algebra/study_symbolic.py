"""Symbolic (sympy) Study-parameter algebra; convention in :mod:`.convention`.

Functions follow a ``<target>_from_<source>`` naming grammar and return tuples of 8 sympy
expressions ``(x0, x1, x2, x3, y0, y1, y2, y3)``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import sympy as sp

from . import convention as cv

Study = tuple[sp.Expr, ...]
AXES = {"x": 0, "y": 1, "z": 2}


def _axis_index(axis: str) -> int:
    try:
        return AXES[axis]
    except KeyError:
        raise ValueError(f"axis must be one of 'x', 'y', 'z', not {axis!r}") from None


def rotation(axis: str, u: sp.Expr) -> Study:
    """Rotation about a frame axis, tan-half-angle ``u``: ``[1:u e_axis:0:0:0:0]`` (004 2.1)."""
    x = [sp.Integer(1), sp.Integer(0), sp.Integer(0), sp.Integer(0)]
    x[1 + _axis_index(axis)] = sp.sympify(u)
    return tuple(x) + (sp.Integer(0),) * 4


def translation(axis: str, s: sp.Expr) -> Study:
    """Translation by ``s`` along a frame axis: ``[1:0:0:0:0:-s/2 e_axis]`` (004 eq. 8 factors)."""
    y = [sp.Integer(0)] * 4
    y[1 + _axis_index(axis)] = -sp.sympify(s) / 2
    return (sp.Integer(1), sp.Integer(0), sp.Integer(0), sp.Integer(0), *y)


def translation_vector(t: Sequence[sp.Expr]) -> Study:
    """Translation by the vector ``t``: ``[1:0:0:0:0:-t/2]``."""
    return (sp.Integer(1), sp.Integer(0), sp.Integer(0), sp.Integer(0), sp.Integer(0)) + tuple(
        -sp.sympify(c) / 2 for c in t
    )


def quaternion_rotation(q: Sequence[sp.Expr]) -> Study:
    """A rotation given by a (not necessarily unit) quaternion ``[q0:q1:q2:q3:0:0:0:0]``."""
    return tuple(sp.sympify(c) for c in q) + (sp.Integer(0),) * 4


def product(*factors: Study) -> Study:
    """Ordered dual-quaternion product ``f1 * f2 * ... * fn``, expanded polynomially."""
    if not factors:
        return (sp.Integer(1),) + (sp.Integer(0),) * 7
    acc = tuple(factors[0])
    for f in factors[1:]:
        acc = tuple(sp.expand(c) for c in cv.study_product(acc, f))
    return acc


def conjugate(a: Study) -> Study:
    """Conjugate dual quaternion (004 eq. 7)."""
    return cv.study_conjugate(a)


def quadric(a: Study) -> sp.Expr:
    """Study quadric ``sum x_i y_i`` (004 eq. 3), expanded."""
    return sp.expand(cv.study_quadric(a))


def normalized(a: Study) -> Study:
    """Scale so that ``x0^2+...+x3^2 = 1`` (004 eq. 2)."""
    n = sp.sqrt(cv.rotation_norm(a))
    return tuple(sp.simplify(c / n) for c in a)


def projectively_equal(a: Iterable[sp.Expr], b: Iterable[sp.Expr]) -> bool:
    """True when ``a = lambda * b`` for some non-zero ``lambda`` (all 2x2 minors vanish)."""
    a, b = list(a), list(b)
    return all(
        sp.expand(a[i] * b[j] - a[j] * b[i]) == 0 for i in range(8) for j in range(i + 1, 8)
    )


def transform_from_study(a: Study) -> sp.Matrix:
    """4x4 homogeneous transform of a Study point (004 eq. 13 and the rotation of eq. 4)."""
    n = cv.rotation_norm(a)
    r = cv.rotation_matrix_times_norm(a)
    t = cv.translation_times_norm(a)
    m = sp.eye(4)
    for i in range(3):
        for j in range(3):
            m[i, j] = r[i][j] / n
        m[i, 3] = t[i] / n
    return m.applyfunc(sp.simplify)


def study_from_transform(m: sp.Matrix, ratio: int = 0) -> Study:
    """Study point of a homogeneous transform using ratio ``ratio`` (0..3) of 004 eq. (4).

    The dual part uses ``y = -1/2 t x`` (004 eq. 5 corrected, see :mod:`.convention`).
    """
    a = [[m[i, j] for j in range(3)] for i in range(3)]
    x = cv.rotation_ratios(a)[ratio]
    if all(sp.simplify(c) == 0 for c in x):
        raise ValueError(f"ratio {ratio} of 004 eq. (4) vanishes for this rotation; use another")
    t = (m[0, 3], m[1, 3], m[2, 3])
    return tuple(sp.expand(c) for c in tuple(x) + cv.dual_part_from_translation(t, x))


def pose_from_study(a: Study) -> tuple[sp.Expr, ...]:
    """``(x, y, z, alpha, beta, gamma)`` of a Study point, ``R = Rz(gamma) Ry(beta) Rx(alpha)``
    (DESIGN.md section 3): the translation of 004 eq. (13) and the Z-Y-X angles of ``R``
    (``beta`` in ``[-pi/2, pi/2]``).  Unsimplified, for code generation."""
    n = cv.rotation_norm(a)
    t = cv.translation_times_norm(a)
    r = cv.rotation_matrix_times_norm(a)  # |x|^2 R: the ratios below need no division
    return (t[0] / n, t[1] / n, t[2] / n, sp.atan2(r[2][1], r[2][2]),
            sp.atan2(-r[2][0], sp.sqrt(r[0][0] ** 2 + r[1][0] ** 2)), sp.atan2(r[1][0], r[0][0]))


def study_from_pose(x, y, z, alpha, beta, gamma) -> Study:
    """Study point of the pose ``(x, y, z, alpha, beta, gamma)`` with ``R = Rz(gamma)
    Ry(beta) Rx(alpha)`` (DESIGN.md section 3), in the tangents of the half angles: the
    inverse of :func:`pose_from_study`."""
    return product(translation_vector((x, y, z)), rotation("z", sp.tan(gamma / 2)),
                   rotation("y", sp.tan(beta / 2)), rotation("x", sp.tan(alpha / 2)))


def tan_half_substitution(expr: sp.Expr, pairs: Iterable[tuple[sp.Symbol, sp.Symbol]]) -> sp.Expr:
    """``sin(a)``, ``cos(a)`` -> ``2t/(1+t^2)``, ``(1-t^2)/(1+t^2)`` for each ``(a, t)``: the
    papers' trigonometric expressions in the tan-half-angle variables of the chains."""
    for ang, t in pairs:
        expr = expr.subs({sp.sin(ang): 2 * t / (1 + t**2), sp.cos(ang): (1 - t**2) / (1 + t**2)})
    return expr
