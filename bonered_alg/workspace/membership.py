"""Whether poses belong to a mechanism's workspace, from its generated module only.

A pose is in the workspace (000 Sect. 5, 001 Sect. 3) when, in one of the allowed working
modes, its inverse kinematics is real and regular (status OK), every actuator stroke and
every passive joint angle is within its range (000 eq. 45-46; the ranges are the module's
``LIMITS`` unless :class:`Criteria` overrides some), and, when asked, the pose is farther
from a singularity than ``min_margin``.

The singularity margin is the inverse condition number of ``J = dq/dX`` with the angular
columns scaled by a length ``L`` (mm per rad, default: the mechanism's ``ra``), so that it
has no units: 0 at a forward (type II) singularity, where ``J`` loses rank, and the
pose is already excluded at an input (type I) singularity, where ``J`` is not defined.
"""

from __future__ import annotations

import fnmatch
import importlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import ModuleType

import numpy as np

from .grid import ANGLES

IN_WORKSPACE = 0
NEAR_SINGULAR = 100  # beyond the generated modules' status codes (< 100)


@dataclass(frozen=True)
class Criteria:
    """What makes a pose reachable.

    ``modes``: working modes tried (a pose is reachable in any of them); ``limits``:
    overrides of ``LIMITS`` ranges, ``{name-pattern: (lo, hi)}`` in the module's units
    (mm, rad; patterns as in :mod:`fnmatch`, e.g. ``"phi_s*"``); ``min_margin``: smallest
    singularity margin allowed (0: off); ``length``: the margin's length scale in mm
    (None: the ``ra`` parameter, else 1).
    """

    modes: tuple[int, ...] = (0,)
    limits: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    min_margin: float = 0.0
    length: float | None = None

    def check(self, module: ModuleType) -> None:
        """Clear errors for a mode or limit name the module does not have."""
        bad = [m for m in self.modes if not 0 <= int(m) < module.MODES]
        if bad or not self.modes:
            raise ValueError(f"{module.MECHANISM}: working modes {list(self.modes)} invalid; "
                             f"expected a non-empty subset of 0..{module.MODES - 1}")
        names = [lim[0] for lim in module.LIMITS]
        for pattern, (lo, hi) in self.limits.items():
            if not fnmatch.filter(names, pattern):
                raise ValueError(f"{module.MECHANISM}: no limit matches {pattern!r}; the "
                                 f"module's limits are {names}")
            if not lo <= hi:
                raise ValueError(f"{module.MECHANISM}: limit {pattern!r} needs lo <= hi, got "
                                 f"({lo}, {hi})")
        if self.min_margin < 0:
            raise ValueError(f"min_margin must be >= 0, got {self.min_margin}")

    def ranges(self, module: ModuleType) -> list[tuple[str, float, float, str]]:
        """``(name, lo, hi, kind)`` of every limit after the overrides."""
        out = []
        for name, lo, hi, kind, *_ in module.LIMITS:
            for pattern, (plo, phi) in self.limits.items():
                if fnmatch.fnmatch(name, pattern):
                    lo, hi = plo, phi
            out.append((name, float(lo), float(hi), kind))
        return out


DEFAULT_CRITERIA = Criteria()


def load_module(mechanism: str | ModuleType) -> ModuleType:
    """The generated module ``bonered_alg.generated.<mechanism>`` (or the module itself)."""
    if isinstance(mechanism, ModuleType):
        return mechanism
    try:
        return importlib.import_module(f"bonered_alg.generated.{mechanism}")
    except ModuleNotFoundError:
        raise ValueError(f"no generated module for mechanism {mechanism!r}; run "
                         "`make derive` (or `bonered-alg derive`) first") from None


def _limit_violations(module, poses, q, ranges, params) -> dict[str, np.ndarray]:
    """Per kind ('stroke', 'passive'): where some limit of that kind is violated."""
    values = module.limit_values(poses, q, **params)
    bad = {"stroke": np.zeros(poses.shape[:-1], dtype=bool),
           "passive": np.zeros(poses.shape[:-1], dtype=bool)}
    for name, lo, hi, kind in ranges:
        v = values[name]
        bad[kind] |= ~((v >= lo) & (v <= hi))
    return bad


def margin(module: ModuleType, poses: np.ndarray, mode: int = 0, length: float | None = None,
           **params) -> np.ndarray:
    """Singularity margin (module docstring) of each pose; NaN where ``J`` is undefined."""
    jac, _ = module.jacobian_and_status(poses, mode, False, **params)
    scale = np.ones(len(module.POSE))
    ell = length if length is not None else float(params.get("ra", module.PARAMETERS.get(
        "ra", 1.0)))
    for i, name in enumerate(module.POSE):
        if name in ANGLES:
            scale[i] = 1.0 / ell
    jac = jac * scale
    ok = np.all(np.isfinite(jac), axis=(-2, -1))
    out = np.full(poses.shape[:-1], np.nan)
    if np.any(ok):
        sv = np.linalg.svd(jac[ok], compute_uv=False)
        out[ok] = sv[..., -1] / sv[..., 0]
    return out


def classify(mechanism: str | ModuleType, poses: np.ndarray, criteria: Criteria = DEFAULT_CRITERIA,
             **params) -> np.ndarray:
    """Code per pose: ``IN_WORKSPACE`` (0) when some allowed mode reaches it, else a module
    status code (why the last mode tried fails; ``module.STATUS`` explains it) or
    ``NEAR_SINGULAR``."""
    module = load_module(mechanism)
    criteria.check(module)
    poses = np.asarray(poses, dtype=float)
    custom = bool(criteria.limits)
    ranges = criteria.ranges(module)
    code = None
    for mode in criteria.modes:
        q, status = module.ik_and_status(poses, mode, not custom, **params)
        status = status.astype(np.int16)
        if custom:  # the module's own check is off: apply the overridden ranges
            ok = status == module.OK
            bad = _limit_violations(module, poses, q, ranges, params)
            status[ok & bad["passive"]] = module.PASSIVE_JOINT_LIMIT
            status[ok & bad["stroke"]] = module.STROKE_LIMIT
        if criteria.min_margin > 0:
            ok = status == module.OK
            if np.any(ok):
                m = margin(module, poses[ok], mode, criteria.length, **params)
                near = ~(m >= criteria.min_margin)
                sub = status[ok]
                sub[near] = NEAR_SINGULAR
                status[ok] = sub
        code = status if code is None else np.where(code == IN_WORKSPACE, code, status)
    return code
