"""The generated 2-URRH RCM manipulator (002) against an independent vector model
(tests/independent_urrh_rcm.py: loop closures solved with scipy), mpmath at 50 digits and
finite differences; the RCM property over the 13 x 13 grid of 002 Sect. 5.2; bad input."""

import independent_urrh_rcm as ind
import mpmath
import numpy as np
import pytest
from bonered_alg.generated import urrh_rcm as m

from bonered_alg.runtime import status as st

PAR = m.PARAMETERS
BIT = dict(m.MODE_BITS)


def _poses(n, seed=0):
    """Random poses within the +-30 deg workspace of 002 Sect. 5.2 (theta1, theta2 up to
    0.5 rad), collars 40-100 mm from O, spins up to 2 rad."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-0.5, 0.5, n), rng.uniform(-0.5, 0.5, n),
                            rng.uniform(40.0, 100.0, n), rng.uniform(-2.0, 2.0, n)])


def _reachable(n, seed=0):
    p = _poses(4 * n, seed)
    q, s = m.ik_and_status(p, limits=False)
    return p[s == st.OK][:n], q[s == st.OK][:n]


def test_ik_gives_every_configuration_of_the_independent_model():
    """Each limb's two elbows (the roots of its loop closure) are the IK's modes with the
    alpha2 bit clear, at 300 random poses; where the vector model finds none, IK is NaN."""
    poses = _poses(300, seed=1)
    every = m.ik_all(poses, limits=False)
    seen = 0
    for pose, modes in zip(poses, every):
        want = ind.ik_all(pose, PAR)
        got = [modes[k] for k in range(m.MODES) if not (k >> BIT["alpha2"]) & 1]
        got = [g for g in got if np.isfinite(g).all()]
        assert len(got) == len(want), (pose, got, want)
        for w in want:
            assert min(np.abs(g - w).max() for g in got) < 1e-9, (pose, w, got)
        seen += len(want)
    assert seen > 200


def test_mode_zero_is_the_physical_elbow_and_alpha2_flip_is_the_half_turn():
    """Mode 0: the crank near its fixed axis, the coupler at a small angle to the shaft
    (002 Sect. 4.4); the alpha2 bit: the U joint half a turn round with beta2 negated,
    the same links (the same B2)."""
    poses, q = _reachable(100, seed=2)
    other = m.ik(poses, mode=(1 << BIT["beta1"]) | (1 << BIT["beta2"]), limits=False)

    def coupler_angle(limb, a, b, d, u):
        c = d * u - ind.crank_point(limb, a, b, PAR)
        return np.arccos(c @ u / np.linalg.norm(c))

    for pose, qq, oo in zip(poses, q, other):
        u, d1, d2 = ind.shaft(pose, PAR)
        for limb, k, d in ((1, 0, d1), (2, 1, d2)):
            assert (coupler_angle(limb, qq[k], qq[2 + k], d, u)
                    < coupler_angle(limb, oo[k], oo[2 + k], d, u)), (pose, limb)
    every = m.ik_all(poses, limits=False)
    flipped = [k for k in range(m.MODES) if (k >> BIT["alpha2"]) & 1]
    kept = [k for k in range(m.MODES) if not (k >> BIT["alpha2"]) & 1]
    checked = 0
    for qq, modes in zip(q, every):
        if not np.isfinite(modes[flipped]).all():
            continue  # a half-turn at tan = infinity (alpha2 = 0 exactly) has no root
        checked += 1
        for k in flipped:
            assert abs(abs(modes[k, 1] - qq[1]) - np.pi) < 1e-9
        b_flip = sorted(tuple(np.round(ind.crank_point(2, modes[k, 1], modes[k, 3], PAR), 6))
                        for k in flipped)
        b_kept = sorted(tuple(np.round(ind.crank_point(2, modes[k, 1], modes[k, 3], PAR), 6))
                        for k in kept)
        assert b_flip == b_kept
    assert checked > 50


def test_fk_gives_every_assembly_mode_and_round_trips():
    """fk of the IK's joints contains the pose; every finite mode is a configuration of the
    vector model: both roots of 002 eq. (8) per limb (with u towards the collars and d1 >= 0
    in one of the two descriptions of each shaft line, theta2 and theta2 + pi)."""
    poses, q = _reachable(300, seed=3)
    fk = m.fk(q)
    assert fk.shape == (len(q), m.FK_MODES, 4)
    err = np.nanmin(np.abs(fk - poses[:, None, :]).max(axis=-1), axis=1)
    assert err.max() < 1e-9
    for qq, modes in zip(q[:60], fk[:60]):
        want = ind.fk_all(qq, PAR)
        finite = [f for f in modes if np.isfinite(f).all()]
        assert len(finite) == 2 * len(want)
        points = {tuple(np.round(np.r_[ind.shaft(f, PAR)[0] * ind.shaft(f, PAR)[1],
                                       ind.shaft(f, PAR)[0] * ind.shaft(f, PAR)[2]], 6))
                  for f in finite}
        wanted = {tuple(np.round(np.r_[ind.shaft(w, PAR)[0] * ind.shaft(w, PAR)[1],
                                       ind.shaft(w, PAR)[0] * ind.shaft(w, PAR)[2]], 6))
                  for w in want}
        assert points == wanted
    back = m.ik(poses, limits=False)
    assert np.abs(back - q).max() < 1e-9


def test_fk_newton_kernel_vanishes_on_assemblies_and_is_its_own_jacobian():
    """The Newton kernel of fk (the leg generators' residuals and their Jacobian in
    FK_UNKNOWNS, parameter coefficients computed once per call): residuals at rounding
    level at the Study coordinates of the poses the IK assembled, the Jacobian against
    central differences of the residuals, and per-configuration geometry arrays giving the
    values of the scalar geometry."""
    poses, q = _reachable(200, seed=11)
    qa = m._MODEL.algebraic(q)
    w1, w2 = np.tan(poses[:, 0] / 2), np.tan(poses[:, 1] / 2)
    d1, d2 = poses[:, 2], poses[:, 2] - PAR["p"] * poses[:, 3]  # 002 eq. (9)
    par = list(PAR.values())
    n = len(m.FK_UNKNOWNS)

    def newton(x, geometry=par):
        vals = [np.broadcast_to(v, (len(qa),)) for v in
                m._fk_newton(*x, *qa.T, *geometry)]
        return np.stack(vals[:len(vals) // (n + 1)], -1), np.stack(
            vals[len(vals) // (n + 1):], -1).reshape(len(qa), -1, n)

    x = [w1, w2, d1, d2]
    f, jac = newton(x)
    size = 1.0 + np.abs(jac).max(axis=-1) * (1.0 + np.abs(np.stack(x, -1))).max(axis=-1)[:, None]
    assert f.shape[-1] > n and (np.abs(f) <= 1e-11 * size).all()
    rng = np.random.default_rng(2)
    x = [v + rng.uniform(-0.05, 0.05, v.shape) * (1.0 + np.abs(v)) for v in x]
    f, jac = newton(x)
    for k in range(n):
        h = 1e-6 * (1.0 + np.abs(x[k]))
        up, down = list(x), list(x)
        up[k], down[k] = x[k] + h, x[k] - h
        fd = (newton(up)[0] - newton(down)[0]) / (2 * h)[:, None]
        scale = 1.0 + np.abs(jac).max(axis=-1)
        assert (np.abs(fd - jac[..., k]) <= 1e-6 * scale).all()
    arrays = [np.full(len(qa), v) for v in par]
    fa, ja = newton(x, arrays)
    assert np.allclose(fa, f, rtol=1e-14, atol=0) and np.allclose(ja, jac, rtol=1e-14, atol=0)


def test_ik_against_mpmath_at_50_digits():
    """The vector model's IK at 50 digits (mpmath.findroot on each loop closure from the
    float root) against the generated float code: 1e-12."""
    mpmath.mp.dps = 50
    poses, q = _reachable(12, seed=4)
    for pose, qq in zip(poses, q):
        t1, t2, d, g = (mpmath.mpf(float(v)) for v in pose)
        u = mpmath.matrix([-mpmath.sin(t2), mpmath.cos(t2) * mpmath.sin(t1),
                           -mpmath.cos(t2) * mpmath.cos(t1)])
        a1 = mpmath.atan(-u[1] / u[2])
        a2 = mpmath.atan(u[0] / u[2])
        assert abs(float(a1) - qq[0]) < 1e-12 and abs(float(a2) - qq[1]) < 1e-12
        for limb, a, b0, di in ((1, a1, qq[2], d), (2, a2, qq[3], d - PAR["p"] * g)):
            loa, lab, lbc = (mpmath.mpf(PAR[f"{k}{limb}"]) for k in ("loa", "lab", "lbc"))

            def closure(b, limb=limb, a=a, loa=loa, lab=lab, lbc=lbc, di=di, u=u):
                if limb == 1:  # Rx(a) (-loa x + lab Ry(b) x)
                    bx, by, bz = -loa + lab * mpmath.cos(b), 0, -lab * mpmath.sin(b)
                    pt = (bx, by * mpmath.cos(a) - bz * mpmath.sin(a),
                          by * mpmath.sin(a) + bz * mpmath.cos(a))
                else:  # Ry(a) (-loa y + lab Rx(b) y)
                    bx, by, bz = 0, -loa + lab * mpmath.cos(b), lab * mpmath.sin(b)
                    pt = (bx * mpmath.cos(a) + bz * mpmath.sin(a), by,
                          -bx * mpmath.sin(a) + bz * mpmath.cos(a))
                return sum((pt[k] - di * u[k]) ** 2 for k in range(3)) - lbc**2

            root = mpmath.findroot(closure, mpmath.mpf(float(b0)))
            assert abs(float(root) - qq[1 + limb]) < 1e-12


def test_jacobian_against_finite_differences_of_the_independent_ik():
    """d(alpha1, alpha2, beta1, beta2)/d(theta1, theta2, d, gamma) against central
    differences of the vector model's IK (the elbow of mode 0)."""
    poses, q = _reachable(40, seed=5)
    J = m.jacobian(poses, limits=False)

    def ik0(p, near):
        sols = ind.ik_all(p, PAR)
        return min(sols, key=lambda s: np.abs(s - near).max())

    h = np.array([1e-6, 1e-6, 1e-4, 1e-5])
    for pose, qq, jj in zip(poses, q, J):
        cols = [(ik0(pose + hk * e, qq) - ik0(pose - hk * e, qq)) / (2 * hk)
                for hk, e in zip(h, np.eye(4))]
        assert np.abs(np.column_stack(cols) - jj).max() < 1e-5 * (1 + np.abs(jj).max())


