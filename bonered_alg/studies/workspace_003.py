"""003 Sect. 2 and Table 2: the workspace of the lamina-milling robot over Table 2's joint
ranges, held against the clinical requirement (Delta x 30 mm, Delta y 15 mm, Delta z 100
mm, Sect. 2).

* The Table 2 box: theta1 in [33.75, 43.75] deg, theta2 in [136.25, 146.25] deg, L in
  [0, 10] mm, a 21 x 21 x 11 grid through the generated ``fk`` in the working mode (the
  assembly whose IK mode 0 gives the joints back: C below E, F away from O).
* The Table 2 path: the simulations move the joints together, theta1 = 33.75 + 10 s deg,
  theta2 = 146.25 - 10 s deg, L = 10 s mm for s in [0, 1] (the table's reversed theta2
  range); H stays on x = 0 (the symmetric bottom chains).
* The clinical box: 30 x 15 x 100 mm centred at home (x = 0, y = 112.67 mm, z = 52.20 mm),
  a 31 x 16 x 101 grid through the generated ``ik`` (mode 0, every status): the joint
  ranges it needs and whether it is free of singular and unreachable poses.
"""

from __future__ import annotations

import numpy as np

from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from .files import csv_text, png, pyplot

NAME = "lamina_milling"
THETA1 = (33.75, 43.75)  # deg, 003 Table 2
THETA2 = (146.25, 136.25)
STROKE = (0.0, 10.0)  # mm
CLINICAL = (30.0, 15.0, 100.0)  # mm, 003 Sect. 2
PATH_POINTS = 101


def working_pose(gen, q: np.ndarray) -> np.ndarray:
    """H for joints ``q`` (..., 3) in the working mode: the FK assembly whose IK mode 0
    gives ``q`` back (NaN where none does)."""
    poses = gen.fk(q)  # (..., modes, 3)
    out = np.full(q.shape, np.nan)
    for k in range(poses.shape[-2]):
        h = poses[..., k, :]
        back = gen.ik(np.where(np.isfinite(h), h, 0.0), limits=False)
        hit = np.isfinite(h).all(-1) & (np.abs(back - q).max(-1) < 1e-9) & \
            ~np.isfinite(out).all(-1)
        out[hit] = h[hit]
    return out


