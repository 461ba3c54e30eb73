"""Stewart platform (6-UPS): the closed-form leg ideal and the generated functions, against
the independent numeric model (tests/independent_stewart.py); the papers print no Stewart
equation."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from bonered_alg.generated import stewart as gen

from bonered_alg.chains.joints import Role, joint, leg
from bonered_alg.elimination import sphere_leg
from bonered_alg.mechanisms import stewart
from bonered_alg.pipeline.algebra import Algebra
from bonered_alg.solvers.legs import DistanceLeg
from tests import independent_stewart as ind

RNG = np.random.default_rng(20261122)


def _random_poses(n):
    return np.column_stack([RNG.uniform(-40, 40, n), RNG.uniform(-40, 40, n),
                            RNG.uniform(180, 260, n), *(RNG.uniform(-0.2, 0.2, (3, n)))])


def test_ik_matches_independent_leg_lengths():
    poses = _random_poses(300)
    for geo in ({}, {"ra": 190.0, "rb": 190.0}, {"ta": 0.25, "tb": 0.0625}):
        q = gen.ik(poses, limits=False, **geo)
        ref = np.array([ind.ik(p, **geo) for p in poses])
        assert np.max(np.abs(q - ref)) < 1e-9


def test_limits_match_independent_joint_angles():
    poses = _random_poses(200)
    q = gen.ik(poses, limits=False)
    vals = gen.limit_values(poses, q)
    at_a, at_b = np.array([ind.joint_angles(p) for p in poses]).transpose(1, 0, 2)
    for k in range(6):
        assert np.max(np.abs(vals[f"phi_u{k + 1}"] - at_a[:, k])) < 1e-7
        assert np.max(np.abs(vals[f"phi_s{k + 1}"] - at_b[:, k])) < 1e-7


def test_jacobian_matches_finite_differences():
    poses = _random_poses(20)
    J = gen.jacobian(poses, limits=False)
    h = 1e-6
    for p, jp in zip(poses, J):
        fd = np.stack([(ind.ik(p + h * e) - ind.ik(p - h * e)) / (2 * h) for e in np.eye(6)],
                      axis=1)
        assert np.max(np.abs(jp - fd)) < 1e-5


def test_negative_strokes_are_the_other_modes():
    pose = np.array([5.0, -3.0, 220.0, 0.05, -0.02, 0.1])
    q_all = gen.ik_all(pose, limits=False)
    assert np.allclose(np.abs(q_all), ind.ik(pose), atol=1e-9)
    assert np.all(q_all[0] > 0) and np.all(q_all[-1] < 0)


def test_distance_leg_is_certified_and_rps_leg_is_not():
    """The U-P-S leg passes the three certificate steps; an R-P-S leg (one revolute before
    the stroke) has a 5-dimensional image and is left to elimination."""
    mech = stewart.MECHANISM
    closure = mech.closures[0]
    ideal = DistanceLeg().derive(mech, closure, closure.legs[1], Algebra.default())
    assert ideal is not None and "dimension 6" in ideal.certificate
    assert ideal.problem.eliminate == ()
    # the same leg with its universal joint reduced to one revolute
    u, e = sp.Symbol("u", real=True), sp.symbols("e0:4", real=True)
    q = sp.Symbol("q", real=True)
    rps = leg("R", joint("t", "offset", "A", vector=(100, 0, 0)),
              joint("t", "revolute", "R", "y", u, Role.PASSIVE),
              joint("t", "prismatic", "P", "z", q, Role.ACTIVE),
              joint("t", "spherical", "S", e, Role.PASSIVE),
              joint("t", "offset", "B", vector=(-50, 0, 0)))
    d = sphere_leg.recognize(rps)
    assert d is not None
    with pytest.raises(sphere_leg.NotADistanceLeg, match="dimension 5"):
        sphere_leg.certify(rps, d, closure.platform, (u, *e), {}, {})


def _plucker_det(pose):
    """det of the six leg lines' normalized Plücker rows (direction; A_k x direction) from
    the independent model: zero exactly where the lines are linearly dependent."""
    v, _ = ind.legs(pose)
    base, _ = ind.corners()
    s = v / np.linalg.norm(v, axis=1)[:, None]
    return np.linalg.det(np.hstack([s, np.cross(base, s)]))


def test_forward_singularity_is_where_the_leg_lines_are_dependent():
    """det_forward_P (Jo with the Study quadric's gradient, from the ideal) changes sign on a
    line of poses exactly where the independent Plücker determinant does (issue 14, item 3),
    and not where it does not."""
    alphas = np.linspace(-1.4, 1.4, 141)
    poses = np.zeros((len(alphas), 6))
    poses[:, 2], poses[:, 3], poses[:, 4] = 210.0, alphas, 0.2
    ours = gen.singularities(poses, gen.ik(poses, limits=False))["det_forward_P"]
    theirs = np.array([_plucker_det(p) for p in poses])
    assert np.isfinite(ours).all()
    flips_ours = np.flatnonzero(np.sign(ours[:-1]) != np.sign(ours[1:]))
    flips_theirs = np.flatnonzero(np.sign(theirs[:-1]) != np.sign(theirs[1:]))
    assert len(flips_ours) > 0 and flips_ours.tolist() == flips_theirs.tolist()
    # bisected on our polynomial, the independent determinant vanishes there too
    a, b = poses[flips_ours[0]].copy(), poses[flips_ours[0] + 1].copy()
    fa = gen.singularities(a, gen.ik(a, limits=False))["det_forward_P"]
    for _ in range(55):
        mid = (a + b) / 2
        fm = gen.singularities(mid, gen.ik(mid, limits=False))["det_forward_P"]
        a, b, fa = (mid, b, fm) if np.sign(fm) == np.sign(fa) else (a, mid, fa)
    assert abs(_plucker_det(a)) < 1e-9 * np.abs(theirs).max()
    # at home the six lines are independent
    home = np.array([0, 0, 210.0, 0, 0, 0])
    assert abs(_plucker_det(home)) > 1e-3
    assert gen.singularities(home, gen.ik(home))["det_forward_P"] != 0


def test_leg_boundaries_are_the_squared_leg_lengths_in_the_chart():
    """boundary_qk, the discriminant of leg k's generator ``scale (q^2 R - 4 D)`` in q, is
    ``16 scale^2 R D = 4 scale^2 R^2 q_k^2`` with ``R = 1 / cos^2(theta/2)`` in the chart x0
    = 1: times ``cos^4(theta/2) = ((1 + tr Rot) / 4)^2`` and over the independent leg length
    squared it is one positive constant per leg over random poses.  The kernels evaluate
    it from the unexpanded sphere form (``codegen.module.compact_boundaries``, about 130
    operations per leg where the expanded ``-4 A C`` took about 2,400)."""
    import independent_stewart as ind

    rng = np.random.default_rng(4)
    poses = np.column_stack([rng.uniform(-30, 30, (40, 2)), rng.uniform(190, 240, 40),
                             rng.uniform(-0.3, 0.3, (40, 3))])
    sing = gen.singularities(poses, gen.ik(poses, limits=False))
    for k in range(6):
        ratio = []
        for pose, value in zip(poses, sing[f"boundary_q{k + 1}"]):
            leg, rot = ind.legs(pose)
            ratio.append(value * ((1 + np.trace(rot)) / 4) ** 2 / np.sum(leg[k] ** 2))
        ratio = np.array(ratio)
        assert (ratio > 0).all() and np.ptp(ratio) <= 1e-12 * ratio.mean(), (k, ratio)
    assert max(gen.OPERATIONS[f"_sing_boundary_q{k}"] for k in range(1, 7)) < 300
