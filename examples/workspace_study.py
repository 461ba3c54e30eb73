"""Workspace study: the (x, y) slice of the tripod_planar hybrid (001) at its homing height,
within the strokes and joint ranges of 001 Sect. 3, and why the edge poses are cut off.

    .venv/bin/python examples/workspace_study.py
"""

import numpy as np
from bonered_alg.generated import tripod_planar as t

from bonered_alg.workspace.grid import Axis, Grid
from bonered_alg.workspace.scan import scan


def main() -> dict:
    grid = Grid(t.POSE, (Axis.from_user("x", -240, 240, 4), Axis.from_user("y", -240, 240, 4)),
                {"z": 210.0, "alpha": 0.0, "beta": 0.0, "gamma": 0.0})
    res = scan("tripod_planar", grid, workers=1)
    print(f"{res.count} of {res.samples} poses reachable; ranges (mm):",
          {k: tuple(round(v, 1) for v in r) for k, r in res.ranges.items()})
    # the first pose beyond the reachable x range, at y = 0: which joint stops it, and why
    x_max = res.ranges["x"][1]
    beyond = np.array([x_max + 4.0, 0.0, 210.0, 0.0, 0.0, 0.0])
    print("just beyond:", t.ik_explain(beyond))
    return {"result": res, "beyond": beyond}


if __name__ == "__main__":
    main()
