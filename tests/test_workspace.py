"""Workspace tool: grids, chunked and parallel scans, membership against the independent
numeric models, boundary search, command line, plots."""

from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest

from bonered_alg.cli import main
from bonered_alg.studies import bone_reduction as br
from bonered_alg.workspace.grid import Axis, Grid
from bonered_alg.workspace.membership import IN_WORKSPACE, classify
from bonered_alg.workspace.plots import overlay
from bonered_alg.workspace.ranges import coordinate_range
from bonered_alg.workspace.scan import scan
from tests import independent_planar_tripod as ind_pt
from tests import independent_stewart as ind_st
from tests import independent_tripod_planar as ind_tp

POSE = ("x", "y", "z", "alpha", "beta", "gamma")
RNG = np.random.default_rng(4)


def _small_grid(z=210.0):
    return Grid(POSE, (Axis.from_user("x", -60, 60, 8), Axis.from_user("y", -60, 60, 8),
                       Axis.from_user("gamma", -30, 30, 5)), {"z": z, "alpha": 0.0, "beta": 0.0})


def test_grid_chunks_cover_every_sample_once():
    g = _small_grid()
    full = np.concatenate([g.poses(a, b) for a, b in g.chunks(100)])
    xs, ys, gs = np.meshgrid(*(a.values() for a in g.axes), indexing="ij")
    assert full.shape == (g.size, 6)
    assert np.array_equal(full[:, 0], xs.ravel()) and np.array_equal(full[:, 5], gs.ravel())
    assert np.all(full[:, 2] == 210.0)
    assert g.axes[2].n == 13 and math.isclose(math.degrees(g.axes[2].step), 5.0)


def test_grid_poses_of_any_index_range_are_the_indexed_samples():
    """Grid.poses builds chunks row by row; every sample must be lo + step * index of its
    own multi-index (numpy.unravel_index, one sample at a time), bit for bit, for ranges
    starting and ending anywhere in a row."""
    g = Grid(POSE, (Axis("x", -1.3, 2.1, 7), Axis("y", 0.0, 5.0, 3), Axis("gamma", -1.0, 0.5, 11)),
             {"z": 200.0, "alpha": 0.1, "beta": -0.2})
    idx = np.unravel_index(np.arange(g.size), g.shape)
    ref = np.empty((g.size, 6))
    ref[:, 2], ref[:, 3], ref[:, 4] = 200.0, 0.1, -0.2
    for a, i in zip(g.axes, idx):
        ref[:, POSE.index(a.name)] = a.lo + a.step * i
    ranges = [(0, g.size), (0, 1), (5, 6), (10, 11), (10, 33), (11, 44), (3, 200), (230, 231)]
    ranges += [tuple(sorted(RNG.integers(0, g.size + 1, 2))) for _ in range(200)]
    for a, b in ranges:
        assert np.array_equal(g.poses(a, b), ref[a:b]), (a, b)


@pytest.mark.parametrize("bad, match", [
    (dict(axes=(Axis("q", 0, 1, 2),), fixed={}), "not pose coordinates"),
    (dict(axes=(Axis("x", 0, 1, 2),), fixed={"z": 1.0}), "neither grid axes nor fixed"),
    (dict(axes=(Axis("x", 0, 1, 2),), fixed={"x": 1, "y": 0, "z": 0, "alpha": 0, "beta": 0,
                                              "gamma": 0}), "both grid axes and fixed"),
])
def test_grid_errors_name_the_coordinate(bad, match):
    with pytest.raises(ValueError, match=match):
        Grid(POSE, **bad)


def test_axis_errors():
    with pytest.raises(ValueError, match="lo <= hi"):
        Axis("x", 2.0, 1.0, 3)
    with pytest.raises(ValueError, match="step must be positive"):
        Axis.from_user("x", 0, 1, 0)


def test_scan_is_the_same_serial_parallel_chunked_and_on_dask():
    g = _small_grid()
    ref = scan("tripod_planar", g, workers=1, chunk=1 << 16)
    assert 0 < ref.count < g.size
    assert ref.count == int(np.count_nonzero(classify("tripod_planar", g.poses(0, g.size))
                                             == IN_WORKSPACE))
    for kwargs in (dict(workers=2, chunk=64), dict(workers=1, chunk=8)):
        other = scan("tripod_planar", g, **kwargs)
        assert other.count == ref.count and np.array_equal(other.mask, ref.mask)
        assert other.ranges == ref.ranges
    pytest.importorskip("dask.distributed")
    dask_res = scan("tripod_planar", g, workers=1, chunk=256, client="local")
    assert np.array_equal(dask_res.mask, ref.mask) and dask_res.reasons == ref.reasons



