"""002 Sect. 5.2-5.3: the +-30 deg workspace of the 2-URRH RCM manipulator.

On the 13 x 13 grid of Sect. 5.2 (the U joints' first angles alpha1, alpha2 from -30 to
30 deg in 5 deg steps) the shaft direction follows from the fixed axes alone (eq. 6, or
the generated ``fk``).  At each direction two routes give the reachable (d, gamma):

* per collar: the positions d1, d2 along the shaft (d_i >= 0, the collars' side of O: the
  module's ``LIMITS``) where that limb's joint of the generated IK (working mode 0, the
  physical elbows) is real; the reachable (d, gamma) is then d in D1 and gamma in
  (d - D2)/p (eq. 9, 11);
* through the workspace tool (:mod:`bonered_alg.workspace`: IK status, every limit): the
  range of d at gamma = 0 and the range of gamma at the middle of it, by boundary search;
  and at the home direction a (d, gamma) scan with its home component (the poses reached
  from home without crossing a singularity).

The two must agree (``tool_error``).  Table 1 gives no slider strokes and the paper no
passive-joint ranges, so nothing else limits them: the ranges are the reach of the planar
linkages.  Sect. 5.3 drives d from 100 to 160 mm; the ranges say whether this model can.
"""

from __future__ import annotations

import numpy as np

from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from ..verification import noise_bound
from ..workspace.components import home_component, signs_near_reachable
from ..workspace.grid import Axis, Grid
from ..workspace.ranges import coordinate_range
from ..workspace.scan import scan
from .files import csv_text, png, pyplot

NAME = "urrh_rcm"
ANGLES_DEG = np.arange(-30.0, 30.0 + 2.5, 5.0)  # 002 Sect. 5.2: 13 values
# mm, the search along the shaft: d >= 0, u pointing from O towards the collars (eq. 5;
# a collar at -d is the same configuration described with the opposite u)
D_GRID = np.arange(0.0, 220.0 + 0.025, 0.05)
D_STEP, D_TOL = 1.0, 1e-4  # mm: the tool's march along d and its bisection
G_STEP, G_TOL = 0.1, 1e-5  # rad: the same along gamma
G_BOUND = 40.0  # rad: the search bound of gamma (at p = 10 mm, 400 mm of collar 2)
HOME_GRID = (Axis("d", 0.0, 200.0, 401), Axis("gamma", -12.0, 12.0, 481))  # 0.5 mm, 0.05 rad


def direction_pose(alpha1: float, alpha2: float) -> tuple[float, float]:
    """(theta1, theta2) of the shaft the U joints' first angles give: theta1 = alpha1
    (the ideal's generator a1 - w1), tan(theta2) = tan(alpha2) cos(theta1) (its generator in
    a2, w1, w2 solved for w2 on the branch |theta2| < pi/2)."""
    return alpha1, float(np.arctan(np.tan(alpha2) * np.cos(alpha1)))


def _interval(ok: np.ndarray) -> tuple[float, float] | None:
    if not ok.any():
        return None
    return float(D_GRID[ok].min()), float(D_GRID[ok].max())


def _contiguous(ok: np.ndarray) -> bool:
    idx = np.flatnonzero(ok)
    return idx.size == 0 or idx[-1] - idx[0] + 1 == idx.size


def collar_ranges(gen, alpha1: float, alpha2: float) -> dict:
    """The reachable d1 and d2 (mm) at the shaft direction of (alpha1, alpha2), whether
    each is one interval, and how well the direction's IK gives back alpha1, alpha2."""
    t1, t2 = direction_pose(alpha1, alpha2)
    poses = np.stack([np.full_like(D_GRID, t1), np.full_like(D_GRID, t2), D_GRID,
                      np.zeros_like(D_GRID)], axis=-1)
    status = gen.ik_joint_status(poses, limits=False)
    ok1 = status[:, gen.JOINTS.index("beta1")] == 0
    ok2 = status[:, gen.JOINTS.index("beta2")] == 0
    q = gen.ik(poses[ok1 & ok2][:1], limits=False)
    back = float(np.abs(q[0, :2] - [alpha1, alpha2]).max()) if len(q) else None
    return {"d1": _interval(ok1), "d2": _interval(ok2), "alpha_error": back,
            "one_interval": _contiguous(ok1) and _contiguous(ok2)}


