"""Forward kinematics where it is hardest (issue 13, item 1): configurations built on purpose
on a basis's pivot locus and at forward singularities, and within 1e-3..1e-12 of them.

The contract checked here: a mode returned with status OK is a true assembly (held against
an independent computation, never the code under test); no real assembly is lost where the
configuration is regular; where the answer is uncertain the status says so
(FORWARD_SINGULAR with the pose, UNVERIFIED with NaN).
"""

import importlib

import numpy as np
import pytest
from forward_singular_lines import singular_heights


def _module(name):
    return importlib.import_module(f"bonered_alg.generated.{name}")


# ----------------------------------------------------------------- Pro-Hep-LCT, t1 = +-w1
def _lower_assemblies(par, t1, w1):
    """Pd of the lower mechanism (004 Sect. 3.2.2) from its two elbows, as the intersection
    of two circles in closed form (independent of the lex basis): centres (0, d/2) + l1 e(th)
    and (0, lq4d - d/2) + l3 e(ph), radii l2 and l4; the generated Pd is -2 (yd1, yd2)."""
    th, ph = 2 * np.arctan(t1), 2 * np.arctan(w1)
    c1 = np.array([0.0, par["d"] / 2]) + par["l1"] * np.array([np.cos(th), np.sin(th)])
    c2 = np.array([0.0, par["lq4d"] - par["d"] / 2]) + par["l3"] * np.array(
        [np.cos(ph), np.sin(ph)])
    dv = c2 - c1
    dd = np.hypot(*dv)
    a = (par["l2"] ** 2 - par["l4"] ** 2 + dd ** 2) / (2 * dd)
    h2 = par["l2"] ** 2 - a ** 2
    if h2 < 0:
        return []
    mid, perp = c1 + a * dv / dd, np.array([-dv[1], dv[0]]) / dd
    return [mid + np.sqrt(h2) * perp, mid - np.sqrt(h2) * perp]


def test_independent_circle_model_matches_fk_at_a_regular_configuration():
    m = _module("pro_hep_lct")
    par = dict(m.PARAMETERS)
    q = np.array([0.4, -0.7, 160.0, 200.0])
    exact = _lower_assemblies(par, *q[:2])
    assert len(exact) == 2
    got = m.fk(q)[:, 2:]
    for e in exact:
        assert np.nanmin(np.abs(got - e).max(axis=-1)) < 1e-9


@pytest.mark.parametrize("delta", [0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-2])
def test_lower_lex_basis_pivot_locus(delta):
    """With l1 = l3 (as recovered from 004 Table 5) the linear step of the lower lex basis
    in yd1 has the pivot 8 l1 (t1^2 - w1^2): it vanishes on t1 = +-w1, 004's sg3, which is
    no singularity.  There no mode may come back wrong under OK (the issue measured 10 mm to
    4e8 mm under ON_BOUNDARY, and NaN on the line itself); modes that are not returned are
    NaN; every assembly is found under OK (through the basis in the other order), on the
    line as well as near it."""
    m = _module("pro_hep_lct")
    par = dict(m.PARAMETERS)
    assert par["l1"] == par["l3"]
    rng = np.random.default_rng(13)
    for _ in range(40):
        w1 = rng.uniform(-1.5, 1.5)
        t1 = rng.choice([1.0, -1.0]) * w1 + delta
        q = np.array([t1, w1, 160.0, 200.0])
        sols, status = m.fk(q), m.fk_status(q)
        exact = _lower_assemblies(par, t1, w1)
        lower = sols[:, 2:]
        for p, s in zip(lower, status):
            if s in (m.OK, m.FORWARD_SINGULAR):
                assert exact and min(np.abs(p - e).max() for e in exact) < 1e-6, (t1, w1, p)
            else:
                assert np.isnan(p).all()
        ok = [p for p, s in zip(lower, status) if s == m.OK]
        for e in exact:
            assert ok and min(np.abs(p - e).max() for p in ok) < 1e-8, (t1, w1)
        if not exact:
            assert (status == m.NO_REAL_SOLUTION).all(), (t1, w1, status)


