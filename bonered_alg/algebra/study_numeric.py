"""Numeric (numpy) Study-parameter algebra, vectorized over leading axes.

Arrays have shape ``(..., 8)`` in the storage order ``[x0..x3, y0..y3]``; transforms have
shape ``(..., 4, 4)``.  Convention in :mod:`.convention` (shared with the symbolic algebra).
"""

from __future__ import annotations

import numpy as np

from . import convention as cv


def _parts(a: np.ndarray) -> list[np.ndarray]:
    a = np.asarray(a, dtype=float)
    if a.shape[-1] != 8:
        raise ValueError(f"a Study point has 8 coordinates in its last axis, got shape {a.shape}")
    return [a[..., i] for i in range(8)]


def product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dual quaternion product ``a * b`` (004 eq. 6)."""
    return np.stack(np.broadcast_arrays(*cv.study_product(_parts(a), _parts(b))), axis=-1)


def conjugate(a: np.ndarray) -> np.ndarray:
    """Conjugate (inverse displacement, 004 eq. 7)."""
    return np.stack(cv.study_conjugate(_parts(a)), axis=-1)


def quadric(a: np.ndarray) -> np.ndarray:
    """Study quadric residual ``sum x_i y_i`` (004 eq. 3)."""
    return cv.study_quadric(_parts(a))


def normalize(a: np.ndarray) -> np.ndarray:
    """Scale to ``|x| = 1`` (004 eq. 2) with ``x0 >= 0`` (the sign is then unique up to x0 = 0)."""
    a = np.asarray(a, dtype=float)
    n = np.sqrt(cv.rotation_norm(_parts(a)))
    if np.any(n == 0):
        raise ValueError("a Study point with x = 0 is not a displacement (004 eq. 1)")
    s = np.where(a[..., 0] < 0, -1.0, 1.0) / n
    return a * s[..., None]


def rotation(axis: str, u: np.ndarray) -> np.ndarray:
    """Rotation about a frame axis by tan-half-angle ``u`` (``[1:u e_axis:0:0:0:0]``)."""
    u = np.asarray(u, dtype=float)
    out = np.zeros(u.shape + (8,))
    out[..., 0] = 1.0
    out[..., 1 + "xyz".index(axis)] = u
    return out


def translation(t: np.ndarray) -> np.ndarray:
    """Translation by the vector ``t`` (shape ``(..., 3)``): ``[1:0:0:0:0:-t/2]``."""
    t = np.asarray(t, dtype=float)
    out = np.zeros(t.shape[:-1] + (8,))
    out[..., 0] = 1.0
    out[..., 5:8] = -t / 2
    return out


def transform_from_study(a: np.ndarray) -> np.ndarray:
    """Homogeneous 4x4 transform of Study points (004 eq. 13 and eq. 4 inverted)."""
    p = _parts(a)
    n = cv.rotation_norm(p)
    r = cv.rotation_matrix_times_norm(p)
    t = cv.translation_times_norm(p)
    shape = np.shape(n)
    m = np.zeros(shape + (4, 4))
    for i in range(3):
        for j in range(3):
            m[..., i, j] = r[i][j] / n
        m[..., i, 3] = t[i] / n
    m[..., 3, 3] = 1.0
    return m


def study_from_transform(m: np.ndarray) -> np.ndarray:
    """Normalized Study points of 4x4 transforms (004 eq. 4-5), half-turns included.

    Of the four ratios of eq. (4) the one with the largest pivot is used per transform, so
    the result is accurate for every rotation (the first ratio alone fails at half-turns).
    """
    m = np.asarray(m, dtype=float)
    if m.shape[-2:] != (4, 4):
        raise ValueError(f"expected transforms of shape (..., 4, 4), got {m.shape}")
    a = [[m[..., i, j] for j in range(3)] for i in range(3)]
    ratios = np.stack([np.stack(r, axis=-1) for r in cv.rotation_ratios(a)], axis=-2)
    pivots = np.stack([ratios[..., k, k] for k in range(4)], axis=-1)
    best = np.argmax(pivots, axis=-1)
    x = np.take_along_axis(ratios, best[..., None, None], axis=-2)[..., 0, :]
    x = x / np.linalg.norm(x, axis=-1, keepdims=True)
    x = np.where(x[..., :1] < 0, -x, x)
    t = [m[..., i, 3] for i in range(3)]
    y = np.stack(cv.dual_part_from_translation(t, [x[..., i] for i in range(4)]), axis=-1)
    return np.concatenate([x, y], axis=-1)