def tool_ranges(gen, alpha1: float, alpha2: float, ranges: dict) -> dict:
    """Through the workspace tool at the direction of (alpha1, alpha2): the range of d at
    gamma = 0 and of gamma at d_ref, the middle of D1 and D2's common part, and the largest
    distance (mm; gamma times p) of their ends from the per-collar route's."""
    t1, t2 = direction_pose(alpha1, alpha2)
    d1, d2 = ranges["d1"], ranges["d2"]
    lo, hi = max(d1[0], d2[0]), min(d1[1], d2[1])
    d_ref = 0.5 * (lo + hi)
    ref = (t1, t2, d_ref, 0.0)
    rd = coordinate_range(gen, ref, "d", (0.0, D_GRID[-1]), D_STEP, D_TOL)
    rg = coordinate_range(gen, ref, "gamma", (-G_BOUND, G_BOUND), G_STEP, G_TOL)
    p = gen.PARAMETERS["p"]
    expect = ((d_ref - d2[1]) / p, (d_ref - d2[0]) / p)  # d2 = d_ref - p gamma in D2
    err = max(abs(rd.lo - lo), abs(rd.hi - hi), p * abs(rg.lo - expect[0]),
              p * abs(rg.hi - expect[1]))
    return {"d": (rd.lo, rd.hi), "gamma": (rg.lo, rg.hi), "d_ref": d_ref, "error": err,
            "stops": (rd.stop_lo, rd.stop_hi, rg.stop_lo, rg.stop_hi)}


def home_scan(gen, home) -> dict:
    """The tool's (d, gamma) scan at the home direction and its home component, against
    the per-collar route's set {d in D1, d - p gamma in D2} on the same samples."""
    grid = Grid(gen.POSE, HOME_GRID, {"theta1": 0.0, "theta2": 0.0})
    res = scan(gen, grid, workers=1)
    comp = home_component(res, signs_near_reachable(res), {"d": 80.0, "gamma": 0.0})
    dd, gg = np.meshgrid(HOME_GRID[0].values(), HOME_GRID[1].values(), indexing="ij")
    d2 = dd - gen.PARAMETERS["p"] * gg
    (lo1, hi1), (lo2, hi2) = home["d1"], home["d2"]
    step = D_GRID[1] - D_GRID[0]  # the per-collar route's resolution
    inner = (dd >= lo1) & (dd <= hi1) & (d2 >= lo2) & (d2 <= hi2)
    outer = ((dd >= lo1 - step) & (dd <= hi1 + step) & (d2 >= lo2 - step)
             & (d2 <= hi2 + step))
    return {"result": res, "component": comp, "inner": int(inner.sum()),
            "outer": int(outer.sum()), "agrees": bool((res.mask >= inner).all()
                                                      and (res.mask <= outer).all())}


def run(d, gen) -> Study:
    p = gen.PARAMETERS["p"]
    rows, table = [], {}
    for a1 in ANGLES_DEG:
        for a2 in ANGLES_DEG:
            r = collar_ranges(gen, np.radians(a1), np.radians(a2))
            table[(float(a1), float(a2))] = r
            d1, d2 = r["d1"] or (np.nan, np.nan), r["d2"] or (np.nan, np.nan)
            t = tool_ranges(gen, np.radians(a1), np.radians(a2), r) if r["d1"] and r["d2"] \
                else None
            r["tool"] = t
            rows.append((a1, a2, *d1, *d2, (d2[1] - d2[0]) / p,
                         *(t["d"] if t else (np.nan, np.nan)),
                         *(t["gamma"] if t else (np.nan, np.nan))))
    d1max = max(r["d1"][1] for r in table.values() if r["d1"])
    d2max = max(r["d2"][1] for r in table.values() if r["d2"])
    both = [r for r in table.values() if r["d1"] and r["d2"]]
    common = max(min(r["d1"][1], r["d2"][1]) for r in both)
    reach_all = len(both) == len(table)
    gamma_min = min((r["d2"][1] - r["d2"][0]) / p for r in both)
    alpha_err = max(r["alpha_error"] for r in both if r["alpha_error"] is not None)
    home = table[(0.0, 0.0)]
    tool_err = max(r["tool"]["error"] for r in both)
    hs = home_scan(gen, home)
    data = {"directions": len(table), "reachable_directions": len(both), "d1_max": d1max,
            "d1_home": home["d1"], "d2_home": home["d2"], "p": p,
            "d2_max": d2max, "common_max": common, "gamma_span_min": gamma_min,
            "alpha_error": noise_bound(alpha_err, 1e-9),
            "one_interval": all(r["one_interval"] for r in table.values()),
            "tool_error": tool_err, "tool_step": D_STEP,
            "home_scan": {"samples": hs["result"].samples, "reachable": hs["result"].count,
                          "component": hs["component"].count, "inner": hs["inner"],
                          "outer": hs["outer"], "agrees": hs["agrees"]}}
    csv = csv_text(("alpha1_deg", "alpha2_deg", "d1_min_mm", "d1_max_mm", "d2_min_mm",
                    "d2_max_mm", "gamma_span_rad", "tool_d_min_mm", "tool_d_max_mm",
                    "tool_gamma_min_rad", "tool_gamma_max_rad"), rows, ".6g")
    return Study("workspace_002", data, {f"{NAME}.workspace.csv": csv,
                                         f"{NAME}.workspace.png": _plot(gen, table, hs)},
                 tuple(_report(data, reach_all, p)))


