"""The per-call shortcuts of the runtime give what the full work gives: the checked
keyword parameters kept for the same objects (runtime.inputs.parameters), and the
compiled path's array addresses through the buffer protocol, with ctypes' own where the
array is read-only or empty (runtime.compiled._address)."""

import numpy as np
import pytest
from bonered_alg.generated import pro_hep_lct as ph
from bonered_alg.generated import stewart as st

from bonered_alg.runtime import compiled
from bonered_alg.runtime import inputs as check


def test_keywords_of_the_same_objects_are_checked_once_and_others_again():
    model = ph._MODEL
    geometry = {"l1": 181.0, "l2": 161.0}
    first = check.parameters(model, "ik", geometry)
    again = check.parameters(model, "ik", geometry)
    assert list(again) == list(first) and np.array_equal(again.vector, first.vector)
    assert again is not first  # a fresh list each call: callers may not share it
    # other objects, even in the same dict, are checked again: a bad value is an error
    geometry["l1"] = -5.0
    with pytest.raises(ValueError, match="l1"):
        check.parameters(model, "ik", geometry)
    with pytest.raises(ValueError, match="l1"):
        check.parameters(model, "ik", geometry)
    # an array keyword (mutable) is never taken from the record
    value = np.array(181.0)
    assert float(check.parameters(model, "ik", {"l1": value})[list(model.parameters).index(
        "l1")]) == 181.0
    value[()] = np.nan
    with pytest.raises(ValueError, match="l1"):
        check.parameters(model, "ik", {"l1": value})
    # the defaults changed under the same keywords: checked again
    geometry = {"l2": 161.0}
    check.parameters(model, "ik", geometry)
    old = model.parameters["l1"]
    try:
        model.parameters["l1"] = -1.0
        with pytest.raises(ValueError, match="l1"):
            check.parameters(model, "ik", geometry)
    finally:
        model.parameters["l1"] = old


def test_keywords_give_the_joints_of_the_full_check():
    poses = np.array([ph.HOME, np.add(ph.HOME, [1.0, -2.0, 3.0, 0.5])])
    geometry = {"l1": 181.0}
    want = ph.ik(poses, limits=False, fast=False, l1=181.0)
    for _ in range(3):  # the second and third from the record
        assert np.array_equal(ph.ik(poses, limits=False, fast=False, **geometry), want,
                              equal_nan=True)


@pytest.mark.skipif(st._MODEL.fast is None or st._MODEL.fast.library() is None,
                    reason="no compiled fast path here")
def test_read_only_and_empty_arrays_through_the_compiled_path():
    rng = np.random.default_rng(4)
    poses = np.asarray(st.HOME) + rng.uniform(-5.0, 5.0, (37, 6)) * [1, 1, 1, 0.01, 0.01, 0.01]
    want = st.ik_and_jacobian(poses, limits=False, fast=True)
    frozen = poses.copy()
    frozen.flags.writeable = False
    got = st.ik_and_jacobian(frozen, limits=False, fast=True)
    for a, b in zip(got, want):
        assert np.array_equal(a, b, equal_nan=True)
    q, J, status = st.ik_and_jacobian(np.empty((0, 6)), fast=True)
    assert q.shape == (0, 6) and J.shape == (0, 6, 6) and status.shape == (0,)
    a = np.arange(6.0)
    assert compiled._address(a) == a.ctypes.data
    a.flags.writeable = False
    assert compiled._address(a) == a.ctypes.data
