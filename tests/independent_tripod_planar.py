"""Independent numeric model of the tripod-planar mechanism (001), for the tests.

Built from the joint geometry only (001 eq. 1-3, 7, 9, 17 with the corner -rb/2, 18-20),
with rotation matrices and scipy, not from any closed form: platform B is found by solving
the loop closure numerically (spherical joints in the planes of their revolute joints,
eq. 9, and the end effector = B * T(x2, y2, d) Rz(gamma_p)), then the leg lengths are
distances and the planar strokes come from intersecting the sliders' lines.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

S3 = np.sqrt(3.0)


def _corners(r, angles_deg):
    a = np.radians(angles_deg)
    return np.stack([r * np.cos(a), r * np.sin(a), np.zeros(3)], axis=1)


def end_effector(pose):
    """(R, t) of the end effector: R = Rz(gamma) Ry(beta) Rx(alpha)."""
    x, y, z, a, b, c = pose
    return Rotation.from_euler("ZYX", [c, b, a]).as_matrix(), np.array([x, y, z])


def platform_b(pose, ra=200.0, rb=200.0, d=0.0):
    """Solve for B (rotation, origin) and the planar coordinates (x2, y2, gamma_p)."""
    re, te = end_effector(pose)
    a_pts = _corners(ra, [-30, 90, 210])
    b_loc = _corners(rb, [-30, 90, 210])
    tangents = np.stack([-np.sin(np.radians([-30, 90, 210])),
                         np.cos(np.radians([-30, 90, 210])), np.zeros(3)], axis=1)

    def split(u):
        rv, gp, x2, y2 = u[:3], u[3], u[4], u[5]
        rb_ = Rotation.from_rotvec(rv).as_matrix()
        rz = Rotation.from_euler("z", gp).as_matrix()
        tb = te - rb_ @ np.array([x2, y2, d])
        return rb_, rz, tb

    def residual(u):
        rb_, rz, tb = split(u)
        rot_err = (rb_ @ rz - re).ravel()
        plane = [(tb + rb_ @ b_loc[k] - a_pts[k]) @ tangents[k] for k in range(3)]
        return np.concatenate([rot_err, plane])

    rz0 = Rotation.from_matrix(re).as_euler("ZYX")[0]
    u0 = np.array([0, 0, 0, rz0, 0, 0], dtype=float)
    u0[:3] = Rotation.from_matrix(re @ Rotation.from_euler("z", -rz0).as_matrix()).as_rotvec()
    sol = least_squares(residual, u0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    rb_, rz, tb = split(sol.x)
    return rb_, tb, sol.x[3], sol.x[4], sol.x[5], float(np.abs(residual(sol.x)).max())


def joints(pose, ra=200.0, rb=200.0, d=0.0):
    """q1..q6 of the pose (mm) and the closure residual of the numeric solve."""
    rb_, tb, gp, x2, y2, res = platform_b(pose, ra, rb, d)
    a_pts = _corners(ra, [-30, 90, 210])
    b_loc = _corners(rb, [-30, 90, 210])
    q = [float(np.linalg.norm(tb + rb_ @ b_loc[k] - a_pts[k])) for k in range(3)]
    # planar stage in B's frame: slider k starts at a lower corner and runs along its edge;
    # R'_k starts at an upper corner C_k and runs along the edge of C (eq. 17-18)
    low = _corners(rb, [-30, 90, 210])[:, :2]
    low_dir = [low[1] - low[0], low[2] - low[1], low[0] - low[2]]
    up = _corners(rb, [30, 150, 270])[:, :2]
    up_dir = [up[1] - up[0], up[2] - up[1], up[0] - up[2]]
    rz = np.array([[np.cos(gp), -np.sin(gp)], [np.sin(gp), np.cos(gp)]])
    for k in range(3):
        e1 = low_dir[k] / np.linalg.norm(low_dir[k])
        e2 = rz @ (up_dir[k] / np.linalg.norm(up_dir[k]))
        start2 = np.array([x2, y2]) + rz @ up[k]
        qk, _lk = np.linalg.solve(np.column_stack([e1, -e2]), start2 - low[k])
        q.append(float(qk))
    return np.array(q), res


def jacobian_fd(pose, h=1e-6, **geo):
    """Central finite differences of :func:`joints` in the pose coordinates."""
    pose = np.asarray(pose, dtype=float)
    cols = []
    for i in range(6):
        step = np.zeros(6)
        step[i] = h
        cols.append((joints(pose + step, **geo)[0] - joints(pose - step, **geo)[0]) / (2 * h))
    return np.stack(cols, axis=1)


def _stage_strokes(gp, x2, y2, rb=200.0):
    """q4..q6 of the planar stage at (x2, y2, gamma_p) in B: the sliders' lines intersected
    (as in :func:`joints`)."""
    low = _corners(rb, [-30, 90, 210])[:, :2]
    low_dir = [low[1] - low[0], low[2] - low[1], low[0] - low[2]]
    up = _corners(rb, [30, 150, 270])[:, :2]
    up_dir = [up[1] - up[0], up[2] - up[1], up[0] - up[2]]
    rz = np.array([[np.cos(gp), -np.sin(gp)], [np.sin(gp), np.cos(gp)]])
    out = []
    for k in range(3):
        e1 = low_dir[k] / np.linalg.norm(low_dir[k])
        e2 = rz @ (up_dir[k] / np.linalg.norm(up_dir[k]))
        out.append(float(np.linalg.solve(np.column_stack([e1, -e2]),
                                         np.array([x2, y2]) + rz @ up[k] - low[k])[0]))
    return out


def all_joints(pose, ra=200.0, rb=200.0, n=20001):
    """The joints (|q1|..|q3|, q4..q6) of every split of the pose into B and the planar stage
    (d = 0): B = R_E Rz(-gamma_p) with (x2, y2) from the three plane conditions (linear in
    them), so the splits are the zeros of the least-squares residual over gamma_p, found by
    a scan of ``n`` values and golden-section refinement.  Unlike :func:`platform_b` (one
    start), no split is missed: a pose of forward kinematics is an assembly of its joints
    exactly when one of these gives them back."""
    re, te = end_effector(pose)
    a_pts, b_loc = _corners(ra, [-30, 90, 210]), _corners(rb, [-30, 90, 210])
    ang = np.radians([-30, 90, 210])
    tang = np.stack([-np.sin(ang), np.cos(ang), np.zeros(3)], axis=1)

    def split(gp):
        gp = np.atleast_1d(gp)
        rb_ = np.einsum("ij,njk->nik", re, Rotation.from_euler("z", -gp[:, None]).as_matrix())
        a = -np.einsum("nik,li->nlk", rb_[:, :, :2], tang)  # plane k: a (x2, y2) = b
        b = -np.einsum("nli,li->nl", te + np.einsum("nij,lj->nli", rb_, b_loc) - a_pts, tang)
        xy = np.linalg.solve(np.einsum("nli,nlj->nij", a, a),
                             np.einsum("nli,nl->ni", a, b)[..., None])[..., 0]
        return rb_, xy, np.linalg.norm(np.einsum("nlk,nk->nl", a, xy) - b, axis=1)

    grid = np.linspace(-np.pi, np.pi, n)
    res = split(grid)[2]
    out = []
    for i in np.flatnonzero((res[1:-1] <= res[:-2]) & (res[1:-1] <= res[2:])) + 1:
        lo, hi = grid[i - 1], grid[i + 1]
        for _ in range(80):
            m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
            lo, hi = (lo, m2) if split(m1)[2][0] < split(m2)[2][0] else (m1, hi)
        gp = 0.5 * (lo + hi)
        rb_, xy, r = split(gp)
        if r[0] > 1e-9 * max(1.0, float(np.abs(te).max())):
            continue
        rb_, (x2, y2) = rb_[0], xy[0]
        tb = te - rb_ @ np.array([x2, y2, 0.0])
        legs = [float(np.linalg.norm(tb + rb_ @ b_loc[k] - a_pts[k])) for k in range(3)]
        out.append(np.array(legs + _stage_strokes(gp, x2, y2, rb)))
    return out