def _plot(gen, table, hs) -> bytes:
    """The radial shaft lines of the grid (002 Fig. 10a), each drawn over the reachable
    positions of collar 1; the reachable d1, d2 along the alpha1 = alpha2 diagonal; the
    tool's (d, gamma) scan at the home direction."""
    plt = pyplot()
    fig = plt.figure(figsize=(13.0, 4.2))
    ax = fig.add_subplot(1, 3, 1, projection="3d")
    for (a1, a2), r in table.items():
        if not r["d1"]:
            continue
        t1, t2 = direction_pose(np.radians(a1), np.radians(a2))
        u = gen.shaft(np.array([t1, t2, 0.0, 0.0]))[:3]
        seg = np.outer(np.array(r["d1"]), u)
        ax.plot(*(np.outer([0.0, r["d1"][0]], u).T), color="0.75", lw=0.4)
        ax.plot(*seg.T, color="C0", lw=0.7)
    ax.plot([], [], color="C0", label="reachable collar 1 (d1)")
    ax.plot([], [], color="0.8", label="shaft from O")
    ax.set(xlabel="x (mm)", ylabel="y (mm)", zlabel="z (mm)",
           title="13 x 13 shaft directions, +-30 deg")
    ax.legend(fontsize=6, loc="upper left")
    ax2 = fig.add_subplot(1, 3, 2)
    diag = sorted((a1, r) for (a1, a2), r in table.items() if a1 == a2)
    xs = [a for a, _ in diag]
    for key, colour, label in (("d1", "C0", "collar 1 (d1)"), ("d2", "C1", "collar 2 (d2)")):
        lo = [r[key][0] if r[key] else np.nan for _, r in diag]
        hi = [r[key][1] if r[key] else np.nan for _, r in diag]
        ax2.fill_between(xs, lo, hi, color=colour, alpha=0.3, label=label)
    ax2.axhspan(100.0, 160.0, color="red", alpha=0.08, label="002 Sect. 5.3: d 100-160 mm")
    ax2.set(xlabel="alpha1 = alpha2 (deg)", ylabel="position along the shaft (mm)",
            title="reachable collar positions (mode 0)")
    ax2.legend(fontsize=6, loc="lower left")
    ax3 = fig.add_subplot(1, 3, 3)
    res, comp = hs["result"], hs["component"].result
    dv, gv = HOME_GRID[0].values(), HOME_GRID[1].values()
    shade = res.mask.astype(float) + comp.mask.astype(float)
    ax3.pcolormesh(dv, gv, shade.T, cmap="Blues", vmin=0.0, vmax=2.5, shading="nearest",
                   rasterized=True)
    ax3.plot([], [], "s", color=plt.get_cmap("Blues")(0.8), label="home component")
    ax3.plot([], [], "s", color=plt.get_cmap("Blues")(0.4), label="reachable elsewhere")
    ax3.set(xlabel="d (mm)", ylabel="gamma (rad)",
            title=f"(d, gamma) at the home direction, p = {gen.PARAMETERS['p']:g} mm")
    ax3.legend(fontsize=6, loc="upper right")
    fig.tight_layout()
    return png(fig)


