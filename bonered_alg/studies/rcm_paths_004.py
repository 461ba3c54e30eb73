"""004 Sect. 4: the RCM paths of Table 5 and the entry-point deviation, through the
generated ``pro_hep_lct`` module and the tool functions (``surgical.pro_hep_lct_tool``).

Every row of Table 5 is solved by the tool IK in the paper's working mode: the pose O (no
insertion) and the paths O->A, O->B (eq. 10: rotation about the entry point, then 100 mm of
insertion towards the patient).  Between the control points of each path (0, 5, ..., 30 deg)
the active joints are interpolated linearly and the forward kinematics gives the vector from
the entry point to the tool axis (the paper's simulation in Siemens NX).
"""

from __future__ import annotations

import numpy as np

from ..papers.p004_pro_hep_lct import (
    TABLE5,
    TABLE5_COLUMNS,
    TABLE5_DEPTH,
    TABLE5_ENTRY,
    TABLE5_MODE,
    TABLE5_TOLERANCE,
)
from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from ..surgical import pro_hep_lct_tool as tool
from .files import csv_text, number, png, pyplot

NAME = "pro_hep_lct"
# the deviation is written at 1 nm: its control-point values are floating-point noise
DEVIATION_RESOLUTION = ".6f"


def table5(gen) -> list[dict]:
    """Every row of 004 Table 5 through the tool IK, with the printed values."""
    rows = []
    for label, axis, angle, u_printed, *printed in TABLE5:
        if axis is None:
            pose = np.asarray(TABLE5_ENTRY)
        else:
            pose = tool.rcm_path(TABLE5_ENTRY, axis, [np.radians(angle)], TABLE5_DEPTH)[0]
        joints, status = tool.tool_ik(pose, gen, mode=TABLE5_MODE, limits=False)
        model = [float(v) for v in joints]
        diff = [m - p for m, p in zip(model, printed)]
        rows.append({"row": label, "axis": axis, "angle_deg": angle, "u_printed": u_printed,
                     "u_exact": None if axis is None else float(np.tan(np.radians(angle) / 2)),
                     "printed": printed, "model": model, "difference": diff,
                     "status": int(status),
                     "within": [abs(x) <= t for x, t in zip(diff, TABLE5_TOLERANCE)]})
    return rows


def rcm_deviation(gen) -> dict:
    """The entry-point deviation between control points when the active joints of each path
    (0, 5, ..., 30 deg, 100 mm deep) are interpolated linearly."""
    out = {}
    for name, axis, sign in (("A", "x", -1), ("B", "y", 1)):
        angles = sign * np.arange(0, 35, 5)
        poses = tool.rcm_path(TABLE5_ENTRY, axis, np.radians(angles), TABLE5_DEPTH)
        ctrl, status = tool.tool_ik(poses, gen, mode=TABLE5_MODE, limits=False)
        s, dev = tool.interpolated_deviation(TABLE5_ENTRY, ctrl, gen, poses[0])
        norm = np.linalg.norm(dev, axis=-1)
        out[name] = {"s": s, "deviation": dev, "max": float(norm.max()),
                     "max_xyz": [float(v) for v in np.abs(dev).max(axis=0)],
                     "at_control_points": float(norm[::50].max()),
                     "control_status": [int(v) for v in status]}
    return out


def _files(rows, dev) -> dict:
    head = (["row", "axis", "angle_deg"] + [f"{c}_printed" for c in TABLE5_COLUMNS]
            + [f"{c}_model" for c in TABLE5_COLUMNS] + ["within_printed_precision"])
    lines = [",".join(head)]
    for r in rows:
        lines.append(",".join([r["row"], r["axis"] or "", str(r["angle_deg"])]
                              + [number(v) for v in r["printed"]]
                              + [number(v) for v in r["model"]]
                              + [str(all(r["within"]))]))
    out = {f"{NAME}.table5.csv": "\n".join(lines) + "\n"}
    table = []
    for name, d in dev.items():
        for s_, v in zip(d["s"], d["deviation"]):
            table.append([name, s_, *v, float((v ** 2).sum()) ** 0.5])
    out[f"{NAME}.rcm_deviation.csv"] = csv_text(
        ["path", "s", "dx", "dy", "dz", "distance"], table,
        ["", ".6g"] + [DEVIATION_RESOLUTION] * 4)
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.4), sharey=False)
    for ax, (name, d) in zip(axes, dev.items()):
        for k, lab in enumerate("xyz"):
            ax.plot(d["s"] * 5, d["deviation"][:, k], label=f"{lab} (mm)")
        ax.set(xlabel="control angle (deg)", ylabel="entry point to tool axis (mm)",
               title=f"path O'{name}")
        ax.legend(fontsize=7)
    out[f"{NAME}.rcm_deviation.png"] = png(fig)
    return out


def _report(rows) -> tuple[str, ...]:
    out = [r"\section{Table 5 reproduced}",
           tex_escape(f"Working mode {TABLE5_MODE}; poses from the entry point O by eq. (10) "
                      f"with exact tan-half-angles and {TABLE5_DEPTH:g} mm insertion towards "
                      "the patient. Printed / model, per active joint (file "
                      f"{NAME}.table5.csv):"),
           r"\begin{center}\small\begin{tabular}{lrrrrr}\hline row & $t_1$ & $w_1$ & "
           r"$q_4$ & $q_5$ & $n$\\\hline"]
    for r in rows:
        cells = []
        for pv, mv, ok in zip(r["printed"], r["model"], r["within"]):
            cell = f"{pv:g} / {mv:.4f}"
            cells.append(cell if ok else r"\textbf{" + cell + "}")
        out.append(f"{tex_escape(r['row'])} & " + " & ".join(cells) + r"\\")
    out += [r"\hline\end{tabular}\end{center}",
            tex_escape("Bold: outside 1.5 units of the last printed digit (see the "
                       "verification section)."),
            r"\section{Entry-point deviation with interpolated joints (004 Sect. 4)}",
            tex_escape("Between control points the joint angles move linearly; the forward "
                       "kinematics of the model gives the vector from the entry point to "
                       f"the tool axis (file {NAME}.rcm_deviation.csv)."),
            r"\begin{center}\includegraphics[width=\textwidth]{" + NAME
            + r".rcm_deviation.png}\end{center}"]
    return tuple(out)


def run(d, gen) -> Study:
    rows, dev = table5(gen), rcm_deviation(gen)
    return Study("rcm_paths", {"table5": rows, "rcm_deviation": dev}, _files(rows, dev),
                 _report(rows))
