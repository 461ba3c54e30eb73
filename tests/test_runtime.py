"""The numpy-only runtime of the generated modules, tested directly on small synthetic step
tables (independent of any mechanism): back-substitution, statuses, limits, Jacobians,
argument checks."""

import subprocess
import sys

import numpy as np
import pytest

from bonered_alg import runtime
from bonered_alg.runtime import status as st
from bonered_alg.runtime.backsubstitution import backsubstitute


def _quadratic(x, y, *par):
    """q^2 - (x^2 + y): two roots +-sqrt(x^2 + y)."""
    return 1.0, 0.0 * x, -(x * x + y)


def _linear(x, y, q, *par):
    """p * x - y: p = y / x (pivot x)."""
    return 0.0, x, -y


STEPS = ((2, _quadratic, 0), (1, _linear, None))


def test_backsubstitution_roots_and_modes():
    inputs = np.array([[3.0, 16.0], [1.0, -4.0], [0.0, 4.0]])
    out0, s0 = backsubstitute(inputs, STEPS, (0, 1), 2, 0, [], True)
    out1, _ = backsubstitute(inputs, STEPS, (0, 1), 2, 1, [], True)
    assert out0[0].tolist() == [5.0, 16.0 / 3.0] and out1[0, 0] == -5.0
    # no real root of the quadratic: the whole configuration is NaN, with its reason
    assert np.isnan(out0[1]).all() and s0[1] == st.NO_REAL_SOLUTION
    # a zero pivot of the linear step: an input singularity
    assert np.isnan(out0[2]).all() and s0[2] == st.INPUT_SINGULAR
    assert s0[0] == st.OK


def test_backsubstitution_boundary_and_invalid_input():
    out, status = backsubstitute(np.array([[2.0, -4.0], [np.nan, 1.0]]), STEPS, (0, 1), 2, 0,
                                 [], True)
    assert status[0] == st.ON_BOUNDARY and out[0, 0] == 0.0  # a double root is valid
    assert status[1] == st.INVALID_INPUT and np.isnan(out[1]).all()


def _study(x, y, *par):
    return (x, y)


def _jac(x, y, q, p, *par):
    # pivots, scales, then dq/dX for q = sqrt(x^2 + y), p = y / x
    return (2 * q, x + 0.0 * y, 2 * np.abs(q) + 2 * np.abs(x) + 1.0, np.abs(x) + np.abs(y),
            x / q, 0.5 / q, -y / (x * x), 1.0 / x)


def _limit(x, y, q, p, *par):
    return (q,)


def toy_model(**kw) -> runtime.Model:
    fields = dict(mechanism="toy", parameters={"k": 1.0}, parameter_units={"k": "mm"},
                  parameter_notes={"k": "a test parameter"}, pose=("x", "y"),
                  study_pose=("x", "y"), joints=("q", "p"), modes=2, study=_study,
                  steps=STEPS, solve_index=(0, 1), jac=_jac,
                  ji=lambda *a: (0.0,) * 4, jo_study=lambda *a: (0.0,) * 4,
                  singularity_kernels={}, limits=(("q", 0.0, 4.5, "stroke", "mm", "test"),),
                  limit_kernel=_limit)
    fields.update(kw)
    return runtime.Model(**fields)


def test_model_ik_limits_and_statuses():
    m = toy_model()
    pose = np.array([[3.0, 16.0], [1.0, 3.0]])
    q, status = m.ik_and_status(pose)
    assert np.isnan(q[0]).all() and status[0] == st.STROKE_LIMIT  # q = 5 > 4.5
    assert np.allclose(q[1], [2.0, 3.0]) and status[1] == st.OK
    assert np.allclose(m.ik(pose, limits=False)[0], [5.0, 16.0 / 3.0])
    both = m.ik_all(pose, limits=False)
    assert both.shape == (2, 2, 2) and np.allclose(both[1, :, 0], [2.0, -2.0])
    assert m.limit_values(pose, q)["q"].shape == (2,)