def test_twist_jacobian_against_finite_differences_of_the_end_effector():
    """002 eq. (17): the spatial twist (omega; v) = (g' g^-1)^vee per unit joint rate,
    against central differences of the end effector's transform through fk."""
    poses, q = _reachable(20, seed=6)
    J = m.twist_jacobian(poses, limits=False)

    def transform(pose):
        t1, t2, d, g = pose
        r = ind.rx(t1) @ ind.ry(t2) @ ind.rz(-g)
        out = np.eye(4)
        out[:3, :3], out[:3, 3] = r, d * (ind.rx(t1) @ ind.ry(t2) @ -ind.Z)
        return out

    h = 1e-6
    for pose, qq, jj in zip(poses, q, J):
        g0 = transform(pose)
        for k in range(4):
            dq = np.eye(4)[k] * h
            plus, minus = (min(m.fk(qq + s * dq), key=lambda f: np.nanmax(np.abs(f - pose)))
                           for s in (1, -1))
            gd = (transform(plus) - transform(minus)) / (2 * h)
            xi = gd @ np.linalg.inv(g0)
            twist = np.r_[xi[2, 1], xi[0, 2], xi[1, 0], xi[:3, 3]]
            assert np.abs(twist - jj[:, k]).max() < 1e-5 * (1 + np.abs(jj).max())


