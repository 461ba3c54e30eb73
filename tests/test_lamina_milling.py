"""The generated lamina-milling robot (003) against an independent trigonometric model
(tests/independent_lamina_milling.py), mpmath at 50 digits and finite differences; its
singular configurations, pure translation, the Table 2 path and bad input."""

import independent_lamina_milling as ind
import mpmath
import numpy as np
import pytest
from bonered_alg.generated import lamina_milling as m

from bonered_alg.runtime import status as st
from bonered_alg.studies import workspace_003

PAR = m.PARAMETERS


def _poses(n, seed=0):
    """Random poses around home (reachable and not)."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-60, 60, n), rng.uniform(40, 190, n),
                            rng.uniform(-40, 160, n)])


def _reachable(n, seed=0):
    p = _poses(4 * n, seed)
    q, s = m.ik_and_status(p, limits=False)
    return p[s == st.OK][:n], q[s == st.OK][:n]


def _same_set(got, want, tol):
    got = [g for g in got if np.isfinite(g).all()]
    assert len(got) == len(want), (got, want)
    for w in want:
        assert min(np.abs(g - w).max() for g in got) < tol, (w, got)


def test_ik_gives_every_configuration_of_the_independent_model():
    """The 8 IK modes are the independent model's 2 x 2 x 2 roots (L's square root, each
    bottom chain's two elbows) at 300 random poses; NaN where it has none."""
    poses = _poses(300, seed=1)
    every = m.ik_all(poses, limits=False)
    seen = 0
    for pose, modes in zip(poses, every):
        want = ind.ik_all(pose, PAR)
        got = [np.array([g[0], ind.wrap(g[1]), ind.wrap(g[2])]) for g in modes]
        _same_set(got, want, 1e-9)
        seen += len(want)
    assert seen > 800


def test_mode_zero_is_the_working_branch():
    """Mode 0: the parallelogram hangs below E (z < dD + L) and the rhombus O A F B opens
    towards F (theta1 below F's direction, theta2 above), as at home (Table 2's middle)."""
    poses, q = _reachable(200, seed=2)
    for pose, qq in zip(poses, q):
        want = ind.ik_working(pose, PAR)
        assert np.abs(np.array([qq[0], ind.wrap(qq[1]), ind.wrap(qq[2])]) - want).max() < 1e-9
    home = m.ik(np.array(m.HOME))
    assert np.allclose(home, [5.0, np.radians(38.75), np.radians(141.25)], atol=1e-4)


def test_fk_gives_every_assembly_mode_and_round_trips():
    """At joints from the IK of 300 random poses, the FK's real modes are the independent
    circle-sphere intersections, the pose is among them and each satisfies eq. (7)-(8)."""
    poses, q = _reachable(300, seed=3)
    every = m.fk(q)
    for pose, qq, modes in zip(poses, q, every):
        want = ind.fk_all(qq, PAR)
        _same_set(list(modes), want, 1e-8)
        assert min(np.abs(g - pose).max() for g in modes if np.isfinite(g).all()) < 1e-9
        for g in modes:
            if np.isfinite(g).all():
                assert np.abs(ind.residuals(g, qq, PAR)).max() < 1e-8


def test_second_circle_intersection_is_the_folded_point_o():
    """With Table 1's equal lengths O lies on both circles of F: the FK's second pair of
    modes is F = O, where the upper chain cannot reach (|dy2 + dy1 + lDE| = 100 > lEC = 90),
    so those modes are NaN with 'no real solution' and never a pose."""
    q = m.ik(np.array(m.HOME))
    poses, status = m.fk(q), m.fk_status(q)
    real = np.isfinite(poses).all(-1)
    assert real.sum() == 2 and (status[~real] == st.NO_REAL_SOLUTION).all()
    assert (np.abs(poses[real, 1] - m.HOME[1]) < 1e-9).all()


