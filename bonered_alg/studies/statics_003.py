"""003 Sect. 2.3 and 3, Table 2: the actuator efforts (f, T1, T2) that hold the lamina-milling
robot under the five load cases of Table 2 with the link weights of Table 1, along the
simulations' path (theta1, theta2, L moved together over the printed ranges), by the
generated ``static_efforts`` in both of its methods (virtual work and the free-body
equilibrium of every body), as CSV tables and plots in the manner of 003 Fig. 11 and 13.

The study also shows how the efforts depend on the readings of the centre-of-gravity
distances (the declaration's ``LinkWeight.reading``): each distance measured from the other
end of its link, and the parallelogram's centre of gravity moved from C to E.
"""

from __future__ import annotations

import numpy as np

from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from .files import csv_text, number, png, pyplot
from .workspace_003 import table2_path

NAME = "lamina_milling"
# 003 Table 2: (Fx, Fy, Fz) in N of simulations 1-5 (the load at H, base frame)
LOADS = ((0.0, 0.0, 0.0), (3.0, -2.0, 8.0), (1.0, -1.0, 6.0), (-3.0, 2.0, 8.0),
         (4.0, -3.0, 6.0))
# the absolute errors of 003's abstract and Sect. 3: 0.001 N and 0.0001 N m
PAPER_FORCE_ERROR, PAPER_TORQUE_ERROR = 0.001, 0.1  # N, N mm
METHODS_RTOL = 1e-9  # virtual work against free body, relative to 1 + the largest |effort|


def _other_readings(par) -> dict:
    """Each centre-of-gravity distance measured from the other end of its link."""
    return {"l4": par["lAF"] - par["l4"], "l5": par["lOA"] - par["l5"],
            "l8": par["lBM"] - par["l8"], "l9": par["lOB"] - par["l9"],
            "l2": par["lEC"] - par["l2"]}


def _r(v: float, digits: int = 3) -> float:
    """``v`` rounded, without the sign of a rounded zero."""
    return round(float(v), digits) + 0.0


def run(d, gen) -> Study:
    par = gen.PARAMETERS
    s, q, h = table2_path(gen)
    rows, cases = [], []
    worst = 0.0
    for k, load in enumerate(LOADS, start=1):
        F = np.broadcast_to(np.array(load), h.shape)
        vw = gen.static_efforts(h, F)
        fb = gen.static_efforts(h, F, method="free_body")
        diff = np.abs(vw - fb) / (1.0 + np.abs(vw).max(-1, keepdims=True))
        worst = max(worst, float(diff.max()))
        cases.append(vw)
        for a, qq, hh, e in zip(s, q, h, vw):
            rows.append((k, float(a), float(qq[0]), float(np.degrees(qq[1])),
                         float(np.degrees(qq[2])), *map(float, hh), *load, *map(float, e)))
    cases = np.array(cases)  # (5, points, 3)
    gravity = cases[0]
    weights = par["G1"] + par["G2"] + par["G7"]
    alt = _other_readings(par)
    shifted = gen.static_efforts(h, np.zeros(3), **alt)
    at_c = gen.static_efforts(h, np.zeros(3), l2=1e-6)
    at_e = gen.static_efforts(h, np.zeros(3), l2=par["lEC"])
    data = {
        "points": len(s), "methods_agree": bool(worst <= METHODS_RTOL),
        "gravity_f_min": _r(gravity[:, 0].min(), 9),
        "gravity_f_max": _r(gravity[:, 0].max(), 9),
        "weights_G1_G2_G7": _r(weights, 9),
        "gravity_T1": [_r(gravity[:, 1].min()), _r(gravity[:, 1].max())],
        "gravity_T2": [_r(gravity[:, 2].min()), _r(gravity[:, 2].max())],
        "cases": [{"load": list(load),
                   "f": [_r(c[:, 0].min()), _r(c[:, 0].max())],
                   "T1": [_r(c[:, 1].min()), _r(c[:, 1].max())],
                   "T2": [_r(c[:, 2].min()), _r(c[:, 2].max())],
                   "f_abs_median": _r(np.median(np.abs(c[:, 0]))),
                   "T_abs_median": _r(np.median(np.abs(c[:, 1:])))}
                  for load, c in zip(LOADS, cases)],
        "readings_max_change": _r(np.abs(shifted - gravity).max(), 9),
        "cog_c_to_e_T_change": _r(np.abs(at_e - at_c)[:, 1:].max()),
        "cog_c_to_e_f_change": _r(np.abs(at_e - at_c)[:, 0].max(), 9),
    }
    f_ratio = [PAPER_FORCE_ERROR / c["f_abs_median"] * 100 for c in data["cases"]]
    t_ratio = [PAPER_TORQUE_ERROR / c["T_abs_median"] * 100 for c in data["cases"]]
    data["paper_force_error_percent"] = [round(v, 3) for v in f_ratio]
    data["paper_torque_error_percent"] = [round(v, 3) for v in t_ratio]
    csv = csv_text(("simulation", "s", "L_mm", "theta1_deg", "theta2_deg", "x_mm", "y_mm",
                    "z_mm", "Fx_N", "Fy_N", "Fz_N", "f_N", "T1_Nmm", "T2_Nmm"), rows,
                   # torques to 1e-4 N mm: their last bits come from LAPACK (machine-specific)
                   (".0f", ".4f", ".6f", ".6f", ".6f", ".6f", ".6f", ".6f", ".3g", ".3g",
                    ".3g", ".6f", ".4f", ".4f"))
    return Study("statics_003", data, {f"{NAME}.statics.csv": csv,
                                       f"{NAME}.statics.png": _plot(s, cases)},
                 tuple(_report(data)))


