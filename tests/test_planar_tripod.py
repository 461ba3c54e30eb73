"""planar_tripod (000): generated module vs. the independent numeric model (layer 2), the
symbolic derivation at 50 digits (layer 3) and the verdicts against the paper (layer 1)."""

import importlib

import independent_planar_tripod as ipt
import numpy as np
import pytest
import sympy as sp
from conftest import symbolic_of, verdicts_of
from independent_planar_tripod import ik as ik_independent
from mpmath_reference import assert_ik_matches_mpmath

RNG = np.random.default_rng(11)


@pytest.fixture(scope="module")
def m():
    return importlib.import_module("bonered_alg.generated.planar_tripod")


@pytest.fixture(scope="module")
def d():
    return symbolic_of("planar_tripod")


def poses(n):
    return np.column_stack([RNG.uniform(-60, 60, n), RNG.uniform(-60, 60, n),
                            RNG.uniform(120, 240, n), RNG.uniform(-0.35, 0.35, n),
                            RNG.uniform(-0.35, 0.35, n), RNG.uniform(-0.9, 0.9, n)])


def test_ik_against_independent_model(m):
    p = poses(300)
    q = m.ik(p, limits=False)
    ref = np.array([ik_independent(pi) for pi in p])
    assert np.max(np.abs(q - ref)) < 1e-9


def test_jacobian_against_finite_differences(m):
    h = np.array([1e-4, 1e-4, 1e-4, 1e-7, 1e-7, 1e-7])
    for pose in poses(12):
        J = m.jacobian(pose, limits=False)
        fd = np.empty((6, 6))
        for k in range(6):
            e = np.zeros(6)
            e[k] = h[k]
            fd[:, k] = (ik_independent(pose + e) - ik_independent(pose - e)) / (2 * h[k])
        assert np.allclose(J, fd, rtol=1e-5, atol=1e-5)


def test_against_mpmath_50_digits(m, d):
    assert_ik_matches_mpmath(m, d, poses(5))