def test_ik_against_mpmath_at_50_digits():
    """Mode 0 against the working branch in 50-digit arithmetic (the geometric formulas of
    the independent model, not the derivation)."""
    mpmath.mp.dps = 50
    poses, q = _reachable(20, seed=4)
    P = {k: mpmath.mpf(v) for k, v in PAR.items()}
    for pose, qq in zip(poses, q):
        x, y, z = (mpmath.mpf(float(v)) for v in pose)
        off = P["dy2"] + P["dy1"] + P["lDE"]
        L = z - P["dD"] + mpmath.sqrt(P["lEC"] ** 2 - x**2 - (y - off) ** 2)
        rho, phi = mpmath.sqrt(x**2 + y**2), mpmath.atan2(y, x)
        a1 = mpmath.acos((rho**2 + P["lOA"] ** 2 - P["lAF"] ** 2) / (2 * P["lOA"] * rho))
        a2 = mpmath.acos((rho**2 + P["lOB"] ** 2 - P["lBM"] ** 2) / (2 * P["lOB"] * rho))
        want = [L, phi - a1, phi + a2]
        for got, w in zip((qq[0], ind.wrap(qq[1]), ind.wrap(qq[2])), want):
            assert abs(got - float(w)) <= 1e-12 * max(1.0, abs(float(w)))


def test_jacobian_against_finite_differences_of_the_independent_ik():
    poses, _ = _reachable(50, seed=5)
    jac = m.jacobian(poses, limits=False)
    h = 1e-5
    for pose, J in zip(poses, jac):
        fd = np.column_stack([(ind.ik_working(pose + h * e, PAR)
                               - ind.ik_working(pose - h * e, PAR)) / (2 * h)
                              for e in np.eye(3)])
        assert np.abs(J - fd).max() < 1e-6 * max(1.0, np.abs(fd).max())


def test_platform_only_translates():
    """twist_jacobian: no angular rows at any pose; the last body of every leg (from the
    passive joints) is the platform at H with no rotation."""
    poses, _ = _reachable(50, seed=6)
    tj = m.twist_jacobian(poses, limits=False)
    assert np.abs(tj[:, :3, :]).max() < 1e-12
    links = m.link_poses(poses)
    names = list(m.LINKS)
    # the upper chain's last body has its frame at C = H - (0, dy2, 0) (the offset CH
    # follows J14); the bottom chains' at H (after the cylinders' slides)
    for leg_end, shift in (("U.4", PAR["dy2"]), ("1.3", 0.0), ("2.3", 0.0)):
        pts = links[:, names.index(leg_end)]
        pts = pts * np.sign(pts[:, :1])
        assert np.abs(pts[:, 1:4]).max() < 1e-12  # no rotation
        want = poses - np.array([0.0, shift, 0.0])
        assert np.abs(pts[:, 5:] * -2 - want).max() < 1e-9  # its translation (x0 = 1)


def test_singular_configurations_are_reported():
    """EC horizontal (boundary_L, the two L roots merge): ON_BOUNDARY; F = O (both bottom
    chains folded, theta undetermined): not OK; A = B (theta1 = theta2): the FK's circles
    coincide and no mode is returned as a valid pose."""
    off = PAR["dy2"] + PAR["dy1"] + PAR["lDE"]
    edge = np.array([60.0, off + np.sqrt(PAR["lEC"] ** 2 - 60.0**2), 60.0])  # |F| < 180
    q, status = m.ik_and_status(edge, limits=False)
    assert status == st.ON_BOUNDARY
    _, status = m.ik_and_status(np.array([0.0, 0.0, 60.0]), limits=False)
    assert status != st.OK
    fs = m.fk_status(np.array([5.0, 1.0, 1.0]))
    assert (fs != st.OK).all()


def test_table2_path_against_the_rhombus():
    """The study's Table 2 path: theta1 + theta2 = 180 deg keeps F on x = 0 with y = 180
    sin(theta1) (the rhombus O A F B), and z from eq. (7) with C below E."""
    s, q, h = workspace_003.table2_path(m, 41)
    y = (PAR["lOA"] + PAR["lAF"]) * np.sin(q[:, 1])
    off = PAR["dy2"] + PAR["dy1"] + PAR["lDE"]
    z = PAR["dD"] + q[:, 0] - np.sqrt(PAR["lEC"] ** 2 - (y - off) ** 2)
    assert np.abs(h[:, 0]).max() < 1e-9
    assert np.abs(h[:, 1] - y).max() < 1e-9 and np.abs(h[:, 2] - z).max() < 1e-9


def test_bad_input():
    with pytest.raises(ValueError, match="lEC"):
        m.ik(np.array(m.HOME), lEC=-1.0)
    with pytest.raises(ValueError):
        m.ik(np.zeros(4))
    q, status = m.ik_and_status(np.array([0.0, 112.0, np.nan]))
    assert status == st.INVALID_INPUT and np.isnan(q).all()
