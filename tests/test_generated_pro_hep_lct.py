"""The generated Pro-Hep-LCT planar module against the independent numeric model (layer 2)
and against mpmath evaluation of the symbolic roots (layer 3)."""

import subprocess
import sys

import numpy as np
import pytest
import sympy as sp
from conftest import ROOT
from independent_pro_hep_lct import (
    GEOMETRY,
    closure_residual_for_active,
    lower_leg1,
    lower_leg2,
    solve_leg,
    upper,
)

RNG = np.random.default_rng(7)
STARTS = [(a, p) for a in np.linspace(-3, 3, 5) for p in (-2.0, -0.7, 0.7, 2.0)]


def reachable_poses(n):
    """Poses built forward from random joints, kept where chain 2 reaches Pd too."""
    g = GEOMETRY
    out = []
    while len(out) < n:
        th1, th2 = RNG.uniform(-1.2, 1.2), RNG.uniform(-2.6, -0.2)
        pd = lower_leg1(th1, th2)
        r = np.hypot(pd[0], pd[1] + g["d"] / 2 - g["lq4d"])
        if not abs(g["l3"] - g["l4"]) + 5 < r < g["l3"] + g["l4"] - 5:
            continue
        q5 = RNG.uniform(100, 300)
        q4 = q5 + RNG.choice([-1.0, 1.0]) * RNG.uniform(20, 180)  # away from eq. (37)
        xu, yu = upper(q4, q5)
        out.append(((xu, yu, pd[0], pd[1]), (np.tan(th1 / 2), q4, q5)))
    return np.array([p for p, _ in out]), [j for _, j in out]