def test_shaft_passes_through_the_rcm_point_over_the_workspace_grid():
    """002 Sect. 2.4, 5.2: over the 13 x 13 grid of the U joints' first angles, the collars
    C1, C2 of the chains (link_poses: the bodies after the passive joints C_i, from the IK
    and the recovered passive joints) lie on a line through O: distance <= 1e-9 mm."""
    from bonered_alg.studies.workspace_002 import ANGLES_DEG, collar_ranges, direction_pose

    names = list(m.LINKS)
    c1, c2 = names.index("1.4"), names.index("2.5")
    worst, count = 0.0, 0
    for a1 in np.radians(ANGLES_DEG):
        for a2 in np.radians(ANGLES_DEG):
            t1, t2 = direction_pose(a1, a2)
            r = collar_ranges(m, a1, a2)  # the middle of each collar's reach
            d1, d2 = (0.5 * (r[k][0] + r[k][1]) + (5.0 if k == "d1" else 0.0)
                      for k in ("d1", "d2"))
            pose = np.array([t1, t2, d1, (d1 - d2) / PAR["p"]])
            assert np.isfinite(m.ik(pose, limits=False)).all(), pose
            links = m.link_poses(pose)
            from bonered_alg.algebra import study_numeric as sn

            p1 = sn.transform_from_study(links[c1])[:3, 3]
            p2 = sn.transform_from_study(links[c2])[:3, 3]
            worst = max(worst, ind.distance_to_line(np.zeros(3), p1, p2))
            count += 1
    assert count == 169 and worst <= 1e-9


