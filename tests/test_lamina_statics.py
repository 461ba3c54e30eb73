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
