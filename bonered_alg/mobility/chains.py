"""The joint screws of a declared leg at a configuration: the spatial twist of its end
frame per unit rate of each joint variable, ``(omega; v) = (g' g^-1)^vee`` as in
``kinematics.twist.pose_twist``, here evaluated numerically: each factor and its derivative
at the configuration's values, the derivative of the product by the product rule.

Each joint contributes as many freedoms as its type has (``chains.joints.JOINT_DOF``; a
spherical joint's four Euler parameters give four columns of rank three); an offset whose
value depends on the closure's coordinates (a collar sliding on a shaft) is a slide, one
prismatic freedom; a helical joint's slide is its pitch times its turn.  A leg on a mount
is taken in its mount's frame (the mount fixed).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_numeric as sn
from ..algebra import study_symbolic as ss
from ..chains.joints import JOINT_DOF, Role
from .screws import ChainScrews


def spatial_twist(g: np.ndarray, dg: np.ndarray) -> np.ndarray:
    """``(omega; v)`` of the Study point ``g`` moving with derivative ``dg`` (any scale):
    omega = 2 vec(x' conj(x)) / |x|^2, v = t' - omega x t (kinematics.twist)."""
    x, dx = g[:4], dg[:4]
    n, dn = float(x @ x), 2.0 * float(x @ dx)
    conj = np.array([x[0], -x[1], -x[2], -x[3]])
    omega = 2.0 * np.array(cv.quaternion_product(dx, conj)[1:]) / n
    tn = np.array(cv.translation_times_norm(g))  # |x|^2 t, bilinear in (x, y)
    dtn = (np.array(cv.translation_times_norm(np.concatenate([dx, g[4:]])))
           + np.array(cv.translation_times_norm(np.concatenate([x, dg[4:]]))))
    t = tn / n
    dt = (dtn - t * dn) / n
    return np.concatenate([omega, dt - np.cross(omega, t)])


def _numeric(point, vals) -> np.ndarray:
    """The coordinates at ``vals`` (symbol -> number), as floats.  Each coordinate gets only
    the values of its own symbols: ``subs`` puts them in one after another in its sorted
    order, which the others would only lengthen (sorting and sympifying the whole
    configuration for every coordinate)."""
    out = []
    for c in map(sp.sympify, point):
        out.append(c.subs({s: vals[s] for s in c.free_symbols if s in vals}))
    stray = sorted({str(s) for c in out for s in c.free_symbols})
    if stray:
        raise ValueError(f"no value for {stray} at the configuration")
    return np.array([float(c) for c in out])


def leg_chain(leg, closure_symbols, values: Mapping[sp.Symbol, float]) -> ChainScrews:
    """The joint screws (rows) of ``leg`` at ``values`` (every joint variable, closure
    coordinate, geometric parameter and constant of the leg)."""
    factors, variables, freedoms, joints = [], [], 0, 0
    vals = dict(values)
    couplings = {c.translation: c for c in leg.couplings}
    for j in leg.joints:
        moving = False
        for f in j.factors:
            point = f.study()
            if f.role is Role.GEOMETRIC and f.free_symbols & set(closure_symbols):
                if f.kind != "translation" or f.axis is None:
                    raise ValueError(f"leg {leg.name!r}, factor {f.label}: only a slide along "
                                     "an axis may depend on the closure's coordinates")
                slide = sp.Symbol(f"slide_{f.label}", real=True)
                vals[slide] = float(sp.sympify(f.args[0]).subs(vals))
                point = ss.translation(f.axis, slide)
                variables.append(slide)
                freedoms += 1
                moving = True
            elif f.role is not Role.GEOMETRIC:
                for s in sorted(f.free_symbols - set(variables), key=str):
                    if s in couplings:  # a helical slide follows its turn
                        c = couplings[s]
                        point = tuple(sp.sympify(x).subs(s, c.pitch * 2 * sp.atan(c.rotation))
                                      for x in point)
                    else:
                        variables.append(s)
                moving = True
            factors.append(point)
        if j.dof:
            freedoms += JOINT_DOF[j.kind]
        joints += 1 if (j.dof or moving) else 0
    try:
        values = [_numeric(f, vals) for f in factors]
        derivs = {v: [_numeric([sp.diff(c, v) for c in f], vals) if any(
            sp.sympify(c).has(v) for c in f) else None for f in factors] for v in variables}
    except ValueError as e:
        raise ValueError(f"leg {leg.name!r}: {e}") from None
    before = [np.eye(1, 8, 0)[0]]
    for f in values:
        before.append(sn.product(before[-1], f))
    after = [np.eye(1, 8, 0)[0]]
    for f in reversed(values):
        after.insert(0, sn.product(f, after[0]))
    g = before[-1]
    rows = []
    for v in variables:
        dg = sum(sn.product(sn.product(before[k], df), after[k + 1])
                 for k, df in enumerate(derivs[v]) if df is not None)
        rows.append(spatial_twist(g, dg))
    return ChainScrews(leg.name, np.array(rows).reshape(-1, 6), joints, freedoms)
