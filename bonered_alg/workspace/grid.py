"""Sampling grids over a subset of the pose coordinates, generated chunk by chunk.

A :class:`Grid` names some pose coordinates (``x``, ``gamma``, ...) with a closed range and a
number of samples each, and fixes the others.  :meth:`Grid.poses` builds the poses of one
chunk of the flattened index range only, so memory stays bounded by the chunk size at any
resolution (10^8 samples are 10^8 / chunk chunks, never one array).

Units are the generated modules' (mm, rad); :meth:`Axis.from_user` takes degrees for angles.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

ANGLES = ("alpha", "beta", "gamma")


@dataclass(frozen=True)
class Axis:
    """``n`` equally spaced samples of pose coordinate ``name`` on ``[lo, hi]`` (mm or rad)."""

    name: str
    lo: float
    hi: float
    n: int

    def __post_init__(self):
        if not (math.isfinite(self.lo) and math.isfinite(self.hi)) or self.hi < self.lo:
            raise ValueError(f"axis {self.name!r}: expected finite lo <= hi, got "
                             f"[{self.lo}, {self.hi}]")
        if self.n < 1 or (self.n == 1 and self.hi != self.lo):
            raise ValueError(f"axis {self.name!r}: expected n >= 2 samples on [{self.lo}, "
                             f"{self.hi}] (n = 1 only for lo = hi), got n = {self.n}")

    @classmethod
    def from_user(cls, name: str, lo: float, hi: float, step: float) -> Axis:
        """Range and step in user units (degrees for angles): ``n`` covers ``[lo, hi]`` with
        spacing at most ``step``."""
        if step <= 0:
            raise ValueError(f"axis {name!r}: the step must be positive, got {step}")
        n = max(2, math.ceil(round((hi - lo) / step, 9)) + 1) if hi > lo else 1
        scale = math.pi / 180 if name in ANGLES else 1.0
        return cls(name, lo * scale, hi * scale, n)

    @property
    def step(self) -> float:
        return (self.hi - self.lo) / (self.n - 1) if self.n > 1 else 0.0

    def values(self) -> np.ndarray:
        return np.linspace(self.lo, self.hi, self.n)


@dataclass(frozen=True)
class Grid:
    """The product of ``axes`` with the other coordinates of ``pose_names`` at ``fixed``."""

    pose_names: tuple[str, ...]
    axes: tuple[Axis, ...]
    fixed: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self):
        names = [a.name for a in self.axes]
        unknown = sorted(set(names) - set(self.pose_names))
        if unknown:
            raise ValueError(f"grid axes {unknown} are not pose coordinates; expected some of "
                             f"{list(self.pose_names)}")
        if len(set(names)) != len(names):
            raise ValueError(f"grid axes repeat a coordinate: {names}")
        both = sorted(set(names) & set(self.fixed))
        if both:
            raise ValueError(f"coordinates {both} are both grid axes and fixed")
        missing = sorted(set(self.pose_names) - set(names) - set(self.fixed))
        if missing:
            raise ValueError(f"pose coordinates {missing} are neither grid axes nor fixed")
        extra = sorted(set(self.fixed) - set(self.pose_names))
        if extra:
            raise ValueError(f"fixed coordinates {extra} are not pose coordinates; expected "
                             f"some of {list(self.pose_names)}")

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.n for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def cell_volume(self) -> float:
        """Product of the steps of the axes with more than one sample (mm^k rad^l)."""
        return math.prod(a.step for a in self.axes if a.n > 1)

    def chunks(self, chunk: int) -> Iterator[tuple[int, int]]:
        """``(start, stop)`` ranges of the flattened (C-order) index, ``chunk`` at most."""
        if chunk < 1:
            raise ValueError(f"chunk must be >= 1, got {chunk}")
        for start in range(0, self.size, chunk):
            yield start, min(start + chunk, self.size)

    def axis_values(self, start: int, stop: int) -> list[np.ndarray]:
        """Each axis's values (contiguous arrays) at flattened indices ``start:stop``.

        Row by row of the last axis (C order): its values tiled, every other axis's value
        repeated along each row, each sample ``lo + step * index`` as indexed one by one
        (per-sample ``unravel_index`` took a third of a compiled scan's time)."""
        m = max(stop - start, 0)
        if not self.axes:
            return []
        if m == 0:
            return [np.empty(0) for _ in self.axes]
        last = self.axes[-1]
        n = last.n
        offset = start % n
        reps = (offset + m + n - 1) // n
        values = last.lo + last.step * np.arange(n, dtype=np.int64)
        out = [np.tile(values, reps)[offset:offset + m]]
        if len(self.axes) > 1:
            first_row, last_row = start // n, (stop - 1) // n
            rows = np.arange(first_row, last_row + 1, dtype=np.int64)
            counts = np.full(len(rows), n, dtype=np.int64)
            counts[-1] = (stop - 1) % n + 1
            counts[0] = (min(n, offset + m) if len(rows) == 1 else n) - offset
            idx = np.unravel_index(rows, self.shape[:-1])
            out = [np.repeat(a.lo + a.step * i, counts)
                   for a, i in zip(self.axes[:-1], idx)] + out
        return out

    def poses(self, start: int, stop: int, values: list[np.ndarray] | None = None
              ) -> np.ndarray:
        """Poses ``(stop - start, len(pose_names))`` of flattened indices ``start:stop``
        (``values``: their :meth:`axis_values`, where the caller has them)."""
        out = np.empty((max(stop - start, 0), len(self.pose_names)))
        for name, value in self.fixed.items():
            out[:, self.pose_names.index(name)] = value
        for a, v in zip(self.axes, values if values is not None
                        else self.axis_values(start, stop)):
            out[:, self.pose_names.index(a.name)] = v
        return out

    def describe(self) -> str:
        parts = [f"{a.name} in [{user_value(a.name, a.lo):g}, {user_value(a.name, a.hi):g}] "
                 f"({a.n} samples, step {user_value(a.name, a.step):.4g})" for a in self.axes]
        parts += [f"{k} = {user_value(k, v):g}" for k, v in self.fixed.items()]
        return "; ".join(parts) + " (mm, deg)"


def user_value(name: str, value: float) -> float:
    """User units for tables and plots: mm stay mm, radians become degrees."""
    return math.degrees(value) if name in ANGLES else value


def user_unit(name: str) -> str:
    """Unit of :func:`user_value`: degrees for the Euler angles, mm for every other pose
    coordinate (the generated modules' lengths, e.g. 004's Xu, Yu)."""
    return "deg" if name in ANGLES else "mm"


def internal_value(name: str, value: float) -> float:
    """Degrees -> radians for angles; mm unchanged."""
    return math.radians(value) if name in ANGLES else value


def fixed_from_user(pose_names: Sequence[str], values: Mapping[str, float]) -> dict[str, float]:
    """User units (deg for angles) -> internal units, checking the names."""
    unknown = sorted(set(values) - set(pose_names))
    if unknown:
        raise ValueError(f"fixed coordinates {unknown} are not pose coordinates; expected "
                         f"some of {list(pose_names)}")
    return {k: internal_value(k, float(v)) for k, v in values.items()}
