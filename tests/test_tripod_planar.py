"""tripod_planar (001): generated module vs. the independent numeric model (layer 2), the
symbolic derivation at 50 digits (layer 3) and the paper's printed equations (layer 1)."""

import importlib

import numpy as np
import pytest
from conftest import symbolic_of, verdicts_of
from independent_tripod_planar import jacobian_fd, joints, platform_b
from mpmath_reference import assert_ik_matches_mpmath
from scipy.spatial.transform import Rotation

RNG = np.random.default_rng(21)
S3 = np.sqrt(3.0)


@pytest.fixture(scope="module")
def m():
    return importlib.import_module("bonered_alg.generated.tripod_planar")


@pytest.fixture(scope="module")
def d():
    return symbolic_of("tripod_planar")


def poses(n):
    return np.column_stack([RNG.uniform(-50, 50, n), RNG.uniform(-50, 50, n),
                            RNG.uniform(170, 290, n), RNG.uniform(-0.3, 0.3, n),
                            RNG.uniform(-0.3, 0.3, n), RNG.uniform(-0.9, 0.9, n)])


def test_ik_against_independent_model(m):
    p = poses(300)
    q = m.ik(p, limits=False)
    worst = 0.0
    for pose, qq in zip(p, q):
        ref, residual = joints(pose)
        assert residual < 1e-9
        worst = max(worst, float(np.max(np.abs(qq - ref))))
    assert worst < 1e-9


def test_ik_with_a_planar_height(m):
    """d != 0 (eq. 7): the generated functions take it as a keyword."""
    for pose in poses(20):
        ref, _ = joints(pose, d=25.0)
        assert np.max(np.abs(m.ik(pose, limits=False, d=25.0) - ref)) < 1e-9


def test_jacobian_against_finite_differences(m):
    for pose in poses(12):
        J = m.jacobian(pose, limits=False)
        assert np.allclose(J, jacobian_fd(pose), rtol=1e-6, atol=1e-5)


def test_against_mpmath_50_digits(m, d):
    assert_ik_matches_mpmath(m, d, poses(4))


def test_zero_torsion_of_platform_b(m):
    """001 eq. (10) read as the derivation reads it: B's rotation quaternion has no k
    component, checked on the independent model's numerically solved platform."""
    for pose in poses(20):
        rot_b, *_ = platform_b(pose)
        quat = Rotation.from_matrix(rot_b).as_quat()  # (x, y, z, w)
        assert abs(quat[2]) < 1e-10
        # the generated split agrees with the numeric solve
        pc = m.paper_coordinates(pose)
        ref = Rotation.from_matrix(rot_b).as_euler("ZYX")  # phi, beta_p, alpha_p
        assert np.allclose(pc[[3, 1, 0]], ref, atol=1e-10)


def test_paper_coordinates_round_trip(m):
    p = poses(50)
    pc = m.paper_coordinates(p)
    back = m.pose_from_paper_coordinates(np.column_stack([p[:, :3], pc[:, :3]]))
    assert np.max(np.abs(back - p)) < 1e-12


def test_home_pose(m):
    """At x = y = 0, alpha = beta = gamma = 0: legs = z, q4 = q5 = q6 = 2 rb / sqrt(3)
    (001 eq. 13 and 21 at the home pose; ra = rb = 200 mm, d = 0)."""
    q = m.ik(np.array([0.0, 0.0, 210.0, 0.0, 0.0, 0.0]))
    assert np.allclose(q, [210.0] * 3 + [400.0 / S3] * 3, atol=1e-12)


def test_planar_input_singularity_as_explicit_poses(m):
    """001 eq. (48)-(49): gamma_p = 2 pi/3 and -pi/3 make det J_C vanish: the pivots of
    q4..q6 are 0 (the sliders are undetermined or run to infinity); the status says so and
    ik returns NaN."""
    for gamma_p in (-np.pi / 3, 2 * np.pi / 3):
        for alpha_p, beta_p in ((0.1, -0.05), (0.0, 0.0)):
            pose = m.pose_from_paper_coordinates(np.array([0.0, 0.0, 230.0, alpha_p, beta_p,
                                                           gamma_p]))
            assert m.ik_status(pose, limits=False) == m.INPUT_SINGULAR
            assert np.all(np.isnan(m.ik(pose, limits=False)[3:]))
    near = m.pose_from_paper_coordinates(np.array([0.0, 0.0, 230.0, 0.1, -0.05,
                                                   -np.pi / 3 + 1e-3]))
    assert m.ik_status(near, limits=False) == m.OK


