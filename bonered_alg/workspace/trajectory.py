"""Paths through a generated module: joint positions and velocities, and the margins to the
stroke limits, the passive joint ranges and the singularities along the path.

:func:`stepwise_path` builds a path as a sequence of straight steps between waypoints
(001 Sect. 4.2: "first the top moving platform is rotated ... then translated ..."), each
step taking one time unit; :func:`follow` evaluates a mechanism along it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .membership import DEFAULT_CRITERIA, IN_WORKSPACE, Criteria, classify, load_module, margin


def stepwise_path(start: Sequence[float], steps: Sequence[Mapping[int, float]],
                  samples_per_step: int = 50) -> tuple[np.ndarray, np.ndarray]:
    """Times and poses of a path that changes, in step ``k``, the coordinates
    ``steps[k]`` (index -> value reached at the end of the step) linearly, the others held;
    step ``k`` runs over ``t in [k, k + 1]``."""
    if samples_per_step < 2:
        raise ValueError(f"samples_per_step must be >= 2, got {samples_per_step}")
    current = np.asarray(start, dtype=float)
    times, poses = [0.0], [current.copy()]
    for k, change in enumerate(steps):
        target = current.copy()
        for i, v in change.items():
            target[i] = v
        s = np.linspace(0.0, 1.0, samples_per_step)[1:]
        poses += list(current + s[:, None] * (target - current))
        times += list(k + s)
        current = target
    return np.array(times), np.array(poses)


@dataclass
class TrajectoryResult:
    """Along a path: ``q`` (N, joints), ``qdot`` (d q / d t), ``code`` (0 = in the
    workspace, else a module status or NEAR_SINGULAR), ``stroke_margin`` (mm to the nearest
    stroke limit, negative outside), ``passive_margin`` (rad to the nearest passive joint
    limit), ``singularity_margin`` (membership.margin)."""

    mechanism: str
    t: np.ndarray
    poses: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    code: np.ndarray
    stroke_margin: np.ndarray
    passive_margin: np.ndarray
    singularity_margin: np.ndarray

    @property
    def feasible(self) -> bool:
        return bool(np.all(self.code == IN_WORKSPACE))

    def first_failure(self) -> float | None:
        bad = np.nonzero(self.code != IN_WORKSPACE)[0]
        return float(self.t[bad[0]]) if bad.size else None


def follow(mechanism: str, t: np.ndarray, poses: np.ndarray,
           criteria: Criteria = DEFAULT_CRITERIA, **params) -> TrajectoryResult:
    """Evaluate ``mechanism`` along the path ``(t, poses)`` in ``criteria.modes[0]``."""
    module = load_module(mechanism)
    mode = criteria.modes[0]
    q, _ = module.ik_and_status(poses, mode, False, **params)
    code = classify(mechanism, poses, criteria, **params)
    qdot = np.gradient(q, t, axis=0)
    values = module.limit_values(poses, q, **params)
    stroke = np.full(len(t), np.inf)
    passive = np.full(len(t), np.inf)
    for name, lo, hi, kind in criteria.ranges(module):
        v = values[name]
        m = np.minimum(v - lo, hi - v)
        if kind == "stroke":
            stroke = np.minimum(stroke, m)
        else:
            passive = np.minimum(passive, m)
    sing = margin(module, poses, mode, criteria.length, **params)
    return TrajectoryResult(module.MECHANISM, t, poses, q, qdot, code, stroke, passive, sing)