def test_imports_without_sympy():
    import subprocess
    import sys

    code = ("import sys; sys.modules['sympy'] = None\n"
            "from bonered_alg.generated import planar_tripod as m\n"
            "import numpy as np\n"
            "print(m.ik(np.array([0.0, 0.0, 200.0, 0.0, 0.0, 0.0])).round(6).tolist())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    q = eval(out.stdout)  # noqa: S307 - our own subprocess output, a list literal
    # home pose: q1 = q2 = q3 = 2 ra / sqrt(3) (000 eq. 17 at gamma = 0), legs = z
    assert np.allclose(q[:3], 2 * 190 / np.sqrt(3)) and np.allclose(q[3:], 200.0)


def test_paper_verdicts():
    got = verdicts_of("planar_tripod")
    for ref in ("000 eq. (10)", "000 eq. (9)", "000 eq. (16)", "000 eq. (42)",
                "000 eq. (5), q1", "000 eq. (5), q2", "000 eq. (5), q3", "000 eq. (37)-(38)",
                "000 eq. (37)"):
        assert got[ref] == "confirmed-symbolic", ref
    for k in range(1, 7):
        eq = 17 if k <= 3 else 21
        assert got[f"000 eq. ({eq}), q{k}"] == "confirmed-numeric"
    assert got["000 eq. (24)-(26)"] == "confirmed-numeric"


def test_parasitic_motion_is_derived_not_assumed(d):
    """000 eq. (10): gamma2 = 0, y2 = 0 and x2 = -rb sa sb come out of the lex basis."""
    from bonered_alg.mechanisms import planar_tripod as pt

    par = d.analyses["parasitic"].solved
    assert par[pt.tg2] == 0 and par[pt.y2] == 0
    a, b = sp.symbols("a b", real=True)
    x2 = par[pt.x2].subs({pt.ta: sp.tan(a / 2), pt.tb: sp.tan(b / 2)})
    assert sp.simplify(x2 + pt.rb * sp.sin(a) * sp.sin(b)) == 0


def test_singular_orientation_of_the_planar_part(m):
    """000 eq. (38): gamma = -pi/3 (and 2 pi/3) makes det A vanish: q1..q3 blow up."""
    for gamma in (-np.pi / 3, 2 * np.pi / 3):
        pose = np.array([0.0, 0.0, 200.0, 0.0, 0.0, gamma])
        assert m.ik_status(pose, limits=False) == m.INPUT_SINGULAR
        assert np.all(np.isnan(m.ik(pose, limits=False)))
        assert m.jacobian_status(pose, limits=False) == m.INPUT_SINGULAR
    near = np.array([0.0, 0.0, 200.0, 0.0, 0.0, -np.pi / 3 + 1e-3])
    assert m.ik_status(near, limits=False) == m.OK


def test_limits_of_table_1(m):
    """000 Table 1: strokes 175-250 mm, revolute +-45 deg, spherical +-20 deg."""
    home = np.array([0.0, 0.0, 200.0, 0.0, 0.0, 0.0])
    assert m.ik_status(home) == m.OK
    # z = 260: the legs (q4 = q5 = q6 = z at alpha = beta = 0) exceed 250 mm
    high = home + np.array([0, 0, 60.0, 0, 0, 0])
    assert m.ik_status(high) == m.STROKE_LIMIT and np.all(np.isnan(m.ik(high)))
    assert np.allclose(m.ik(high, limits=False)[3:], 260.0)
    # alpha = 0.37 rad at z = 180: strokes fine, the spherical joints D1, D3 tilt past 20 deg
    tilt = np.array([0.0, 0.0, 180.0, 0.37, 0.0, 0.0])
    q = m.ik(tilt, limits=False)
    vals = m.limit_values(tilt, q)
    assert np.all((q >= 175) & (q <= 250))
    assert np.degrees(vals["phi_s1"]) > 20 and m.ik_status(tilt) == m.PASSIVE_JOINT_LIMIT
    # independent value of the spherical angle of D1: angle between MP2's normal and C1D1
    from independent_planar_tripod import RA, RB, mp1_pose, rot

    x1, y1, g1 = mp1_pose(tilt)
    r2 = rot("z", -g1) @ rot("z", tilt[5]) @ rot("y", tilt[4]) @ rot("x", tilt[3])
    d1 = rot("z", -g1) @ (np.array([0, 0, tilt[2]]) + rot("x", tilt[3]) @ [RB, 0, 0]
                          - np.array([x1, y1, 0]))
    leg = d1 - np.array([RA, 0, 0])
    angle = np.arccos(r2[:, 2] @ leg / np.linalg.norm(leg))
    assert abs(angle - vals["phi_s1"]) < 1e-12


def _fd_jacobian(pose, h=1e-5):
    """dq/dX of the independent model by central differences."""
    cols = []
    for i in range(6):
        e = np.zeros(6)
        e[i] = h
        cols.append((ik_independent(pose + e) - ik_independent(pose - e)) / (2 * h))
    return np.array(cols).T


def _printed_jd(pose):
    """000 eq. (32)-(34) on the independent geometry (MP1 solved numerically, not eq. 16):
    J_C = diag(q4..q6) and J_D, the undefined a_ij read as the coefficients of alpha', beta'
    in eq. (30)."""
    x, y, z, a, b, g = pose
    sa, ca, sb, cb, sg, cg = np.sin(a), np.cos(a), np.sin(b), np.cos(b), np.sin(g), np.cos(g)
    x1, y1, g1 = ipt.mp1_pose(pose)
    r = ipt.rot("z", g) @ ipt.rot("y", b) @ ipt.rot("x", a)
    rb = ipt.RB
    a11, a12, a21, a22 = rb * ca * sb * cg, rb * sa * cb * cg, rb * ca * sb * sg, rb * sa * cb * sg
    jd, lengths = np.zeros((3, 6)), []
    for k in range(3):
        ck_w = ipt.rot("z", g1) @ ipt.C[k]
        rho = np.array([x, y, z]) + r @ ipt.D[k] - np.array([x1, y1, 0.0]) - ck_w
        c_, d_ = np.cross(ck_w, rho), np.cross(r @ ipt.D[k], rho)
        jd[k, 2] = rho[2]
        jd[k, 3] = (-(rho[0] * a11 + rho[1] * a21) + d_[0] * cg * cb + d_[1] * sg * cb
                    - sb * (d_[2] - c_[2]))
        jd[k, 4] = -(rho[0] * a12 + rho[1] * a22) - d_[0] * sg + d_[1] * cg
        lengths.append(np.linalg.norm(rho))
    return np.diag(lengths), jd


def _printed_jb(pose, q):
    """000 eq. (24)-(26): J_A (a scalar times I) and J_B with q1..q3 given."""
    x, y, _, a, b, g = pose
    s, c, r3 = np.sin(g), np.cos(g), np.sqrt(3.0)
    ra = rb = ipt.RA
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    jb = np.array([
        [-2 * s, 2 * c, 0, 0, 0,
         -ra * s - 2 * y * s - 2 * x * c + r3 * ra * c - q[0] * (c - r3 * s)],
        [s - r3 * c, -c - r3 * s, 0, -r3 * rb * ca * sb, -r3 * rb * sa * cb,
         -ra * s + y * s + x * c - r3 * y * c + r3 * x * s + r3 * ra * c - q[1] * (c - r3 * s)],
        [s + r3 * c, -c + r3 * s, 0, r3 * rb * ca * sb, r3 * rb * sa * cb,
         -ra * s + y * s + x * c + r3 * y * c - r3 * x * s + r3 * ra * c - q[2] * (c - r3 * s)]])
    return s + r3 * c, jb


def test_velocity_model_of_eq_34_35_against_finite_differences():
    """000 eq. (34), (35): with a_ij read from eq. (30) the printed J_C^-1 J_D, and the
    assembled blkdiag(J_A, J_C)^-1 [J_B; J_D], equal the independent model's dq/dX."""
    got = verdicts_of("planar_tripod")
    rng = np.random.default_rng(5)
    for _ in range(6):
        pose = np.array([rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(170, 230),
                         *rng.uniform(-0.3, 0.3, 2), rng.uniform(-0.8, 0.8)])
        jfd = _fd_jacobian(pose)
        jc, jd = _printed_jd(pose)
        assert np.allclose(np.linalg.solve(jc, jd), jfd[3:], atol=1e-6)
        ja, jb = _printed_jb(pose, ik_independent(pose)[:3])
        full = np.linalg.solve(np.diag([ja] * 3 + list(np.diag(jc))), np.vstack([jb, jd]))
        assert np.allclose(full, jfd, atol=1e-6)
    for ref in ("000 eq. (27)", "000 eq. (29)", "000 eq. (34)", "000 eq. (35)"):
        assert got[ref] == "confirmed-numeric", ref
    for ref in ("000 eq. (30)", "000 eq. (31)-(33)", "000 eq. (39)"):
        assert got[ref] == "confirmed-symbolic", ref


def test_eq_40_leaves_out_the_tripod_factor_of_det_b():
    """000 eq. (39)-(40): det B also vanishes where the tripod's J_D[z, alpha, beta] is
    singular (forward singularity), which eq. (40), the planar factor alone, does not show."""
    def tripod_det(z):
        pose = np.array([0.0, 0.0, z, 0.2, 0.2, 0.0])
        return np.linalg.det(_fd_jacobian(pose)[3:, 2:5])

    zs = np.linspace(20.0, 80.0, 13)
    signs = np.sign([tripod_det(z) for z in zs])
    assert np.any(signs[:-1] != signs[1:])  # a forward singularity of the tripod
    i = int(np.argmax(signs[:-1] != signs[1:]))
    pose = np.array([0.0, 0.0, (zs[i] + zs[i + 1]) / 2, 0.2, 0.2, 0.0])
    _, jb = _printed_jb(pose, ik_independent(pose)[:3])
    assert abs(np.linalg.det(jb[:, [0, 1, 5]])) > 1.0  # eq. (40) is far from zero there
    assert verdicts_of("planar_tripod")["000 eq. (40)"] == "erratum"


def test_eq_41_lacks_the_factor_3_ra():
    """000 eq. (41): J_B16 + J_B26 + J_B36 with the (independent) q1..q3 is 3 ra times the
    printed (1 - c(gamma + pi/3)) / s(gamma + pi/3)."""
    for g in (-0.9, -0.3, 0.2, 0.7, 1.5):
        pose = np.array([13.0, -7.0, 200.0, 0.1, -0.15, g])
        _, jb = _printed_jb(pose, ik_independent(pose)[:3])
        printed = (1 - np.cos(g + np.pi / 3)) / np.sin(g + np.pi / 3)
        assert abs(jb[:, 5].sum() - 3 * ipt.RA * printed) < 1e-8 * ipt.RA
        assert abs(jb[:, 5].sum() - printed) > 1.0
    assert verdicts_of("planar_tripod")["000 eq. (41)"] == "erratum"


def test_leg_line_rows_keep_the_generators_pivot_ratio(m, d):
    """The tripod legs' Jacobian rows come from the leg line (codegen leg_line_steps): q_k
    dq_k/dX = l . dl/dX.  Their input-singularity test |pivot| > rtol * scale must mean what
    it meant for the generator g_k = A q_k^2 + C of the derivation: |dg/dq| / (|dg/dq| +
    sum_m |dg/dX_m|), here computed from the generator itself (sympy, the pose map, 30
    digits), equals |q| / (|q| + sum_m |q dq/dX_m|) from the generated module's J."""
    pose = sp.symbols("x y z alpha beta gamma", real=True)
    for p in poses(4):
        q = m.ik(p, limits=False)
        J = m.jacobian(p, limits=False)
        at = dict(zip(pose, map(sp.Float, p, [30] * 6)))
        for st in d.steps[3:]:
            k = list(m.JOINTS).index(str(st.joint))
            g = sp.sympify(st.generator).xreplace(dict(d.pose_to_study)).xreplace(
                {sp.Symbol(n, real=True): v for n, v in m.PARAMETERS.items()})
            value = {**at, st.joint: sp.Float(q[k], 30)}
            pivot = abs(sp.diff(g, st.joint).evalf(30, subs=value))
            rate = sum(abs(sp.diff(g, x).evalf(30, subs=value)) for x in pose)
            ratio_generator = float(pivot / (pivot + rate))
            ratio_line = abs(q[k]) / (abs(q[k]) + np.sum(np.abs(q[k] * J[k])))
            assert ratio_line == pytest.approx(ratio_generator, rel=1e-9)