def test_scan_of_a_module_object_runs_here_and_refuses_processes():
    """A module object (e.g. one a derivation just generated, not yet on disk) is scanned
    in this process or on threads; process workers would import the file instead."""
    import importlib

    mod = importlib.import_module("bonered_alg.generated.tripod_planar")
    g = _small_grid()
    ref = scan("tripod_planar", g, workers=1, chunk=1 << 16)
    got = scan(mod, g, workers=1, chunk=1 << 16)
    assert got.count == ref.count and np.array_equal(got.mask, ref.mask)
    with pytest.raises(ValueError, match="tripod_planar: a module object is scanned"):
        scan(mod, g, workers=1, client="local")

def _stewart_sample(n, xy=80.0, z=(170.0, 300.0), ang=0.35):
    return np.column_stack([RNG.uniform(-xy, xy, n), RNG.uniform(-xy, xy, n),
                            RNG.uniform(*z, n), *(RNG.uniform(-ang, ang, (3, n)))])


def test_stewart_membership_matches_independent_model():
    poses = _stewart_sample(3000)
    got = classify("stewart", poses) == IN_WORKSPACE
    ref = np.array([ind_st.in_workspace(p) for p in poses])
    assert 0.05 < ref.mean() < 0.95  # both kinds of sample are present
    assert np.array_equal(got, ref)


def test_stewart_membership_with_000_limits_matches_independent_model():
    poses = _stewart_sample(2000, 50.0, (160.0, 220.0), 0.2)
    got = classify("stewart", poses, br.STEWART_000, **br.STEWART_000_PARAMS) == IN_WORKSPACE
    ref = np.array([ind_st.in_workspace(p, (175.0, 250.0), np.radians(45), np.radians(20),
                                        ra=190.0, rb=190.0) for p in poses])
    assert 0.02 < ref.mean() < 0.98
    assert np.array_equal(got, ref)


def _tripod_planar_inside(pose):
    """001 Sect. 3 limits on the independent model (tests/independent_tripod_planar.py)."""
    q, res = ind_tp.joints(pose)
    if res > 1e-9:
        return None  # the independent least-squares solve did not converge: not decided
    rb_, tb, *_ = ind_tp.platform_b(pose)
    a_pts = ind_tp._corners(200.0, [-30, 90, 210])
    b_loc = ind_tp._corners(200.0, [-30, 90, 210])
    legs = [tb + rb_ @ b_loc[k] - a_pts[k] for k in range(3)]
    ang = [math.acos(rb_[:, 2] @ v / np.linalg.norm(v)) for v in legs]
    return bool(np.all((q[:3] >= 160) & (q[:3] <= 320)) and np.all((q[3:] >= 120)
                & (q[3:] <= 325)) and max(ang) <= math.radians(20))


def _planar_tripod_inside(pose):
    """000 Table 1 limits, eq. 45-46, on the independent model
    (tests/independent_planar_tripod.py)."""
    q = ind_pt.ik(pose)
    x1, y1, g1 = ind_pt.mp1_pose(pose)
    rot = ind_pt.rot("z", pose[5]) @ ind_pt.rot("y", pose[4]) @ ind_pt.rot("x", pose[3])
    normal = ind_pt.rot("z", -g1) @ rot[:, 2]
    dw = ind_pt.world_d(pose)
    ok = bool(np.all((q >= 175) & (q <= 250)))
    for k in range(3):
        leg = ind_pt.rot("z", -g1) @ (dw[k] - np.array([x1, y1, 0.0])) - ind_pt.C[k]
        n = np.linalg.norm(leg)
        ok &= math.acos(leg[2] / n) <= math.radians(45)
        ok &= math.acos(normal @ leg / n) <= math.radians(20)
    return ok


@pytest.mark.parametrize("name, inside, centre, span", [
    ("tripod_planar", _tripod_planar_inside, 240.0, (80, 40, 0.3, 0.9)),
    ("planar_tripod", _planar_tripod_inside, 215.0, (25, 20, 0.15, 0.3)),
])
def test_hybrid_membership_matches_independent_models(name, inside, centre, span):
    n = 300
    xy, dz, tilt, turn = span
    poses = np.column_stack([RNG.uniform(-xy, xy, n), RNG.uniform(-xy, xy, n),
                             RNG.uniform(centre - dz, centre + dz, n),
                             *(RNG.uniform(-tilt, tilt, (2, n))), RNG.uniform(-turn, turn, n)])
    got = classify(name, poses) == IN_WORKSPACE
    ref = [inside(p) for p in poses]
    decided = np.array([r is not None for r in ref])
    assert decided.mean() > 0.9
    ref = np.array([bool(r) for r in ref])
    assert 0.05 < ref[decided].mean() < 0.95
    assert np.array_equal(got[decided], ref[decided])


def test_boundary_search_brackets_the_independent_boundary():
    """001 Table 1 set-up: the alpha range of tripod_planar at the homing position; just
    inside each end is in the workspace of the independent model, just outside is not."""
    ref = [0.0, 0.0, 210.0, 0.0, 0.0, 0.0]
    r = coordinate_range("tripod_planar", ref, "alpha", br.ANGLE_BOUND, br.ANGLE_STEP,
                         br.ANGLE_TOL)
    assert r.lo < 0 < r.hi
    eps = 2 * br.ANGLE_TOL
    for end, out in ((r.lo, -1), (r.hi, 1)):
        inner, outer = list(ref), list(ref)
        inner[3], outer[3] = end - out * 1e-9, end + out * eps
        assert _tripod_planar_inside(inner)
        assert not _tripod_planar_inside(outer)


