"""Why a pose fails, joint by joint (issue 14, item 5), and the argument checks of every
generated function: types, flags, parameter domains; the physical branch as mode 0."""

import numpy as np
import pytest
from conftest import ROOT  # noqa: F401 - the generated modules are importable
from independent_planar_tripod import ik as independent_planar_ik
from test_runtime import toy_model

from bonered_alg.runtime import status as st
from bonered_alg.runtime.backsubstitution import backsubstitute


def _no_root(x, y, *par):
    """q^2 + 1 + x^2: no real root."""
    return 1.0, 0.0 * x, 1.0 + x * x


def _uses_first(x, y, q, *par):
    """p - q: needs the first unknown."""
    return 0.0, 1.0 + 0.0 * x, -q


def _independent(x, y, q, p, *par):
    """r - y: needs neither."""
    return 0.0, 1.0 + 0.0 * x, -y


def test_per_step_codes_name_the_failed_step_and_those_that_depend_on_it():
    steps = ((2, _no_root, 0), (1, _uses_first, None), (1, _independent, None))
    info = {}
    out, status = backsubstitute(np.array([[1.0, 2.0]]), steps, (0, 1, 2), 3, 0, [], True,
                                 info)
    assert status[0] == st.NO_REAL_SOLUTION and np.isnan(out).all()
    assert info["codes"][0].tolist() == [st.NO_REAL_SOLUTION, st.NOT_SOLVED, st.OK]
    assert info["discriminants"][0][0] == -8.0  # 0 - 4 (1 + 1)
    assert info["roots"][0, 2] == 2.0  # the independent step keeps its own root


def test_toy_joint_status_and_explanation():
    m = toy_model()
    pose = np.array([[3.0, 16.0], [1.0, -4.0], [1.0, 3.0], [np.nan, 1.0]])
    codes = m.ik_joint_status(pose)
    assert codes.tolist() == [[st.STROKE_LIMIT, st.OK], [st.NO_REAL_SOLUTION, st.OK],
                              [st.OK, st.OK], [st.INVALID_INPUT] * 2]
    why = m.ik_explain(pose)
    assert why[0] == "q = 5 mm above its upper limit 4.5 mm (stroke limit, test)"
    assert why[1].startswith("q: no real root (the discriminant of its quadratic step is -12")
    assert why[2] == "ok" and why[3] == "pose coordinate(s) x not finite"
    assert m.ik_explain(pose[2]) == "ok"  # one pose: one string


def test_planar_tripod_reasons_agree_with_an_independent_model():
    """The joints flagged STROKE_LIMIT are those whose stroke, from the independent
    geometric model (tests/independent_planar_tripod.py), is outside 000 Table 1's
    175-250 mm; the explanation names them with their values."""
    from bonered_alg.generated import planar_tripod as m

    rng = np.random.default_rng(5)
    poses = np.column_stack([rng.uniform(-40, 40, 12), rng.uniform(-40, 40, 12),
                             rng.uniform(190, 250, 12), rng.uniform(-0.15, 0.15, 12),
                             rng.uniform(-0.15, 0.15, 12), rng.uniform(-0.4, 0.4, 12)])
    codes = m.ik_joint_status(poses, limits=True)
    why = m.ik_explain(poses)
    flagged = 0
    for pose, c, text in zip(poses, codes, why):
        q = independent_planar_ik(pose)
        out = (q < 175.0) | (q > 250.0)
        assert ((c == st.STROKE_LIMIT) == out).all(), (pose, q, c)
        for k in np.flatnonzero(out):
            side = "above its upper limit 250" if q[k] > 250 else "below its lower limit 175"
            assert f"q{k + 1} = " in text and side in text.split(f"q{k + 1} = ")[1], text
            flagged += 1
        if not out.any() and (c == st.OK).all():
            assert text == "ok"
    assert flagged > 0  # the sample exercises the limits


