"""An independent numeric model of the lamina-milling robot (003 Sect. 2.2, Fig. 6) in plain
trigonometry: no Study parameters, no elimination, no generated code.

Upper chain: E = (0, dy1 + lDE, dD + L) and C = H - (0, dy2, 0) at distance lEC (eq. 7);
bottom chain i: A_i = l_O (cos theta_i, sin theta_i, 0) at distance l_F from F = (x, y, 0)
(eq. 8).  The IK solves each chain on its own (a square root for L, the two elbows of a
triangle for theta_i); the FK intersects the two circles of F and then the sphere of C.
"""

from __future__ import annotations

import itertools
import math

import numpy as np


def _upper(par):
    return par["dy2"] + par["dy1"] + par["lDE"], par["dD"], par["lEC"]


def stroke_roots(pose, par):
    """L with |C - E| = lEC: L = z - dD +- sqrt(lEC^2 - x^2 - (y - dy2 - dy1 - lDE)^2)
    (+: C below E)."""
    x, y, z = pose
    off, dd, lec = _upper(par)
    r2 = lec**2 - x**2 - (y - off) ** 2
    if r2 < 0:
        return []
    r = math.sqrt(r2)
    return [z - dd + r, z - dd - r]


def elbow_roots(pose, lo, lf):
    """theta with |A - F| = lf, A = lo (cos theta, sin theta): phi -+ alpha, phi the
    direction of F, alpha the angle at O of the triangle O A F (first: theta < phi)."""
    x, y = pose[0], pose[1]
    rho = math.hypot(x, y)
    if rho == 0:
        return []
    c = (rho**2 + lo**2 - lf**2) / (2 * lo * rho)
    if abs(c) > 1:
        return []
    phi, alpha = math.atan2(y, x), math.acos(c)
    return [phi - alpha, phi + alpha]


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def ik_all(pose, par):
    """Every real (L, theta1, theta2), angles in (-pi, pi]."""
    out = []
    for L, a, b in itertools.product(stroke_roots(pose, par),
                                     elbow_roots(pose, par["lOA"], par["lAF"]),
                                     elbow_roots(pose, par["lOB"], par["lBM"])):
        out.append(np.array([L, wrap(a), wrap(b)]))
    return out


def ik_working(pose, par):
    """The working branch: C below E, elbow A on the side of smaller angle and B on the
    side of larger angle than F's direction (the rhombus O A F B opened towards +y)."""
    L = stroke_roots(pose, par)
    a = elbow_roots(pose, par["lOA"], par["lAF"])
    b = elbow_roots(pose, par["lOB"], par["lBM"])
    if not (L and a and b):
        return None
    return np.array([L[0], wrap(a[0]), wrap(b[1])])


def fk_all(q, par):
    """Every real H for joints (L, theta1, theta2): the intersections F of the circles about
    A and B, each with its two heights."""
    L, t1, t2 = q
    a = par["lOA"] * np.array([math.cos(t1), math.sin(t1)])
    b = par["lOB"] * np.array([math.cos(t2), math.sin(t2)])
    ra, rb = par["lAF"], par["lBM"]
    dab = np.linalg.norm(b - a)
    if dab == 0 or dab > ra + rb or dab < abs(ra - rb):
        return []
    u = (b - a) / dab
    s = (dab**2 + ra**2 - rb**2) / (2 * dab)
    h = math.sqrt(max(ra**2 - s**2, 0.0))
    normal = np.array([-u[1], u[0]])
    out = []
    off, dd, lec = _upper(par)
    for f in (a + s * u + h * normal, a + s * u - h * normal):
        r2 = lec**2 - f[0] ** 2 - (f[1] - off) ** 2
        if r2 < 0:
            continue
        r = math.sqrt(r2)
        out += [np.array([f[0], f[1], dd + L - r]), np.array([f[0], f[1], dd + L + r])]
    return out


def residuals(pose, q, par):
    """003 eq. (7)-(8) (minus signs restored) at (pose, joints)."""
    x, y, z = pose
    L, t1, t2 = q
    off, dd, lec = _upper(par)
    return np.array([
        x**2 + (y - off) ** 2 + (z - dd - L) ** 2 - lec**2,
        (par["lOA"] * math.cos(t1) - x) ** 2 + (par["lOA"] * math.sin(t1) - y) ** 2
        - par["lAF"] ** 2,
        (par["lOB"] * math.cos(t2) - x) ** 2 + (par["lOB"] * math.sin(t2) - y) ** 2
        - par["lBM"] ** 2])
