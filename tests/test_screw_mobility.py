"""Screw-theory mobility (bonered_alg.mobility.screws) against 003 Sect. 2.1 (its printed
joint screws, eq. 3, give its constraint systems, eq. 4, the common couple about Y, one
redundant constraint and M = 3, eq. 5-6, and pure translation) and against the textbook
counts of a 6-UPS platform (6) and a planar 3-RRR (3, order 3)."""

import numpy as np
import pytest

from bonered_alg.mobility import screws as sc

RNG = np.random.default_rng(2003)


def _span_equal(a, b) -> bool:
    a, b = np.atleast_2d(a), np.atleast_2d(b)
    return sc.rank(a) == sc.rank(b) == sc.rank(np.vstack([a, b]))


def _chains_003(v):
    """003 eq. (3) with the printed placeholders a1..b6 set to the values ``v``."""
    a1, b1, a2, b2, a3, b3, a4, b4, a5, b5, a6, b6 = v
    upper = np.array([[0, 0, 0, 0, 0, 1], [1, 0, 0, 0, a1, b1], [0, 0, 0, 0, a2, b2],
                      [0, 0, 0, 1, 0, 0]], dtype=float)
    bottom1 = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, a3, b3, 0], [0, 0, 1, a4, b4, 0],
                        [0, 0, 0, 0, 0, 1]], dtype=float)
    bottom2 = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, a5, b5, 0], [0, 0, 1, a6, b6, 0],
                        [0, 0, 0, 0, 0, 1]], dtype=float)
    # joints: J11-J14; J21, J22, J23 (cylindrical, two screws); the same for chain 3
    return [sc.ChainScrews("upper", upper, 4), sc.ChainScrews("bottom 1", bottom1, 3),
            sc.ChainScrews("bottom 2", bottom2, 3)]


def test_003_constraint_systems_order_redundancy_and_mobility():
    for _ in range(20):
        chains = _chains_003(RNG.uniform(-100.0, 100.0, 12))
        m = sc.mobility(chains)
        y, z, x = np.eye(6)[4], np.eye(6)[5], np.eye(6)[3]  # couples about Y, Z, X
        w = [sc.reciprocal(c.screws) for c in chains]
        assert _span_equal(w[0], [y, z])  # 003 eq. (4): S11r, S12r
        assert _span_equal(w[1], [x, y]) and _span_equal(w[2], [x, y])  # S21r.., S31r..
        assert _span_equal(m.common, [y])  # eq. (5): the common couple about Y
        assert (m.order, m.redundant, m.local) == (5, 1, 0)
        assert (m.links, m.joints, m.freedoms) == (9, 10, 12)
        assert m.kutzbach_grubler == 3  # eq. (6): 5 (9 - 10 - 1) + 12 + 1 = 3
        assert m.platform_dimension == 3 and m.translational and m.rotational_dimension == 0


def test_reciprocal_product_is_the_work_of_a_wrench_on_a_twist():
    """A force along a line does no work on a rotation about an axis meeting it, and the
    unit force along x does unit work per unit translation along x."""
    p = RNG.normal(size=3)
    axis = RNG.normal(size=3)
    force_dir = np.cross(axis, RNG.normal(size=3))
    twist = sc.revolute(axis, p)
    wrench = sc.revolute(force_dir, p)  # a force through p
    assert abs(sc.reciprocal_product(wrench, twist)) < 1e-12
    assert sc.reciprocal_product(sc.revolute([1, 0, 0], [0, 0, 0]),
                                 sc.prismatic([1, 0, 0])) == pytest.approx(1.0)


