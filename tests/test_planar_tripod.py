"""planar_tripod (000): generated module vs. the independent numeric model (layer 2), the
symbolic derivation at 50 digits (layer 3) and the verdicts against the paper (layer 1)."""

import importlib

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