def _report(data, reach_all, p) -> list[str]:
    return [
        r"\section{Workspace (002 Sect.~5.2--5.3)}",
        "On the $13\\times 13$ grid of the U joints' first angles ($\\pm 30^\\circ$, "
        "$5^\\circ$ steps) the shaft direction follows from $\\alpha_1, \\alpha_2$ alone; "
        "at each direction the reachable positions of collar~1 and collar~2 along the shaft "
        "are the intervals where the IK of $\\beta_1$, resp.\\ $\\beta_2$ is real in working "
        "mode~0 (the physical elbows), searched in steps of 0.05~mm from $O$ along $u$ "
        "($d_i \\ge 0$: $u$ points towards the collars, and the collars stay on their side "
        "of $O$, the module's limits). Table~1 gives no slider strokes and the paper no "
        "passive-joint ranges: nothing else limits them here (assumed).",
        "The same through the workspace tool (membership: the IK real and regular in mode~0 "
        "and every limit): at each direction the range of $d$ at $\\gamma = 0$ and the "
        "range of $\\gamma$ at the middle $d_{\\mathrm{ref}}$ of the collars' common range, "
        f"by a march of {data['tool_step']:g}~mm (0.1~rad) and bisection. They are "
        "$D_1\\cap D_2$ and $(d_{\\mathrm{ref}} - D_2)/p$ to "
        f"{data['tool_error']:.3f}~mm (the per-collar route's 0.05~mm steps): the two routes "
        "agree. At the home direction the tool's $(d, \\gamma)$ scan "
        f"({data['home_scan']['samples']} samples, 0.5~mm by 0.05~rad) finds "
        f"{data['home_scan']['reachable']} reachable, "
        + ("all inside the per-collar set and every sample of it found"
           if data["home_scan"]["agrees"] else "NOT the per-collar set")
        + f"; {data['home_scan']['component']} of them are reached from home "
        "($d = 80$~mm, $\\gamma = 0$) without crossing a singularity (the plot's right "
        "panel).",
        f"Directions with both collars reachable: {data['reachable_directions']} of "
        f"{data['directions']}"
        + (" (every direction of the grid)." if reach_all else ".")
        + f" Largest $d_1$: {data['d1_max']:.1f}~mm; largest $d_2$: {data['d2_max']:.1f}~mm; "
        f"largest $d$ with $\\gamma = 0$ (both collars at $d$): {data['common_max']:.1f}~mm. "
        f"The spin range at a fixed $d$ is $|D_2|/p$, at least "
        f"{data['gamma_span_min']:.2f}~rad at $p = {p:g}$~mm (assumed): "
        + ("full-cycle rotation everywhere, as Sect.~5.2 states."
           if data["gamma_span_min"] >= 2 * np.pi else
           "less than a full turn at some directions, against Sect.~5.2's full-cycle "
           "rotation at this pitch."),
        "Sect.~5.3 drives $d$ from 100 to 160~mm at five directions about home (Table~2, "
        "column \\#0 presumably home). Measured from $O$ to collar~1 (eq.~9), at the home "
        f"direction collar~1 reaches $d_1 \\in [{data['d1_home'][0]:.1f}, "
        f"{data['d1_home'][1]:.1f}]$~mm and collar~2 $d_2 \\in [{data['d2_home'][0]:.1f}, "
        f"{data['d2_home'][1]:.1f}]$~mm, so with $\\gamma = 0$ (both collars at $d$) "
        f"$d \\le {min(data['d1_home'][1], data['d2_home'][1]):.1f}$~mm; only directions "
        f"tilted towards a limb's base reach further (at most {data['d1_max']:.1f}~mm on the "
        "grid). The paper's 100--160~mm cannot be collar~1's distance from the RCM point "
        "with Table~1's lengths; they must be measured from another origin on the shaft "
        "(the tool frame $\\{T\\}$ of Sect.~5.1, whose offset from the collar is not "
        "given) or be relative displacements.",
        f"The grid's IK gives back $\\alpha_1, \\alpha_2$ to {data['alpha_error']:.0e}~rad"
        + ("; each reachable set is one interval" if data["one_interval"] else
           "; some reachable sets are not one interval (the table gives their hull)")
        + ". "
        "Tables: " + tex_escape("urrh_rcm.workspace.csv") + "; plot: "
        + tex_escape("urrh_rcm.workspace.png") + ".",
        r"\begin{center}\includegraphics[width=0.95\textwidth]{urrh_rcm.workspace.png}"
        r"\end{center}",
    ]