def _rot(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def test_a_6_ups_platform_has_six_freedoms_and_no_common_constraint():
    chains = []
    for _ in range(6):
        a, b = RNG.uniform(-100, 100, 3), RNG.uniform(-100, 100, 3) + [0, 0, 300]
        leg = (b - a) / np.linalg.norm(b - a)
        u1 = np.cross(leg, RNG.normal(size=3))
        u2 = np.cross(leg, u1)
        s = [sc.revolute(u1, a), sc.revolute(u2, a), sc.prismatic(leg),
             *[sc.revolute(e, b) for e in np.eye(3)]]
        chains.append(sc.ChainScrews("UPS", np.array(s), 4))  # U as two joints, S one
    m = sc.mobility(chains)
    assert (m.order, m.redundant, m.local, m.kutzbach_grubler) == (6, 0, 0, 6)
    assert m.platform_dimension == 6 and not m.translational


def test_a_planar_3_rrr_has_order_three_and_three_freedoms():
    chains = []
    for k in range(3):
        pts = RNG.uniform(-50, 50, (3, 2))
        s = [sc.revolute([0, 0, 1], [*p, 0.0]) for p in pts]
        chains.append(sc.ChainScrews(f"RRR{k}", np.array(s), 3))
    m = sc.mobility(chains)
    assert m.order == 3 and m.redundant == 0 and m.kutzbach_grubler == 3
    assert m.platform_dimension == 3 and m.rotational_dimension == 1


def test_an_ss_leg_has_a_local_freedom():
    """A leg with spherical joints at both ends spins about its own line: one local
    freedom, which the count subtracts."""
    a, b = np.zeros(3), np.array([10.0, 20.0, 300.0])
    s = [*[sc.revolute(e, a) for e in np.eye(3)], *[sc.revolute(e, b) for e in np.eye(3)]]
    m = sc.mobility([sc.ChainScrews("SS", np.array(s), 2)])
    assert m.local == 1 and m.kutzbach_grubler == 6 * (3 - 2 - 1) + 6 - 1


def test_bad_screws_get_a_clear_error():
    with pytest.raises(ValueError, match="chain 'x'.*shape"):
        sc.mobility([sc.ChainScrews("x", np.zeros((2, 5)), 2)])
    with pytest.raises(ValueError, match="at least one chain"):
        sc.mobility([])


def test_leg_screws_are_the_symbolic_twist_of_the_leg():
    """The numeric product rule of mobility.chains against kinematics.twist.pose_twist on
    the Study product (002's limb 1 and limb 2 at random joint values)."""
    import sympy as sp

    from bonered_alg.kinematics.twist import pose_twist
    from bonered_alg.mechanisms import urrh_rcm as U
    from bonered_alg.mobility.chains import leg_chain

    mech = U.MECHANISM
    par = {p.symbol: p.value for p in mech.parameters}
    limb1, limb2 = mech.closures[0].legs
    vals = {**par, **dict(zip((U.a1, U.b1, U.t1, U.s1), RNG.uniform(-0.8, 0.8, 4)))}
    chain = leg_chain(limb1, (), vals)
    ref = pose_twist(limb1.product(), (U.a1, U.b1, U.t1, U.s1))
    want = np.array(ref.subs(vals).evalf(), dtype=float).T
    assert np.allclose(chain.screws, want, rtol=1e-12, atol=1e-9)
    assert (chain.joints, chain.freedoms) == (4, 4)
    # limb 2 ends in collar 2's spin and its slide along the shaft (d2 - d1): a slide
    vals.update(dict(zip((U.a2, U.b2, U.t2, U.s2, U.k2), RNG.uniform(-0.8, 0.8, 5))))
    vals.update({U.d1: 70.0, U.d2: 60.0})
    c2 = leg_chain(limb2, (U.w1, U.w2, U.d1, U.d2), vals)
    assert (c2.joints, c2.freedoms, len(c2.screws)) == (6, 6, 6)
    e = sp.Symbol("e")
    moved = pose_twist(tuple(sp.sympify(c).subs(U.d2, U.d1 + e) for c in limb2.product()),
                       (U.a2, U.b2, U.t2, U.s2, U.k2, e))
    want2 = np.array(moved.subs({**vals, e: -10.0}).evalf(), dtype=float).T
    assert np.allclose(c2.screws, want2, rtol=1e-12, atol=1e-9)