def test_slider_functions_are_the_slider_crank_triangle():
    """002 eq. (13) and (7): q^2 + 2 l_ae cos(beta) q + l_ae^2 - l_ef^2 = 0 (the triangle
    A E F, angle pi - beta at A), and the two functions inverse to each other."""
    beta = np.radians(np.linspace(100.0, 170.0, 15))
    q = m.slider_inputs(np.column_stack([beta, beta]))
    for k, (lae, lef) in enumerate(((PAR["lae1"], PAR["lef1"]), (PAR["lae2"], PAR["lef2"]))):
        res = q[:, k] ** 2 + 2 * lae * np.cos(beta) * q[:, k] + lae**2 - lef**2
        assert np.abs(res).max() < 1e-8 * lae**2 and (q[:, k] > 0).all()
    assert np.abs(m.crank_angles(q) - beta[:, None]).max() < 1e-12


def test_shaft_and_its_inverse():
    poses = _poses(50, seed=7)
    s = m.shaft(poses)
    assert np.allclose(np.linalg.norm(s[:, :3], axis=1), 1.0)
    assert np.allclose(m.pose_from_shaft(s), poses)
    assert np.allclose(m.pose_from_shaft(np.c_[3.0 * s[:, :3], s[:, 3:]]), poses)


def test_bad_input_and_unreachable_directions():
    home = np.asarray(m.HOME)
    with pytest.raises(ValueError, match=r"urrh_rcm.ik: pose must have shape \(\.\.\., 4\)"):
        m.ik(home[:3])
    with pytest.raises(TypeError, match=r"urrh_rcm.ik: pose must be real numbers"):
        m.ik(np.array(["0"] * 4))
    with pytest.raises(ValueError, match=r"urrh_rcm.fk: joints must have shape \(\.\.\., 4\)"):
        m.fk(np.zeros(3))
    with pytest.raises(ValueError, match=r"geometric parameter 'p' must be > 0"):
        m.ik(home, p=0.0)
    bad = np.array([[np.nan, 0, 80, 0], [0, 0, np.inf, 0]])
    assert np.isnan(m.ik(bad)).all()
    assert (m.ik_status(bad) == st.INVALID_INPUT).all()
    # the shaft tilted away from limb 2's base by 0.5 rad: collar 2 out of its reach
    far = np.array([0.5, 0.0, 80.0, 0.0])
    assert np.isnan(m.ik(far)).all() and m.ik_status(far) == st.NO_REAL_SOLUTION
    text = m.ik_explain(far)
    assert text.startswith("beta2: no real root") and "out of the reach" in text


