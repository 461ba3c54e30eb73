"""The planar actuators' stroke that 000 does not give, recovered from its Table 2.

000 Table 1 lists one stroke range, 175-250 mm, without saying which actuators it bounds;
with it on the planar actuators too, the (x, y, gamma) workspace is far smaller than Table
2's (Delta x = 175 mm, Delta y = 170 mm, Delta gamma = 105 deg).  As 004's Table 4 was
recovered from its Table 5, the stroke range (q_min, q_max) of q1..q3 is searched here that
reproduces those three printed ranges, with everything else as in the Table 2 set-up
(:mod:`.bone_reduction`: the tripod at its mid-stroke height, alpha = beta = 0, 000 Table
1's tripod limits) and the workspace counted as the home component
(:mod:`..workspace.components`).

The inverse kinematics and the singularity signs are evaluated once on the search grid
(the signs only where some candidate range can reach: a sixth of the grid); each candidate
range is then a mask, a connected-component labelling and the extents.  A 5 mm lattice of
candidates is refined to 1 mm around its best point; on the 5 mm lattice only the blocks
whose error bound can reach the best error are read (the ranges grow with the stroke
range: :func:`best_on_lattice`, 123 of 624 points, the same choice as reading all).
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace

import numpy as np

from ..workspace.components import HomeNotReachable, SignSides, home_component, nearest_index
from ..workspace.membership import Criteria, load_module
from ..workspace.scan import scan
from ..workspace.singular_loci import polynomial_signs
from .bone_reduction import TABLE2_000, slice_extents, table2_setups, xyg_grid

SEARCH_AXES = dict(x=(-160.0, 160.0, 4.0), y=(-160.0, 160.0, 4.0), gamma=(-90.0, 90.0, 1.0))
COARSE = (np.arange(100.0, 216.0, 5.0), np.arange(225.0, 351.0, 5.0))  # q_min, q_max (mm)
REFINE = 5  # mm either side of the coarse optimum, 1 mm steps
# every candidate (q_min, q_max) lies within these: the coarse lattice and its refinement
BOUNDS = (float(COARSE[0].min()) - REFINE, float(COARSE[1].max()) + REFINE)
TARGET = {k: float(TABLE2_000["planar_tripod"][k]) for k in ("x", "y", "gamma")}
PLANAR = "q[123]"
HOME = {"x": 0.0, "y": 0.0, "gamma": 0.0}


@dataclass(frozen=True)
class StrokeFit:
    q_min: float
    q_max: float
    ranges: dict[str, float]  # Delta x, Delta y (mm), Delta gamma (deg) of the fit
    gamma_at_max_x_deg: float
    relative_errors: dict[str, float]
    within_resolution: list[tuple[float, float]]  # lattice points matching all three ranges
    grid: str

    def summary(self) -> dict:
        """The fit as written to the comparison record."""
        lo = [p[0] for p in self.within_resolution]
        hi = [p[1] for p in self.within_resolution]
        return {"ref": "000 Table 2 (planar strokes not in Table 1)", "target": TARGET,
                "q_min": self.q_min, "q_max": self.q_max, "ranges": self.ranges,
                "gamma_at_max_x_deg": self.gamma_at_max_x_deg,
                "relative_errors": self.relative_errors,
                "q_min_within": [min(lo), max(lo)] if lo else None,
                "q_max_within": [min(hi), max(hi)] if hi else None,
                "lattice_points_within": len(self.within_resolution),
                "refined_window_mm": REFINE, "grid": self.grid}


class _Search:
    """The Table 2 (x, y, gamma) slice of ``planar_tripod`` with the planar strokes free;
    candidate ranges within ``BOUNDS``."""

    def __init__(self, workers: int | None = None):
        setup = next(s for s in table2_setups() if s.mechanism == "planar_tripod"
                     and not s.variant)
        module = load_module("planar_tripod")
        free = Criteria(limits={PLANAR: (-math.inf, math.inf)})
        self.res = scan("planar_tripod", xyg_grid(module.POSE, setup.height, SEARCH_AXES), free,
                        workers=workers)
        self.height = setup.height
        flat = np.nonzero(self.res.mask.reshape(-1))[0]
        poses = self.res.grid.poses(0, self.res.grid.size)[flat]
        q = module.ik(poses, 0, False)[:, :3]
        self.q_lo = np.full(self.res.grid.size, np.inf)
        self.q_hi = np.full(self.res.grid.size, -np.inf)
        self.q_lo[flat], self.q_hi[flat] = q.min(axis=1), q.max(axis=1)
        self.q_lo = self.q_lo.reshape(self.res.grid.shape)
        self.q_hi = self.q_hi.reshape(self.res.grid.shape)
        # home_component reads the signs on a candidate's mask only (the stroke search
        # asks for no bounding loci), and every candidate's mask lies in this one
        self.reach = self.res.mask & (self.q_lo >= BOUNDS[0]) & (self.q_hi <= BOUNDS[1])
        signs = polynomial_signs(self.res, where=self.reach)
        self.signs = signs
        # the signs around home, read for every candidate: built once
        self.sides = SignSides(signs, nearest_index(self.res, HOME))

    def ranges(self, q_min: float, q_max: float) -> tuple[dict[str, float], float] | None:
        if not BOUNDS[0] <= q_min <= q_max <= BOUNDS[1]:
            raise ValueError(f"planar_tripod stroke search: the candidate ({q_min}, {q_max}) "
                             f"mm lies outside the searched bounds {BOUNDS}")
        mask = self.reach & (self.q_lo >= q_min) & (self.q_hi <= q_max)
        cand = replace(self.res, mask=mask, count=int(np.count_nonzero(mask)))
        try:
            comp = home_component(cand, self.signs, HOME, self.sides).result
        except HomeNotReachable:  # home itself outside these strokes
            return None
        ext_x, gam = slice_extents(comp, "x", "gamma")
        ext_y, _ = slice_extents(comp, "y", "gamma")
        best = int(np.nanargmax(ext_x))
        return ({"x": float(np.nanmax(ext_x)), "y": float(np.nanmax(ext_y)),
                 "gamma": math.degrees(comp.extent("gamma"))}, math.degrees(gam[best]))


def _error(r: dict[str, float]) -> float:
    return sum(((r[k] - TARGET[k]) / TARGET[k]) ** 2 for k in TARGET)


def _error_bound(narrow: dict[str, float] | None, wide: dict[str, float]) -> float:
    """No candidate whose ranges lie between ``narrow``'s and ``wide``'s (each range) has a
    smaller :func:`_error`: per range, the term of the end nearest the target (0 where the
    target lies between), summed in ``_error``'s order.  Exact in floating point:
    ``((r - T) / T) ** 2`` does not decrease as ``|r - T|`` grows (subtraction, division
    and squaring are correctly rounded, hence monotone), and a sum does not decrease as
    any of its terms grows."""
    total = 0.0
    for k in TARGET:
        lo, hi = (narrow[k] if narrow is not None else 0.0), wide[k]
        end = lo if TARGET[k] < lo else hi if TARGET[k] > hi else TARGET[k]
        total += ((end - TARGET[k]) / TARGET[k]) ** 2
    return total


LATTICE_BLOCK = 4  # points per side of the blocks the coarse search bounds


def best_on_lattice(los, his, results) -> tuple[float, float]:
    """The point ``(q_min, q_max)`` of the lattice ``los`` x ``his`` whose ranges have the
    least :func:`_error` (the smallest point among equals: ``min`` over ``(error, point)``),
    reading fewer points than all.  ``results(points)``: each point's ranges, None where
    home is not reachable.  A candidate's home component grows with its stroke range (a
    larger mask holds the smaller one's component), so over a block of the lattice each
    range lies between those of the block's narrowest corner (largest q_min, smallest
    q_max) and its widest; blocks are read in the order of their bound
    (:func:`_error_bound`) until it exceeds the best error read (equal bounds are read)."""
    los, his = [float(v) for v in los], [float(v) for v in his]
    blocks = [([(a, b) for a in los[i:i + LATTICE_BLOCK] for b in his[j:j + LATTICE_BLOCK]],
               (los[min(i + LATTICE_BLOCK, len(los)) - 1], his[j]),
               (los[i], his[min(j + LATTICE_BLOCK, len(his)) - 1]))
              for i in range(0, len(los), LATTICE_BLOCK)
              for j in range(0, len(his), LATTICE_BLOCK)]
    corners = results(sorted({c for _, narrow, wide in blocks for c in (narrow, wide)}))
    best = min(((_error(r), p) for p, r in corners.items() if r is not None),
               default=(math.inf, None))
    bounded = sorted(((_error_bound(corners[narrow], corners[wide]), points)
                      for points, narrow, wide in blocks
                      if corners[wide] is not None),  # else home is in none of them
                     key=lambda t: t[0])
    for bound, points in bounded:
        if bound > best[0]:
            break
        best = min([best] + [(_error(r), p) for p, r in results(points).items()
                             if r is not None])
    if best[1] is None:
        raise ValueError("planar_tripod stroke search: home is reachable with no candidate "
                         "of the lattice")
    return best[1]


def recover(workers: int | None = None) -> StrokeFit:
    """The (q_min, q_max) of q1..q3 on a 1 mm lattice that best reproduces 000 Table 2's
    Delta x, Delta y, Delta gamma (least squares of the relative errors), and every lattice
    point within the search grid's resolution of all three."""
    s = _Search(workers)
    steps = {a.name: a.step for a in s.res.grid.axes}
    tol = {"x": steps["x"], "y": steps["y"], "gamma": math.degrees(steps["gamma"])}
    seen: dict[tuple[float, float], tuple[dict[str, float], float] | None] = {}
    threads = workers or os.cpu_count() or 1

    def evaluate(lo, hi):
        key = (float(lo), float(hi))
        if key not in seen:
            seen[key] = s.ranges(*key)
        return seen[key]

    def read(points):
        # the candidates not yet seen, on ``threads`` threads (the labelling and the masks
        # release the GIL: two threads take about half the time); the same ranges as one
        # by one
        todo = list(dict.fromkeys((float(lo), float(hi)) for lo, hi in points
                                  if (float(lo), float(hi)) not in seen))
        if todo:
            with ThreadPoolExecutor(max_workers=max(1, min(threads, len(todo)))) as pool:
                seen.update(zip(todo, pool.map(lambda key: s.ranges(*key), todo)))

    def best_of(points):
        # the choice reads the candidates in the order of ``points``: the least error, the
        # first point among equals
        read(points)
        scored = [(_error(r[0]), p) for p in points if (r := evaluate(*p)) is not None]
        return min(scored)[1]

    def results(points):
        read(points)
        return {p: None if seen[p] is None else seen[p][0] for p in points}

    lo0, hi0 = best_on_lattice(COARSE[0], COARSE[1], results)
    fine = [(lo0 + i, hi0 + j) for i in range(-REFINE, REFINE + 1)
            for j in range(-REFINE, REFINE + 1)]
    q_min, q_max = best_of(fine)
    got, g_at = evaluate(q_min, q_max)
    within = sorted((float(p[0]), float(p[1])) for p in fine if (r := evaluate(*p)) is not None
                    and all(abs(r[0][k] - TARGET[k]) <= tol[k] for k in TARGET))
    return StrokeFit(float(q_min), float(q_max), {k: round(v, 3) for k, v in got.items()},
                     round(g_at, 3),
                     {k: round((got[k] - TARGET[k]) / TARGET[k], 4) for k in TARGET}, within,
                     s.res.grid.describe())
