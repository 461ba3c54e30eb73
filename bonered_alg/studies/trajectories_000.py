"""The test trajectories of paper 000, eq. (43) and (44), through ``generated/planar_tripod``.

000 eq. (43)-(44) give z(t) near 0, where the tripod legs would have zero length; the
paper's z must be measured from a home height it does not state.  We add the mid-stroke
height of Table 1, ``Z_HOME = (175 + 250) / 2`` mm (at alpha = beta = 0 the legs have length
z).  Joint positions and velocities (``q' = J X'``) over ``t`` in [0, 2 pi] go to CSV and
PNG files beside the report; limits are not applied (``limits=False``) so the curves are
complete, and the column ``within_limits`` comes from the generated ``ik_status``.
"""

from __future__ import annotations

import numpy as np

from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from .files import csv_text, png, pyplot

NAME = "planar_tripod"
Z_HOME = 212.5
POSE = ("x", "y", "z", "alpha", "beta", "gamma")


def trajectory_eq43(t):
    """000 eq. (43): pure rotation, parasitic compensation test (Fig. 6), z about Z_HOME."""
    zero = np.zeros_like(t)
    pose = np.stack([zero, zero, zero + Z_HOME, np.pi / 12 * np.sin(t), np.pi / 15 * np.sin(t),
                     np.pi / 6 * np.cos(2 * t)], axis=-1)
    rate = np.stack([zero, zero, zero, np.pi / 12 * np.cos(t), np.pi / 15 * np.cos(t),
                     -np.pi / 3 * np.sin(2 * t)], axis=-1)
    return pose, rate


def trajectory_eq44(t):
    """000 eq. (44): the 6-DoF test trajectory (Figs. 7-8), z about Z_HOME."""
    pose = np.stack([20 * np.sin(t), 20 * np.sin(t), Z_HOME + 50 * np.cos(2 * t),
                     2 * np.pi / 45 * np.sin(t), np.pi / 18 * np.sin(t),
                     np.pi / 12 * np.cos(2 * t)], axis=-1)
    rate = np.stack([20 * np.cos(t), 20 * np.cos(t), -100 * np.sin(2 * t),
                     2 * np.pi / 45 * np.cos(t), np.pi / 18 * np.cos(t),
                     -np.pi / 6 * np.sin(2 * t)], axis=-1)
    return pose, rate


def run(d, gen) -> Study:
    plt = pyplot()
    t = np.linspace(0.0, 2 * np.pi, 361)
    files = {}
    for label, traj in (("eq43", trajectory_eq43), ("eq44", trajectory_eq44)):
        pose, rate = traj(t)
        q = gen.ik(pose, limits=False)
        jac = gen.jacobian(pose, limits=False)
        qdot = np.einsum("nij,nj->ni", jac, rate)
        par = gen.parasitic_motion(pose)
        mp1 = gen.mp1_pose(pose)
        inside = (gen.ik_status(pose) == gen.OK).astype(float)
        header = (["t", *POSE] + [f"q{k}" for k in range(1, 7)]
                  + [f"q{k}dot" for k in range(1, 7)] + ["x_par", "y_par", "x1", "y1",
                                                         "gamma1", "within_limits"])
        rows = np.column_stack([t, pose, q, qdot, par, mp1, inside])
        files[f"{NAME}.trajectory_{label}.csv"] = csv_text(header, rows)
        fig, axes = plt.subplots(1, 3 if label == "eq43" else 2, figsize=(11, 3.4))
        for k in range(6):
            axes[0].plot(t, q[:, k], label=f"q{k + 1}")
            axes[1].plot(t, qdot[:, k], label=f"q{k + 1}'")
        axes[0].set(xlabel="t", ylabel="joint position (mm)")
        axes[1].set(xlabel="t", ylabel="joint velocity (mm per unit t)")
        axes[0].legend(fontsize=7, ncol=2)
        if label == "eq43":
            axes[2].plot(t, par[:, 0], label="x_par (eq. 42)")
            axes[2].plot(t, par[:, 1], label="y_par (eq. 42)")
            axes[2].plot(t, mp1[:, 0], "--", label="MP1 x1 (eq. 16)")
            axes[2].plot(t, mp1[:, 1], "--", label="MP1 y1 (eq. 16)")
            axes[2].set(xlabel="t", ylabel="mm")
            axes[2].legend(fontsize=7)
        fig.suptitle(f"000 eq. ({label[2:]}) through generated/{NAME}.py")
        files[f"{NAME}.trajectory_{label}.png"] = png(fig)
    report = (
        r"\section{Trajectories (000 eq. 43-44)}",
        tex_escape("Joint positions and velocities along the paper's test trajectories, "
                   "computed by the generated functions (files "
                   f"{NAME}.trajectory_eq43.csv and {NAME}.trajectory_eq44.csv). "
                   "Eq. (43)-(44) put z near 0, where the legs would have zero length, so "
                   "the paper's z must be measured from a home height it does not state; "
                   f"z(t) is offset here by the mid-stroke height {Z_HOME} mm of Table 1. "
                   "Limits are not applied to the curves; the CSV column within_limits "
                   "marks the samples inside the strokes and joint ranges of Table 1."),
        r"\begin{center}\includegraphics[width=\textwidth]{" + NAME
        + r".trajectory_eq43.png}\end{center}",
        r"\begin{center}\includegraphics[width=0.75\textwidth]{" + NAME
        + r".trajectory_eq44.png}\end{center}")
    return Study("trajectories", files=files, report=report)
