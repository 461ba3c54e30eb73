"""The static model of the lamina-milling robot (003 Sect. 2.3): the generated
static_efforts by virtual work against its free-body equilibrium, against the vertical
force balance, against -J_H^T F and against an independent potential-energy model (the
trigonometric model of tests/independent_lamina_milling.py, finite differences)."""

import dataclasses

import independent_lamina_milling as ind
import numpy as np
import pytest
from bonered_alg.generated import lamina_milling as m
from bonered_alg.generated import urrh_rcm

from bonered_alg.declaration import WeightPoint, validate
from bonered_alg.errors import MechanismDefinitionError
from bonered_alg.mechanisms import lamina_milling as decl

PAR = m.PARAMETERS
WEIGHTS = PAR["G1"] + PAR["G2"] + PAR["G7"]


def _sample(n, seed):
    rng = np.random.default_rng(seed)
    h = np.column_stack([rng.uniform(-25, 25, 3 * n), rng.uniform(90, 135, 3 * n),
                         rng.uniform(10, 110, 3 * n)])
    _, status = m.ik_and_status(h)
    h = h[status == 0][:n]
    return h, rng.normal(scale=5.0, size=h.shape)


def test_virtual_work_equals_the_free_body_equilibrium():
    h, F = _sample(300, 1)
    vw = m.static_efforts(h, F)
    fb = m.static_efforts(h, F, method="free_body")
    assert np.isfinite(vw).all() and len(h) == 300
    # relative to each pose's largest effort (N and N mm; 1 + for the unloaded near-zeros)
    scale = 1.0 + np.abs(vw).max(-1, keepdims=True)
    assert (np.abs(vw - fb) / scale).max() < 1e-9


def test_vertical_actuator_carries_the_upper_chain_and_the_platform():
    """No load: f = G1 + G2 + G7 at every pose (the bottom chains' cylinders slide along
    Z0 and their links turn at fixed heights); with a load, f = G1 + G2 + G7 - Fz."""
    h, F = _sample(100, 2)
    assert np.abs(m.static_efforts(h, np.zeros(3))[:, 0] - WEIGHTS).max() < 1e-9
    assert np.abs(m.static_efforts(h, F)[:, 0] - (WEIGHTS - F[:, 2])).max() < 1e-9
    # the bottom links' weights do no virtual work
    heavy = m.static_efforts(h, F, G3=50.0, G4=50.0, G5=50.0, G6=50.0)
    assert np.abs(heavy - m.static_efforts(h, F)).max() < 1e-9


def test_load_part_is_minus_jh_transpose_f():
    """tau(F) - tau(0) = -J_H^T F with J_H = dH/dq, the inverse of the independent IK's
    Jacobian (central differences)."""
    h, F = _sample(40, 3)
    part = m.static_efforts(h, F) - m.static_efforts(h, np.zeros(3))
    step = 1e-5
    for pose, load, got in zip(h, F, part):
        J = np.column_stack([(ind.ik_working(pose + step * e, PAR)
                              - ind.ik_working(pose - step * e, PAR)) / (2 * step)
                             for e in np.eye(3)])
        want = -np.linalg.inv(J).T @ load
        assert np.abs(got - want).max() < 1e-6 * (1.0 + np.abs(want).max())


def _potential(pose, par):
    """Potential energy of the weights (N mm) from plain geometry: the parallelogram's
    centre of gravity l2 from C towards E, DE with the slide, the platform at H; the
    bottom links stay at height 0."""
    L = ind.ik_working(pose, par)[0]
    zc, ze = pose[2], par["dD"] + L
    lam = par["l2"] / par["lEC"]
    return (par["G1"] * ((1 - lam) * zc + lam * ze) + par["G2"] * (par["dD"] + L)
            + par["G7"] * pose[2])


def test_efforts_against_an_independent_potential_energy_model():
    """J^T tau = grad V - F (the weights' potential V and the load's work), everything by
    central differences of the trigonometric model."""
    h, F = _sample(40, 4)
    got = m.static_efforts(h, F)
    step = 1e-5
    for pose, load, g in zip(h, F, got):
        J = np.column_stack([(ind.ik_working(pose + step * e, PAR)
                              - ind.ik_working(pose - step * e, PAR)) / (2 * step)
                             for e in np.eye(3)])
        grad = np.array([(_potential(pose + step * e, PAR) - _potential(pose - step * e, PAR))
                         / (2 * step) for e in np.eye(3)])
        want = np.linalg.solve(J.T, grad - load)
        assert np.abs(g - want).max() < 1e-6 * (1.0 + np.abs(want).max())


