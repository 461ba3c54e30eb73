"""Forward kinematics of the two tripod mechanisms (000 planar_tripod, 001 tripod_planar).

Neither paper gives the tripod's forward kinematics (issue 3, item 6), so the references are
independent computations: the pose the IK started from, the IK of every returned mode, and
an exact count of the real assembly modes from the plain leg geometry (sympy resultants and
real-root isolation over Q, no code under test).
"""

import importlib
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from forward_singular_lines import singular_heights

RNG = np.random.default_rng(33)
TRIPOD_MODES, PLANAR_MODES = 16, 2


def _module(name):
    return importlib.import_module(f"bonered_alg.generated.{name}")


def _poses(name, n):
    z = (230, 280) if name == "tripod_planar" else (190, 235)
    p = np.column_stack([RNG.uniform(-20, 20, n), RNG.uniform(-20, 20, n),
                         RNG.uniform(*z, n), RNG.uniform(-0.2, 0.2, (n, 3))])
    p[0] = (0.0, 0.0, sum(z) / 2, 0.0, 0.0, 0.0)  # home: vertical legs, u = 0 exactly
    return p


def _pose_error(a, b):
    d = a - b
    d[..., 3:] = np.angle(np.exp(1j * d[..., 3:]))
    return np.abs(d).max(axis=-1)


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_fk_returns_the_pose_ik_started_from(name):
    m = _module(name)
    assert m.FK_MODES == TRIPOD_MODES * PLANAR_MODES and m.RPS_MODES == TRIPOD_MODES
    pose = _poses(name, 200)
    q = m.ik(pose, limits=False)
    assert np.isfinite(q).all()
    sols = m.fk(q)
    assert sols.shape == (200, m.FK_MODES, 6)
    err = np.nanmin(_pose_error(sols, pose[:, None, :]), axis=1)
    assert err.max() < 1e-9, err.max()


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_every_real_mode_has_the_given_joints(name):
    """Each real assembly mode is a pose whose IK (some working mode) gives back q."""
    m = _module(name)
    q = m.ik(_poses(name, 20), limits=False)
    sols, status = m.fk(q), m.fk_status(q)
    ok = status == m.OK
    real = ok | (status == m.INPUT_SINGULAR) | (status == m.FORWARD_SINGULAR)
    assert (np.isfinite(sols).all(axis=-1) == real).all(), "NaN exactly where not real"
    for k in range(len(q)):
        back = m.ik_all(sols[k][ok[k]], limits=False)  # (n_ok, MODES, 6)
        err = np.nanmin(np.abs(back - q[k]).max(axis=-1), axis=-1)
        assert err.max() < 1e-7, (k, err)
        # an input-singular mode: the IK of its pose cannot give joints back in any mode
        singular = sols[k][status[k] == m.INPUT_SINGULAR]
        if len(singular):
            codes = np.stack([m.jacobian_status(singular, mode, limits=False)
                              for mode in range(m.MODES)])
            assert (codes != m.OK).all()


def _exact_real_modes(legs, platform, q):
    """Number of real solutions of |B_i - B_j| = |P_i - P_j| with each leg's centre
    B_k = C_k + q_k (sin t rho_k + cos t e_z) (radial plane rho_k): the iterated resultant
    over Q, its real roots isolated exactly, the other two angles at 60 digits."""
    u = sp.symbols("u1:4")
    pts = []
    for (c, rho), qk, uk in zip(legs, q, u):
        # angle t = psi + phi with tan(psi/2) = u and cos phi = 3/5, sin phi = 4/5: no
        # solution sits at u = infinity (the mirror of a vertical leg, t = pi, does not)
        sp_, cp = 2 * uk / (1 + uk**2), (1 - uk**2) / (1 + uk**2)
        s, co = sp_ * sp.Rational(3, 5) + cp * sp.Rational(4, 5), (
            cp * sp.Rational(3, 5) - sp_ * sp.Rational(4, 5))
        pts.append([c[i] + qk * s * rho[i] + (qk * co if i == 2 else 0) for i in range(3)])
    eqs = []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        d2 = sum((pts[i][k] - pts[j][k]) ** 2 for k in range(3)) - sum(
            (platform[i][k] - platform[j][k]) ** 2 for k in range(3))
        eqs.append(sp.factor(sp.numer(sp.together(d2))))
    # drop the factors 1 + u_k^2 (no real zeros) and numeric content
    eqs = [sp.Mul(*[f**e for f, e in sp.factor_list(x)[1] if len(f.free_symbols) > 1])
           for x in eqs]
    r = sp.resultant(sp.resultant(eqs[0], eqs[1], u[1]), eqs[2], u[2])
    scale = max(abs(c) for c in sp.Poly(eqs[1], u[1], u[2]).coeffs())
    count = 0
    # every real root of the eliminant (exact isolation), then the real (u2, u3) over it that
    # satisfy all three equations, at 60 digits: solutions are counted, not their projections
    for root in sp.Poly(r, u[0]).sqf_part().real_roots():
        r1 = sp.N(root, 60)

        def real_roots(e, v, r1=r1):
            return [z for z in sp.Poly(sp.expand(e.subs(u[0], r1)), v).nroots(n=50)
                    if abs(sp.im(z)) < 1e-30]

        pairs = {(sp.re(a), sp.re(b)) for a in real_roots(eqs[0], u[1])
                 for b in real_roots(eqs[2], u[2])
                 if abs(eqs[1].subs({u[1]: sp.re(a), u[2]: sp.re(b)}))
                 < 1e-25 * scale * (1 + sp.re(a) ** 2) * (1 + sp.re(b) ** 2)}
        count += len(pairs)
    return count