def test_angle_joints_convert_at_the_edges():
    """JOINTS are radians; the algebra's tan-half-angles t are internal (ALGEBRA_JOINTS):
    input_jacobian is dG/dq = dG/dt dt/dq, so its determinant is det_Ji (in t, from the
    ideal) times the product of dt/dq = (1 + t^2)/2."""
    assert m.JOINTS == ("alpha1", "alpha2", "beta1", "beta2")
    assert m.ALGEBRA_JOINTS == ("a1", "a2", "b1", "b2") and m.JOINT_ANGLES == (0, 1, 2, 3)
    poses, q = _reachable(20, seed=8)
    det_t = m.singularities(poses, q)["det_Ji_shaft"]
    det_q = np.linalg.det(m.input_jacobian(poses, q))
    scale = np.prod((1 + np.tan(q / 2) ** 2) / 2, axis=1)
    # (the sign differs where a generator was negated to orient mode 0)
    assert np.allclose(np.abs(det_q), np.abs(det_t) * scale, rtol=1e-9)
    assert np.abs(m.ik(poses, limits=False) - q).max() < 1e-12
    assert np.all(np.abs(q) < np.pi)


def _collar_on(limb, theta, coupler_angle, par):
    """A configuration of limb ``limb`` built from plain geometry: the shaft of pose angles
    ``theta``, the coupler B C at ``coupler_angle`` from the shaft (in the limb plane),
    collar position d and crank angle beta solving |B - A| = l_ab; returns (pose, q_limb)."""
    u, _, _ = ind.shaft((*theta, 0.0, 0.0), par)
    a1, a2 = ind.alphas(u)
    alpha = a1 if limb == 1 else a2
    n = (ind.rx(a1) @ ind.Y) if limb == 1 else (ind.ry(a2) @ ind.X)
    e = np.cross(n, u)  # in the limb plane, normal to the shaft
    a_pt = -par[f"loa{limb}"] * (ind.X if limb == 1 else ind.Y)
    lbc, lab = par[f"lbc{limb}"], par[f"lab{limb}"]
    best = None
    for side in (1, -1):
        off = lbc * (np.cos(coupler_angle) * -u + side * np.sin(coupler_angle) * e)
        # |d u + off - A| = lab: d^2 + 2 d u.(off - A) + |off - A|^2 - lab^2 = 0
        w = off - a_pt
        disc = (u @ w) ** 2 - (w @ w - lab**2)
        if disc < 0:
            continue
        for d in (-(u @ w) + np.sqrt(disc), -(u @ w) - np.sqrt(disc)):
            if d > 0 and (best is None or d > best[0]):
                best = (d, d * u + off, alpha)
    d, b_pt, alpha = best
    return d, b_pt, alpha