def test_bad_input():
    h = np.array(m.HOME)
    with pytest.raises(ValueError, match="load"):
        m.static_efforts(h, np.zeros(2))
    with pytest.raises(ValueError, match="method"):
        m.static_efforts(h, np.zeros(3), method="lagrange")
    with pytest.raises(ValueError, match="G1"):
        m.static_efforts(h, np.zeros(3), G1=-1.0)
    with pytest.raises(ValueError, match="finite"):
        m.static_efforts(h, np.array([np.nan, 0.0, 0.0]))
    assert not hasattr(urrh_rcm, "static_efforts")  # no link weights declared there
    # unreachable poses give NaN, not numbers
    out = m.static_efforts(np.array([0.0, 400.0, 50.0]), np.zeros(3))
    assert np.isnan(out).all()


def test_declaration_of_link_weights_is_checked():
    mech = decl.MECHANISM
    w = mech.link_weights[0]
    bad_body = dataclasses.replace(w, points=(WeightPoint("U.9", (0, 0, 0)),))
    with pytest.raises(MechanismDefinitionError, match="unknown body"):
        validate(dataclasses.replace(mech, link_weights=(bad_body,)))
    bad_share = dataclasses.replace(w, points=(WeightPoint("U.2", (0, 0, 0), 0.5),))
    with pytest.raises(MechanismDefinitionError, match="sum to 1"):
        validate(dataclasses.replace(mech, link_weights=(bad_share,)))


def test_link_weights_need_one_closure_on_the_fixed_base():
    """Stacked closures (a leg standing on another closure's platform) are refused with a
    clear error rather than given a wrong model."""
    from bonered_alg.mechanisms import planar_tripod as pt

    weight = decl.MECHANISM.link_weights[-1]  # on the platform
    mech = dataclasses.replace(pt.MECHANISM, link_weights=(weight,))
    with pytest.raises(MechanismDefinitionError, match="one actuated closure"):
        validate(mech)


@pytest.mark.parametrize("method", ["virtual_work", "free_body"])
def test_efforts_in_chunks_are_the_efforts_in_one_piece(method, monkeypatch):
    """static_efforts evaluates STATICS_CHUNK (FREE_BODY_CHUNK) poses at a time (100,000
    poses in one piece took 16 GB by the free-body method): with chunks of 7 (a leading
    shape of two axes, a load broadcast against the poses, unreachable and NaN poses among
    them) the efforts are those of one piece, to the bit."""
    from bonered_alg.runtime import model as runtime_model
    from bonered_alg.runtime import statics

    # numpy's IK and Jacobian, the reference (the fast path's own batch independence:
    # test_fast_path.test_a_poses_numbers_do_not_depend_on_its_batch)
    monkeypatch.setenv("BONERED_ALG_FAST", "0")
    h, F = _sample(60, 7)
    h[5] = [0.0, 500.0, 50.0]  # out of reach
    h[11, 1] = np.nan
    h = h.reshape(2, 30, 3)
    size = "FREE_BODY_CHUNK" if method == "free_body" else "STATICS_CHUNK"
    monkeypatch.setattr(runtime_model, size, 10 ** 9)
    whole = m.static_efforts(h, F[:30], method=method)
    monkeypatch.setattr(runtime_model, size, 7)
    sizes = []
    name = "free_body" if method == "free_body" else "efforts"
    inner = getattr(statics, name)
    monkeypatch.setattr(statics, name, lambda model, pose, *a: (sizes.append(len(pose)),
                                                                inner(model, pose, *a))[1])
    assert np.array_equal(m.static_efforts(h, F[:30], method=method), whole, equal_nan=True)
    assert sizes == [7] * 8 + [4]  # 60 poses in chunks of 7
    assert whole.shape == (2, 30, 3)
    assert np.isnan(whole[0, 5]).all() and np.isnan(whole[0, 11]).all()
    assert np.isfinite(whole).sum() == 3 * 58


def test_a_singular_row_does_not_change_the_others():
    """The statics' linear solves per row: an exactly singular system gives NaN (or the
    pseudo-inverse's least-squares solution) on its own row, not an error for the batch or
    another method for the other rows; the other rows are, to the bit, what they are
    alone."""
    from bonered_alg.runtime import statics

    rng = np.random.default_rng(4)
    a = rng.normal(size=(5, 3, 3))
    b = rng.normal(size=(5, 3, 1))
    a[2] = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]]  # rank 2
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.solve(a, b)
    x = statics._solve_or_nan(a, b)
    assert np.isnan(x[2]).all()
    for k in (0, 1, 3, 4):
        assert np.array_equal(x[k], np.linalg.solve(a[k], b[k]))
    # least squares: (6, 2) systems, one whose R has a zero on its diagonal
    a = rng.normal(size=(4, 6, 2))
    b = rng.normal(size=(4, 6, 3))
    a[1, :, 1] = 0.0
    x = statics._least_squares(a, b)
    for k in (0, 2, 3):
        assert np.array_equal(x[k], statics._least_squares(a[k:k + 1], b[k:k + 1])[0])
    assert np.allclose(x[1], np.linalg.pinv(a[1]) @ b[1])