def _geometry(name):
    s3 = sp.sqrt(3)
    if name == "tripod_planar":  # 001 eq. (1)-(2): corners at -30, 90, 210 deg, r = 200
        ra = rb = 200
        rho = [(s3 / 2, -sp.Rational(1, 2), 0), (0, 1, 0), (-s3 / 2, -sp.Rational(1, 2), 0)]
        legs = [((ra * r[0], ra * r[1], 0), r) for r in rho]
        return legs, [(rb * r[0], rb * r[1], 0) for r in rho], (0, 1, 2)
    ra = rb = 190  # 000 eq. (7), (18): C_k and D_k on the x and y axes
    rho = [(1, 0, 0), (0, 1, 0), (-1, 0, 0)]
    legs = [((ra * r[0], ra * r[1], 0), r) for r in rho]
    return legs, [(rb * r[0], rb * r[1], 0) for r in rho], (3, 4, 5)


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_number_of_real_modes_is_exact(name):
    m = _module(name)
    legs, platform, cols = _geometry(name)
    q = m.ik(_poses(name, 4), limits=False)
    status = m.fk_status(q).reshape(len(q), TRIPOD_MODES, PLANAR_MODES)
    for k in range(len(q)):
        exact = _exact_real_modes(legs, platform,
                                  [sp.Rational(Fraction(float(q[k, c]))) for c in cols])
        found = int((status[k] == m.OK).any(axis=-1).sum())
        assert found == exact, (k, found, exact)


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_unassemblable_leg_lengths_are_reported(name):
    m = _module(name)
    q = m.ik(_poses(name, 1), limits=False)[0]
    legs = [0, 1, 2] if name == "tripod_planar" else [3, 4, 5]
    q[legs] = (50.0, 50.0, 900.0)  # one leg longer than the other two can reach
    status = m.fk_status(q)
    assert np.isnan(m.fk(q)).all()
    assert set(np.unique(status)) <= {m.NO_REAL_SOLUTION}


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_forward_singularity_is_where_two_assembly_modes_merge(name):
    """At a zero of det d(e12, e23, e31)/d(u) along a line in z, the pose's assembly mode
    meets another one: the forward kinematics folds there, so at the joints of the pose at
    z* - h the other mode is (to first order) the pose at z* + h, about 2 h away; far from
    z* the nearest other mode is far."""
    m = _module(name)
    base = np.array([5.0, -3.0, 0.0, 0.3, -0.2, 0.1])
    crossings = singular_heights(m, base, np.linspace(40.0, 300.0, 131), count=1)
    assert crossings, "the line crosses a forward singularity"
    z_star = crossings[0]

    def other_mode(zz):
        pose = np.array([*base[:2], zz, *base[3:]])
        err = np.sort(_pose_error(m.fk(m.ik(pose, limits=False)), pose[None, :]))
        assert err[0] < 1e-6  # the pose itself is one of the modes
        return err[1]

    for h in (0.1, 0.01):
        assert 0.5 * h < other_mode(z_star - h) < 10 * h, (z_star, h, other_mode(z_star - h))
    assert other_mode(z_star - 20.0) > 1.0
