"""Ranges of one pose coordinate about a reference pose, by boundary search.

001 Table 1 gives, at a fixed position, ``[alpha_min; alpha_max]`` and the same for beta
and gamma: the interval of one angle, the others at zero, over which the pose stays in the
workspace.  :func:`coordinate_range` finds the connected interval that contains the
reference value: it marches outwards on a grid of spacing ``step`` until the first pose
outside, then bisects each boundary to ``tol``.  The result is exact to ``tol`` where the
workspace boundary along the line is crossed once between two grid points; a gap narrower
than ``step`` would be missed, which is why the march step is reported with the range.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .membership import DEFAULT_CRITERIA, IN_WORKSPACE, Criteria, classify, load_module


@dataclass(frozen=True)
class CoordinateRange:
    """``[lo, hi]`` of ``name`` about ``reference`` (internal units), and why each end
    stops: the module status code of the first pose outside (or ``None`` at the search
    bound)."""

    name: str
    lo: float
    hi: float
    step: float
    tol: float
    stop_lo: int | None
    stop_hi: int | None

    @property
    def width(self) -> float:
        return self.hi - self.lo


def _inside(mechanism, pose, name_index, values, criteria, params) -> np.ndarray:
    poses = np.repeat(np.asarray(pose, dtype=float)[None, :], len(values), axis=0)
    poses[:, name_index] = values
    return classify(mechanism, poses, criteria, **params)


def coordinate_range(mechanism: str, reference: Sequence[float], name: str,
                     bound: tuple[float, float], step: float, tol: float,
                     criteria: Criteria = DEFAULT_CRITERIA, **params) -> CoordinateRange:
    """Connected range of coordinate ``name`` through ``reference`` within ``bound``
    (module docstring); NaN bounds when the reference itself is outside."""
    module = load_module(mechanism)
    if name not in module.POSE:
        raise ValueError(f"{module.MECHANISM}: {name!r} is not a pose coordinate; expected "
                         f"one of {module.POSE}")
    if not (step > 0 and tol > 0):
        raise ValueError(f"step and tol must be positive, got {step}, {tol}")
    k = module.POSE.index(name)
    ref = float(reference[k])
    code0 = _inside(mechanism, reference, k, np.array([ref]), criteria, params)[0]
    if code0 != IN_WORKSPACE:
        return CoordinateRange(name, np.nan, np.nan, step, tol, int(code0), int(code0))
    ends, stops, brackets = [None, None], [None, None], []
    for side, (direction, limit) in enumerate(((-1.0, bound[0]), (1.0, bound[1]))):
        n = int(np.ceil(abs(limit - ref) / step))
        values = ref + direction * step * np.arange(1, n + 1)
        values = np.clip(values, min(bound), max(bound))
        codes = _inside(mechanism, reference, k, values, criteria, params)
        outside = np.nonzero(codes != IN_WORKSPACE)[0]
        if outside.size == 0:
            ends[side] = limit
            continue
        i = outside[0]
        # inside, outside, the status there
        brackets.append([side, ref if i == 0 else values[i - 1], values[i], int(codes[i])])
    # both ends bisected together, one classification per halving for the two (each end's
    # numbers are those of bisecting it alone: every pose is its own)
    while live := [br for br in brackets if abs(br[2] - br[1]) > tol]:
        mids = np.array([0.5 * (br[1] + br[2]) for br in live])
        codes = _inside(mechanism, reference, k, mids, criteria, params)
        for br, mid, c in zip(live, mids, codes):
            if c == IN_WORKSPACE:
                br[1] = mid
            else:
                br[2], br[3] = mid, int(c)
    for side, a, _, stop in brackets:
        ends[side], stops[side] = a, stop
    return CoordinateRange(name, ends[0], ends[1], step, tol, stops[0], stops[1])


def ranges_about(mechanism: str, reference: Sequence[float], names: Sequence[str],
                 bounds: Mapping[str, tuple[float, float]], step: Mapping[str, float],
                 tol: Mapping[str, float], criteria: Criteria = DEFAULT_CRITERIA,
                 **params) -> dict[str, CoordinateRange]:
    """:func:`coordinate_range` for each of ``names``."""
    return {n: coordinate_range(mechanism, reference, n, bounds[n], step[n], tol[n], criteria,
                                **params) for n in names}
