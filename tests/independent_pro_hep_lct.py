"""Independent numeric model of the Pro-Hep-LCT planar chains (trigonometry + scipy).

It knows nothing of Study parameters, ideals or the generated closed forms: joint geometry
as read from 004 Tables 1-2 and eq. (14), written with cosines and sines, and loop closures
solved numerically.  The geometry values are test values, not the paper's (Table 4 of 004 is
missing from the source text).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

GEOMETRY = dict(Dz=120.0, lq5=150.0, ld4=200.0, l1=180.0, l2=160.0, l3=170.0, l4=150.0,
                d=60.0, lq4d=250.0)


def lower_leg1(theta1, theta2, g=GEOMETRY):
    """Pd from chain 1: l1 at theta1, l2 at theta1+theta2, then +d/2 along Y (link d fixed)."""
    return np.array([g["l1"] * np.cos(theta1) + g["l2"] * np.cos(theta1 + theta2),
                     g["l1"] * np.sin(theta1) + g["l2"] * np.sin(theta1 + theta2) + g["d"] / 2])


def lower_leg2(phi1, phi2, g=GEOMETRY):
    """Pd from chain 2: base at (0, lq4d), l3, l4, then -d/2 along Y."""
    return np.array([g["l3"] * np.cos(phi1) + g["l4"] * np.cos(phi1 + phi2),
                     g["lq4d"] + g["l3"] * np.sin(phi1) + g["l4"] * np.sin(phi1 + phi2)
                     - g["d"] / 2])


def upper(q4, q5, g=GEOMETRY, sign=1.0):
    """(Xu, Yu) of Pu: slider q5 along Y, carriage at lq5 + lq4 along X, rod ld4 to slider q4."""
    lq4 = sign * np.sqrt(g["ld4"] ** 2 - (q5 - q4) ** 2)
    return np.array([g["lq5"] + lq4, q5])


def solve_leg(forward, target, starts):
    """All distinct (active, passive) angle pairs closing ``forward(a, p) = target``."""
    sols = []
    for a0, p0 in starts:
        r = least_squares(lambda v: forward(v[0], v[1]) - target, [a0, p0], xtol=1e-15,
                          ftol=1e-15, gtol=1e-15)
        if np.max(np.abs(r.fun)) < 1e-9:
            a, p = np.mod(r.x + np.pi, 2 * np.pi) - np.pi
            if not any(abs(a - s[0]) < 1e-7 and abs(p - s[1]) < 1e-7 for s in sols):
                sols.append((a, p))
    return sols


def closure_residual_for_active(forward, target, active, passive_guesses):
    """Smallest closure error (mm) over the passive angle, with the active angle fixed."""
    best = np.inf
    for p0 in passive_guesses:
        r = least_squares(lambda v: forward(active, v[0]) - target, [p0], xtol=1e-15,
                          ftol=1e-15, gtol=1e-15)
        best = min(best, float(np.max(np.abs(r.fun))))
    return best
