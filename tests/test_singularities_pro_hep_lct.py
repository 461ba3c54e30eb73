"""The interpretations given to the Pro-Hep-LCT singularity polynomials, checked numerically
at configurations built from the independent joint geometry (not from the polynomials)."""

import numpy as np
from independent_pro_hep_lct import GEOMETRY, lower_leg1
from scipy.optimize import brentq

G = GEOMETRY


def unit(a):
    return np.array([np.cos(a), np.sin(a)])


def parallel_l2_l4(alpha, flip):
    """theta1, phi1 and Pd with l2 and l4 both along alpha (flip: l4 along alpha + pi)."""
    beta = alpha + (np.pi if flip else 0.0)

    def gap(th1):
        pd = G["l1"] * unit(th1) + G["l2"] * unit(alpha) + np.array([0, G["d"] / 2])
        v = pd - np.array([0, G["lq4d"]]) + np.array([0, G["d"] / 2]) - G["l4"] * unit(beta)
        return np.linalg.norm(v) - G["l3"]

    grid = np.linspace(-np.pi, np.pi, 721)
    vals = [gap(t) for t in grid]
    k = next(i for i in range(720) if np.sign(vals[i]) != np.sign(vals[i + 1]))
    th1 = brentq(gap, grid[k], grid[k + 1], xtol=1e-14)
    pd = G["l1"] * unit(th1) + G["l2"] * unit(alpha) + np.array([0, G["d"] / 2])
    v = pd - np.array([0, G["lq4d"]]) + np.array([0, G["d"] / 2]) - G["l4"] * unit(beta)
    return th1, np.arctan2(v[1], v[0]), pd


def test_det_jo_pd_vanishes_when_l2_parallel_l4(gen):
    for alpha, flip in [(0.3, False), (-0.8, False), (1.2, True)]:
        th1, phi1, pd = parallel_l2_l4(alpha, flip)
        assert np.allclose(lower_leg1(th1, alpha - th1), pd)
        pose = np.array([300.0, 200.0, *pd])
        q = np.array([np.tan(th1 / 2), np.tan(phi1 / 2), 100.0, 200.0])
        s = gen.singularities(pose, q, **G)
        # relative to the same polynomial at a generic (non-parallel) configuration nearby
        q_off = q + np.array([0.05, -0.05, 0, 0])
        ref = abs(gen.singularities(pose, q_off, **G)["det_Jo_Pd"])
        assert abs(s["det_Jo_Pd"]) < 1e-9 * ref


def test_det_ji_pd_vanishes_when_l1_l2_aligned(gen):
    th1 = 0.9
    pd = lower_leg1(th1, 0.0)  # l1 and l2 aligned: chain 1 stretched
    pose = np.array([300.0, 200.0, *pd])
    q = np.array([np.tan(th1 / 2), 0.1, 100.0, 200.0])
    s = gen.singularities(pose, q, **G)
    inner = gen.singularities(pose + np.array([0, 0, -20.0, 0]), q, **G)
    assert abs(s["boundary_t1"]) < 1e-9 * abs(inner["boundary_t1"])
    assert abs(s["det_Ji_Pd"]) < 1e-9 * abs(inner["det_Ji_Pd"])
    # the IK reports the double root as a valid value on the boundary, the Jacobian as singular
    assert gen.ik_status(pose, 0, **G) == gen.ON_BOUNDARY
    assert np.isclose(gen.ik(pose, 0, **G)[0], np.tan(th1 / 2))
    assert gen.jacobian_status(pose, 0, **G) == gen.INPUT_SINGULAR


def test_det_jo_pu_at_rod_along_oy(gen):
    pose = np.array([G["lq5"], 200.0, 150.0, 150.0])
    q = np.array([0.1, 0.1, 200.0 - G["ld4"], 200.0])
    assert abs(gen.singularities(pose, q, **G)["det_Jo_Pu"]) < 1e-9
