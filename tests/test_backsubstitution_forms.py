"""The lean back-substitution (the hot path of ``ik``, ``ik_and_status``, ``ik_and_jacobian``)
against the detailed one (the per-step record behind ``ik_joint_status`` and ``ik_explain``):
the same roots bit for bit, the same NaN and the same status codes, on synthetic steps that
reach every code and on every generated mechanism's own steps; and every mode at once
(``backsubstitute_modes``, behind ``ik_all``) against the lean form mode by mode."""

import importlib

import numpy as np
import pytest

from bonered_alg.registry import MECHANISMS
from bonered_alg.runtime import status as st
from bonered_alg.runtime.backsubstitution import (
    backsubstitute_detailed,
    backsubstitute_lean,
    backsubstitute_modes,
)
from bonered_alg.runtime.inputs import stacked


def _pure(x, y, *par):
    """q^2 x - y (B the constant 0, as a distance leg): q = +-sqrt(y / x)."""
    return x, 0.0, -y


def _general(x, y, q, *par):
    """p^2 + q p + y: a general quadratic, its discriminant q^2 - 4 y."""
    return 1.0, q, y


def _linear(x, y, q, p, *par):
    """(x - 1) r - p: r = p / (x - 1), pivot x - 1."""
    return 0.0, x - 1.0, -p


STEPS = ((2, _pure, 0), (2, _general, 1), (1, _linear, None))


def _assert_same(a, b):
    (qa, sa), (qb, sb) = a, b
    assert np.array_equal(np.isnan(qa), np.isnan(qb))
    assert np.array_equal(qa, qb, equal_nan=True)
    assert (sa is None) == (sb is None)
    if sa is not None:
        assert np.array_equal(sa, sb)


def test_every_status_code_as_the_detailed_form():
    inputs = np.array([
        [2.0, 8.0],     # q = 2, p^2 + 2p + 8: no real root (step 2)
        [0.125, 0.5],   # q = 2, p^2 + 2p + 1/2 = 0: two real roots, r = p / (x - 1): OK
        [-1.0, 4.0],    # y / x < 0: no real root of the pure step
        [1.0, 0.0],     # q = 0: a double root of the pure step (ON_BOUNDARY) ...
        [1.0, 1.0],     # q = 1, p^2 + p + 1: no real root; pivot x - 1 = 0 too (later step)
        [4.0, 4.0],     # q = 1: p^2 + p + 4: no real root
        [0.25, 0.25],   # q = 1, p^2 + p + 1/4: a double root p = -1/2 (ON_BOUNDARY)
        [0.0, 1.0],     # A = 0 and C != 0: the pure step's root at infinity
        [np.nan, 1.0],  # invalid input
        [2.0, np.inf],  # invalid input
        [1.0, -1.0],    # no real root of the pure step before the zero pivot
    ])
    seen = set()
    for mode in range(4):
        for with_status in (False, True):
            lean = backsubstitute_lean(inputs, STEPS, (0, 1, 2), 3, mode, [], with_status)
            detailed = backsubstitute_detailed(inputs, STEPS, (0, 1, 2), 3, mode, [],
                                               with_status)
            _assert_same(lean, detailed)
            if with_status:
                seen |= set(lean[1].tolist())
    # the cases reach every code a back-substitution gives
    assert {st.OK, st.NO_REAL_SOLUTION, st.JOINT_AT_INFINITY, st.ON_BOUNDARY,
            st.INPUT_SINGULAR, st.INVALID_INPUT} <= seen


def test_zero_pivot_of_a_linear_step_as_the_detailed_form():
    # x = 1: the linear step's pivot vanishes after two valid steps (q = 1, p^2 + p - 2)
    inputs = np.array([[1.0, 1.0], [1.0, 1.0]])
    steps = ((2, _pure, 0), (2, lambda x, y, q: (1.0, q, -2.0 * y), 1), (1, _linear, None))
    lean = backsubstitute_lean(inputs, steps, (0, 1, 2), 3, 0, [], True)
    _assert_same(lean, backsubstitute_detailed(inputs, steps, (0, 1, 2), 3, 0, [], True))
    assert (lean[1] == st.INPUT_SINGULAR).all()


