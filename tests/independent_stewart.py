"""Independent numeric model of the Stewart platform layout of ``mechanisms/stewart.py``.

Written from the layout's description only (joint pairs at theta_j +- phi_a on the base
ring, theta_j + 60 deg +- phi_b on the platform ring, theta_j = -30, 90, 210 deg, each base
joint joined to the nearer platform joint of the next pair), with scipy rotations: leg
lengths are distances, joint angles are angles to the leg's homing direction.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

THETA = np.radians([-30.0, 90.0, 210.0])
HOME = np.array([0.0, 0.0, 210.0])


def _ring(r, angles):
    return np.stack([r * np.cos(angles), r * np.sin(angles), np.zeros_like(angles)], axis=1)


def corners(ra=200.0, rb=200.0, ta=0.125, tb=0.125):
    """Base joints A_k and platform joints B_k (platform frame), k = 1..6."""
    pa, pb = 2 * np.arctan(ta), 2 * np.arctan(tb)
    a_ang, b_ang = [], []
    for j in range(3):
        mid = THETA[j] + np.radians(60.0)
        a_ang += [THETA[j] + pa, THETA[(j + 1) % 3] - pa]
        b_ang += [mid - pb, mid + pb]
    return _ring(ra, np.array(a_ang)), _ring(rb, np.array(b_ang))


def legs(pose, **geo):
    """Leg vectors A_k -> B_k in the base frame, and the rotation of the platform."""
    x, y, z, a, b, c = pose
    rot = Rotation.from_euler("ZYX", [c, b, a]).as_matrix()
    base, plat = corners(**geo)
    return np.array([x, y, z]) + plat @ rot.T - base, rot


def ik(pose, **geo):
    return np.linalg.norm(legs(pose, **geo)[0], axis=1)


def joint_angles(pose, **geo):
    """(angle at A_k, angle at B_k) of each leg to its homing direction, radians."""
    v, rot = legs(pose, **geo)
    h, _ = legs([*HOME, 0.0, 0.0, 0.0], **geo)
    un = v / np.linalg.norm(v, axis=1)[:, None]
    hn = h / np.linalg.norm(h, axis=1)[:, None]
    at_a = np.arccos(np.clip(np.sum(un * hn, axis=1), -1, 1))
    at_b = np.arccos(np.clip(np.sum((un @ rot) * hn, axis=1), -1, 1))
    return at_a, at_b


TWENTY_DEG = np.radians(20.0)


def in_workspace(pose, q_range=(160.0, 320.0), u_max=TWENTY_DEG, s_max=TWENTY_DEG, **geo):
    q = ik(pose, **geo)
    at_a, at_b = joint_angles(pose, **geo)
    return bool(np.all((q >= q_range[0]) & (q <= q_range[1])) and np.all(at_a <= u_max)
                and np.all(at_b <= s_max))