def _plot(s, cases) -> bytes:
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(12.0, 3.6))
    labels = ("f (N)", "T1 (N mm)", "T2 (N mm)")
    for j, ax in enumerate(axes):
        for k, c in enumerate(cases, start=1):
            ax.plot(s, c[:, j], lw=1.2, label=f"simulation {k}")
        ax.set_xlabel("s (theta1 = 33.75 + 10 s deg, theta2 = 146.25 - 10 s deg, L = 10 s mm)",
                      fontsize=6)
        ax.set_ylabel(labels[j])
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6)
    fig.suptitle("Actuator efforts along Table 2's path (003 Fig. 11, 13)", fontsize=8)
    return png(fig)


def _report(data) -> list[str]:
    lines = [
        r"\section{Statics (003 Sect.~2.3, 3; Tables~1--2)}",
        "The efforts that hold the robot under a load $F$ at $H$ and the weights of Table~1 "
        "(each actuator's effort on its driven link in the positive sense of its joint: $f$ "
        "along $+Z_0$ in N, $T_1$, $T_2$ about $+Z_0$ in N\\,mm; gravity along $-Z_0$; $F$ in "
        "the base frame) come from the generated \\texttt{static\\_efforts} by virtual work, "
        "$J^T\\tau = -(P_H^T F + \\sum_k P_k^T W_k)$ with $J = dq/dX$ and $P_k$ the Jacobian of "
        "each centre of gravity, and by the free-body equilibrium of every body (the joints' "
        "reaction wrenches as unknowns, each joint freedom doing no work but the actuator's). "
        f"Along Table~2's path ({data['points']} points, five load cases) the two "
        + ("agree to better than $10^{-9}$ (relative)." if data["methods_agree"] else
           "DISAGREE by more than $10^{-9}$ (relative)."),
        "Without load, $f$ is "
        f"{number(data['gravity_f_min'], '.4f')} N at every pose (largest "
        f"{number(data['gravity_f_max'], '.4f')} N): the "
        f"weights $G_1 + G_2 + G_7 = {number(data['weights_G1_G2_G7'], '.2f')}$ N of the "
        "parallelogram, "
        "the link $DE$ with its carriage and the platform.  The bottom chains carry none of "
        "it: their cylindrical joints slide freely along $Z_0$, and their links turn about "
        "vertical axes at fixed heights, so their weights $G_3$--$G_6$ do no virtual work "
        "(the joints' bearings hold them).  The torques are not zero: the parallelogram "
        "holds the weights along $EC$, which is inclined, and the bottom chains take the "
        f"horizontal part ($T_1 \\in [{number(data['gravity_T1'][0], '.1f')}, "
        f"{number(data['gravity_T1'][1], '.1f')}]$, $T_2 \\in "
        f"[{number(data['gravity_T2'][0], '.1f')}, {number(data['gravity_T2'][1], '.1f')}]$ "
        "N\\,mm).  "
        "With a load, $f = G_1 + G_2 + G_7 - F_z$.",
        r"\begin{center}\begin{tabular}{lrrrr}\hline simulation & $F$ (N) & $f$ (N) & "
        r"$T_1$ (N\,mm) & $T_2$ (N\,mm)\\\hline",
    ]
    for k, c in enumerate(data["cases"], start=1):
        lines.append(f"{k} & ({', '.join(f'{v:g}' for v in c['load'])}) & "
                     f"$[{number(c['f'][0], '.3f')}, {number(c['f'][1], '.3f')}]$ & "
                     f"$[{number(c['T1'][0], '.1f')}, {number(c['T1'][1], '.1f')}]$ & "
                     f"$[{number(c['T2'][0], '.1f')}, {number(c['T2'][1], '.1f')}]$\\\\")
    lines += [
        r"\hline\end{tabular}\end{center}",
        "Readings of the centre-of-gravity distances: measuring each of $l_2, l_4, l_5, l_8, "
        f"l_9$ from the other end of its link changes the efforts by at most "
        f"{data['readings_max_change']:.1e} (the bottom links' weights do no work, and "
        "$l_2 = 45$ mm is the middle of $l_1 = |CE| = 90$ mm either way).  Moving the "
        "parallelogram's centre of gravity from $C$ to $E$ would change $T_1, T_2$ by up to "
        f"{number(data['cog_c_to_e_T_change'], '.2f')} N\\,mm and $f$ by "
        f"{data['cog_c_to_e_f_change']:.1e} N.",
        "The abstract's errors of 0.001 N and 0.0001 N\\,m against these efforts (the median "
        "$|f|$ and $|T_i|$ of each simulation along the path): "
        + ", ".join(f"{a:.2f}" for a in data["paper_force_error_percent"])
        + "\\,\\% of $f$ and "
        + ", ".join(f"{a:.2f}" for a in data["paper_torque_error_percent"])
        + "\\,\\% of the torques in simulations 1--5 (see the verification).",
        r"\begin{center}\includegraphics[width=\textwidth]{" + NAME
        + r".statics.png}\end{center}",
        f"Tables: \\texttt{{{tex_escape(NAME)}.statics.csv}} (each simulation along the path).",
    ]
    return lines