def test_single_input_without_leading_axes():
    for x in ([0.125, 0.5], [-1.0, 4.0], [1.0, 0.0], [np.nan, 1.0]):
        inputs = np.array(x)
        for mode, with_status in ((m, w) for m in range(4) for w in (False, True)):
            lean = backsubstitute_lean(inputs, STEPS, (0, 1, 2), 3, mode, [], with_status)
            _assert_same(lean, backsubstitute_detailed(inputs, STEPS, (0, 1, 2), 3, mode, [],
                                                       with_status))
            assert lean[0].shape == (3,)
            assert lean[1] is None if not with_status else lean[1].shape == ()


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_generated_steps_as_the_detailed_form(name):
    """Every mechanism's IK steps on its Study coordinates of random poses around home,
    many of them out of reach, in every working mode."""
    m = importlib.import_module(f"bonered_alg.generated.{name}")
    model = m._MODEL
    rng = np.random.default_rng(7)
    home = np.array(m.HOME) if getattr(m, "HOME", None) else None
    scale = np.array([40.0 if u == "mm" else 0.4 for u in m.POSE_UNITS])
    centre = home if home is not None else np.zeros(len(m.POSE))
    poses = centre + rng.uniform(-1.0, 1.0, (3000, len(m.POSE))) * scale
    poses[::97, 0] = np.nan
    par = [m.PARAMETERS[k] for k in m.PARAMETERS]
    study = stacked(model.study_values(poses, par), poses.shape[:-1])
    codes = set()
    for mode in range(min(model.modes, 8)):
        args = (study, model.steps, model.solve_index, len(model.joints), mode, par)
        lean = backsubstitute_lean(*args, True)
        _assert_same(lean, backsubstitute_detailed(*args, True))
        _assert_same(backsubstitute_lean(*args, False), backsubstitute_detailed(*args, False))
        codes |= set(lean[1].tolist())
    assert st.OK in codes and len(codes) > 1  # valid poses and failures both


def test_every_mode_at_once_as_mode_by_mode():
    """backsubstitute_modes shares a step between the modes that agree on the earlier
    roots; each mode's roots and NaN must be the lean form's, bit for bit, on inputs that
    reach every failure, with leading axes and without."""
    inputs = np.array([[2.0, 8.0], [0.125, 0.5], [-1.0, 4.0], [1.0, 0.0], [1.0, 1.0],
                       [0.25, 0.25], [0.0, 1.0], [np.nan, 1.0], [1.0, -1.0]])
    calls = []

    def independent(x, y, q, *par):  # reads no earlier root: evaluated once for 4 modes
        calls.append(1)
        return 1.0, y, -x

    steps_free = ((2, _pure, 0), (2, independent, 1), (1, _linear, None))
    for x in (inputs, inputs[1]):
        # every earlier step read (uses None), and each step's true inputs: STEPS's
        # _general reads q (step 0) and _linear p (step 1); ``independent`` reads nothing
        for steps, uses in ((STEPS, None), (STEPS, ((), (0,), (1,))),
                            (steps_free, ((), (), (1,)))):
            calls.clear()
            every = dict(backsubstitute_modes(x, steps, (2, 0, 1), 3, range(4), [], uses))
            evaluated = len(calls)
            assert sorted(every) == [0, 1, 2, 3]
            for mode, q in every.items():
                lean = backsubstitute_lean(x, steps, (2, 0, 1), 3, mode, [])[0]
                assert q.shape == lean.shape
                assert np.array_equal(q, lean, equal_nan=True)
            if steps is steps_free:
                assert evaluated == 1  # not once per root of the step before


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_ik_all_is_ik_mode_by_mode(name):
    """ik_all (numpy: the Study map once, each step once per choice of the earlier roots)
    gives each working mode's ik bit for bit, with the limits and without."""
    m = importlib.import_module(f"bonered_alg.generated.{name}")
    rng = np.random.default_rng(8)
    home = np.array(m.HOME) if getattr(m, "HOME", None) else np.zeros(len(m.POSE))
    scale = np.array([40.0 if u == "mm" else 0.4 for u in m.POSE_UNITS])
    poses = home + rng.uniform(-1.0, 1.0, (500, len(m.POSE))) * scale
    poses[::37, 1] = np.nan
    for limits in (False, True):
        every = m.ik_all(poses, limits=limits, fast=False)
        assert every.shape == (500, m.MODES, len(m.JOINTS))
        for mode in range(m.MODES):
            one = m.ik(poses, mode=mode, limits=limits, fast=False)
            assert np.array_equal(every[:, mode], one, equal_nan=True)
        assert np.isfinite(every).any()  # some poses are reached
    single = m.ik_all(poses[0], fast=False)
    assert np.array_equal(single, every[0], equal_nan=True)


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_step_uses_are_the_roots_each_kernel_reads(name):
    """STEP_USES-style metadata (Model.step_uses, from the free symbols of each step's
    coefficients) lets ik_all evaluate a step once per choice of the roots it reads: a
    kernel's coefficients must not move when any other earlier root does, and must move
    when one it is said to read does."""
    m = importlib.import_module(f"bonered_alg.generated.{name}")
    model = m._MODEL
    assert len(model.step_uses) == len(model.steps)
    rng = np.random.default_rng(3)
    home = np.array(m.HOME) if getattr(m, "HOME", None) else np.zeros(len(m.POSE))
    scale = np.array([10.0 if u == "mm" else 0.1 for u in m.POSE_UNITS])
    poses = home + rng.uniform(-1.0, 1.0, (50, len(m.POSE))) * scale
    par = [m.PARAMETERS[k] for k in m.PARAMETERS]
    study = stacked(model.study_values(poses, par), poses.shape[:-1])
    cols = [np.ascontiguousarray(study[..., i]) for i in range(study.shape[-1])]
    roots = [rng.uniform(0.5, 2.0, len(poses)) for _ in model.steps]

    def coefficients(kern, earlier):
        return np.array([np.broadcast_to(np.asarray(v, dtype=float), (len(poses),))
                         for v in kern(*cols, *earlier, *par)])

    for k, (_, kern, _) in enumerate(model.steps):
        base = coefficients(kern, roots[:k])
        moved = [r if j in model.step_uses[k] else r + rng.uniform(1.0, 2.0, len(poses))
                 for j, r in enumerate(roots[:k])]
        assert np.array_equal(coefficients(kern, moved), base), (k, model.step_uses[k])
        for j in model.step_uses[k]:
            other = list(roots[:k])
            other[j] = other[j] + 1.0
            assert not np.array_equal(coefficients(kern, other), base), (k, j)