# ----------------------------------------------------------- 3-RPS forward singularities
def _pose_error(a, b):
    d = a - b
    d[..., 3:] = np.angle(np.exp(1j * d[..., 3:]))
    return np.abs(d).max(axis=-1)


@pytest.mark.parametrize("name,seed,lines,crossings", [("planar_tripod", 11, 12, 5),
                                                       ("tripod_planar", 3, 60, 1)])
def test_forward_singularities_lose_no_pose(name, seed, lines, crossings):
    """At and near (1e-9, 1e-6, 1e-3 mm either side) the forward singularities crossed by
    vertical lines of poses: the pose the IK started from is a returned mode (to 1e-8 mm
    under OK; to 1e-3 mm under FORWARD_SINGULAR, where two modes merge and the pose is
    determined only to about sqrt(eps) over the fold's curvature); every OK mode gives the
    joints back through the IK.  The issue found the real pose dropped at 2 of 9 such
    configurations and FORWARD_SINGULAR raised at only 2."""
    m = _module(name)
    rng = np.random.default_rng(seed)
    lo = 100.0 if name == "tripod_planar" else 40.0
    checked = 0
    for _ in range(lines):
        base = np.array([*rng.uniform(-30, 30, 2), 0.0, *rng.uniform(-0.4, 0.4, 3)])
        for z_star in singular_heights(m, base, np.linspace(lo, 340.0, 301)):
            for h in (0.0, 1e-9, -1e-9, 1e-6, -1e-6, 1e-3, -1e-3):
                pose = np.array([*base[:2], z_star + h, *base[3:]])
                q = m.ik(pose, limits=False)
                sols, status = m.fk(q), m.fk_status(q)
                err = _pose_error(sols, pose[None, :])
                ok_hit = (status == m.OK) & (err < 1e-8)
                fs_hit = (status == m.FORWARD_SINGULAR) & (err < 1e-3)
                assert (ok_hit | fs_hit).any(), (name, base, z_star, h, np.nanmin(err))
                ok = sols[status == m.OK]
                back = m.ik_all(ok, limits=False)
                if len(ok):
                    assert np.nanmin(np.abs(back - q).max(axis=-1), axis=-1).max() < 1e-6
                checked += 1
    assert checked >= 7 * crossings, checked


# ----------------------------------------------------------------- the 3-RPS's half-turn mode
def _assembly_error(ind, pose, q):
    """How far the joints of the pose's nearest split (the independent model's every split
    into B and the planar stage) are from ``q``, relative to the largest joint."""
    return min((np.abs(np.abs(j) - np.abs(q)).max() for j in ind.all_joints(pose)),
               default=np.inf) / np.abs(q).max()


@pytest.mark.parametrize("q", [(-532.24, 526.74, 309.13, -139.62, 525.94, 233.11),
                               (210.0, 210.0, 210.0, 230.94010768, 230.94010768,
                                230.94010768)])
def test_tripod_planar_ok_poses_are_assemblies_of_their_joints(q):
    """The 3-RPS has a second operation mode, x0 = 0 (the platform turned by a half-turn), off
    the chart x0 = 1 of its Study coordinates.  At the first q, 4 of its 16 assemblies lie on
    it: there 1 + trace R is rounding noise, and the chart gave finite, meaningless
    coordinates (x = (-1, -2, -0.75)), three poses of them returned under OK, 3-130 mm from
    every assembly.  Every OK pose must split into B and the planar stage with these joints
    (tests/independent_tripod_planar.py, every split); the half-turn ones are OUTSIDE_CHART
    with NaN.  The second q is home."""
    import independent_tripod_planar as ind

    m = _module("tripod_planar")
    q = np.array(q)
    sols, status = m.fk(q), m.fk_status(q)
    assert (status == m.OK).sum() >= 4
    for pose in sols[status == m.OK]:
        assert _assembly_error(ind, pose, q) < 1e-9, pose
    assert np.isnan(sols[status == m.OUTSIDE_CHART]).all()