def test_imports_without_sympy():
    code = ("import sys; sys.modules['sympy'] = None\n"
            "from bonered_alg.generated import pro_hep_lct as m\n"
            "assert 'sympy' not in [k for k, v in sys.modules.items() if v is not None]\n"
            "print(m.MECHANISM, m.MODES)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["pro_hep_lct", "8"]


def test_contract_constants(gen):
    assert gen.POSE == ("Xu", "Yu", "Xd", "Yd")
    assert gen.JOINTS == ("t1", "w1", "q4", "q5")
    assert len(gen.DERIVATION_HASH) == 64
    # 004 Sect. 3.4: four working modes of the lower planar mechanism, two of the upper
    assert gen.MODES == 8


def test_ik_against_independent_model(gen):
    poses, truth = reachable_poses(200)
    sols = gen.ik_all(poses, **GEOMETRY)
    assert sols.shape == (200, 8, 4)
    worst = 0.0
    for pose, (t1_true, q4_true, q5_true), s in zip(poses, truth, sols):
        # the generating joint values are one of the working modes
        assert np.min(np.abs(s[:, 0] - t1_true)) < 1e-9 * max(1, abs(t1_true))
        assert np.min(np.abs(s[:, 2] - q4_true)) < 1e-9
        assert np.allclose(s[:, 3], q5_true, atol=1e-9)
        # every mode closes each loop (passive angles solved numerically, errors in mm)
        for t1, w1, q4, q5 in s[::3]:
            r1 = closure_residual_for_active(lower_leg1, pose[2:], 2 * np.arctan(t1),
                                             (-2.0, -0.5, 0.5, 2.0))
            r2 = closure_residual_for_active(lower_leg2, pose[2:], 2 * np.arctan(w1),
                                             (-2.0, -0.5, 0.5, 2.0))
            ru = np.max(np.abs(upper(q4, q5, sign=np.sign(pose[0] - GEOMETRY["lq5"]))
                               - pose[:2]))
            worst = max(worst, r1, r2, ru)
    assert worst < 1e-9


def test_numeric_mode_set_matches(gen):
    """Numerically found closures of chain 2 (many starts) = the generated w1 values."""
    poses, _ = reachable_poses(20)
    for pose in poses:
        numeric = sorted(np.tan(a / 2) for a, _ in solve_leg(lower_leg2, pose[2:], STARTS))
        generated = sorted(set(np.round(gen.ik_all(pose, **GEOMETRY)[:, 1], 9)))
        assert len(numeric) == len(generated) == 2
        assert np.allclose(numeric, generated, atol=1e-8)


def independent_ik(pose, near, seeds=None):
    """Active joints near ``near`` (t1, w1, q4, q5) from the independent model, and the
    (active, passive) angle pair of each lower leg.  With ``seeds`` (those pairs at a pose
    close by) each leg is solved from its seed alone instead of searched over 13 starts."""
    def active(forward, target, a0, seed):
        a, p = least_squares_two(forward, target, a0, seed)
        return np.tan(a / 2), (a, p)

    s1, s2 = seeds if seeds is not None else (None, None)
    t1, s1 = active(lower_leg1, pose[2:], 2 * np.arctan(near[0]), s1)
    w1, s2 = active(lower_leg2, pose[2:], 2 * np.arctan(near[1]), s2)
    q5 = pose[1]
    s = np.sign(near[3] - near[2]) if near[3] != near[2] else 1.0
    q4 = q5 - s * np.sqrt(GEOMETRY["ld4"] ** 2 - (pose[0] - GEOMETRY["lq5"]) ** 2)
    return np.array([t1, w1, q4, q5]), (s1, s2)


def least_squares_two(forward, target, a0, seed=None):
    """The (active, passive) pair closing ``forward = target`` whose active angle is nearest
    ``a0``, over 13 passive starts; from ``seed`` alone if one is given."""
    from scipy.optimize import least_squares

    best = None
    starts = [seed] if seed is not None else [[a0, p0] for p0 in np.linspace(-3, 3, 13)]
    for start in starts:
        r = least_squares(lambda v: forward(v[0], v[1]) - target, start, xtol=1e-15,
                          ftol=1e-15, gtol=1e-15)
        if np.max(np.abs(r.fun)) < 1e-10 and (best is None or abs(r.x[0] - a0) < abs(best[0] - a0)):
            best = (r.x[0], r.x[1])
    assert best is not None, "the independent model found no closure"
    return best


def test_jacobian_against_finite_differences(gen):
    poses, _ = reachable_poses(15)
    h = 1e-4
    for pose in poses:
        for mode in (0, 3, 6):
            J = gen.jacobian(pose, mode, **GEOMETRY)
            q0 = gen.ik(pose, mode, **GEOMETRY)
            if not np.all(np.isfinite(J)):
                continue
            # the branch of each lower leg at the pose itself, then each step from it
            _, seeds = independent_ik(pose, q0)
            fd = np.empty((4, 4))
            for k in range(4):
                e = np.zeros(4)
                e[k] = h
                fd[:, k] = (independent_ik(pose + e, q0, seeds)[0]
                            - independent_ik(pose - e, q0, seeds)[0]) / (2 * h)
            assert np.allclose(J, fd, rtol=1e-5, atol=1e-7), (pose, mode, J, fd)


def test_jacobian_is_implicit_derivative(gen):
    """J = -Ji^{-1} Jo: Ji J + dG/dX = 0 with the exported matrices."""
    poses, _ = reachable_poses(30)
    J = gen.jacobian(poses, 5, **GEOMETRY)
    q = gen.ik(poses, 5, **GEOMETRY)
    ji = gen.input_jacobian(poses, q, **GEOMETRY)
    jo_study = gen.output_jacobian(poses, q, **GEOMETRY)
    # dy/dX = -1/2 identity (004 eq. 13 with x = [1:0:0:0])
    assert np.allclose(ji @ J + jo_study @ (-0.5 * np.eye(4)), 0.0, atol=1e-6)


def test_against_mpmath_50_digits(gen, derivation):
    """Layer 3: the symbolic roots evaluated at 50 digits vs. the generated float code."""
    pose_map = derivation.mechanism.pose
    poses, _ = reachable_poses(10)
    par = {sp.Symbol(k, real=True): sp.Float(v, 50) for k, v in GEOMETRY.items()}
    for pose in poses:
        q = gen.ik(pose, 0, **GEOMETRY)
        vals = dict(par)
        for sym, val in zip(pose_map.coordinates, pose):
            vals[sym] = sp.Float(val, 50)
        vals.update({k: v.subs(vals) for k, v in pose_map.to_study.items()})
        for step in derivation.steps:
            root = step.roots()[0]  # mode 0: '+sqrt' everywhere
            exact = sp.N(root.subs(vals), 50)
            vals[step.joint] = exact
            got = q[gen.JOINTS.index(str(step.joint))]
            assert abs(float(exact) - got) <= 1e-12 * max(1.0, abs(float(exact)))


def test_unreachable_pose_gives_nan_and_reason(gen):
    far = np.array([[400.0, 200.0, 5000.0, 0.0], [GEOMETRY["lq5"] + 10 * GEOMETRY["ld4"],
                                                  200.0, 200.0, 100.0]])
    q = gen.ik(far, **GEOMETRY)
    status = gen.ik_status(far, **GEOMETRY)
    assert np.isnan(q[0, 0]) and status[0] == gen.NO_REAL_SOLUTION
    assert np.isnan(q[1, 2]) and status[1] == gen.NO_REAL_SOLUTION
    assert "no real solution" in gen.STATUS[int(status[0])]
    assert np.all(np.isnan(gen.jacobian(far, **GEOMETRY)))


def test_input_singularity_is_flagged(gen):
    """On the upper boundary (Xu = lq5 + ld4, q4 = q5: 004 eq. 37) the Jacobian is NaN."""
    pose = np.array([GEOMETRY["lq5"] + GEOMETRY["ld4"], 200.0, 150.0, 150.0])
    status = gen.jacobian_status(pose, **GEOMETRY)
    q = gen.ik(pose, **GEOMETRY)
    assert np.isclose(q[2], q[3])
    assert status == gen.INPUT_SINGULAR
    sing = gen.singularities(pose, q, **GEOMETRY)
    assert abs(sing["det_Ji_Pu"]) < 1e-9


def test_vectorized_over_leading_axes(gen):
    poses, _ = reachable_poses(12)
    grid = poses.reshape(3, 4, 4)
    assert gen.ik(grid, **GEOMETRY).shape == (3, 4, 4)
    assert gen.jacobian(grid, **GEOMETRY).shape == (3, 4, 4, 4)
    assert np.allclose(gen.ik(grid, **GEOMETRY).reshape(12, 4), gen.ik(poses, **GEOMETRY),
                       equal_nan=True)


def test_bad_input_errors(gen):
    with pytest.raises(ValueError, match=r"pro_hep_lct.ik: geometric parameter 'Dz' is not "
                                         r"finite"):
        gen.ik(np.zeros(4), Dz=np.inf)
    with pytest.raises(TypeError, match="unknown geometric parameter"):
        gen.ik(np.zeros(4), bogus=1.0, **GEOMETRY)
    with pytest.raises(ValueError, match=r"pose must have shape \(\.\.\., 4\)"):
        gen.ik(np.zeros(3), **GEOMETRY)
    with pytest.raises(ValueError, match=r"mode must be an integer in \[0, 8\)"):
        gen.ik(np.zeros(4), mode=8, **GEOMETRY)
    assert gen.ik_status(np.array([np.nan, 0, 0, 0]), **GEOMETRY) == gen.INVALID_INPUT


def test_fk_recovers_every_ik_mode(gen):
    """X is among fk(ik(X, m)) for every working mode m (all assembly modes returned)."""
    poses, _ = reachable_poses(60)
    q_all = gen.ik_all(poses, **GEOMETRY)  # (60, 8, 4)
    sols = gen.fk(q_all, **GEOMETRY)  # (60, 8, FK_MODES, 4)
    assert sols.shape == (60, 8, gen.FK_MODES, 4)
    dist = np.max(np.abs(sols - poses[:, None, None, :]), axis=-1)  # (60, 8, FK_MODES)
    err = np.nanmin(dist, axis=-1)
    # the separation from the nearest other assembly mode: where two modes nearly merge (a
    # forward singularity) the pose is determined only to eps / separation, and the status
    # OK promises the closure to VERIFY_RTOL (1 + |x|) (runtime/fk.py::verify), not 1e-9 mm
    best = np.nanargmin(dist, axis=-1)
    match = np.take_along_axis(sols, best[..., None, None], axis=-2)
    sep = np.max(np.abs(sols - match), axis=-1)
    np.put_along_axis(sep, best[..., None], np.inf, axis=-1)
    apart = np.nanmin(sep, axis=-1) > 1.0
    assert apart.mean() > 0.9
    assert np.max(err[apart]) < 1e-9
    assert np.all(err <= 1e-9 * (1 + np.max(np.abs(poses), axis=-1))[:, None])


def test_fk_against_independent_circle_intersection(gen):
    """Lower mechanism: Pd from t1, w1 solved numerically from the joint geometry."""
    from scipy.optimize import least_squares

    g = GEOMETRY
    for th1, ph1 in [(0.3, 1.9), (-0.4, 2.3), (0.8, 1.2)]:
        e1 = g["l1"] * np.array([np.cos(th1), np.sin(th1)])
        e2 = np.array([0, g["lq4d"]]) + g["l3"] * np.array([np.cos(ph1), np.sin(ph1)])

        def residual(p, e1=e1, e2=e2):
            return [np.hypot(*(p - np.array([0, g["d"] / 2]) - e1)) - g["l2"],
                    np.hypot(*(p + np.array([0, g["d"] / 2]) - e2)) - g["l4"]]

        numeric = []
        for start in ([300, 0], [-300, 0], [0, 300], [0, -300], [200, 200], [-200, -200]):
            r = least_squares(residual, start, xtol=1e-15, ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(r.fun)) < 1e-9 and not any(np.allclose(r.x, n, atol=1e-6)
                                                        for n in numeric):
                numeric.append(r.x)
        q = np.array([np.tan(th1 / 2), np.tan(ph1 / 2), 100.0, 200.0])
        lower = gen.fk(q, **GEOMETRY)[:, 2:]
        found = {tuple(np.round(p, 6)) for p in lower if np.all(np.isfinite(p))}
        assert len(numeric) == len(found)
        for n in numeric:
            assert np.min(np.max(np.abs(lower - n), axis=-1)) < 1e-8


def test_fk_without_real_assembly(gen):
    # the two elbows farther apart than l2 + l4 + d: no real Pd; a stroke q5 - q4 > ld4: no Pu
    q = np.array([np.tan(-1.4 / 2), np.tan(1.5 / 2), 0.0, GEOMETRY["ld4"] + 50.0])
    sols = gen.fk(q, **GEOMETRY)
    status = gen.fk_status(q, **GEOMETRY)
    assert np.all(np.isnan(sols)) and np.all(status == gen.NO_REAL_SOLUTION)
