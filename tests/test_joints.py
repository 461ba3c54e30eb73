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


def matrix_of(factors, values):
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
    assert all(f.coupling and "atan(u1)" in f.coupling for f in hel)
    assert np.allclose(matrix_of(hel, {u1: np.tan(th / 2), s: 4.0 * th / (2 * np.pi)}),
                       rot("z", th) @ trans([0, 0, 4.0 * th / (2 * np.pi)]))


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
    leg = jt.Leg("L", tuple(jt.offset("O1", vector=(1.0, 2.0, 3.0))
                            + jt.revolute("R", "z", u1) + jt.offset("O2", axis="x", value=5.0)))
    th = 0.3
    got = np.array(ss.transform_from_study(leg.product()).subs({u1: np.tan(th / 2)}),
                   dtype=float)
    assert np.allclose(got, trans([1, 2, 3]) @ rot("z", th) @ trans([5, 0, 0]))
    assert {f.role for f in leg.factors} == {jt.Role.GEOMETRIC, jt.Role.PASSIVE}


def test_bad_joint_arguments():
    with pytest.raises(ValueError, match="universal joint U: needs two axes"):
        jt.universal("U", ("z",), (u1,))
    with pytest.raises(ValueError, match="axis must be one of"):
        jt.revolute("R", "w", u1)[0].study()
