"""The README's worked example: adding a planar 3-RRR mechanism is one declaration
(``tests/example_planar_3rrr.py``), derived end to end without touching the engine, and
checked here against plain planar geometry (numpy), not the code under test."""

import example_planar_3rrr
import numpy as np
import pytest
from conftest import ROOT, assert_close, in_joint_quantities, record_of
from example_planar_3rrr import BASE, PLATFORM

from bonered_alg.pipeline import outputs

RNG = np.random.default_rng(3)
GEO = {"L": 300.0, "b": 100.0, "l1": 160.0, "l2": 160.0}


@pytest.fixture(scope="module")
def record():
    return record_of(example_planar_3rrr)


def _platform_points(pose):
    x, y, phi = pose
    c, s = np.cos(phi), np.sin(phi)
    return [np.array([x + c * px - s * py, y + s * px + c * py]) for px, py, _ in
            ((GEO["b"] * a, GEO["b"] * b_, 0) for a, b_ in ((0, 0), (1, 0), (0, 1)))]


def _independent_angles(pose):
    """Both actuated angles of each leg: B_k at distance l2 from E_k = A_k + l1 (cos, sin)."""
    out = []
    for (ax, ay, _), bk in zip(((0, 0, 0), (GEO["L"], 0, 0), (0, GEO["L"], 0)),
                               _platform_points(pose)):
        d = bk - np.array([ax, ay])
        r = np.hypot(*d)
        c = (r * r + GEO["l1"] ** 2 - GEO["l2"] ** 2) / (2 * GEO["l1"] * r)
        base = np.arctan2(d[1], d[0])
        out.append({base + np.arccos(c), base - np.arccos(c)})
    return out


def _poses(n):
    return np.column_stack([RNG.uniform(60, 110, n), RNG.uniform(60, 110, n),
                            RNG.uniform(-0.3, 0.3, n)])


def test_the_declaration_is_the_one_in_the_readme():
    text = (ROOT / "README.md").read_text()
    source = (ROOT / "tests" / "example_planar_3rrr.py").read_text()
    body = source[source.index("import sympy as sp"):]
    assert body.strip() in text


def test_mode_zero_is_the_declared_assembly(record):
    """The elimination's sign of the generator of u2 gives the other elbow at home; the
    declared branch negates it, so mode 0 is the assembly as built."""
    gen = record.generated.module
    q = gen.ik(np.array(gen.HOME))
    assert np.allclose(q, [1.55, 0.86, 0.04], atol=0.01)
    flipped = {str(b.joint) for b in record.derivation.branches if b.negated}
    assert flipped == {"u2"}
    want = _independent_angles(np.array(gen.HOME))
    for k in range(3):  # and it is one of the geometry's two elbows of each leg
        assert min(abs(np.angle(np.exp(1j * (2 * np.arctan(q[k]) - a)))) for a in want[k]) \
            < 1e-9


def test_ik_every_working_mode_against_planar_geometry(record):
    gen = record.generated.module
    assert gen.MODES == 8 and gen.JOINTS == ("u1", "u2", "u3")
    assert len(BASE) == len(PLATFORM) == 3
    for pose in _poses(20):
        want = _independent_angles(pose)
        got = 2 * np.arctan(gen.ik_all(pose))  # (8, 3) joint angles
        assert np.isfinite(got).all()
        for k in range(3):
            found = {round(float(np.angle(np.exp(1j * a))), 9) for a in got[:, k]}
            expected = {round(float(np.angle(np.exp(1j * a))), 9) for a in want[k]}
            assert found == expected, (pose, k)


def test_jacobian_passive_joints_and_twist(record):
    gen = record.generated.module
    h = 1e-6
    for pose in _poses(5):
        J = gen.jacobian(pose)
        fd = np.stack([(gen.ik(pose + h * e) - gen.ik(pose - h * e)) / (2 * h)
                       for e in np.eye(3)], axis=-1)
        assert np.allclose(J, fd, rtol=1e-6, atol=1e-9)
        passive = dict(zip(gen.PASSIVE, gen.passive_joints(pose)))
        q = gen.ik(pose)
        for k, bk in enumerate(_platform_points(pose)):
            # the elbow angle closes the leg: A_k + l1 e(theta) + l2 e(theta + elbow) = B_k
            th = 2 * np.arctan(q[k])
            el = th + 2 * np.arctan(passive[f"e{k + 1}"])
            a = np.array(((0, 0), (GEO["L"], 0), (0, GEO["L"]))[k])
            tip = a + GEO["l1"] * np.array([np.cos(th), np.sin(th)]) + GEO["l2"] * np.array(
                [np.cos(el), np.sin(el)])
            assert np.allclose(tip, bk, atol=1e-9)
        assert np.allclose(gen.twist_jacobian(pose) @ J, gen.pose_twist(pose), atol=1e-9)


def test_it_gets_a_report_and_singularities(record):
    files = outputs.files(record)
    assert set(files) == {"generated/planar_3rrr.py", "generated/planar_3rrr.c",
                          "derivations/planar_3rrr.tex",
                          "derivations/planar_3rrr.verification.json",
                          "derivations/planar_3rrr.algebra.json",
                          "derivations/planar_3rrr.configurations.png",
                          "derivations/planar_3rrr.mobility.csv"}
    # a new mechanism gets its mobility two ways: a planar 3-RRR, order 3, M = 3 = the
    # tangent dimension of its ideal
    row = files["derivations/planar_3rrr.mobility.csv"].splitlines()[1].split(",")
    assert row[1] == "3" and row[7] == "3" and row[10] == "3", row
    names = {s.name for s in record.derivation.singularities}
    assert {"det_Ji_platform", "det_Jo_platform", "boundary_u1"} <= names
    assert "not generated" in record.generated.module.FK_NOTE or record.generated.module.FK_NOTE


def test_a_new_mechanism_gets_a_compiled_fast_path(record, tmp_path):
    """The module and its C file written side by side and imported from there: the compiled
    IK and Jacobian agree with the numpy runtime to 1e-12 relative (the joints as angles),
    status codes included."""
    import importlib.util

    for rel, content in outputs.files(record).items():
        if rel.startswith("generated/"):
            (tmp_path / rel.split("/")[1]).write_text(content)
    spec = importlib.util.spec_from_file_location("planar_3rrr_from_file",
                                                  tmp_path / "planar_3rrr.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    poses = np.asarray(gen.HOME) + RNG.uniform(-1, 1, (500, 3)) * [200.0, 200.0, 1.5]
    poses[0, 1] = np.nan
    for mode in range(gen.MODES):
        qa, Ja, sa = gen.ik_and_jacobian(poses, mode=mode, fast=False)
        qb, Jb, sb = gen.ik_and_jacobian(poses, mode=mode, fast=True)
        assert (sa == sb).all()
        # u1..u3 are tan(theta/2): compared as angles (conftest.in_joint_quantities)
        ta, Ta = in_joint_quantities(gen, qa, Ja)
        tb, Tb = in_joint_quantities(gen, qb, Jb)
        assert_close(ta, tb)
        assert_close(Ta, Tb)
    assert (sa == gen.OK).any() and (sa != gen.OK).any()
