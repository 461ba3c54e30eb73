"""004 Sect. 3.4: the operational workspace of the Pro-Hep-LCT tool and its dexterous part.

On a grid of tool origins ``DEPTH`` below the plane of Pd (as the entry point O), in the
working mode of Table 5: the points reachable with the tool vertical, the dexterous ones
(every tool direction within ``CONE_DEG`` of the vertical reachable), the left and right ends
of the dexterous region on Y = 180 mm for several depths, and the self-motion locus of the
lower mechanism (``det_Jo_Pd = 0``, tool vertical).
"""

from __future__ import annotations

import numpy as np

from ..papers.p004_pro_hep_lct import TABLE5_MODE
from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from ..surgical import pro_hep_lct_tool as tool
from .files import png, pyplot

NAME = "pro_hep_lct"
GRID = {"X": (100.0, 460.0, 4.0), "Y": (-60.0, 460.0, 4.0)}
DEPTH = 110.0
CONE_DEG = 30.0  # 004 Sect. 5: RCM manipulation within +-30 deg in all directions
DEPTH_STUDY = (0.0, 20.0, 40.0, 60.0, 80.0, 110.0, 140.0)


def workspace(gen) -> dict:
    xs, ys = (np.arange(lo, hi + step / 2, step) for lo, hi, step in GRID.values())
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    pts = np.stack([gx, gy, np.full_like(gx, -DEPTH)], axis=-1)
    cone = tool.cone_directions(CONE_DEG)
    vertical = tool.reachable(pts, np.array([[0.0, 0.0, 1.0]]), gen, TABLE5_MODE)[..., 0]
    dexterous = tool.reachable_in_every(pts, cone, gen, TABLE5_MODE)
    c = gen.PARAMETERS["c"]
    planar = np.stack([gx, gy, gx - c, gy], axis=-1)
    q = gen.ik(planar, mode=TABLE5_MODE, limits=False)
    sing = gen.singularities(planar, q)
    line_x = np.arange(100.0, 460.0, 1.0)
    study = []
    for depth in DEPTH_STUDY:
        lp = np.stack([line_x, np.full_like(line_x, 180.0), np.full_like(line_x, -depth)], -1)
        ok = tool.reachable_in_every(lp, cone, gen, TABLE5_MODE)
        study.append((depth, float(line_x[ok].min()) if ok.any() else None,
                      float(line_x[ok].max()) if ok.any() else None))
    return {"X": xs, "Y": ys, "vertical": vertical, "dexterous": dexterous,
            "det_Jo_Pd": sing["det_Jo_Pd"], "det_Jo_Pu": sing["det_Jo_Pu"],
            "depth_study": study, "grid": GRID, "depth": DEPTH, "cone_deg": CONE_DEG,
            "entry_260_180": bool(tool.reachable(np.array([260.0, 180.0, -DEPTH]),
                                                 cone, gen, TABLE5_MODE).all()),
            "entry_200_180": bool(tool.reachable(np.array([200.0, 180.0, -DEPTH]),
                                                 cone, gen, TABLE5_MODE).all())}


def _files(ws, gen) -> dict:
    lines = ["X,Y,vertical_tool_reachable,dexterous"]
    for i, x in enumerate(ws["X"]):
        for j, y in enumerate(ws["Y"]):
            if ws["vertical"][i, j]:
                lines.append(f"{x:g},{y:g},1,{int(ws['dexterous'][i, j])}")
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.2, 5.6))
    ext = (ws["X"][0], ws["X"][-1], ws["Y"][0], ws["Y"][-1])
    img = np.where(ws["dexterous"], 2, np.where(ws["vertical"], 1, 0)).T
    ax.imshow(img, origin="lower", extent=ext, cmap="Blues", vmin=0, vmax=2.4,
              interpolation="nearest", aspect="equal")
    with np.errstate(all="ignore"):
        ax.contour(ws["X"], ws["Y"], np.where(ws["vertical"], ws["det_Jo_Pd"], np.nan).T,
                   levels=[0.0], colors="red", linewidths=1.0)
    ax.axvline(gen.PARAMETERS["lq5"], color="orange", lw=1.0, ls="--",
               label="lq4 = 0 (upper output singularity)")
    ax.axvline(214.0, color="blue", lw=0.8, ls=":", label="004 Fig. 4b: X = 214")
    ax.plot([286.66], [200.0], "kx", label="004: self-motion point")
    ax.plot([260.0, 200.0], [180.0, 180.0], "k.", label="004 Fig. 5 entry points")
    ax.plot([], [], color="red", lw=1.0, label="det_Jo_Pd = 0 (l2 parallel to l4)")
    ax.set(xlabel="X (mm)", ylabel="Y (mm)",
           title=f"tool vertical (light) and dexterous +-{CONE_DEG:g} deg (dark)")
    ax.legend(fontsize=6, loc="lower left")
    return {f"{NAME}.workspace.csv": "\n".join(lines) + "\n", f"{NAME}.workspace.png": png(fig)}


def run(d, gen) -> Study:
    ws = workspace(gen)
    report = (
        r"\section{Operational workspace (004 Sect. 3.4)}",
        tex_escape(f"Tool origins {DEPTH:g} mm below the plane of Pd (as O), grid "
                   f"{GRID['X'][2]:g} mm, working mode {TABLE5_MODE}: reachable with the tool "
                   f"vertical at {int(ws['vertical'].sum())} grid points, dexterous (every "
                   f"direction within {CONE_DEG:g} deg, {6 * 36} directions) at "
                   f"{int(ws['dexterous'].sum())} (file {NAME}.workspace.csv). Left and right "
                   "ends of the dexterous region on Y = 180 mm by depth of the entry point: "
                   + "; ".join(f"{dp:g} mm: {lo} to {hi}" for dp, lo, hi in ws["depth_study"])
                   + "."),
        r"\begin{center}\includegraphics[width=0.8\textwidth]{" + NAME
        + r".workspace.png}\end{center}")
    return Study("workspace", ws, _files(ws, gen), report)
