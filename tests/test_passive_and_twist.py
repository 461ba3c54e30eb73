"""Passive-joint recovery and the twist Jacobian of the generated modules, against the
chains themselves and an independent rotation model (scipy), not the code under test."""

import importlib

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

from bonered_alg.registry import load

SEED = 404


def _rng(name):
    """A generator per mechanism and test, so the samples do not depend on the order the
    tests run in (pytest-xdist)."""
    return np.random.default_rng([SEED, sum(map(ord, name))])


def _poses(name, n):
    if name == "pro_hep_lct":
        return None
    rng = _rng(name)
    z = (230, 280) if name == "tripod_planar" else (190, 235)
    return np.column_stack([rng.uniform(-20, 20, n), rng.uniform(-20, 20, n),
                            rng.uniform(*z, n), rng.uniform(-0.2, 0.2, (n, 3))])


def _pro_hep_lct_poses(gen, n):
    """``n`` poses from joint values where the FK's mode 0 is real, so every pose is
    reachable (mode 0 of the IK)."""
    rng, out = _rng("pro_hep_lct"), []
    while sum(len(p) for p in out) < n:
        q = np.column_stack([rng.uniform(-0.3, 0.0, n), rng.uniform(0.0, 0.2, n),
                             rng.uniform(40, 120, n), rng.uniform(150, 200, n)])
        poses = gen.fk(q)[:, 0]
        out.append(poses[np.isfinite(poses).all(axis=-1)])
    return np.concatenate(out)[:n]


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar", "stewart", "pro_hep_lct"])
def test_passive_joints_close_every_leg(name):
    """With the IK's actuated joints and the recovered passive ones, each leg's chain
    product (sympy, from the declaration) is the closure's platform point."""
    gen = importlib.import_module(f"bonered_alg.generated.{name}")
    mech = load(name).MECHANISM
    assert gen.PASSIVE and not gen.PASSIVE_NOTES
    poses = _pro_hep_lct_poses(gen, 12) if name == "pro_hep_lct" else _poses(name, 12)
    q = gen.ik(poses, limits=False)
    passive = gen.passive_joints(poses)
    ok = np.isfinite(q).all(axis=-1)
    assert ok.sum() >= 8 and np.isfinite(passive[ok]).all()
    geo = {p.symbol: gen.PARAMETERS[p.name] for p in mech.parameters}
    consts = {c.symbol: float(c.value) for c in mech.constants}
    study_names = [sp.Symbol(s, real=True) for s in gen.STUDY_POSE]
    for closure in mech.actuated_closures:
        for leg in closure.legs:
            names = [s for s in leg.free_symbols if str(s) in gen.PASSIVE + gen.JOINTS]
            prod = sp.lambdify(names, [sp.sympify(c).subs({**geo, **consts})
                                       for c in leg.product()], "numpy")
            known, plat = _platform_point(closure, study_names, {**geo, **consts})
            for pose, qq, pp in zip(poses[ok], q[ok], passive[ok]):
                values = dict(zip(gen.JOINTS, qq)) | dict(zip(gen.PASSIVE, pp))
                chain = np.array(prod(*[values[str(s)] for s in names]), dtype=float)[known]
                study = gen._study(*pose, *gen.PARAMETERS.values())
                point = np.array([np.broadcast_to(v, ()) for v in plat(*study)], dtype=float)
                # projectively equal: the chain is a multiple of the platform point
                lam = chain @ point / (point @ point)
                err = np.abs(chain - lam * point).max() / np.abs(chain).max()
                assert err < 1e-9, (closure.name, leg.name, err)


def _platform_point(closure, study_names, values):
    """The coordinates of the closure's platform point that the pose map gives (a fixed one,
    e.g. Pu's yu3 = -Dz/2, is not a coordinate of the pose) and a function of the Study
    coordinates evaluating them."""
    known = [k for k, c in enumerate(closure.platform)
             if sp.sympify(c).free_symbols <= set(study_names)]
    return known, sp.lambdify(study_names, [sp.sympify(closure.platform[k]).subs(values)
                                            for k in known], "numpy")


def _independent_pose(pose):
    r = Rotation.from_euler("ZYX", pose[5:2:-1]).as_matrix()  # Rz(gamma) Ry(beta) Rx(alpha)
    return r, np.asarray(pose[:3])


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar", "stewart"])
def test_pose_twist_against_finite_differences(name):
    gen = importlib.import_module(f"bonered_alg.generated.{name}")
    h = 1e-6
    for pose in _poses(name, 5):
        twist = gen.pose_twist(pose)
        r, t = _independent_pose(pose)
        for k in range(6):
            e = np.zeros(6)
            e[k] = h
            (rp, tp), (rm, tm) = _independent_pose(pose + e), _independent_pose(pose - e)
            dr, dt = (rp - rm) / (2 * h), (tp - tm) / (2 * h)
            w = dr @ r.T
            omega = np.array([w[2, 1], w[0, 2], w[1, 0]])
            v = dt - np.cross(omega, t)
            assert np.allclose(twist[:, k], np.r_[omega, v], atol=1e-6), (name, k)


@pytest.mark.parametrize("name", ["planar_tripod", "stewart"])
def test_twist_jacobian_maps_joint_rates_to_the_twist(name):
    gen = importlib.import_module(f"bonered_alg.generated.{name}")
    pose = _poses(name, 3)
    tj = gen.twist_jacobian(pose, limits=False)
    J = gen.jacobian(pose, limits=False)
    assert np.allclose(tj @ J, gen.pose_twist(pose), atol=1e-9)


@pytest.mark.parametrize("name", ["planar_tripod", "pro_hep_lct"])
def test_link_poses_end_on_the_platform(name):
    """Each leg's last body, carried by the leg's trailing fixed factors (sympy, from the
    declaration, multiplied numerically), is the closure's platform point."""
    from bonered_alg.algebra import study_numeric as sn

    gen = importlib.import_module(f"bonered_alg.generated.{name}")
    mech = load(name).MECHANISM
    poses = _pro_hep_lct_poses(gen, 6) if name == "pro_hep_lct" else _poses(name, 6)
    links = gen.link_poses(poses)
    assert links.shape == poses.shape[:-1] + (len(gen.LINKS), 8)
    geo = {p.symbol: gen.PARAMETERS[p.name] for p in mech.parameters}
    consts = {c.symbol: float(c.value) for c in mech.constants}
    study_names = [sp.Symbol(s, real=True) for s in gen.STUDY_POSE]
    for closure in mech.actuated_closures:
        known, plat = _platform_point(closure, study_names, {**geo, **consts})
        for leg in closure.legs:
            moving = [k for k, j in enumerate(leg.joints) if j.kind != "offset"]
            tail = [f for j in leg.joints[moving[-1] + 1:] for f in j.factors]
            tail_point = np.array([float(sp.sympify(c).subs({**geo, **consts})) for c in (
                sp.Matrix(1, 8, list(_product(tail))))], dtype=float)
            last = gen.LINKS.index(f"{leg.name}.{len(moving)}")
            for pose, link in zip(poses, links[:, last]):
                chain = sn.product(link, tail_point)[known]
                study = gen._study(*pose, *gen.PARAMETERS.values())
                point = np.array([np.broadcast_to(v, ()) for v in plat(*study)], dtype=float)
                lam = chain @ point / (point @ point)
                assert np.abs(chain - lam * point).max() < 1e-9 * np.abs(chain).max(), leg.name


def _product(factors):
    from bonered_alg.algebra import study_symbolic as ss

    return ss.product(*[f.study() for f in factors])