def test_model_jacobian_against_finite_differences():
    m = toy_model()
    pose = np.array([1.5, 2.0])
    J, status = m.jacobian_and_status(pose, limits=False)
    h = 1e-6
    fd = np.stack([(m.ik(pose + h * e, limits=False) - m.ik(pose - h * e, limits=False))
                   / (2 * h) for e in np.eye(2)], axis=-1)
    assert status == st.OK and np.allclose(J, fd, atol=1e-8)
    # on the boundary of the quadratic (q = 0) the Jacobian is not defined
    J, status = m.jacobian_and_status(np.array([2.0, -4.0]), limits=False)
    assert status == st.INPUT_SINGULAR and np.isnan(J).all()


def test_argument_errors_name_the_mechanism_and_what_was_expected():
    m = toy_model()
    with pytest.raises(ValueError, match=r"toy.ik: pose must have shape \(\.\.\., 2\) with "
                                         r"coordinates \('x', 'y'\), got shape \(3,\)"):
        m.ik(np.zeros(3))
    with pytest.raises(TypeError, match=r"toy.ik: unknown geometric parameter\(s\) \['kk'\]"):
        m.ik(np.zeros(2), params={"kk": 1.0})
    with pytest.raises(ValueError, match="toy.ik: geometric parameter 'k' is not finite"):
        m.ik(np.zeros(2), params={"k": np.inf})
    with pytest.raises(ValueError, match=r"toy.ik: mode must be an integer in \[0, 2\)"):
        m.ik(np.zeros(2), mode=2)
    with pytest.raises(NotImplementedError, match="forward kinematics is not generated"):
        toy_model(fk=runtime.ForwardKinematics(note="none here")).fk_all(np.zeros(2))


def test_plain_scalar_parameters_are_checked_as_arrays_are():
    """The float comparisons for plain scalars (check.parameters' shortcut) give the array
    checks' values and reject what they reject; the checked defaults, kept per model, come
    back as a fresh list each call.  A scalar, by either path, is a numpy.float64 (numpy's
    arithmetic: infinity, not ZeroDivisionError, where a kernel divides by a parameter
    difference that is zero)."""
    from bonered_alg.runtime import inputs

    m = toy_model(parameters={"k": 1.0, "r": 2.0, "n": 0.0},
                  parameter_units={"k": "mm", "r": "mm", "n": "mm"},
                  parameter_notes={"k": "a", "r": "b", "n": "c"},
                  parameter_domains={"r": "positive", "n": "nonnegative"})
    for value in (3, 3.5, np.float64(-2.25), 2**53 + 1, 1e-300, np.array(3.5),
                  np.float32(0.1), np.int64(-7)):
        got = inputs.parameters(m, "f", {"k": value})[0]
        assert type(got) is np.float64 and got.ndim == 0
        assert got == np.asarray(value).astype(float)
    zero = inputs.parameters(m, "f", {"k": 2.0, "n": 2})
    with np.errstate(divide="ignore"):
        assert zero[0] / (zero[0] - zero[2]) == np.inf
    bad = [({"r": 0.0}, ValueError, "'r' must be > 0"), ({"r": -1}, ValueError, "'r' must be > 0"),
           ({"n": -1e-300}, ValueError, "'n' must be >= 0"),
           ({"k": float("nan")}, ValueError, "'k' is not finite"),
           ({"k": -np.inf}, ValueError, "'k' is not finite"),
           ({"k": True}, TypeError, "booleans"), ({"k": 10**400}, TypeError, "Python objects")]
    for params, error, text in bad:
        with pytest.raises(error, match=text):
            inputs.parameters(m, "f", params)
    first, second = inputs.parameters(m, "f", {}), inputs.parameters(m, "f", {})
    assert first is not second and [float(v) for v in first] == [1.0, 2.0, 0.0]
    assert first.vector.tolist() == [1.0, 2.0, 0.0] and not first.vector.flags.writeable
    first.clear()
    assert len(inputs.parameters(m, "f", {})) == 3
    arrays = inputs.parameters(m, "f", {"k": [1.0, 2.0]})  # an array: no scalar vector
    assert arrays.vector is None and arrays[0].tolist() == [1.0, 2.0]
    assert inputs.parameters(m, "f", {"k": 7}).vector.tolist() == [7.0, 2.0, 0.0]
    assert inputs.parameters(m, "f", {"n": 4})[2] == 4.0  # keywords are never the cache
    m.parameters["r"] = 5.0  # a module's PARAMETERS given a new default: checked again
    assert inputs.parameters(m, "f", {}).vector.tolist() == [1.0, 5.0, 0.0]
    m.parameters["r"] = -5.0
    with pytest.raises(ValueError, match="'r' must be > 0"):
        inputs.parameters(m, "f", {})
    with pytest.raises(ValueError, match="'k' has no value"):  # no default: never cached
        inputs.parameters(toy_model(parameters={"k": None}), "f", {})