def test_workspace_command_writes_table_and_plots(tmp_path, capsys):
    rc = main(["workspace", "stewart", "--axis", "x=-60:60:20", "--axis", "y=-60:60:20",
               "--fix", "z=220", "--fix", "alpha=0", "--fix", "beta=0", "--fix", "gamma=10",
               "--workers", "1", "--no-progress", "--out", str(tmp_path)])
    assert rc == 0
    summary = (tmp_path / "stewart_summary.csv").read_text()
    g = Grid(POSE, (Axis.from_user("x", -60, 60, 20), Axis.from_user("y", -60, 60, 20)),
             {"z": 220.0, "alpha": 0.0, "beta": 0.0, "gamma": math.radians(10)})
    count = int(np.count_nonzero(classify("stewart", g.poses(0, g.size)) == IN_WORKSPACE))
    assert f"reachable,{count}," in summary
    points = (tmp_path / "stewart_points.csv").read_text().splitlines()
    assert len(points) == count + 1
    png = (tmp_path / "stewart_x_y.png").read_bytes()
    main(["workspace", "stewart", "--axis", "x=-60:60:20", "--axis", "y=-60:60:20",
          "--fix", "z=220", "--fix", "alpha=0", "--fix", "beta=0", "--fix", "gamma=10",
          "--workers", "1", "--no-progress", "--out", str(tmp_path)])
    assert (tmp_path / "stewart_x_y.png").read_bytes() == png  # deterministic
    assert (tmp_path / "stewart_x_y.pdf").read_bytes()[:4] == b"%PDF"