def test_tripod_planar_ok_poses_are_assemblies_far_from_home():
    """The same on joints of random poses up to 80 mm and 1 rad from home, every working
    mode (negative strokes too: the algebra's joints are signed); before CHART_TOL, 6 of the
    98 OK modes of these 12 configurations were no assembly of their joints (4-17 of about
    100 for 23 of 30 seeds)."""
    import independent_tripod_planar as ind

    m = _module("tripod_planar")
    rng = np.random.default_rng(0)
    home = np.array(m.HOME)
    poses = home + rng.uniform(-1, 1, (40, 6)) * np.array([80, 80, 80, 1, 1, 1])
    q = np.concatenate([m.ik(poses[k::8], mode=k, limits=False) for k in range(8)])
    q = q[np.isfinite(q).all(axis=-1)][:12]
    sols, status = m.fk(q), m.fk_status(q)
    checked = 0
    for c in range(len(q)):
        for pose in sols[c][status[c] == m.OK]:
            assert _assembly_error(ind, pose, q[c]) < 1e-9, (q[c], pose)
            checked += 1
    assert checked >= 40, checked


# ----------------------------------------------------------------- polish hands verify its system
def _configurations(m, rng, tries, keep, perturbed, spread):
    """Joints (user's units) of up to ``keep`` random poses around home that the IK solves
    (mm coordinates within 20 mm, angles within 0.3 rad), then ``perturbed`` of them
    scaled by 1 +- ``spread`` (some modes no longer real) and two rows of NaN."""
    home = np.array([0.0 if v is None else v for v in m.HOME])
    scale = np.array([20.0 if u == "mm" else 0.3 for u in m.POSE_UNITS])
    q = m.ik(home + rng.uniform(-1, 1, (tries, len(home))) * scale, limits=False)
    q = q[np.isfinite(q).all(axis=-1)][:keep]
    return np.concatenate([q, q[:perturbed] * rng.uniform(1 - spread, 1 + spread,
                                                          q[:perturbed].shape),
                           np.full((2, q.shape[1]), np.nan)])


@pytest.mark.parametrize("name", ["urrh_rcm", "pro_hep_lct", "lamina_milling"])
def test_verify_on_the_system_polish_kept_decides_as_a_fresh_evaluation(name):
    """:func:`polish` returns the residuals and Jacobian of each row's last evaluation (at
    most one step below STEP_RTOL before the polished unknowns) and :func:`verify` takes
    them instead of evaluating the Newton kernel again.  Held against the kernel evaluated
    at the polished unknowns: the same Jacobian to rounding (each row to its own scale),
    and the same verdicts and unknowns in every mode, on configurations from the IK,
    perturbed ones (some modes not real) and NaN joints."""
    from bonered_alg.runtime import fk as fk_solver
    from bonered_alg.runtime.backsubstitution import backsubstitute

    m = _module(name)
    model = m._MODEL
    spec = model.fk
    q = model.algebraic(_configurations(m, np.random.default_rng(3), 400, 400, 100, 0.3))
    par = [np.asarray(v, dtype=float) for v in m.PARAMETERS.values()]
    n, checked = len(spec.unknowns), 0
    for mode in range(2 ** len(spec.mode_bits)):
        study, status = backsubstitute(q, spec.steps, spec.index, n, mode, par, True)
        polished, (f, jac) = fk_solver.polish(spec, q, study, par)
        f0, jac0 = fk_solver.closure_system(spec, q, polished, par)
        rows = np.isfinite(polished).all(axis=-1)
        assert np.isnan(jac[~rows]).all()
        # each equation at its own scale (the generators' units differ), as verify scales it
        scale_j = 1.0 + np.abs(jac0[rows]).max(axis=-1, keepdims=True)
        assert (np.abs(jac[rows] - jac0[rows]) <= 1e-9 * scale_j).all()
        kept = fk_solver.verify(spec, q, polished, par, status, (f, jac))
        fresh = fk_solver.verify(spec, q, polished, par, status)
        assert np.array_equal(kept[1], fresh[1])
        assert np.array_equal(kept[0], fresh[0], equal_nan=True)
        checked += int(rows.sum())
    assert checked > 400