def test_pro_hep_lct_unreachable_lower_point_names_its_two_joints():
    """Pd 900 mm from the base: beyond l1 + l2 = 336 mm of both lower chains (004 Table 2
    geometry), so t1 and w1 have no real root while the upper chain's q4, q5 are fine."""
    from bonered_alg.generated import pro_hep_lct as m

    pose = np.array([300.0, 180.0, 900.0, 180.0])
    assert m.ik_joint_status(pose).tolist() == [st.NO_REAL_SOLUTION, st.NO_REAL_SOLUTION,
                                                st.OK, st.OK]
    text = m.ik_explain(pose)
    assert text.startswith("t1: no real root") and "w1: no real root" in text


@pytest.mark.parametrize("fast", [False, True], ids=["numpy", "compiled"])
@pytest.mark.parametrize("name", ["planar_tripod", "pro_hep_lct", "stewart", "urrh_rcm"])
def test_bad_arguments_are_clear_errors(name, fast):
    """The same errors on both paths: the numpy runtime and the compiled fast path."""
    import importlib

    m = importlib.import_module(f"bonered_alg.generated.{name}")
    home = np.asarray(m.HOME)
    with pytest.raises(TypeError, match=rf"{name}.ik: pose must be real numbers .* strings"):
        m.ik(np.array(["1"] * len(m.POSE)), fast=fast)
    with pytest.raises(TypeError, match=rf"{name}.ik: limits must be True or False, got 'no'"):
        m.ik(home, limits="no", fast=fast)
    with pytest.raises(ValueError, match=rf"{name}.jacobian: mode must be an integer"):
        m.jacobian(home, mode=True, fast=fast)
    positive = [p for p, d in m.PARAMETER_DOMAINS.items() if d == "positive"]
    assert positive  # every mechanism here has lengths
    with pytest.raises(ValueError, match=rf"{name}.ik_all: geometric parameter "
                                         rf"'{positive[0]}' must be > 0"):
        m.ik_all(home, fast=fast, **{positive[0]: -1.0})
    with pytest.raises(TypeError, match=rf"{name}.ik_status: pose must be real numbers"):
        m.ik_status([[1 + 2j] * len(m.POSE)], fast=fast)
    with pytest.raises(ValueError, match=rf"{name}.ik_and_jacobian: pose must have shape"):
        m.ik_and_jacobian(home[:-1], fast=fast)
    with pytest.raises(TypeError, match=rf"{name}.ik: fast must be None, True or False"):
        m.ik(home, fast="yes")


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar", "pro_hep_lct", "stewart",
                                  "urrh_rcm"])
def test_mode_zero_is_the_declared_physical_branch(name):
    """At HOME, mode 0 reproduces PHYSICAL_BRANCH (the values the declaration gives)."""
    import importlib

    m = importlib.import_module(f"bonered_alg.generated.{name}")
    q = m.ik(np.asarray(m.HOME), limits=False)
    for joint, value in m.PHYSICAL_BRANCH:
        got = q[m.JOINTS.index(joint)]
        assert abs(got - value) <= 1e-3 * (1 + abs(value)), (joint, got, value)


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar", "pro_hep_lct", "urrh_rcm",
                                  "lamina_milling"])
def test_fk_of_a_batch_with_unreachable_joints(name):
    """Joints that are NaN (``ik`` of an unreachable pose) in a batch: their modes are NaN
    with the status INVALID_INPUT, and the other rows are what they are alone.  With a NaN
    row, planar_tripod's and tripod_planar's forward kinematics take their other charts,
    whose kernels raised a NameError (see test_codegen_and_planning)."""
    import importlib

    m = importlib.import_module(f"bonered_alg.generated.{name}")
    q = np.atleast_2d(m.ik(np.asarray(m.HOME, dtype=float), limits=False))
    batch = np.vstack([q, np.full_like(q, np.nan), q])
    sols, status = m.fk(batch), m.fk_status(batch)
    alone, alone_status = m.fk(q[0]), m.fk_status(q[0])
    assert np.isnan(sols[1]).all() and (status[1] == st.INVALID_INPUT).all()
    for k in (0, 2):
        assert np.array_equal(sols[k], alone, equal_nan=True)
        assert np.array_equal(status[k], alone_status)
    home = np.asarray(m.HOME, dtype=float)
    assert np.nanmin(np.abs(alone - home).max(axis=-1)) < 1e-8
