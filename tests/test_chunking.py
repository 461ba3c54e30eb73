"""Every vectorized function of the generated modules evaluates its poses in chunks (memory
bounded at any batch size): with chunks of 7 the values are those of one piece, to the bit,
for each of the six mechanisms (the numpy runtime, the reference; the fast path's own batch
independence is test_fast_path.test_a_poses_numbers_do_not_depend_on_its_batch), and the
chunks are the size asked for."""

import importlib

import numpy as np
import pytest

from bonered_alg.runtime import model as runtime_model

MECHANISMS = ["planar_tripod", "tripod_planar", "pro_hep_lct", "stewart", "urrh_rcm",
              "lamina_milling"]


def _poses(m, n=50, seed=3):
    """Poses around HOME (some out of reach), one not finite, as a (2, n/2) batch."""
    rng = np.random.default_rng(seed)
    scale = np.array([0.15 if u == "rad" else 8.0 for u in m.POSE_UNITS])
    poses = np.array(m.HOME) + rng.normal(size=(n, len(m.POSE))) * scale
    poses[4, 0] = np.nan
    return poses.reshape(2, n // 2, len(m.POSE))


FUNCTIONS = {
    "singularities": lambda m, p, q: m.singularities(p, q),
    "limit_values": lambda m, p, q: m.limit_values(p, q),
    "input_jacobian": lambda m, p, q: m.input_jacobian(p, q),
    "output_jacobian": lambda m, p, q: m.output_jacobian(p, q),
    "ik_joint_status": lambda m, p, q: m.ik_joint_status(p),
    "passive_joints": lambda m, p, q: m.passive_joints(p),
    "link_poses": lambda m, p, q: m.link_poses(p),
}


def _same(a, b):
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("name", MECHANISMS)
def test_chunks_give_the_values_of_one_piece(name, monkeypatch):
    monkeypatch.setenv("BONERED_ALG_FAST", "0")
    m = importlib.import_module(f"bonered_alg.generated.{name}")
    poses = _poses(m)
    q = m.ik(poses, limits=False)
    assert np.isfinite(q).any() and np.isnan(q).any()
    inner = runtime_model._rows_in_chunks
    sizes = []

    def spy(arrays, par, fn, size=None):
        def recorded(*rows):
            sizes.append(len(rows[0]))
            return fn(*rows)
        return inner(arrays, par, recorded, size)

    for func, call in FUNCTIONS.items():
        monkeypatch.setattr(runtime_model, "CHUNK", 10 ** 9)
        whole = call(m, poses, q)
        monkeypatch.setattr(runtime_model, "CHUNK", 7)
        monkeypatch.setattr(runtime_model, "_rows_in_chunks", spy)
        sizes.clear()
        got = call(m, poses, q)
        monkeypatch.setattr(runtime_model, "_rows_in_chunks", inner)
        assert _same(got, whole), f"{name}.{func}"
        if func == "limit_values" and not m.LIMITS:
            assert whole == {}
            continue
        # 50 poses in chunks of 7 (those of the IK inside passive_joints and link_poses too)
        assert sizes and max(sizes) == 7 and sizes.count(7) == 7 * (sum(sizes) // 50), \
            f"{name}.{func}: chunks {sizes}"
        values = whole.values() if isinstance(whole, dict) else [whole]
        assert all(np.asarray(v).shape[:2] == (2, 25) for v in values), f"{name}.{func}"