def test_api_version_mismatch_is_a_clear_error():
    runtime.require(runtime.API_VERSION, "toy")
    with pytest.raises(ImportError, match="written for runtime API 0.*run `make derive`"):
        runtime.require(0, "toy")


def test_every_status_is_documented():
    codes = [v for k, v in vars(st).items() if k.isupper() and isinstance(v, int)]
    assert sorted(codes) == sorted(st.STATUS)


def test_runtime_imports_without_sympy():
    code = ("import sys; sys.modules['sympy'] = None\n"
            "import bonered_alg.runtime, bonered_alg.generated.stewart\n"
            "print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


@pytest.mark.parametrize("name", ["stewart", "urrh_rcm", "tripod_planar", "planar_tripod",
                                  "pro_hep_lct", "lamina_milling"])
def test_geometry_as_per_pose_arrays_gives_the_scalar_values(name):
    """The kernels compute their parameters' coefficients once per call (hoisted before the
    array program): given as one value per pose, the geometry must give what the scalar
    geometry gives, in the singularity polynomials, Ji, Jo, the IK with its Jacobian, the
    passive joints, the link poses and the forward kinematics (the default geometry,
    broadcast to the poses; the 3-RPS closures' forward kinematics raised a broadcasting
    error here before 2026-12-07)."""
    import importlib

    m = importlib.import_module(f"bonered_alg.generated.{name}")
    rng = np.random.default_rng(4)
    home = np.array([0.0 if v is None else v for v in m.HOME])
    scale = np.array([20.0 if u == "mm" else 0.3 for u in m.POSE_UNITS])
    pose = home + rng.uniform(-1, 1, (300, len(home))) * scale
    q = m.ik(pose, limits=False)
    keep = np.isfinite(q).all(axis=-1)
    pose, q = pose[keep], q[keep]
    arrays = {k: np.full(len(pose), v) for k, v in m.PARAMETERS.items()}
    assert len(pose) > 100

    def same(a, b):
        """Equal to rounding, each value against the largest of its row (with the default
        geometry the kernels may have it folded into constants)."""
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        assert np.array_equal(np.isfinite(a), np.isfinite(b))
        size = 1.0 + np.nanmax(np.abs(b), axis=-1, keepdims=True, initial=0.0)
        assert (np.abs(np.where(np.isfinite(b), a - b, 0.0)) <= 1e-13 * size).all()

    for k, v in m.singularities(pose, q).items():
        same(m.singularities(pose, q, **arrays)[k], v)
    same(m.input_jacobian(pose, q, **arrays), m.input_jacobian(pose, q))
    same(m.output_jacobian(pose, q, **arrays), m.output_jacobian(pose, q))
    for a, b in zip(m.ik_and_jacobian(pose, limits=False, **arrays),
                    m.ik_and_jacobian(pose, limits=False)):
        same(a, b)
    same(m.passive_joints(pose, **arrays), m.passive_joints(pose))
    same(m.link_poses(pose, **arrays), m.link_poses(pose))
    if m.FK_MODES:
        same(m.fk(q[:50], **{k: v[:50] for k, v in arrays.items()}),
             m.fk(q[:50]))
