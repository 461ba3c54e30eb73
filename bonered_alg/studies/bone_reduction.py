"""The papers' workspace comparisons of the hybrid mechanisms with the Stewart platform.

* **001 Table 1**: ranges of alpha, beta, gamma (the other two at 0) at the homing
  position (0, 0, 210) mm and at the bone-reduction target (-8.8, -50, 283.8) mm, for
  ``tripod_planar`` and ``stewart`` with the dimensions of 001 Sect. 3.  Computed by
  boundary search (:mod:`.ranges`): march step 0.5 deg, bisection to 0.01 deg.
* **000 Table 2**: ranges Delta x, Delta y, Delta gamma of the (x, y, gamma) workspace and
  Delta z, Delta alpha, Delta beta of the (alpha, beta, z) workspace (000 Sect. 5, Figs.
  10-11), for ``planar_tripod`` and ``stewart`` with the parameters of 000 Table 1, from
  grid scans (:mod:`.scan`).  000 does not say at which height the (x, y, gamma) workspace
  is taken, nor at which (x, y, gamma) the (alpha, beta, z) one: both are taken here at
  each mechanism's mid-stroke height (all tripod or all Stewart strokes at
  (q_min + q_max) / 2, angles 0, x = y = 0), and "range" is read as the extent of the
  reachable set along the coordinate; Delta x and Delta y are the largest extents over
  the gamma slices (000: "the maximum (xy) planar motion range is at gamma = 0 for the
  Stewart platform, around gamma = 23 degrees for the hybrid mechanism").
* **Stewart layout**: neither paper gives the joint spacing on the rings; the 001 Table 1
  ranges are recomputed for several spacings (``ta = tb = tan(phi/2)``).

The Stewart limits under 000 Table 1: strokes 175-250 mm, the base universal joints +-45
deg (the range 000 gives the hybrid's revolute joints at the same place) and the platform
spherical joints +-20 deg.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..workspace.components import HomeComponent, home_component, signs_near_reachable
from ..workspace.grid import Axis, Grid, fixed_from_user
from ..workspace.membership import DEFAULT_CRITERIA, Criteria, load_module
from ..workspace.ranges import coordinate_range
from ..workspace.scan import ScanResult, scan

DEG = math.pi / 180

# ---------------------------------------------------------------- printed values
HOMING = (0.0, 0.0, 210.0)  # 001 Table 1
TARGET = (-8.8, -50.0, 283.8)  # 001 Table 1 (Sect. 4.2 prints z = 283.7 once)
TABLE1_001 = {  # (mechanism, position) -> angle -> (min, max, printed width), degrees
    ("stewart", "homing"): {"alpha": (-16, 16, 32), "beta": (-16, 14, 30),
                            "gamma": (-23, 23, 46)},
    ("tripod_planar", "homing"): {"alpha": (-14.5, 19.5, 34), "beta": (-17.5, 17.5, 35),
                                  "gamma": (-52, 49, 101)},
    ("stewart", "target"): {"alpha": (-5, 15, 20), "beta": (-17, 10, 27),
                            "gamma": (-8, 8, 16)},
    ("tripod_planar", "target"): {"alpha": (-23, 9, 32), "beta": (-14.5, 14.5, 29),
                                  "gamma": (-28, 31, 54)},
}
TABLE2_000 = {  # mechanism -> coordinate -> printed range (mm, deg)
    "planar_tripod": {"x": 175, "y": 170, "z": 75, "alpha": 37, "beta": 22, "gamma": 105},
    "stewart": {"x": 150, "y": 150, "z": 77, "alpha": 32, "beta": 28, "gamma": 40},
}
TABLE1_000 = {"ra": 190.0, "rb": 190.0, "q": (175.0, 250.0), "revolute_deg": 45.0,
              "spherical_deg": 20.0}
STEWART_000 = Criteria(limits={"q*": TABLE1_000["q"],
                               "phi_u*": (-TABLE1_000["revolute_deg"] * DEG,
                                          TABLE1_000["revolute_deg"] * DEG),
                               "phi_s*": (-TABLE1_000["spherical_deg"] * DEG,
                                          TABLE1_000["spherical_deg"] * DEG)})
STEWART_000_PARAMS = {"ra": TABLE1_000["ra"], "rb": TABLE1_000["rb"]}
LAYOUTS = (1 / 16, 1 / 8, 1 / 5, 1 / 4)  # tan(phi/2) of the Stewart layout study

ANGLE_STEP = 0.5 * DEG
ANGLE_TOL = 0.01 * DEG
ANGLE_BOUND = (-90 * DEG, 90 * DEG)


@dataclass(frozen=True)
class RangeRow:
    ref: str
    mechanism: str
    position: str
    coordinate: str
    paper: tuple[float, float, float] | None  # min, max, printed width
    ours: tuple[float, float]
    resolution: str
    stops: tuple[str, str]


def _status_name(module, code) -> str:
    if code is None:
        return "search bound"
    return {getattr(module, k): k for k in ("OK", "NO_REAL_SOLUTION", "JOINT_AT_INFINITY",
                                            "ON_BOUNDARY", "INPUT_SINGULAR", "INVALID_INPUT",
                                            "STROKE_LIMIT", "PASSIVE_JOINT_LIMIT",
                                            "FORWARD_SINGULAR", "OUTSIDE_CHART")}.get(
        code, f"code {code}")


def angular_ranges(mechanism: str, position: Sequence[float], criteria: Criteria = DEFAULT_CRITERIA,
                   **params) -> dict[str, tuple[float, float, tuple[str, str]]]:
    """001 Table 1 ranges (degrees) of alpha, beta, gamma at ``position`` (x, y, z)."""
    module = load_module(mechanism)
    ref = [*position, 0.0, 0.0, 0.0]
    out = {}
    for name in ("alpha", "beta", "gamma"):
        r = coordinate_range(mechanism, ref, name, ANGLE_BOUND, ANGLE_STEP, ANGLE_TOL,
                             criteria, **params)
        out[name] = (math.degrees(r.lo), math.degrees(r.hi),
                     (_status_name(module, r.stop_lo), _status_name(module, r.stop_hi)))
    return out


def table1_001() -> list[RangeRow]:
    rows = []
    for (mech, where), printed in TABLE1_001.items():
        pos = HOMING if where == "homing" else TARGET
        got = angular_ranges(mech, pos)
        for name, (lo, hi, stops) in got.items():
            rows.append(RangeRow("001 Table 1", mech, f"{where} {pos}", name, printed[name],
                                 (lo, hi), "boundary search: step 0.5 deg, bisection to "
                                 "0.01 deg", stops))
    return rows


def layout_study() -> list[dict]:
    """001 Table 1 Stewart rows for several joint spacings ``ta = tb``."""
    out = []
    for t in LAYOUTS:
        for where, pos in (("homing", HOMING), ("target", TARGET)):
            got = angular_ranges("stewart", pos, ta=t, tb=t)
            out.append({"tan_half_phi": t, "phi_deg": round(2 * math.degrees(math.atan(t)), 4),
                        "position": where,
                        **{f"{k}_range_deg": [rounded(v[0]), rounded(v[1])]
                           for k, v in got.items()}})
    return out


def rounded(v: float | None, nd: int = 2) -> float | None:
    """Rounded for the written tables; None (JSON null) for None or NaN, e.g. the reference
    pose itself outside the workspace."""
    return round(v, nd) if v is not None and math.isfinite(v) else None


# ------------------------------------------------------------------ 000 Table 2
def mid_stroke_height(mechanism: str, joints: Sequence[int], stroke: float,
                      criteria: Criteria = DEFAULT_CRITERIA, **params) -> float:
    """The height z (x = y = 0, angles 0) at which the mean of ``joints`` is ``stroke``
    (bisection on the IK, limits off)."""
    module = load_module(mechanism)

    def mean_q(z):
        q = module.ik(np.array([0.0, 0.0, z, 0.0, 0.0, 0.0]), criteria.modes[0], False,
                      **params)
        return float(np.mean(q[list(joints)]))

    lo, hi = 1.0, 2000.0
    if not mean_q(lo) < stroke < mean_q(hi):
        raise ValueError(f"{mechanism}: no height in [{lo}, {hi}] mm gives a mean stroke of "
                         f"{stroke} mm")
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mean_q(mid) < stroke else (lo, mid)
    return 0.5 * (lo + hi)


@dataclass(frozen=True)
class Table2Setup:
    mechanism: str
    criteria: Criteria
    params: dict
    height: float
    variant: str = ""  # a sensitivity variant of an unspecified set-up choice
    planar_only: bool = False  # only the (x, y, gamma) scan


PLANAR_STROKES_001 = (120.0, 325.0)  # 001 Sect. 3, the double-triangular stage's range


def table2_setups(recovered: tuple[float, float] | None = None) -> list[Table2Setup]:
    """The 000 Table 2 set-ups; ``recovered``: a planar stroke range (mm) found by
    :mod:`.planar_stroke_000`, added as one more planar-only variant."""
    mid = sum(TABLE1_000["q"]) / 2
    h_hybrid = mid_stroke_height("planar_tripod", (3, 4, 5), mid)
    extra = [] if recovered is None else [
        Table2Setup("planar_tripod", Criteria(limits={"q[123]": recovered}), {}, h_hybrid,
                    f"planar strokes {recovered[0]:g}-{recovered[1]:g} mm, recovered from "
                    "Table 2", planar_only=True)]
    return [Table2Setup("planar_tripod", Criteria(), {}, h_hybrid),
            Table2Setup("planar_tripod", Criteria(limits={"q[123]": PLANAR_STROKES_001}), {},
                        h_hybrid, "planar strokes 120-325 mm", planar_only=True), *extra,
            Table2Setup("stewart", STEWART_000, dict(STEWART_000_PARAMS),
                        mid_stroke_height("stewart", range(6), mid, STEWART_000,
                                          **STEWART_000_PARAMS))]


XY_AXES = dict(x=(-160.0, 160.0, 2.0), y=(-160.0, 160.0, 2.0), gamma=(-90.0, 90.0, 1.0))
ABZ_AXES = dict(alpha=(-40.0, 40.0, 0.5), beta=(-40.0, 40.0, 0.5), z=(-80.0, 80.0, 1.0))


def user_grid(pose_names, axes: dict, fixed: dict) -> Grid:
    return Grid(tuple(pose_names), tuple(Axis.from_user(k, *v) for k, v in axes.items()),
                fixed_from_user(pose_names, fixed))


def xyg_grid(pose_names, height: float, axes=XY_AXES) -> Grid:
    return user_grid(pose_names, axes, {"z": height, "alpha": 0.0, "beta": 0.0})


def abz_grid(pose_names, height: float, axes=ABZ_AXES) -> Grid:
    ax = []
    for k, (lo, hi, step) in axes.items():
        ax.append(Axis.from_user(k, height + lo, height + hi, step) if k == "z"
                  else Axis.from_user(k, lo, hi, step))
    return Grid(tuple(pose_names), tuple(ax), {"x": 0.0, "y": 0.0, "gamma": 0.0})


def slice_extents(res: ScanResult, along: str, across: str) -> tuple[np.ndarray, np.ndarray]:
    """Per sample of axis ``across``: the extent of the reachable set along ``along``
    (NaN where the slice is empty), and the ``across`` values."""
    names = [a.name for a in res.grid.axes]
    i, j = names.index(along), names.index(across)
    ax_i, ax_j = res.grid.axes[i], res.grid.axes[j]
    other = tuple(k for k in range(len(names)) if k not in (i, j))
    present = res.mask.any(axis=other) if other else res.mask  # shape in (i, j) order
    if i > j:
        present = present.T
    vals = ax_i.values()
    ext = np.full(ax_j.n, np.nan)
    for c in range(ax_j.n):
        hit = np.nonzero(present[:, c])[0]
        if hit.size:
            ext[c] = vals[hit[-1]] - vals[hit[0]]
    return ext, ax_j.values()


def _home_scan(mechanism: str, grid: Grid, criteria: Criteria, home: dict[str, float],
               workers: int | None, params: dict) -> tuple[ScanResult, HomeComponent]:
    """A scan and its home component: the poses reachable from ``home`` (internal units)
    without crossing a singularity (:mod:`..workspace.components`)."""
    res = scan(mechanism, grid, criteria, workers=workers, **params)
    return res, home_component(res, signs_near_reachable(res), home)


def _clipped(comp: ScanResult, name: str) -> bool:
    """Does the component reach the end of the grid axis ``name`` (its range then only a
    lower bound)?"""
    ax = next(a for a in comp.grid.axes if a.name == name)
    lo, hi = comp.ranges[name]
    return bool(lo <= ax.lo + 1e-12 or hi >= ax.hi - 1e-12)


def table2_000(workers: int | None = None, recovered: tuple[float, float] | None = None
               ) -> tuple[list[dict], dict[str, ScanResult]]:
    """000 Table 2 rows and the scans behind them (masks kept for the plots).  Each range
    is that of the home component (x = y = gamma = 0, resp. alpha = beta = 0 at the
    mid-stroke height): the poses reachable from home without crossing a singularity; the
    rows also give the extent of every pose within the joint ranges (``limits_only``)."""
    rows, scans = [], {}
    for s in table2_setups(recovered):
        module = load_module(s.mechanism)
        xyg_all, xyg_home = _home_scan(s.mechanism, xyg_grid(module.POSE, s.height),
                                       s.criteria, {"x": 0.0, "y": 0.0, "gamma": 0.0},
                                       workers, s.params)
        xyg = xyg_home.result
        found = {"xyg": (xyg_all, xyg_home)}
        ext_x, gam = slice_extents(xyg, "x", "gamma")
        ext_y, _ = slice_extents(xyg, "y", "gamma")
        best = int(np.nanargmax(ext_x)) if np.any(np.isfinite(ext_x)) else None
        steps = {a.name: a.step for a in xyg.grid.axes}
        got = {
            "x": (float(np.nanmax(ext_x)), steps["x"], "xyg"),
            "y": (float(np.nanmax(ext_y)), steps["y"], "xyg"),
            "gamma": (math.degrees(xyg.extent("gamma")), math.degrees(steps["gamma"]), "xyg"),
        }
        if not s.planar_only:
            abz_all, abz_home = _home_scan(s.mechanism, abz_grid(module.POSE, s.height),
                                           s.criteria, {"alpha": 0.0, "beta": 0.0,
                                                        "z": s.height}, workers, s.params)
            abz = abz_home.result
            found["abz"] = (abz_all, abz_home)
            scans[f"{s.mechanism}/xyg"], scans[f"{s.mechanism}/abz"] = xyg, abz
            steps.update({a.name: a.step for a in abz.grid.axes})
            got.update({
                "z": (abz.extent("z"), steps["z"], "abz"),
                "alpha": (math.degrees(abz.extent("alpha")), math.degrees(steps["alpha"]),
                          "abz"),
                "beta": (math.degrees(abz.extent("beta")), math.degrees(steps["beta"]),
                         "abz"),
            })
        for name, (value, step, which) in got.items():
            res_all, home = found[which]
            unit = 1.0 if name in "xyz" else math.degrees(1.0)
            if name in "xy":
                e_all, _ = slice_extents(res_all, name, "gamma")
                limits_only = float(np.nanmax(e_all))
            else:
                limits_only = res_all.extent(name) * unit
            rows.append({"ref": "000 Table 2", "mechanism": s.mechanism,
                         "variant": s.variant, "coordinate": name,
                         "unit": "mm" if name in "xyz" else "deg",
                         "paper": TABLE2_000[s.mechanism][name], "ours": round(value, 3),
                         "limits_only": round(limits_only, 3),
                         "clipped_by_grid": _clipped(home.result, name),
                         "bounding_loci": sorted(k for k, n in home.bounding.items() if n),
                         "grid_step": round(step, 6),
                         "height_mm": round(s.height, 3),
                         "gamma_at_max_x_deg": (round(math.degrees(gam[best]), 3)
                                                if best is not None and name in "xy" else None)})
    return rows, scans


# ------------------------------------------------------------- 001 Sect. 4.2 path
# the steps of 001 Sect. 4.2 in the paper's coordinates (x, y, z, alpha, beta, gamma; mm,
# deg), from the homing position; their sums are Table 2 (z: 43.8 + 30 = 73.8 against the
# printed 73.7, the target z of Table 1 is 210 + 73.8 = 283.8)
PATH_001 = (
    {5: -22.2},                                  # rotate -22.2 deg about z
    {0: -8.8, 1: -50.0, 2: HOMING[2] + 43.8},    # translate x, y and 43.8 mm along z
    {3: 2.7, 4: -10.9},                          # rotate alpha 2.7 deg, beta -10.9 deg
    {2: HOMING[2] + 43.8 + 30.0},                # translate 30 mm along z
    {3: 2.7 + 3.0, 4: -10.9 - 12.0},             # rotate alpha 3 deg, beta -12 deg
)
PATH_SAMPLES = 41


STROKES_ONLY = Criteria(limits={"phi*": (-math.pi, math.pi)})  # passive ranges switched off
D_STUDY = tuple(float(d) for d in range(0, 101, 1))  # mm, height of the planar stage


def path_001(samples_per_step: int = PATH_SAMPLES) -> tuple[np.ndarray, np.ndarray]:
    """Times and paper coordinates of the 001 Sect. 4.2 path (angles in rad)."""
    from ..workspace.trajectory import stepwise_path

    steps = [{i: (math.radians(v) if i >= 3 else v) for i, v in s.items()} for s in PATH_001]
    return stepwise_path([*HOMING, 0.0, 0.0, 0.0], steps, samples_per_step)


def trajectory_001(samples_per_step: int = PATH_SAMPLES, d: float = 0.0):
    """The 001 Sect. 4.2 bone-reduction path for ``tripod_planar`` (the steps are in the
    paper's mechanism coordinates, converted with ``pose_from_paper_coordinates``) and for
    ``stewart`` (the same end-effector poses), each step one time unit; ``d`` is the
    hybrid's planar-stage height (not given in 001)."""
    from ..workspace.trajectory import follow

    t, paper = path_001(samples_per_step)
    poses = load_module("tripod_planar").pose_from_paper_coordinates(paper, d=d)
    return paper, {"tripod_planar": follow("tripod_planar", t, poses, d=d),
                   "stewart": follow("stewart", t, poses)}


def d_study_001(samples_per_step: int = PATH_SAMPLES) -> list[dict]:
    """Whether the hybrid follows the 001 path, for each planar-stage height d in
    ``D_STUDY``: with the strokes only (001 Sect. 4.2 checks the input variables) and
    with the spherical-joint range as well."""
    from ..workspace.trajectory import follow

    t, paper = path_001(samples_per_step)
    module = load_module("tripod_planar")
    out = []
    for d in D_STUDY:
        poses = module.pose_from_paper_coordinates(paper, d=d)
        strokes = follow("tripod_planar", t, poses, STROKES_ONLY, d=d)
        full = follow("tripod_planar", t, poses, d=d)
        out.append({"d_mm": d, "strokes_only_feasible": strokes.feasible,
                    "min_stroke_margin_mm": rounded(float(np.nanmin(strokes.stroke_margin))),
                    "feasible_with_spherical_range": full.feasible,
                    "min_spherical_margin_deg": rounded(math.degrees(float(
                        np.nanmin(full.passive_margin))))})
    return out


# ------------------------------------------------- 001 Sect. 3: singularities inside?
SING_GRIDS_001 = {  # name -> (axes in user units (lo, hi, step), fixed in user units)
    "xyz": (dict(x=(-150.0, 150.0, 3.0), y=(-150.0, 150.0, 3.0), z=(150.0, 350.0, 4.0)),
            dict(alpha=0.0, beta=0.0, gamma=0.0)),
    "abg_homing": (dict(alpha=(-40.0, 40.0, 1.0), beta=(-40.0, 40.0, 1.0),
                        gamma=(-90.0, 90.0, 2.0)), dict(x=0.0, y=0.0, z=HOMING[2])),
}
SING_SLICES_001 = {  # 2-D slices for the plots
    "gamma_alpha": (dict(gamma=(-90.0, 90.0, 0.5), alpha=(-40.0, 40.0, 0.5)),
                    dict(x=0.0, y=0.0, z=HOMING[2], beta=0.0)),
    "x_y": (dict(x=(-200.0, 200.0, 2.0), y=(-200.0, 200.0, 2.0)),
            dict(z=HOMING[2], alpha=0.0, beta=0.0, gamma=0.0)),
}


def singularities_001(workers: int | None = None) -> tuple[list[dict], dict]:
    """For ``tripod_planar`` and, for the comparison, ``stewart`` (its forward singularity
    ``det_forward_P`` among its polynomials): per grid of ``SING_GRIDS_001``, the reachable
    samples and, per singularity polynomial, the reachable neighbour pairs it separates
    (``singular_loci``), the home component (the homing pose's,
    :mod:`..workspace.components`) and the loci it reaches; and the 2-D slices (scan,
    signs) for the plots."""
    from ..workspace.singular_loci import crossings, polynomial_signs, signs_on_reachable

    module = load_module("tripod_planar")
    home_pose = dict(zip(module.POSE, (*HOMING, 0.0, 0.0, 0.0)))
    rows = []
    for mech, (name, (axes, fixed)) in ((m, g) for m in ("tripod_planar", "stewart")
                                        for g in SING_GRIDS_001.items()):
        res = scan(mech, user_grid(module.POSE, axes, fixed), workers=workers)
        # the signs on the reachable samples and two steps around them: all that the
        # crossings, the counts on the reachable set and the home component read
        signs = signs_near_reachable(res)
        home = home_component(res, signs, {a.name: home_pose[a.name] for a in res.grid.axes})
        rows.append({"mechanism": mech, "grid": name, "description": res.grid.describe(),
                     "samples": res.samples,
                     "reachable": res.count, "crossing_pairs": crossings(res, signs),
                     "signs_on_reachable": signs_on_reachable(res, signs),
                     "home_component": {"samples": home.count,
                                        "reachable_elsewhere": home.reachable_elsewhere,
                                        "samples_next_to_locus": home.bounding,
                                        "vanishing_at_home": list(home.vanishing_at_home)}})
    slices = {}
    for name, (axes, fixed) in SING_SLICES_001.items():
        res = scan("tripod_planar", user_grid(module.POSE, axes, fixed), workers=workers)
        slices[name] = (res, polynomial_signs(res, workers=workers))
    return rows, slices


# ------------------------------------------------------- 000 eq. 43-44 and Stewart
PATH_000_SAMPLES = 361


def paths_000() -> dict[str, dict]:
    """000 eq. (43) and (44) (t in [0, 2 pi]) for ``planar_tripod`` (z about its mid-stroke
    height, as in its report) and for ``stewart`` with 000 Table 1 (z about its own
    mid-stroke height): can each follow them within its strokes and joint ranges?"""
    from ..workspace.trajectory import follow
    from .trajectories_000 import Z_HOME, trajectory_eq43, trajectory_eq44

    t = np.linspace(0.0, 2 * np.pi, PATH_000_SAMPLES)
    setups = table2_setups()
    h_stewart = next(s.height for s in setups if s.mechanism == "stewart")
    out = {}
    for label, traj in (("eq43", trajectory_eq43), ("eq44", trajectory_eq44)):
        pose, _ = traj(t)
        shifted = pose.copy()
        shifted[:, 2] += h_stewart - Z_HOME
        out[label] = {"planar_tripod": follow("planar_tripod", t, pose),
                      "stewart": follow("stewart", t, shifted, STEWART_000,
                                        **STEWART_000_PARAMS)}
    return out


# ------------------------------------------------------ 001 Figs. 9-10 and Sect. 3
LINEAR_001 = {"stewart": {"x": 155.0, "y": 150.0, "z": 165.0},  # 001 Sect. 3 text
              "tripod_planar": {"x": 197.0, "y": 194.0}}
FIG9_AXES = dict(x=(-160.0, 160.0, 4.0), y=(-160.0, 160.0, 4.0), z=(120.0, 380.0, 4.0))
FIG10_AXES = dict(alpha=(-40.0, 40.0, 1.0), beta=(-40.0, 40.0, 1.0), gamma=(-90.0, 90.0, 2.0))


def figures_001(workers: int | None = None) -> tuple[list[dict], dict]:
    """001 Fig. 9 (the (x, y, z) workspace, angles 0) and Fig. 10 (the angular workspace
    at the homing position and at the target) for both mechanisms, and the linear ranges
    quoted in 001 Sect. 3 (extents of the Fig. 9 workspace)."""
    rows, scans = [], {}
    for mech in ("tripod_planar", "stewart"):
        names = load_module(mech).POSE
        res = scan(mech, user_grid(names, FIG9_AXES, dict(alpha=0.0, beta=0.0, gamma=0.0)),
                   workers=workers)
        scans[f"{mech}/xyz"] = res
        for c, printed in LINEAR_001[mech].items():
            step = next(a.step for a in res.grid.axes if a.name == c)
            rows.append({"ref": "001 Sect. 3", "mechanism": mech, "coordinate": c,
                         "paper_mm": printed, "ours_mm": round(res.extent(c), 3),
                         "grid_step_mm": step})
        for where, pos in (("homing", HOMING), ("target", TARGET)):
            scans[f"{mech}/abg_{where}"] = scan(
                mech, user_grid(names, FIG10_AXES, dict(zip(("x", "y", "z"), pos))),
                workers=workers)
    return rows, scans