def table2_path(gen, points: int = PATH_POINTS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(s, joints, H) along the Table 2 path."""
    s = np.linspace(0.0, 1.0, points)
    q = np.column_stack([STROKE[0] + (STROKE[1] - STROKE[0]) * s,
                         np.radians(THETA1[0] + (THETA1[1] - THETA1[0]) * s),
                         np.radians(THETA2[0] + (THETA2[1] - THETA2[0]) * s)])
    return s, q, working_pose(gen, q)


def _box(gen):
    t1 = np.radians(np.linspace(*THETA1, 21))
    t2 = np.radians(np.linspace(*THETA2, 21))
    L = np.linspace(*STROKE, 11)
    q = np.stack(np.meshgrid(L, t1, t2, indexing="ij"), axis=-1).reshape(-1, 3)
    return q, working_pose(gen, q)


def _clinical(gen):
    home = np.asarray(gen.HOME, dtype=float)
    axes = [np.linspace(c - w / 2, c + w / 2, n) for c, w, n in zip(home, CLINICAL,
                                                                    (31, 16, 101))]
    h = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    q, status = gen.ik_and_status(h, limits=False)
    return h, q, status


def run(d, gen) -> Study:
    qb, hb = _box(gen)
    lo, hi = np.nanmin(hb, axis=0), np.nanmax(hb, axis=0)
    s, qp, hp = table2_path(gen)
    hc, qc, sc = _clinical(gen)
    ok = sc == 0
    qlo, qhi = qc[ok].min(axis=0), qc[ok].max(axis=0)
    data = {
        "box_reached": int(np.isfinite(hb).all(-1).sum()), "box_points": len(qb),
        "box_min": [round(float(v), 3) for v in lo], "box_max": [round(float(v), 3) for v in hi],
        "box_span": [round(float(v), 3) for v in hi - lo],
        "path_reached": int(np.isfinite(hp).all(-1).sum()), "path_points": len(s),
        "path_x_max": round(float(np.nanmax(np.abs(hp[:, 0]))), 9),
        "path_y": [round(float(np.nanmin(hp[:, 1])), 3), round(float(np.nanmax(hp[:, 1])), 3)],
        "path_z": [round(float(np.nanmin(hp[:, 2])), 3), round(float(np.nanmax(hp[:, 2])), 3)],
        "clinical_points": len(hc), "clinical_ok": int(ok.sum()),
        "clinical_status": {int(k): int(v) for k, v in zip(*np.unique(sc, return_counts=True))},
        "clinical_L": [round(float(qlo[0]), 3), round(float(qhi[0]), 3)],
        "clinical_theta1_deg": [round(float(np.degrees(qlo[1])), 3),
                                round(float(np.degrees(qhi[1])), 3)],
        "clinical_theta2_deg": [round(float(np.degrees(qlo[2])), 3),
                                round(float(np.degrees(qhi[2])), 3)],
    }
    data["table2_meets_clinical"] = bool(all(sp_ >= need for sp_, need in
                                             zip(data["box_span"], CLINICAL)))
    csv = csv_text(("s", "L_mm", "theta1_deg", "theta2_deg", "x_mm", "y_mm", "z_mm"),
                   [(float(a), float(q[0]), float(np.degrees(q[1])), float(np.degrees(q[2])),
                     *map(float, h)) for a, q, h in zip(s, qp, hp)], ".6f")
    return Study("workspace_003", data, {f"{NAME}.table2_path.csv": csv,
                                         f"{NAME}.workspace.png": _plot(hb, hc, ok, gen)},
                 tuple(_report(data)))


def _plot(hb, hc, ok, gen) -> bytes:
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.0))
    home = np.asarray(gen.HOME, dtype=float)
    for ax, (i, j) in zip(axes, ((0, 1), (1, 2))):
        ax.plot(hb[:, i], hb[:, j], ".", ms=1.5, color="tab:blue",
                label="Table 2 joint box (fk, working mode)")
        w, h_ = CLINICAL[i], CLINICAL[j]
        ax.add_patch(plt.Rectangle((home[i] - w / 2, home[j] - h_ / 2), w, h_, fill=False,
                                   ec="tab:red", lw=1.2, label="clinical box (Sect. 2)"))
        bad = ~ok
        if bad.any():
            ax.plot(hc[bad, i], hc[bad, j], "x", ms=2, color="k", label="clinical: not ok")
        ax.set_xlabel("xyz"[i] + " (mm)")
        ax.set_ylabel("xyz"[j] + " (mm)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(fontsize=6, loc="upper left")
    axes[0].set_title("H over Table 2's ranges, top view", fontsize=8)
    axes[1].set_title("side view (y, z)", fontsize=8)
    return png(fig)


def _report(data) -> list[str]:
    span = data["box_span"]
    st = ", ".join(f"{v} with status {k}" for k, v in data["clinical_status"].items())
    return [
        r"\section{Workspace against the clinical requirement (003 Sect.~2, Table~2)}",
        "Over Table 2's joint ranges ($\\theta_1 \\in [33.75, 43.75]^\\circ$, $\\theta_2 "
        "\\in [136.25, 146.25]^\\circ$, $L \\in [0, 10]$ mm; a $21\\times21\\times11$ grid "
        f"through the generated \\texttt{{fk}}, working mode; {data['box_reached']} of "
        f"{data['box_points']} reached) the tool point $H$ spans "
        f"$\\Delta x = {span[0]:.1f}$, $\\Delta y = {span[1]:.1f}$, $\\Delta z = "
        f"{span[2]:.1f}$ mm (x in [{data['box_min'][0]:.1f}, {data['box_max'][0]:.1f}], y "
        f"in [{data['box_min'][1]:.1f}, {data['box_max'][1]:.1f}], z in "
        f"[{data['box_min'][2]:.1f}, {data['box_max'][2]:.1f}] mm), against the clinical "
        "$30\\times15\\times100$ mm: "
        + ("met." if data["table2_meets_clinical"] else
           "not met (Table 2's ranges are those of the simulations, not the robot's "
           "strokes, which the paper does not print)."),
        "Along the simulations' path ($\\theta_1$, $\\theta_2$, $L$ moved together; "
        f"{data['path_reached']} of {data['path_points']} points reached) $H$ stays on "
        f"$x = 0$ (largest $|x|$ {data['path_x_max']:.1g} mm) with y from "
        f"{data['path_y'][0]:.2f} to {data['path_y'][1]:.2f} mm and z from "
        f"{data['path_z'][0]:.2f} to {data['path_z'][1]:.2f} mm "
        f"(\\texttt{{{tex_escape(NAME)}.table2\\_path.csv}}).",
        "The clinical box centred at home ($31\\times16\\times101$ poses through the "
        f"generated \\texttt{{ik}}, mode 0: {st}) needs $L \\in [{data['clinical_L'][0]:.1f}, "
        f"{data['clinical_L'][1]:.1f}]$ mm, $\\theta_1 \\in "
        f"[{data['clinical_theta1_deg'][0]:.2f}, {data['clinical_theta1_deg'][1]:.2f}]^\\circ$ "
        f"and $\\theta_2 \\in [{data['clinical_theta2_deg'][0]:.2f}, "
        f"{data['clinical_theta2_deg'][1]:.2f}]^\\circ$"
        + (", and it contains no pose where the IK fails or is singular."
           if data["clinical_ok"] == data["clinical_points"] else
           "; some of its poses are not reached (status above)."),
        r"\begin{center}\includegraphics[width=0.9\textwidth]{" + NAME
        + r".workspace.png}\end{center}",
    ]