def test_verify_rejects_a_least_squares_point_that_is_no_solution():
    """An overdetermined closure (urrh_rcm: 11 generators in 4 unknowns) has least-squares
    points where J^T f = 0 and f is not, and a Gauss-Newton step there is zero: verify
    must still reject such a point (its residual test), and accept the same Jacobian with
    f at rounding.  Rows of unit norm at x = 0, so that equilibration changes nothing."""
    from bonered_alg.runtime import fk as fk_solver
    from bonered_alg.runtime.status import OK, UNVERIFIED

    jac = np.array([[[1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [1.0, 0.0]]] * 2)
    x = np.zeros((2, 2))
    f = np.array([[0.0, 1e-4, 1e-4, 0.0],  # J^T f = 0: a stationary point, no root
                  [1e-17, -2e-17, 0.0, 0.0]])  # a root to rounding
    study, status = fk_solver.verify(None, None, x, None, np.zeros(2, dtype=np.int8),
                                     (f, jac))
    assert status.tolist() == [UNVERIFIED, OK]
    assert np.isnan(study[0]).all() and np.array_equal(study[1], x[1])


# urrh_rcm configurations with alpha2 near a half-turn whose assemblies 05dd4b0..325b523 lost
# (UNVERIFIED), from the IK of random poses near home (two fuzz runs: 3 of 45,200
# configurations and 5 of 30,804 assemblies lost)
HALF_TURN_CONFIGURATIONS = (
    (-0.013671271939181582, 3.137764292837258, 1.022729316460777, 0.14832293569801402),
    (-0.03518910200902355, 3.111412492357666, -0.057426446755056065, 0.8500186110500498),
    (-0.04767760022188687, -3.1161251916438437, -0.06009681851874621, 0.8637465494193429),
    (-0.04767760022188687, -3.1161251916438437, 1.0426513947834035, 0.8637465494193429),
    (-0.04087256697857188, -3.1296729123123783, 1.0385744119170328, 0.14786140056071453),
    (-0.04846061338574577, 3.1311344512956665, 1.0161911295124377, 0.10509781683199995),
)


def test_urrh_rcm_joint_near_a_half_turn_loses_no_assembly():
    """A U joint near a half-turn (alpha2 -> pi: its tan-half-angle ~ 500) makes the rows of
    the leg generators' Jacobian differ by up to 16 orders of magnitude.  Gauss-Newton on the
    raw normal equations (condition squared) moved a correct lex-basis solution 5 mm off and
    the check declared the mode UNVERIFIED: the assembly was lost.  Every assembly of the
    independent model (tests/independent_urrh_rcm.py: plain vectors, 002 eq. (8)) must come
    back under OK (these six configurations, in one batch)."""
    from independent_urrh_rcm import fk_all

    m = _module("urrh_rcm")
    par = dict(m.PARAMETERS)
    qs = np.array(HALF_TURN_CONFIGURATIONS)
    sols, status = m.fk(qs), m.fk_status(qs)
    found = 0
    for q, sol, st in zip(qs, sols, status):
        exact = fk_all(q, par)
        assert len(exact) == 4
        for e in exact:
            err = np.abs(sol - e)
            err[:, 3] /= 1.0 + abs(e[3])  # gamma = (d1 - d2) / p: a difference of slides
            assert ((err.max(axis=-1) < 1e-8) & (st == m.OK)).any(), (q, e, st)
            found += 1
        assert (st != m.UNVERIFIED).all(), (q, st)
    assert found == 4 * len(qs)


@pytest.mark.parametrize("name", ["urrh_rcm", "tripod_planar"])
def test_fk_in_chunks_is_fk_in_one_piece(name, monkeypatch):
    """fk and fk_status evaluate FK_CHUNK configurations at a time: with chunks of 97
    (many boundaries, a leading shape of two axes, NaN and unreachable joints among them)
    the poses and statuses are those of one piece, to the bit."""
    from bonered_alg.runtime import model as runtime_model

    m = _module(name)
    rng = np.random.default_rng(5)
    q = _configurations(m, rng, 300, 200, 40, 0.5)
    q = q[rng.permutation(len(q))][: len(q) // 2 * 2].reshape(-1, 2, q.shape[1])
    monkeypatch.setattr(runtime_model, "FK_CHUNK", 10 ** 9)
    whole, whole_status = m.fk(q), m.fk_status(q)
    monkeypatch.setattr(runtime_model, "FK_CHUNK", 97)
    assert np.array_equal(m.fk(q), whole, equal_nan=True)
    assert np.array_equal(m.fk_status(q), whole_status)
    assert whole.shape == q.shape[:2] + (m.FK_MODES, len(m.POSE))
    assert np.isfinite(whole).any() and np.isnan(whole).any()


def _svd_step(js, fs):
    """The Gauss-Newton step and rank test by the SVD alone (the pseudo-inverse with the
    singular values below COND_RTOL of the largest cut): the reference for _scaled_step."""
    from bonered_alg.runtime.status import COND_RTOL

    u, sv, vt = np.linalg.svd(js, full_matrices=False)
    kept = sv > COND_RTOL * sv[..., :1]
    inv = np.where(kept, 1.0 / np.where(kept, sv, 1.0), 0.0)
    step = np.einsum("...ij,...i->...j", vt, inv * np.einsum("...ji,...j->...i", u, fs))
    return step, sv[..., -1] > COND_RTOL * sv[..., 0]


@pytest.mark.parametrize("m, n", [(11, 4), (3, 3), (6, 6), (2, 3)])
def test_scaled_step_is_the_svd_least_squares_step_at_every_condition(m, n):
    """verify's Gauss-Newton step and rank test (_scaled_step: the normal equations where
    det(G) / trace(G)^n certifies the conditioning, else the SVD) against the SVD alone, on
    unit-row matrices with sigma_min / sigma_max from 1 to 1e-14 and exactly rank
    deficient ones, small and large right-hand sides, and rows that are not finite: the same
    rank decisions, the same steps to 1e-6 of their size plus rounding."""
    from bonered_alg.runtime.fk import _scaled_step

    rng = np.random.default_rng(m * 10 + n)
    mats, rhs = [], []
    for ratio in np.logspace(0, -14, 57):
        for _ in range(6):
            a, _ = np.linalg.qr(rng.standard_normal((m, m)))
            b, _ = np.linalg.qr(rng.standard_normal((n, n)))
            k = min(m, n)
            sv = np.geomspace(1.0, ratio, k) if k > 1 else np.ones(1)
            if rng.random() < 0.1:
                sv[-1] = 0.0
            js = a[:, :k] @ np.diag(sv) @ b[:k, :]
            js /= np.maximum(np.linalg.norm(js, axis=-1, keepdims=True), 1e-300)
            mats.append(js)
            rhs.append(rng.standard_normal(m) * 10.0 ** rng.integers(-16, 1))
    js, fs = np.array(mats), np.array(rhs)
    finite = rng.random(len(js)) > 0.05
    step, cond_ok = _scaled_step(js, fs, finite)
    ref_step, ref_ok = _svd_step(js, fs)
    assert np.array_equal(cond_ok[finite], ref_ok[finite])
    assert np.isnan(step[~finite]).all()
    size = np.abs(ref_step[finite]).max(axis=-1, keepdims=True)
    assert (np.abs(step[finite] - ref_step[finite]) <= 1e-6 * size + 1e-13).all()
    assert ref_ok[finite].any() and not ref_ok[finite].all()


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar"])
def test_geometry_per_configuration_at_forward_singularities(name, monkeypatch):
    """The geometry may be given per configuration (an array of one value per joint
    configuration).  At and near forward singularities the 3-RPS solver searches for the
    lost partner of a nearly double root on the configurations with an odd number of real
    modes only; it took the whole array there and raised a broadcasting error.  With every
    geometric parameter given as an array of its default, fk and fk_status are those of
    the scalar defaults, to the bit, and the search ran."""
    from bonered_alg.runtime import rps

    m = _module(name)
    rng = np.random.default_rng(11 if name == "planar_tripod" else 3)
    lo = 40.0 if name == "planar_tripod" else 100.0
    q = []
    while len(q) < 21:
        base = np.array([*rng.uniform(-30, 30, 2), 0.0, *rng.uniform(-0.4, 0.4, 3)])
        for z_star in singular_heights(m, base, np.linspace(lo, 340.0, 301)):
            for h in (0.0, 1e-9, -1e-6, 1e-3):
                q.append(m.ik(np.array([*base[:2], z_star + h, *base[3:]]), limits=False))
    q = np.array(q)
    searched = []
    partners = rps.partners
    monkeypatch.setattr(rps, "partners", lambda *a: searched.append(1) or partners(*a))
    scalar, scalar_status = m.fk(q), m.fk_status(q)
    arrays = {k: np.full(len(q), float(v)) for k, v in m.PARAMETERS.items()}
    assert searched
    assert np.array_equal(m.fk(q, **arrays), scalar, equal_nan=True)
    assert np.array_equal(m.fk_status(q, **arrays), scalar_status)


@pytest.mark.parametrize("name", ["urrh_rcm", "pro_hep_lct", "tripod_planar"])
def test_modes_polished_together_or_apart_agree_to_the_bit(name, monkeypatch):
    """The modes of a configuration are polished and checked together, as many as make
    fk.MODE_ROWS rows (every mode of a few configurations at once, one mode at a time on
    many).  Every mode at once, one at a time, and one configuration per call give the same
    poses and statuses to the bit: on configurations from the IK, perturbed ones, NaN
    joints and, for pro_hep_lct, joints on and near the lower lex basis's pivot locus t1 =
    +-w1 (the modes the other elimination order gives: fk.from_charts)."""
    from bonered_alg.runtime import fk as fk_solver

    m = _module(name)
    rng = np.random.default_rng(17)
    q = _configurations(m, rng, 200, 60, 20, 0.5)
    if name == "pro_hep_lct":
        w1 = rng.uniform(-1.5, 1.5, 12)
        t1 = rng.choice([1.0, -1.0], 12) * w1 + np.repeat([0.0, 1e-9, 1e-4], 4)
        q = np.concatenate([q, np.column_stack([t1, w1, np.full(12, 160.0),
                                                np.full(12, 200.0)])])
    monkeypatch.setattr(fk_solver, "MODE_ROWS", 1)
    apart, apart_status = m.fk(q), m.fk_status(q)
    monkeypatch.setattr(fk_solver, "MODE_ROWS", 10 ** 9)
    assert np.array_equal(m.fk(q), apart, equal_nan=True)
    assert np.array_equal(m.fk_status(q), apart_status)
    monkeypatch.undo()
    for k in range(0, len(q), 9):
        assert np.array_equal(m.fk(q[k]), apart[k], equal_nan=True)
        assert np.array_equal(m.fk_status(q[k]), apart_status[k])
    assert np.isfinite(apart).any() and np.isnan(apart).any()
    assert len(set(apart_status.ravel().tolist())) >= 2


@pytest.mark.parametrize("name", ["urrh_rcm", "lamina_milling", "pro_hep_lct",
                                  "planar_tripod", "tripod_planar"])
def test_fk_of_no_configurations(name):
    """An empty batch (no configurations, or an empty axis among others) gives empty poses
    and statuses of the right shapes, as the IK does (the modes' axis once failed here)."""
    m = _module(name)
    for lead in ((0,), (2, 0), (0, 3)):
        q = np.zeros(lead + (len(m.JOINTS),))
        assert m.fk(q).shape == lead + (m.FK_MODES, len(m.POSE))
        assert m.fk_status(q).shape == lead + (m.FK_MODES,)