def test_singularities_at_configurations_built_independently():
    """002 Sect. 4.4: the coupler of a limb perpendicular to the shaft (l_cd = 0, Fig. 8c)
    zeroes det_Jo; crank and coupler aligned (the edge of the reach) zeroes det_Ji and the
    limb's boundary polynomial; the shaft along u2 zeroes boundary_a2.  Each relative to its
    value at a regular configuration."""
    theta = (0.15, -0.1)
    regular = _reachable(1, seed=9)
    ref = {k: abs(float(v[0])) for k, v in m.singularities(*regular).items()}
    for limb in (1, 2):
        d, b_pt, alpha = _collar_on(limb, theta, np.pi / 2, PAR)  # coupler normal to u
        pose = None  # the other collar anywhere it is reachable
        for d_other in np.linspace(40.0, 110.0, 141):
            d1, d2 = (d, d_other) if limb == 1 else (d_other, d)
            cand = np.array([*theta, d1, (d1 - d2) / PAR["p"]])
            q = m.ik_all(cand, limits=False)
            ok = [k for k in range(m.MODES) if np.isfinite(q[k]).all()
                  and np.allclose(ind.crank_point(limb, q[k][limb - 1], q[k][limb + 1], PAR),
                                  b_pt, atol=1e-6)]
            if ok:
                pose, qq = cand, q[ok[0]]
                break
        assert pose is not None, limb
        s = m.singularities(pose, qq)
        assert abs(s["det_Jo_shaft"]) < 1e-9 * ref["det_Jo_shaft"], (limb, s)
        assert abs(s["det_Ji_shaft"]) > 1e-6 * ref["det_Ji_shaft"]
    # limb 1 stretched: |C1 - A1| = l_ab1 + l_bc1 on the shaft of theta
    u, _, _ = ind.shaft((*theta, 0.0, 0.0), PAR)
    a_pt = -PAR["loa1"] * ind.X
    reach = PAR["lab1"] + PAR["lbc1"]
    d = -(u @ -a_pt) + np.sqrt((u @ -a_pt) ** 2 - (a_pt @ a_pt - reach**2))
    sing = m.singularities(np.array([*theta, d, 0.0]), np.zeros(4))
    assert abs(sing["boundary_b1"]) < 1e-9 * ref["boundary_b1"]
    # the shaft along u2 = y: theta1 = -pi/2, theta2 = 0 gives u = Rx(-pi/2) (0, 0, -1) = y
    along_y = m.singularities(np.array([-np.pi / 2, 0.0, 80.0, 0.0]), np.zeros(4))
    assert abs(along_y["boundary_a2"]) < 1e-12 * max(ref["boundary_a2"], 1.0)


def test_workspace_tool_agrees_with_the_per_collar_ranges():
    """002 Sect. 5.2 through the workspace tool (boundary search on the full membership
    test, the collar limits d_i >= 0 included) against the per-collar intervals of the
    IK's joint statuses: the range of d at gamma = 0 is D1 and D2's common part, the range
    of gamma at its middle is (d_ref - D2)/p, to the per-collar grid's 0.05 mm."""
    from bonered_alg.studies import workspace_002 as ws

    for a1, a2 in ((-30.0, 30.0), (0.0, 0.0), (25.0, -10.0)):
        r = ws.collar_ranges(m, np.radians(a1), np.radians(a2))
        t = ws.tool_ranges(m, np.radians(a1), np.radians(a2), r)
        assert t["error"] <= 0.05 + 1e-3, (a1, a2, t)
        assert t["d"][0] == 0.0  # collar limits: d_i >= 0 binds at O
    home = ws.collar_ranges(m, 0.0, 0.0)
    hs = ws.home_scan(m, home)
    assert hs["agrees"] and hs["inner"] <= hs["result"].count <= hs["outer"]
    assert hs["component"].count > 0.9 * hs["result"].count


def test_collar_limits_flag_a_collar_beyond_the_rcm_point():
    """gamma large enough puts collar 2 at d2 = d - p gamma < 0 (inside the patient): a
    passive-joint limit, named in the joint statuses."""
    pose = np.array([0.0, 0.0, 40.0, 6.0])  # d2 = 40 - 60 = -20 mm
    assert m.ik_status(pose, limits=False) == st.OK
    assert m.ik_status(pose) == m.PASSIVE_JOINT_LIMIT
    assert m.limit_values(pose, m.ik(pose, limits=False))["d2"] == pytest.approx(-20.0)