@pytest.mark.parametrize("signs", ["positive", "negative", "mixed", "zero"])
def test_quadratic_roots_whatever_the_signs_of_b(signs):
    """The lean quadratic root divides only the branch that applies where B has one sign
    throughout the batch: the same numbers, bit for bit, as the rule written out per
    element (s = |B| + sqrt(disc); the +sqrt root s / 2A where B <= 0, -2C / s where
    B > 0; the -sqrt root s / -2A where B >= 0, 2C / s where B < 0), every mode, with B of
    one sign, of both, zero, and with NaN."""
    from bonered_alg.runtime.backsubstitution import _step_root

    rng = np.random.default_rng(21)
    n = 500
    a = rng.uniform(0.5, 2.0, n) * rng.choice([-1.0, 1.0], n)
    b = {"positive": rng.uniform(0.1, 3.0, n), "negative": -rng.uniform(0.1, 3.0, n),
         "mixed": rng.uniform(-3.0, 3.0, n), "zero": np.zeros(n)}[signs]
    c = -a * rng.uniform(0.0, 2.0, n)  # a c <= 0: real roots
    if signs == "mixed":
        b[7] = np.nan
    with np.errstate(all="ignore"):
        s = np.abs(b) + np.sqrt(b * b - 4.0 * a * c)
        expected = {0: np.where(b > 0.0, -2.0 * c / s, s / (2.0 * a)),
                    1: np.where(b < 0.0, 2.0 * c / s, s / (-2.0 * a))}
        for minus in (0, 1):
            dest = np.empty(n)
            _step_root(2, a, b, c, minus, dest)
            assert np.array_equal(dest, expected[minus], equal_nan=True), minus
    assert np.isfinite(expected[0]).sum() >= n - 1


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_fused_step_coefficients_are_the_step_kernels(name):
    """Where no IK step reads an earlier root, the module's ``_step_coefficients`` (one CSE
    program of every step's A, B, C: what the numpy runtime evaluates) gives each step
    kernel's coefficients to rounding, and the lean and detailed forms fed with it agree
    bit for bit, roots, NaN and status codes, in every working mode."""
    m = importlib.import_module(f"bonered_alg.generated.{name}")
    model = m._MODEL
    fused_kernel = model.step_coefficients
    if fused_kernel is None:  # some step reads an earlier root, or there is one step
        assert any(model.step_uses) or len(model.steps) <= 1
        return
    assert not any(model.step_uses)
    rng = np.random.default_rng(11)
    home = np.array(m.HOME) if getattr(m, "HOME", None) else np.zeros(len(m.POSE))
    scale = np.array([40.0 if u == "mm" else 0.4 for u in m.POSE_UNITS])
    poses = home + rng.uniform(-1.0, 1.0, (2000, len(m.POSE))) * scale
    poses[::89, 0] = np.nan
    par = [m.PARAMETERS[k] for k in m.PARAMETERS]
    study = stacked(model.study_values(poses, par), poses.shape[:-1])
    cols = [np.ascontiguousarray(study[..., i]) for i in range(study.shape[-1])]
    shape = (len(poses),)
    fused = fused_kernel(*cols, *par)
    assert len(fused) == 3 * len(model.steps)
    unread = [rng.uniform(0.5, 2.0, len(poses)) for _ in model.steps]  # no kernel reads them
    for k, (_, kern, _) in enumerate(model.steps):
        for got, want in zip(fused[3 * k:3 * k + 3], kern(*cols, *unread[:k], *par)):
            got, want = (np.broadcast_to(np.asarray(v, dtype=float), shape) for v in (got, want))
            assert np.array_equal(np.isnan(got), np.isnan(want))
            ok = np.isfinite(want)
            size = np.max(np.abs(want[ok]), initial=1.0)
            np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12 * size)
    codes = set()
    for mode in range(min(model.modes, 8)):
        args = (study, model.steps, model.solve_index, len(model.joints), mode, par)
        lean = backsubstitute_lean(*args, True, fused_kernel)
        _assert_same(lean, backsubstitute_detailed(*args, True, None, fused_kernel))
        every = dict(backsubstitute_modes(study, model.steps, model.solve_index,
                                          len(model.joints), [mode], par, model.step_uses,
                                          fused_kernel))
        assert np.array_equal(every[mode], lean[0], equal_nan=True)
        codes |= set(lean[1].tolist())
    assert st.OK in codes and len(codes) > 1  # valid poses and failures both