@pytest.mark.parametrize("argv, match", [
    (["--axis", "q=0:1:1"], "not pose coordinates"),
    (["--axis", "x=0:1"], "3 finite numbers"),
    (["--axis", "x=0:10:1", "--param", "rr=3"], "unknown parameter 'rr'"),
    (["--axis", "x=0:10:1", "--limit", "zz*=0:1"], "no limit matches 'zz\\*'"),
    # issue 14: each malformed option says which form it expects, a bad mode is caught
    # before the scan starts
    (["--axis", "x"], "--axis 'x': expected NAME=LO:HI:STEP"),
    (["--axis", "x=0:10:1", "--limit", "q*"], "--limit 'q\\*': expected PATTERN=LO:HI"),
    (["--axis", "x=0:10:1", "--mode", "99"], "working modes \\[99\\] invalid"),
])
def test_workspace_command_errors(argv, match, tmp_path, capsys):
    base = ["workspace", "stewart", "--fix", "y=0", "--fix", "z=220", "--fix", "alpha=0",
            "--fix", "beta=0", "--fix", "gamma=0", "--no-progress", "--out", str(tmp_path)]
    rc = main(base + argv)
    err = capsys.readouterr().err
    assert rc == 2
    assert re.search(match, err), err
    assert "samples" not in err  # before the banner: no work started
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("argv, match", [
    (["nosuch", "--axis", "x=0:1:1"], "unknown mechanism 'nosuch'; generated: .*stewart"),
    (["pro_hep_lct", "--axis", "Xu=0:1:1", "--fix", "Yu=200", "--fix", "Xd=0", "--fix", "Yd=100",
      "--limit", "q*=0:1"], "declares no LIMITS"),
])
def test_workspace_command_mechanism_errors(argv, match, tmp_path, capsys):
    rc = main(["workspace", *argv, "--no-progress", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert rc == 2 and re.search(match, err), err


def test_workspace_command_warns_where_the_grid_cuts_the_workspace(tmp_path, capsys):
    """A grid inside the workspace: every range ends at the grid, and the summary says so
    instead of presenting the grid's bounds as the workspace's."""
    rc = main(["workspace", "stewart", "--axis", "x=-10:10:10", "--fix", "y=0", "--fix",
               "z=220", "--fix", "alpha=0", "--fix", "beta=0", "--fix", "gamma=0",
               "--workers", "1", "--no-progress", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert rc == 0 and "3 of 3 samples reachable" in out, out
    assert "cut by the lower and upper grid edge" in out


def test_overlay_is_deterministic(tmp_path):
    res = scan("stewart", _small_grid(220.0), workers=1)
    a = overlay([res], "y", "x", "t", tmp_path / "a")
    b = overlay([res], "y", "x", "t", tmp_path / "b")
    assert [p.read_bytes() for p in a] == [p.read_bytes() for p in b]


def test_printed_table_inconsistencies_are_found():
    """001 Table 1 prints gamma in [-28; 31] with width 54 for the hybrid at the target, and
    Sect. 3 says +128% for gamma at homing where the widths 101 / 46 give +119.6%."""
    from bonered_alg.studies.comparison_report import _printed_consistency

    found = {c["quantity"]: c["finding"] for c in _printed_consistency()}
    assert "59" in found["tripod_planar target gamma"]
    assert "119.6" in found["improvement of gamma (homing)"]
    assert len(found) == 2


def test_comparison_outputs_are_current():
    from conftest import ROOT

    from bonered_alg.studies.comparison_report import comparison_hash, recorded_hash

    assert recorded_hash(ROOT) == comparison_hash()


def test_000_table2_tripod_ranges_reproduced_within_one_grid_step():
    """000 Table 2, hybrid mechanism: Delta z = 75 mm, Delta alpha = 37 deg, Delta beta =
    22 deg.  Read at x = y = gamma = 0 (the paper does not say; the tripod's strokes and
    joint ranges, which bound this workspace, are all in Table 1)."""
    from bonered_alg.generated import planar_tripod as m

    setup = br.table2_setups()[0]
    res = scan("planar_tripod", br.abz_grid(m.POSE, setup.height), workers=2)
    steps = {a.name: a.step for a in res.grid.axes}
    assert abs(res.extent("z") - 75.0) <= steps["z"]
    assert abs(math.degrees(res.extent("alpha")) - 37.0) <= math.degrees(steps["alpha"])
    assert abs(math.degrees(res.extent("beta")) - 22.0) <= math.degrees(steps["beta"])


def test_stepwise_path_moves_one_group_of_coordinates_per_step():
    from bonered_alg.workspace.trajectory import stepwise_path

    t, p = stepwise_path([0, 0, 210, 0, 0, 0], [{5: -0.3}, {0: -8.8, 2: 250.0}], 11)
    assert t.shape == (21,) and t[0] == 0 and t[-1] == 2
    assert np.allclose(p[10], [0, 0, 210, 0, 0, -0.3]) and np.allclose(p[-1],
                                                                      [-8.8, 0, 250, 0, 0, -0.3])
    assert np.allclose(p[:11, :5], [0, 0, 210, 0, 0])  # step 1 changes gamma only
    assert np.allclose(p[10:, 5], -0.3)  # step 2 keeps it


def test_path_velocities_and_margins_match_the_jacobian_and_independent_lengths():
    """Along the 001 Sect. 4.2 path (Stewart): dq/dt from the samples equals J dX/dt inside
    each step, and the stroke margin is min(q - 160, 320 - q) of the independent model."""
    from bonered_alg.generated import stewart as st

    paper, runs = br.trajectory_001(samples_per_step=81)
    r = runs["stewart"]
    q_ind = np.array([ind_st.ik(p) for p in r.poses])
    assert np.allclose(r.q, q_ind, atol=1e-9)  # limits off: every sample has its lengths
    assert np.allclose(r.stroke_margin, np.min(np.minimum(q_ind - 160, 320 - q_ind), axis=1),
                       atol=1e-9)
    J = st.jacobian(r.poses, limits=False)
    interior = [i for i in range(1, len(r.t) - 1) if np.floor(r.t[i - 1]) == np.floor(r.t[i + 1])]
    for i in interior[::7]:
        xdot = (r.poses[i + 1] - r.poses[i - 1]) / (r.t[i + 1] - r.t[i - 1])
        assert np.allclose(r.qdot[i], J[i] @ xdot, rtol=1e-3, atol=1e-2)


def test_001_path_end_needs_a_raised_planar_stage_independent_model():
    """The finding of the comparison report: with d = 0 the last pose of the 001 path needs a
    tripod stroke beyond 320 mm, with d = 40 mm all strokes are in range (independent
    model, tests/independent_tripod_planar.py)."""
    from bonered_alg.generated import tripod_planar as tp

    _, paper = br.path_001()
    for d, inside in ((0.0, False), (40.0, True)):
        pose = tp.pose_from_paper_coordinates(paper[-1], d=d)
        q, res = ind_tp.joints(pose, d=d)
        assert res < 1e-9
        in_range = bool(np.all((q[:3] >= 160) & (q[:3] <= 320)) and np.all((q[3:] >= 120)
                        & (q[3:] <= 325)))
        assert in_range is inside, (d, q)


def test_planar_singularity_splits_the_gamma_range_at_homing():
    """The planar stage's input singularity gamma_p = -60 deg (001 eq. 52-53 corrected, see
    derivations/tripod_planar.tex) separates reachable poses at the homing position: the
    sign of det_Ji_C flips there and nowhere else on the line."""
    from bonered_alg.workspace.singular_loci import crossings, polynomial_signs, signs_on_reachable

    g = Grid(POSE, (Axis.from_user("gamma", -80, -40, 1),),
             {"x": 0.0, "y": 0.0, "z": 210.0, "alpha": 0.0, "beta": 0.0})
    res = scan("tripod_planar", g, workers=1)
    signs = polynomial_signs(res)
    s = signs["det_Ji_C"]
    flips = np.nonzero(s[:-1] * s[1:] <= 0)[0]
    gam = np.degrees(g.axes[0].values())
    assert len(flips) in (1, 2) and all(abs(gam[i] + 60) <= 1.0 for i in flips)
    assert not res.mask[np.argmin(np.abs(gam + 60))]  # the singular sample itself: excluded
    both = signs_on_reachable(res, signs)["det_Ji_C"]
    assert both["positive"] > 0 and both["negative"] > 0
    assert crossings(res, signs)["det_Ji_C"] == 0  # no reachable pair straddles it


def test_workspace_command_on_a_planar_mechanism_with_other_pose_names(tmp_path):
    """004's pose is (Xu, Yu, Xd, Yd) in mm and its geometry has no published values: the
    same command scans it with --param (tests/independent_pro_hep_lct.py geometry)."""
    from tests.independent_pro_hep_lct import GEOMETRY

    params = [f"--param={k}={v}" for k, v in GEOMETRY.items()]
    rc = main(["workspace", "pro_hep_lct", "--axis", "Xu=200:400:10", "--axis", "Yu=100:300:10",
               "--fix", "Xd=200", "--fix", "Yd=150", *params, "--workers", "1",
               "--no-progress", "--out", str(tmp_path)])
    assert rc == 0
    summary = (tmp_path / "pro_hep_lct_summary.csv").read_text()
    assert "Xu_range" in summary and (tmp_path / "pro_hep_lct_Xu_Yu.png").is_file()


def _comparison_record() -> dict:
    import json

    from conftest import ROOT

    return json.loads((ROOT / "derivations" / "bone_reduction_workspace.json").read_text())


def _planar_extents_independent(q_min: float, q_max: float, z: float, step_deg: float = 1.0):
    """Delta x, Delta y (mm) and the gamma interval (deg) of the (x, y, gamma) workspace of
    the 000 planar stage with the strokes [q_min, q_max] (alpha = beta = 0, height z), from
    the independent model: at fixed gamma each q_k is affine in (x, y), so each slice is the
    polygon cut out by six lines, whose vertices give its exact extents; the slices are
    followed from gamma = 0 until one is empty, or to the input singularity at -60 deg."""
    import itertools

    extents = {}
    for gd in np.arange(-59.0, 120.0, step_deg):
        g = math.radians(gd)
        base = ind_pt.ik(np.array([0.0, 0.0, z, 0.0, 0.0, g]))[:3]
        a = np.column_stack([ind_pt.ik(np.array([1.0, 0.0, z, 0.0, 0.0, g]))[:3] - base,
                             ind_pt.ik(np.array([0.0, 1.0, z, 0.0, 0.0, g]))[:3] - base])
        lines = [(a[k], b - base[k]) for k in range(3) for b in (q_min, q_max)]
        corners = []
        for (a1, b1), (a2, b2) in itertools.combinations(lines, 2):
            m = np.array([a1, a2])
            if abs(np.linalg.det(m)) > 1e-12:
                p = np.linalg.solve(m, [b1, b2])
                q = base + a @ p
                if np.all(q >= q_min - 1e-9) and np.all(q <= q_max + 1e-9):
                    corners.append(p)
        extents[gd] = np.ptp(np.array(corners), axis=0) if corners else None
    gs = sorted(extents)
    lo = hi = gs.index(0.0)
    while lo > 0 and extents[gs[lo - 1]] is not None:
        lo -= 1
    while hi < len(gs) - 1 and extents[gs[hi + 1]] is not None:
        hi += 1
    run = [extents[gs[i]] for i in range(lo, hi + 1)]
    return max(r[0] for r in run), max(r[1] for r in run), (gs[lo], gs[hi])


def test_recovered_planar_stroke_reproduces_000_table2_independently():
    """The planar stroke recovered from 000 Table 2 (studies/planar_stroke_000.py) gives,
    in the independent model's exact polygon extents, Delta x = 175, Delta y = 170 mm and
    Delta gamma = 105 deg to the search grid's resolution (4 mm, 1 deg; a grid extent falls
    short of the exact one by up to two steps), and the committed Table 2 row (2 mm grid)
    agrees with the exact extents to two of its steps."""
    data = _comparison_record()
    fit = data["planar_stroke_000"]
    height = next(r["height_mm"] for r in data["table2_000"] if r["mechanism"] ==
                  "planar_tripod")
    dx, dy, (g_lo, g_hi) = _planar_extents_independent(fit["q_min"], fit["q_max"], height)
    assert abs(dx - 175) <= 8 and abs(dy - 170) <= 8 and abs((g_hi - g_lo) - 105) <= 1
    assert g_lo == -59.0  # the home component ends at the input singularity (000 eq. 38)
    rows = {r["coordinate"]: r for r in data["table2_000"] if "recovered" in r["variant"]}
    assert abs(rows["x"]["ours"] - dx) <= 4 and abs(rows["y"]["ours"] - dy) <= 4
    assert abs(rows["gamma"]["ours"] - (g_hi - g_lo)) <= 1
    # with Table 1's 175-250 mm on the planar actuators too the ranges are far smaller
    dx0, dy0, _ = _planar_extents_independent(175.0, 250.0, height)
    assert dx0 < 100 and dy0 < 100


def test_stroke_search_bound_finds_the_brute_force_optimum(monkeypatch):
    """best_on_lattice (the coarse stroke search) returns the point that min over every
    lattice point's (error, point) returns, ties included, reading fewer points, for
    synthetic ranges that grow with the stroke range as the home component does (None,
    home unreachable, for narrow ranges), quantized to steps so that errors tie."""
    from bonered_alg.studies import planar_stroke_000 as ps

    los, his = np.arange(100.0, 216.0, 5.0), np.arange(225.0, 351.0, 5.0)

    def ranges(lo, hi, scale):
        if hi - lo < 40.0:
            return None
        w = hi - lo
        return {"x": 4.0 * np.floor(scale * w ** 0.9 / 4.0),
                "y": 4.0 * np.floor(scale * (0.6 * w + 0.2 * hi) / 4.0),
                "gamma": float(min(180.0, np.floor(0.8 * w)))}

    exact = tuple(ranges(100.0, 250.0, 1.0).values())  # error 0 at several points: ties
    for target, scale in (((175.0, 170.0, 105.0), 1.0), ((150.0, 140.0, 160.0), 1.3),
                          ((400.0, 1.0, 30.0), 0.7), (exact, 1.0)):
        monkeypatch.setattr(ps, "TARGET", dict(zip(("x", "y", "gamma"), target)))
        read = []

        def results(points, scale=scale, read=read):
            read.extend(points)
            return {p: ranges(*p, scale) for p in points}

        got = ps.best_on_lattice(los, his, results)
        every = [(ps._error(r), (float(a), float(b))) for a in los for b in his  # noqa: SLF001
                 if (r := ranges(a, b, scale)) is not None]
        assert got == min(every)[1]
        assert len(set(read)) < len(los) * len(his)


def test_home_component_stops_at_the_planar_input_singularity():
    """000 variant with 001's planar strokes (120-325 mm): poses beyond gamma = -60 deg are
    within every joint range (independent model) but reachable from home only through the
    input singularity of 000 eq. (38), so the home component ends there while the
    limits-only count runs on to the end of the scan."""
    from bonered_alg.generated import planar_tripod as m

    from bonered_alg.workspace.components import home_component, signs_near_reachable
    from bonered_alg.workspace.membership import Criteria

    setup = next(s for s in br.table2_setups() if s.variant == "planar strokes 120-325 mm")
    grid = Grid(POSE, (Axis.from_user("x", -40, 40, 8), Axis.from_user("y", -40, 40, 8),
                       Axis.from_user("gamma", -90, 60, 1)),
                {"z": setup.height, "alpha": 0.0, "beta": 0.0})
    res = scan("planar_tripod", grid, Criteria(limits={"q[123]": (120.0, 325.0)}), workers=1)
    home = home_component(res, signs_near_reachable(res), {"x": 0.0, "y": 0.0, "gamma": 0.0})
    assert math.degrees(res.ranges["gamma"][0]) < -75
    assert math.isclose(math.degrees(home.result.ranges["gamma"][0]), -59.0, abs_tol=1e-9)
    assert home.reachable_elsewhere > 0 and home.bounding["det_Ji_MP1"] > 0
    q = ind_pt.ik(np.array([0.0, 0.0, setup.height, 0.0, 0.0, math.radians(-70.0)]))
    assert np.all((q[:3] >= 120) & (q[:3] <= 325))  # beyond the locus, within the strokes
    assert m.ik_status(np.array([0.0, 0.0, setup.height, 0.0, 0.0, -math.pi / 3]),
                       limits=False) == m.INPUT_SINGULAR


def test_home_component_on_a_synthetic_grid():
    """A sign change at x = 3 cuts a fully reachable 5 x 5 grid: the component of home
    (0, 0) is x <= 2, the locus is within two steps of x = 1, 2; errors for a home off the
    grid or unreachable."""
    from bonered_alg.workspace.components import HomeNotReachable, home_component
    from bonered_alg.workspace.membership import Criteria
    from bonered_alg.workspace.scan import ScanResult

    grid = Grid(POSE, (Axis("x", 0.0, 4.0, 5), Axis("y", 0.0, 4.0, 5)),
                {"z": 200.0, "alpha": 0.0, "beta": 0.0, "gamma": 0.0})
    mask = np.ones((5, 5), dtype=bool)
    res = ScanResult("synthetic", grid, Criteria(), {}, count=25, mask=mask)
    s = np.ones((5, 5), dtype=np.int8)
    s[3:, :] = -1
    home = home_component(res, {"f": s, "flat": np.ones((5, 5), dtype=np.int8)},
                          {"x": 0.0, "y": 0.0})
    assert home.count == 15 and home.reachable_elsewhere == 10
    assert home.result.ranges == {"x": (0.0, 2.0), "y": (0.0, 4.0)}
    assert home.bounding == {"f": 10, "flat": 0}
    with pytest.raises(ValueError, match="outside the grid axis"):
        home_component(res, {"f": s}, {"x": 9.0, "y": 0.0})
    res.mask[0, 0] = False
    with pytest.raises(HomeNotReachable, match="not reachable"):
        home_component(res, {"f": s}, {"x": 0.0, "y": 0.0})


def test_sign_sides_built_once_give_each_mask_its_own_component():
    """planar_stroke_000 labels hundreds of masks of one scan with the signs around home
    built once (``SignSides``): each mask's component, bounding counts and lists are those
    of home_component building them itself; sides of other signs or another home sample are
    an error."""
    from bonered_alg.workspace.components import SignSides, home_component
    from bonered_alg.workspace.membership import Criteria
    from bonered_alg.workspace.scan import ScanResult

    rng = np.random.default_rng(5)
    grid = Grid(POSE, (Axis("x", 0.0, 10.0, 11), Axis("y", 0.0, 12.0, 13)),
                {"z": 200.0, "alpha": 0.0, "beta": 0.0, "gamma": 0.0})
    signs = {"f": np.where(rng.random((11, 13)) < 0.15, -1, 1).astype(np.int8),
             "g": np.where(np.arange(11)[:, None] > 7, -1, 1) * np.ones((1, 13), np.int8),
             "zero_at_home": rng.integers(-1, 2, (11, 13)).astype(np.int8)}
    signs["f"][0, 0] = signs["g"][0, 0] = 1
    signs["zero_at_home"][0, 0] = 0
    sides = SignSides(signs, (0, 0))
    assert sides.used == ("f", "g") and sides.skipped == ("zero_at_home",)
    for k in range(6):
        mask = rng.random((11, 13)) < 0.5 + 0.1 * k
        mask[0, 0] = True
        res = ScanResult("synthetic", grid, Criteria(), {}, count=int(mask.sum()), mask=mask)
        alone = home_component(res, signs, {"x": 0.0, "y": 0.0})
        shared = home_component(res, signs, {"x": 0.0, "y": 0.0}, sides)
        assert np.array_equal(alone.result.mask, shared.result.mask)
        assert (alone.count, alone.reachable_elsewhere, alone.polynomials,
                alone.vanishing_at_home, alone.result.ranges) == (
            shared.count, shared.reachable_elsewhere, shared.polynomials,
            shared.vanishing_at_home, shared.result.ranges)
        assert alone.bounding == shared.bounding
        # the counts by the definition: component samples within two steps (one axis) of
        # the opposite sign
        for name in ("f", "g"):
            other = np.pad(signs[name] == -1, 2)
            near = np.zeros_like(other)
            for dx, dy in ((1, 0), (2, 0), (-1, 0), (-2, 0), (0, 1), (0, 2), (0, -1), (0, -2)):
                near |= np.roll(np.roll(other, dx, 0), dy, 1)
            want = int(np.count_nonzero(shared.result.mask & near[2:-2, 2:-2]))
            assert shared.bounding[name] == want
    res.mask[1, 0] = True  # another home sample, reachable
    with pytest.raises(ValueError, match="other signs or another home sample"):
        home_component(res, signs, {"x": 1.0, "y": 0.0}, sides)
    with pytest.raises(ValueError, match="other signs or another home sample"):
        home_component(res, dict(signs), {"x": 0.0, "y": 0.0}, sides)


def test_scan_threads_run_every_chunk_once_and_raise_the_first_error(monkeypatch):
    """scan._run_threads: each task's result exactly once, progress counted up to the total;
    an error in one chunk stops the workers and reaches the caller."""
    from bonered_alg.workspace import scan as scan_module

    seen = []

    def fake_chunk(k, fail):
        if k == fail:
            raise RuntimeError(f"chunk {k} failed")
        return k

    monkeypatch.setattr(scan_module, "scan_chunk", fake_chunk)
    tasks = [(k, -1) for k in range(37)]
    out = scan_module._run_threads(tasks, 2, lambda done, total: seen.append((done, total)))
    assert sorted(out) == list(range(37))
    assert seen[-1] == (37, 37) and [d for d, _ in seen] == list(range(1, 38))
    with pytest.raises(RuntimeError, match="chunk 5 failed"):
        scan_module._run_threads([(k, 5) for k in range(37)], 2, None)


def test_process_workers_are_kept_between_scans_and_give_the_same_scan(monkeypatch):
    """scan keeps its spawned workers (the numpy runtime's: the compiled path runs on
    threads) for the next scan of the process, since starting them costs more than a small
    scan; a scan on them equals the serial one, twice, on one pool, and a shut-down pool is
    started again."""
    from bonered_alg.workspace import scan as scan_module

    monkeypatch.setenv("BONERED_ALG_FAST", "0")
    scan_module.shutdown_pools()  # workers started under this environment
    try:
        g = _small_grid()
        ref = scan("tripod_planar", g, workers=1, chunk=1 << 16)
        first = scan("tripod_planar", g, workers=2, chunk=64)
        key = (os.getpid(), 2)
        pool = scan_module._POOLS[key]
        again = scan("tripod_planar", g, workers=2, chunk=128)
        assert scan_module._POOLS[key] is pool
        for other in (first, again):
            assert other.count == ref.count and np.array_equal(other.mask, ref.mask)
            assert other.ranges == ref.ranges and other.reasons == ref.reasons
        scan_module.shutdown_pools()
        assert not scan_module._POOLS
        third = scan("tripod_planar", g, workers=2, chunk=64)
        assert np.array_equal(third.mask, ref.mask) and scan_module._POOLS[key] is not pool
    finally:
        scan_module.shutdown_pools()


def test_kept_workers_belong_to_the_process_that_started_them(monkeypatch):
    """A forked child (another process id) gets a pool of its own and its shutdown_pools
    leaves the parent's alone (no process starts: a pool spawns its workers on first use)."""
    from bonered_alg.workspace import scan as scan_module

    parent = scan_module.process_pool(3)
    real = os.getpid()
    monkeypatch.setattr(scan_module.os, "getpid", lambda: real + 1)
    child = scan_module.process_pool(3)
    assert child is not parent and scan_module.process_pool(3) is child
    scan_module.shutdown_pools()
    monkeypatch.setattr(scan_module.os, "getpid", lambda: real)
    assert scan_module.process_pool(3) is parent
    scan_module.shutdown_pools()
    assert not scan_module._POOLS


def test_polynomial_signs_on_threads_equal_one_thread():
    """polynomial_signs evaluates the grid's chunks on threads: the same signs as on one
    thread, with and without ``where``."""
    from bonered_alg.workspace import singular_loci

    g = Grid(POSE, (Axis.from_user("gamma", -80, 80, 0.5), Axis.from_user("x", -60, 60, 2)),
             {"y": 0.0, "z": 210.0, "alpha": 0.05, "beta": -0.03})
    res = scan("tripod_planar", g, workers=1)
    where = np.zeros(g.shape, dtype=bool)
    where[::3] = True
    old = singular_loci.CHUNK
    singular_loci.CHUNK = 1000  # several chunks per thread
    try:
        for w in (None, where):
            one = singular_loci.polynomial_signs(res, where=w, workers=1)
            two = singular_loci.polynomial_signs(res, where=w, workers=2)
            assert one.keys() == two.keys()
            assert all(np.array_equal(one[k], two[k]) for k in one)
            assert any(np.any(v > 0) for v in one.values())
            assert any(np.any(v < 0) for v in one.values())
    finally:
        singular_loci.CHUNK = old


def _grid_around_home(module, n=(13, 11, 9)):
    """A grid over three pose coordinates through the module's home pose (the others fixed
    there), wide enough to hold reached and unreached samples."""
    home = dict(zip(module.POSE, module.HOME))
    axes = []
    for name, k in zip(module.POSE[:3], n):
        span = 60.0 if name not in ("alpha", "beta", "gamma") else 0.6
        axes.append(Axis(name, home[name] - span, home[name] + span, k))
    fixed = {p: v for p, v in home.items() if p not in module.POSE[:3]}
    return Grid(tuple(module.POSE), tuple(axes), fixed)


@pytest.mark.parametrize("name", ["planar_tripod", "tripod_planar", "stewart", "urrh_rcm",
                                  "lamina_milling"])
def test_compiled_scan_chunk_is_the_reduction_of_classify(name, monkeypatch):
    """scan_chunk's one compiled call (bonered_scan: the grid's samples, every allowed mode,
    the counts, extremes, reasons and mask) against the same chunk classified and reduced in
    numpy around the module's IK: equal field by field, for chunks that start and stop
    anywhere and for one and two working modes."""
    import importlib

    from bonered_alg.workspace import scan as scan_module
    from bonered_alg.workspace.membership import Criteria

    m = importlib.import_module(f"bonered_alg.generated.{name}")
    if m._MODEL.fast is None or m._MODEL.fast.library() is None:
        pytest.skip("no C compiler")
    g = _grid_around_home(m)
    for criteria in (Criteria(), Criteria(modes=(1, 0))):
        assert scan_module.compiled_scan(m, criteria, {}) is not None
        for a, b in ((0, g.size), (5, 203), (64, 128), (g.size - 77, g.size)):
            fast = scan_module.scan_chunk(name, g, a, b, criteria, {}, True)
            with monkeypatch.context() as mp:
                mp.setattr(scan_module, "compiled_scan", lambda *args: None)
                ref = scan_module.scan_chunk(name, g, a, b, criteria, {}, True)
            assert fast == ref, (name, criteria, a, b)
    whole = scan(name, g, workers=1)
    assert 0 < whole.count < g.size and sum(whole.reasons.values()) == g.size
    # custom limits or a singularity margin: classify in numpy around the IK
    assert scan_module.compiled_scan(m, Criteria(min_margin=1e-3), {}) is None
