"""Every joint type's factors against homogeneous matrices built independently (numpy)."""

import numpy as np
import pytest
import sympy as sp

from bonered_alg.algebra import study_symbolic as ss
from bonered_alg.chains import joints as jt

u1, u2, s, q0, q1, q2, q3 = sp.symbols("u1 u2 s q0 q1 q2 q3", real=True)


def rot(axis, theta):
    c, sn = np.cos(theta), np.sin(theta)
    i = "xyz".index(axis)
    m = np.eye(4)
    j, k = (i + 1) % 3, (i + 2) % 3
    m[j, j], m[j, k], m[k, j], m[k, k] = c, -sn, sn, c
    return m


def trans(v):
    m = np.eye(4)
    m[:3, 3] = v
    return m


def matrix_of(joint, values):
    factors = joint.factors if isinstance(joint, jt.Joint) else joint
    study = ss.product(*[f.study() for f in factors])
    return np.array(ss.transform_from_study(study).subs(values), dtype=float)


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_revolute_and_prismatic(axis):
    th = 0.83
    got = matrix_of(jt.revolute("R", axis, u1), {u1: np.tan(th / 2)})
    assert np.allclose(got, rot(axis, th))
    e = np.zeros(3)
    e["xyz".index(axis)] = 12.5
    assert np.allclose(matrix_of(jt.prismatic("P", axis, s), {s: 12.5}), trans(e))


def test_cylindrical_and_helical():
    th, d = -1.1, 7.0
    cyl = jt.cylindrical("C", "z", u1, s)
    vals = {u1: np.tan(th / 2), s: d}
    assert np.allclose(matrix_of(cyl, vals), rot("z", th) @ trans([0, 0, d]))
    hel = jt.helical("H", "z", u1, s, pitch=4.0)
    # the coupling is typed and carried, not eliminated: s = pitch * theta (per radian)
    assert hel.coupling == jt.HelicalCoupling(u1, s, sp.Float(4.0))
    assert hel.dof == 1 and cyl.dof == 2 and hel.variables == (u1, s)
    assert np.allclose(matrix_of(hel, {u1: np.tan(th / 2), s: 4.0 * th}),
                       rot("z", th) @ trans([0, 0, 4.0 * th]))


def test_parallelogram_is_a_circular_translation():
    """The far link of a parallelogram moves on a circle and keeps its orientation."""
    th, link = 0.7, (30.0, 0.0, 5.0)
    par = jt.parallelogram("Pa", "y", u1, link)
    got = matrix_of(par, {u1: np.tan(th / 2)})
    assert np.allclose(got[:3, :3], np.eye(3))
    assert np.allclose(got[:3, 3], rot("y", th)[:3, :3] @ np.array(link))
    assert par.dof == 1 and par.variables == (u1,)
    with pytest.raises(ValueError, match="needs three coordinates"):
        jt.parallelogram("Pa", "y", u1, (1.0, 2.0))


def test_universal():
    a, b = 0.4, -0.9
    got = matrix_of(jt.universal("U", ("z", "y"), (u1, u2)), {u1: np.tan(a / 2),
                                                             u2: np.tan(b / 2)})
    assert np.allclose(got, rot("z", a) @ rot("y", b))


def test_spherical_is_any_rotation():
    axis = np.array([1.0, -2.0, 0.5])
    axis /= np.linalg.norm(axis)
    th = 2.5
    q = np.r_[np.cos(th / 2), np.sin(th / 2) * axis]
    got = matrix_of(jt.spherical("S", (q0, q1, q2, q3)), dict(zip((q0, q1, q2, q3), 3 * q)))
    kx = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    r = np.eye(3) + np.sin(th) * kx + (1 - np.cos(th)) * kx @ kx  # Rodrigues
    assert np.allclose(got[:3, :3], r)


def test_offsets_and_leg_order():
    leg = jt.leg("L", jt.offset("O1", vector=(1.0, 2.0, 3.0)), jt.revolute("R", "z", u1),
                 jt.offset("O2", axis="x", value=5.0))
    th = 0.3
    got = np.array(ss.transform_from_study(leg.product()).subs({u1: np.tan(th / 2)}),
                   dtype=float)
    assert np.allclose(got, trans([1, 2, 3]) @ rot("z", th) @ trans([5, 0, 0]))
    assert {f.role for f in leg.factors} == {jt.Role.GEOMETRIC, jt.Role.PASSIVE}


def test_bad_joint_arguments():
    with pytest.raises(ValueError, match="universal joint U: needs two axes"):
        jt.universal("U", ("z",), (u1,))
    with pytest.raises(ValueError, match="axis must be one of"):
        jt.revolute("R", "w", u1).factors[0].study()
    with pytest.raises(TypeError, match="expected Joint objects"):
        jt.leg("L", jt.revolute("R", "z", u1).factors)
