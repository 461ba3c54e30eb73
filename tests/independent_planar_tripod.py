"""Independent numeric model of the 000 hybrid planar-tripod mechanism (plain geometry).

No Study parameters, ideals or closed forms: joint positions from the paper's figures and
eq. (1), (2), (7), (18), the tripod's revolute-plane constraints solved numerically (scipy)
for the MP1 pose, and each planar leg's two prismatic strokes from a 2x2 linear solve.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

RA = RB = 190.0
S = np.sqrt(3.0)
A = [np.array([S / 2 * RA, -RA / 2]), np.array([0.0, RA]), np.array([-S / 2 * RA, -RA / 2])]
E = [np.array([-0.5, S / 2]), np.array([-0.5, -S / 2]), np.array([1.0, 0.0])]
B = [np.array([S / 2 * RA, RA / 2]), np.array([-S / 2 * RA, RA / 2]), np.array([0.0, -RA])]
EP = [np.array([-1.0, 0.0]), np.array([0.5, -S / 2]), np.array([0.5, S / 2])]
C = [np.array([RA, 0, 0]), np.array([0, RA, 0]), np.array([-RA, 0, 0])]
D = [np.array([RB, 0, 0]), np.array([0, RB, 0]), np.array([-RB, 0, 0])]


def rot(axis, t):
    c, s = np.cos(t), np.sin(t)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def world_d(pose):
    x, y, z, a, b, g = pose
    r = rot("z", g) @ rot("y", b) @ rot("x", a)
    return [np.array([x, y, z]) + r @ d for d in D]


def mp1_pose(pose):
    """(x1, y1, gamma1) such that every D_k lies in the plane of its revolute joint."""
    dw = world_d(pose)

    def residual(v):
        x1, y1, g1 = v
        rinv = rot("z", -g1)
        dl = [rinv @ (d - np.array([x1, y1, 0.0])) for d in dw]
        return [dl[0][1], dl[1][0], dl[2][1]]

    r = least_squares(residual, [pose[0], pose[1], pose[5]], xtol=1e-15, ftol=1e-15, gtol=1e-15)
    assert np.max(np.abs(r.fun)) < 1e-10
    return r.x


def ik(pose):
    """q1..q6 of the independent model."""
    x1, y1, g1 = mp1_pose(pose)
    rz = rot("z", g1)[:2, :2]
    q = []
    for k in range(3):
        # A_k + q e_k = O1 + Rz (B_k + l e'_k): unknowns q, l
        m = np.column_stack([E[k], -rz @ EP[k]])
        rhs = np.array([x1, y1]) + rz @ B[k] - A[k]
        q.append(np.linalg.solve(m, rhs)[0])
    dw = world_d(pose)
    for k in range(3):
        d_local = rot("z", -g1) @ (dw[k] - np.array([x1, y1, 0.0]))
        q.append(np.linalg.norm(d_local - C[k]))
    return np.array(q)
