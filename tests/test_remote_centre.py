"""The remote-centre proof from the ideal (bonered_alg.analyses.remote_centre) on the
2-URRH limbs of 002: it proves the RCM property, refutes a wrong plane and a limb moved off
the centre, and the one configuration family it leaves out (coinciding limb planes, 002
Sect. 4.4) really loses the RCM: a real configuration of the declared chains with the shaft
20 mm from O, found by a numeric solve."""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import least_squares

from bonered_alg.analyses.remote_centre import RemoteCentre, certificate_holds
from bonered_alg.declaration import joint, leg
from bonered_alg.errors import MechanismDefinitionError
from bonered_alg.mechanisms import urrh_rcm as U
from bonered_alg.pipeline.algebra import Algebra

pytestmark = pytest.mark.xdist_group("remote_centre")
MECH = U.MECHANISM
PAR = {p.symbol: p.value for p in MECH.parameters}


def _run(analysis, mech=MECH):
    return analysis.run(SimpleNamespace(mechanism=mech), Algebra.default())


def test_the_limbs_prove_the_remote_centre():
    res = _run(U.REMOTE_CENTRE)
    assert certificate_holds()
    assert res.proved
    by_leg = {g.leg: g for g in res.legs}
    assert by_leg["2"].dropped == ("K2", "E2")  # the collar's spin and slide on the shaft
    assert by_leg["1"].dropped == ()
    # N = n1 x n2 vanishes only at a1 = +-1 and a2 = +-1 (alpha1 = alpha2 = +-pi/2)
    sols = sp.solve(list(res.degenerate), [U.a1, U.a2], dict=True)
    assert {(s[U.a1], s[U.a2]) for s in sols} == {(a, b) for a in (-1, 1) for b in (-1, 1)}


def test_a_wrong_plane_normal_is_refuted():
    a1 = U.a1
    wrong = RemoteCentre("rc", "shaft", {"1": (1 - a1**2, 0, 2 * a1),
                                         "2": U.REMOTE_CENTRE.normals["2"]})
    res = _run(wrong)
    first = next(g for g in res.legs if g.leg == "1")
    assert not first.direction_in_plane and not first.origin_in_plane and not res.proved


def test_a_limb_moved_off_the_centre_is_refuted():
    """Limb 1's plane moved 5 mm along its normal: its lines stay parallel to the plane
    through O but no longer lie in it."""
    limb = MECH.closures[0].legs[0]
    moved = leg("1", limb.joints[0],
                joint(U.NAME, "offset", "OFF", axis="y", value=sp.Integer(5),
                      description="limb plane moved along n1"),
                *limb.joints[1:])
    closure = replace(MECH.closures[0], legs=(moved, MECH.closures[0].legs[1]))
    res = _run(U.REMOTE_CENTRE, replace(MECH, closures=(closure,)))
    first = next(g for g in res.legs if g.leg == "1")
    assert first.direction_in_plane and not first.origin_in_plane and not res.proved


def test_check_names_the_mechanism_and_the_missing_leg():
    bad = RemoteCentre("rc", "shaft", {"1": U.REMOTE_CENTRE.normals["1"]})
    with pytest.raises(MechanismDefinitionError, match="urrh_rcm.*two legs"):
        bad.check(MECH)
    stray = RemoteCentre("rc", "shaft", {"1": (U.t1, 0, 1), "2": U.REMOTE_CENTRE.normals["2"]})
    with pytest.raises(MechanismDefinitionError, match="urrh_rcm.*actuated joints.*t1"):
        stray.check(MECH)


def _frame(legobj, drop=0):
    """The numeric 4x4 frame of a leg's chain (the last ``drop`` factors left out), as a
    function of its joint angles, through the declared factors."""
    factors = legobj.factors[:len(legobj.factors) - drop]
    syms = sorted(set().union(*(f.free_symbols for f in factors)) - set(PAR), key=str)
    mats = []
    for f in factors:
        if f.kind == "rotation":
            mats.append(("R", f.axis, f.args[0]))
        else:
            mats.append(("T", f.axis, sp.sympify(f.args[0]).subs(PAR)))

    def frame(values):
        env = dict(zip(syms, values))
        out = np.eye(4)
        for kind, axis, arg in mats:
            m = np.eye(4)
            k = "xyz".index(axis)
            if kind == "R":
                ang = 2 * np.arctan(float(sp.sympify(arg).subs(env)))
                c, s = np.cos(ang), np.sin(ang)
                i, j = [(1, 2), (2, 0), (0, 1)][k]
                m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
            else:
                m[k, 3] = float(arg)
            out = out @ m
        return out
    return syms, frame


def test_coinciding_planes_lose_the_remote_centre():
    """alpha1 = alpha2 = pi/2 (tan-halves 1): both limb planes are z = 0; the declared
    chains close with both collars on the line x = -20 mm, the shaft 20 mm from O."""
    l1, l2 = MECH.closures[0].legs
    s1, f1 = _frame(l1)
    s2, f2 = _frame(l2, drop=2)  # collar 2's frame, before its spin and slide
    assert [str(s) for s in s1] == ["a1", "b1", "s1", "t1"]
    assert [str(s) for s in s2] == ["a2", "b2", "s2", "t2"]
    c1, c2, u = np.array([-20.0, -10.0, 0.0]), np.array([-20.0, -60.0, 0.0]), np.array(
        [0.0, 1.0, 0.0])

    def residual(v):
        g1 = f1([1.0, *v[:3]])
        g2 = f2([1.0, *v[3:]])
        return np.concatenate([g1[:3, 3] - c1, g2[:3, 3] - c2,
                               np.cross(g1[:3, 2], u), np.cross(g2[:3, 2], u)])

    best = min((least_squares(residual, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
                for x0 in np.random.default_rng(3).uniform(-1.5, 1.5, (20, 6))),
               key=lambda r: np.abs(r.fun).max())
    assert np.abs(best.fun).max() < 1e-9
    g1 = f1([1.0, *best.x[:3]])
    p, d = g1[:3, 3], g1[:3, 2]
    assert np.linalg.norm(np.cross(p, d)) / np.linalg.norm(d) == pytest.approx(20.0, abs=1e-8)