def test_printed_eq_53_is_not_singular(m):
    """001 eq. (53) claims a forward singularity at gamma = pi/3.  There the printed J_D
    (eq. 37-46, with eq. 21-23) is regular, and the Jacobian of the generated IK agrees with
    finite differences of the independent model."""
    x2, y2, g, rb = 12.0, -7.0, np.pi / 3, 200.0
    s, c = np.sin(g), np.cos(g)
    den = s + S3 * c
    q4 = (rb + (S3 * rb - 2 * x2) * s + (rb + 2 * y2) * c) / den
    q5 = (rb + (S3 * rb + x2 - S3 * y2) * s + (rb - S3 * x2 - y2) * c) / den
    q6 = (rb + (S3 * rb + x2 + S3 * y2) * s + (rb + S3 * x2 - y2) * c) / den
    jd = np.array([
        [-2 * s, 2 * c, (S3 * rb - 2 * x2) * c - (rb + 2 * y2) * s - q4 * (c - S3 * s)],
        [s - S3 * c, -c - S3 * s, (S3 * rb + x2 - S3 * y2) * c - (rb - S3 * x2 - y2) * s
         - q5 * (c - S3 * s)],
        [s + S3 * c, -c + S3 * s, (S3 * rb + x2 + S3 * y2) * c - (rb + S3 * x2 - y2) * s
         - q6 * (c - S3 * s)]])
    assert abs(np.linalg.det(jd)) > 100.0  # 2 sqrt3 * 3 rb (2 - 1/2 + 3/2) / sqrt3 = 3600
    assert abs(np.linalg.det(jd) - 2 * S3 * 3 * rb * (2 - c + S3 * s) / den) < 1e-9
    pose = m.pose_from_paper_coordinates(np.array([0.0, 0.0, 230.0, 0.0, 0.0, g]))
    assert m.jacobian_status(pose, limits=False) == m.OK
    assert np.allclose(m.jacobian(pose, limits=False), jacobian_fd(pose), atol=1e-5)


def test_limits(m):
    """001 Sect. 3: strokes 160-320 / 120-325 mm, spherical joints +-20 deg."""
    home = np.array([0.0, 0.0, 210.0, 0.0, 0.0, 0.0])
    assert m.ik_status(home) == m.OK
    high = home + np.array([0, 0, 120.0, 0, 0, 0])  # legs 330 mm > 320
    assert m.ik_status(high) == m.STROKE_LIMIT and np.all(np.isnan(m.ik(high)))
    tilt = np.array([0.0, 0.0, 240.0, 0.38, 0.0, 0.0])
    q = m.ik(tilt, limits=False)
    assert np.all((q[:3] >= 160) & (q[:3] <= 320)) and np.all((q[3:] >= 120) & (q[3:] <= 325))
    vals = m.limit_values(tilt, q)
    # independent spherical angle: platform normal vs leg, from the numeric model
    rot_b, t_b, *_ = platform_b(tilt)
    worst = 0.0
    for k, ang in enumerate((-30, 90, 210)):
        a_k = 200.0 * np.array([np.cos(np.radians(ang)), np.sin(np.radians(ang)), 0.0])
        leg = t_b + rot_b @ a_k - a_k
        ref = np.arccos(rot_b[:, 2] @ leg / np.linalg.norm(leg))
        assert abs(ref - vals[f"phi_s{k + 1}"]) < 1e-12
        worst = max(worst, ref)
    assert np.degrees(worst) > 20 and m.ik_status(tilt) == m.PASSIVE_JOINT_LIMIT


def test_paper_verdicts():
    got = verdicts_of("tripod_planar")
    for ref in ("001 eq. (9)", "001 eq. (10)", "001 eq. (11)", "001 eq. (12)", "001 eq. (21)",
                "001 eq. (22)", "001 eq. (23)", "001 eq. (48)-(49)", "001 eq. (50)"):
        assert got[ref] == "confirmed-symbolic", ref
    for ref in ("001 eq. (13), q1", "001 eq. (13), q2", "001 eq. (13), q3", "001 eq. (21), q4",
                "001 eq. (22), q5", "001 eq. (23), q6", "001 eq. (27)", "001 eq. (29)",
                "001 eq. (34)-(46)"):
        assert got[ref] == "confirmed-numeric", ref
    for ref in ("001 eq. (17)", "001 eq. (28)", "001 eq. (33)", "001 eq. (30)-(33)",
                "001 eq. (52)", "001 eq. (53)"):
        assert got[ref] == "erratum", ref


def test_imports_without_sympy():
    import subprocess
    import sys

    code = ("import sys; sys.modules['sympy'] = None\n"
            "from bonered_alg.generated import tripod_planar as m\n"
            "import numpy as np\n"
            "print(m.ik(np.array([0.0, 0.0, 210.0, 0.0, 0.0, 0.0])).round(6).tolist())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


def test_eq_51_is_the_sum_of_the_third_column_not_det_jd():
    """001 eq. (51): its right side is J_D13 + J_D23 + J_D33 (eq. 40, 43, 46), which is
    det J_D / (2 sqrt3) by eq. (50), so the printed left side det J_D is off by 2 sqrt3."""
    rng = np.random.default_rng(8)
    rb = 200.0
    for _ in range(5):
        x2, y2, g = rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-0.9, 0.9)
        q = rng.uniform(150, 300, 3)
        s, c = np.sin(g), np.cos(g)
        col3 = [(S3 * rb - 2 * x2) * c - (rb + 2 * y2) * s - q[0] * (c - S3 * s),
                (S3 * rb + x2 - S3 * y2) * c - (rb - S3 * x2 - y2) * s - q[1] * (c - S3 * s),
                (S3 * rb + x2 + S3 * y2) * c - (rb + S3 * x2 - y2) * s - q[2] * (c - S3 * s)]
        jd = np.array([[-2 * s, 2 * c, col3[0]], [s - S3 * c, -c - S3 * s, col3[1]],
                       [s + S3 * c, -c + S3 * s, col3[2]]])
        rhs51 = 3 * rb * (S3 * c - s) - q.sum() * (c - S3 * s)
        assert abs(sum(col3) - rhs51) < 1e-9 * abs(rhs51)
        assert abs(np.linalg.det(jd) - 2 * S3 * rhs51) < 1e-9 * abs(rhs51)
    assert verdicts_of("tripod_planar")["001 eq. (51)"] == "erratum"
