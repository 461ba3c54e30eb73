"""Study-parameter algebra pinned against pytransform3d (an independent implementation).

pytransform3d stores ``[p_w, p_x, p_y, p_z, q_w, q_x, q_y, q_z]`` with ``q = 1/2 t p``; our
convention (004 eq. 13, Husty) has ``y = -1/2 t x``, i.e. the dual part negated.
"""

import numpy as np
import pytest
import pytransform3d.rotations as pr
import pytransform3d.transformations as pt
import sympy as sp

from bonered_alg.algebra import convention as cv
from bonered_alg.algebra import study_numeric as sn
from bonered_alg.algebra import study_symbolic as ss

RNG = np.random.default_rng(20261122)


def random_transforms(n):
    return np.array(
        [pt.transform_from(pr.random_matrix(RNG), RNG.normal(scale=100.0, size=3))
         for _ in range(n)]
    )


def half_turn_transforms():
    out = []
    for axis in (np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, 1.0]),
                 np.array([1.0, 1.0, 0]) / np.sqrt(2), np.array([1.0, -2.0, 3.0]) / np.sqrt(14)):
        r = pr.matrix_from_axis_angle(np.r_[axis, np.pi])
        out.append(pt.transform_from(r, RNG.normal(scale=50.0, size=3)))
    return np.array(out)


def as_pytransform3d(study):
    s = sn.normalize(study)
    return np.concatenate([s[..., :4], -s[..., 4:]], axis=-1)


def same_dq(a, b):
    """Dual quaternions equal up to the double cover sign."""
    return np.allclose(a, b, atol=1e-9) or np.allclose(a, -b, atol=1e-9)


@pytest.mark.parametrize("transforms", [random_transforms(50), half_turn_transforms()])
def test_study_from_transform_matches_pytransform3d(transforms):
    s = sn.study_from_transform(transforms)
    for si, ti in zip(s, transforms):
        assert same_dq(as_pytransform3d(si), pt.dual_quaternion_from_transform(ti))
    assert np.allclose(sn.quadric(s), 0.0, atol=1e-9)
    assert np.allclose(np.linalg.norm(s[:, :4], axis=1), 1.0)


@pytest.mark.parametrize("transforms", [random_transforms(50), half_turn_transforms()])
def test_round_trip_transform(transforms):
    back = sn.transform_from_study(sn.study_from_transform(transforms))
    assert np.allclose(back, transforms, atol=1e-9)


def test_product_is_the_homomorphism_of_matrix_products():
    a, b = random_transforms(20), random_transforms(20)
    sab = sn.product(sn.study_from_transform(a), sn.study_from_transform(b))
    assert np.allclose(sn.transform_from_study(sab), a @ b, atol=1e-8)
    for ai, bi, si in zip(a, b, sab):
        ref = pt.concatenate_dual_quaternions(
            pt.dual_quaternion_from_transform(ai), pt.dual_quaternion_from_transform(bi)
        )
        # pytransform3d's concatenate_dual_quaternions(dq1, dq2) is the product dq1 * dq2
        assert same_dq(as_pytransform3d(si), ref)


def test_conjugate_is_inverse():
    s = sn.study_from_transform(random_transforms(10))
    ident = sn.normalize(sn.product(s, sn.conjugate(s)))
    assert np.allclose(ident, np.r_[1.0, np.zeros(7)], atol=1e-9)


def test_elementary_factors_match_matrices():
    phi, d = 0.7, 12.5
    rz = sn.transform_from_study(sn.rotation("z", np.tan(phi / 2)))
    assert np.allclose(rz[:3, :3], pr.active_matrix_from_angle(2, phi))
    ry = sn.transform_from_study(sn.rotation("y", np.tan(phi / 2)))
    assert np.allclose(ry[:3, :3], pr.active_matrix_from_angle(1, phi))
    tx = sn.transform_from_study(sn.translation(np.array([d, 0, 0])))
    assert np.allclose(tx[:3, 3], [d, 0, 0])
    # DESIGN.md section 3: translation t along x is [1:0:0:0:0:-t/2:0:0]
    assert np.allclose(sn.translation(np.array([d, 0, 0])), [1, 0, 0, 0, 0, -d / 2, 0, 0])


def test_symbolic_and_numeric_algebra_agree():
    u, s, v = sp.symbols("u s v")
    chain = ss.product(ss.rotation("z", u), ss.translation("x", s), ss.rotation("y", v))
    vals = {u: 0.3, s: 7.0, v: -1.2}
    num = sn.product(sn.product(sn.rotation("z", 0.3), sn.translation(np.array([7.0, 0, 0]))),
                     sn.rotation("y", -1.2))
    assert np.allclose([float(c.subs(vals)) for c in chain], num)
    assert ss.quadric(chain) == 0
    m = ss.transform_from_study(chain)
    assert np.allclose(np.array(m.subs(vals), dtype=float), sn.transform_from_study(num))


def test_symbolic_study_from_transform_all_ratios():
    phi = sp.Rational(1, 3)
    rz = ss.transform_from_study(ss.rotation("z", phi))
    for k in (0, 3):
        assert ss.projectively_equal(ss.study_from_transform(rz, k), ss.rotation("z", phi))
    with pytest.raises(ValueError, match="ratio 1"):
        ss.study_from_transform(rz, 1)


def test_printed_eq5_is_off_the_study_quadric():
    """004 eq. (5) as printed: y1 = -1/2 (tz x2 - ty x3 + tx x0).  It violates eq. (3)."""
    t = RNG.normal(size=3)
    x = sn.study_from_transform(random_transforms(1))[0, :4]
    tx, ty, tz = t
    x0, x1, x2, x3 = x
    printed = [-(tz * x3 + ty * x2 + tx * x1) / 2, -(tz * x2 - ty * x3 + tx * x0) / 2,
               -(-tz * x1 - ty * x0 + tx * x3) / 2, -(-tz * x0 + ty * x1 - tx * x2) / 2]
    assert abs(np.dot(x, printed)) > 1e-6
    ours = cv.dual_part_from_translation(t, x)
    assert abs(np.dot(x, ours)) < 1e-12
