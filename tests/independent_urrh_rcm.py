"""An independent numeric model of the 2-URRH RCM manipulator (002 Sect. 2.4, 4.1-4.2), in
plain vectors: no Study parameters, no elimination, no generated code.

Frame {S}: x = u1, y = u2; limb i's plane normal n1 = Rx(alpha1) y, n2 = Ry(alpha2) x
(v1 = u2, v2 = u1); A_i = -l_oa u_i; B_i = A_i + l_ab exp(n_i^ beta_i) u_i (002 eq. 7);
collar C_i = d_i u on the shaft with |B_i C_i| = l_bc.  The pose (theta1, theta2, d, gamma)
is the virtual chain of eq. (14)-(16): u = Rx(theta1) Ry(theta2) (0, 0, -1), d1 = d,
d2 = d - p gamma (eq. 9, 11).  The loop closure of each limb, |B_i(beta_i) - C_i| = l_bc,
is solved for beta_i numerically (scipy.optimize.brentq on the branch's bracket).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

X, Y, Z = np.eye(3)


def rx(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def ry(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def rz(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def shaft(pose, par) -> tuple[np.ndarray, float, float]:
    """u, d1, d2 of a pose."""
    t1, t2, d, g = pose
    return rx(t1) @ ry(t2) @ -Z, d, d - par["p"] * g


def alphas(u: np.ndarray) -> tuple[float, float]:
    """The U-joint angles whose limb planes contain u (n_i . u = 0), on the branch near 0:
    n1 = (0, c1, s1): tan alpha1 = -u_y / u_z; n2 = (c2, 0, -s2): tan alpha2 = u_x / u_z."""
    return float(np.arctan(-u[1] / u[2])), float(np.arctan(u[0] / u[2]))


def crank_point(limb: int, alpha: float, beta: float, par) -> np.ndarray:
    """B_i of eq. (7)."""
    if limb == 1:
        return rx(alpha) @ (-par["loa1"] * X + par["lab1"] * ry(beta) @ X)
    return ry(alpha) @ (-par["loa2"] * Y + par["lab2"] * rx(beta) @ Y)


def beta_roots(limb: int, alpha: float, c: np.ndarray, par, grid: int = 2001) -> list[float]:
    """Every beta in (-pi, pi) with |B_i(beta) - C_i| = l_bc (the loop closure), by sign
    changes on a grid refined with brentq."""
    lbc = par[f"lbc{limb}"]

    def f(b):
        return float(np.linalg.norm(crank_point(limb, alpha, b, par) - c) - lbc)

    bs = np.linspace(-np.pi, np.pi, grid)
    vals = [f(b) for b in bs]
    out = []
    for b0, b1, v0, v1 in zip(bs[:-1], bs[1:], vals[:-1], vals[1:]):
        if v0 == 0:
            out.append(float(b0))
        elif v0 * v1 < 0:
            out.append(brentq(f, b0, b1, xtol=1e-15, rtol=1e-15, maxiter=200))
    return out


def ik_all(pose, par) -> list[np.ndarray]:
    """Every (alpha1, alpha2, beta1, beta2) of a pose with the U joints on the branch near 0
    (each limb's two elbows)."""
    u, d1, d2 = shaft(pose, par)
    a1, a2 = alphas(u)
    out = []
    for b1 in beta_roots(1, a1, d1 * u, par):
        for b2 in beta_roots(2, a2, d2 * u, par):
            out.append(np.array([a1, a2, b1, b2]))
    return out


def collar_positions(q, u, par) -> list[list[float]]:
    """Both roots of 002 eq. (8) per limb: d = u.B +- sqrt(l_bc^2 - |(I - u u^T) B|^2)."""
    out = []
    for limb, a, b in ((1, q[0], q[2]), (2, q[1], q[3])):
        rb = crank_point(limb, a, b, par)
        along = float(u @ rb)
        perp2 = float(rb @ rb - along**2)
        disc = par[f"lbc{limb}"] ** 2 - perp2
        out.append([] if disc < 0 else [along + np.sqrt(disc), along - np.sqrt(disc)])
    return out


def fk_all(q, par) -> list[np.ndarray]:
    """Every pose of joints q: u normal to both limb planes (pointing to -z), d1 and d2 from
    both roots of eq. (8); theta1 = alpha1, theta2 = phi1 - pi/2 (eq. 16)."""
    n1 = rx(q[0]) @ Y
    n2 = ry(q[1]) @ X
    u = np.cross(n1, n2)
    u /= np.linalg.norm(u)
    if u[2] > 0:
        u = -u
    theta2 = float(np.arccos(np.clip(u @ X, -1, 1)) - np.pi / 2)
    theta1 = float(np.arctan2(u[1], -u[2]))
    out = []
    for d1 in collar_positions(q, u, par)[0]:
        for d2 in collar_positions(q, u, par)[1]:
            out.append(np.array([theta1, theta2, d1, (d1 - d2) / par["p"]]))
    return out


def distance_to_line(point: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Distance of ``point`` from the line through a and b."""
    e = (b - a) / np.linalg.norm(b - a)
    r = point - a
    return float(np.linalg.norm(r - (r @ e) * e))
