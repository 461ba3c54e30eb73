"""The part of a scanned workspace that the mechanism reaches from its home pose without
crossing a singularity (issue 13, item 6).

A grid sample belongs to it if the scan found it reachable, every singularity polynomial of
the generated module has there the sign it has at home, and a path of reachable grid
neighbours (along one axis at a time) with those signs leads to it from the home sample.
A sample where a polynomial changes sign lies beyond a singular locus: the mechanism cannot
get there without passing through the singularity, even where every joint stays in range.

Limits: the grid's resolution; a polynomial that touches zero without changing sign (a
factor of even multiplicity) is not seen; a polynomial that vanishes at home itself cannot
fix a side and is left out (listed in ``vanishing_at_home``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np
from scipy import ndimage

from .scan import ScanResult
from .singular_loci import polynomial_signs


class HomeNotReachable(ValueError):
    """The home pose itself is outside the scanned workspace (not reachable on the grid)."""


@dataclass(frozen=True)
class HomeComponent:
    """A scan restricted to the home pose's component (``result``) and what was left out."""

    result: ScanResult
    home_index: tuple[int, ...]
    polynomials: tuple[str, ...]
    vanishing_at_home: tuple[str, ...]
    reachable_elsewhere: int  # reachable samples outside the component
    sides: SignSides  # the signs around home (for ``bounding``)

    @property
    def count(self) -> int:
        return self.result.count

    @property
    def bounding(self) -> dict[str, int]:
        """Polynomial -> component samples near its sign change (:meth:`SignSides.bounding`),
        counted when asked for."""
        return self.sides.bounding(self.result.mask)


def nearest_index(res: ScanResult, home: Mapping[str, float]) -> tuple[int, ...]:
    """The grid sample nearest to ``home`` (internal units, one value per grid axis)."""
    missing = [a.name for a in res.grid.axes if a.name not in home]
    if missing:
        raise ValueError(f"{res.mechanism}: the home pose gives no value for the grid axes "
                         f"{missing}")
    idx = []
    for a in res.grid.axes:
        v = a.values()
        i = int(np.argmin(np.abs(v - home[a.name])))
        if abs(v[i] - home[a.name]) > 0.5 * a.step + 1e-12:
            raise ValueError(f"{res.mechanism}: the home value {a.name} = {home[a.name]} lies "
                             f"outside the grid axis [{v[0]}, {v[-1]}]")
        idx.append(i)
    return tuple(idx)


def _faces(ndim: int) -> np.ndarray:
    return ndimage.generate_binary_structure(ndim, 1)


def shell(mask: np.ndarray, steps: int = 2) -> np.ndarray:
    """``mask`` and the samples up to ``steps`` face-neighbour steps from it."""
    return ndimage.binary_dilation(mask, structure=_faces(mask.ndim), iterations=steps)


def signs_near_reachable(res: ScanResult) -> dict[str, np.ndarray]:
    """The singularity polynomials' signs on the reachable samples and those up to two
    steps from them (all that :func:`home_component` reads), 0 elsewhere."""
    if res.mask is None:
        raise ValueError(f"{res.mechanism}: the scan kept no mask (keep_mask=False)")
    return polynomial_signs(res, where=shell(res.mask))


class SignSides:
    """What :func:`home_component` reads of the singularity polynomials' signs around the
    home sample ``at``, for any mask of the same grid: the polynomials used (not zero at
    home) and skipped, where all used ones have home's sign, and per polynomial the samples
    within two grid steps of its opposite sign (built when first asked for).  A search that
    labels many masks of one scan builds it once (:mod:`..studies.planar_stroke_000`)."""

    def __init__(self, signs: Mapping[str, np.ndarray], at: tuple[int, ...]):
        self.signs, self.at = signs, at
        self.used = tuple(n for n in sorted(signs) if signs[n][at] != 0)
        self.skipped = tuple(n for n in sorted(signs) if signs[n][at] == 0)
        self.agree = None
        for name in self.used:
            same = signs[name] == signs[name][at]
            self.agree = same if self.agree is None else self.agree & same
        self._near: dict[str, np.ndarray] = {}

    def near(self, name: str) -> np.ndarray:
        """The samples within two grid steps (along one axis) of a sample where ``name``
        has the sign opposite to home's."""
        if name not in self._near:
            s = self.signs[name]
            other = s == -s[self.at]
            near = np.zeros(other.shape, dtype=bool)
            for axis in range(other.ndim):
                for k in (1, 2):
                    lo = [slice(None)] * other.ndim
                    hi = [slice(None)] * other.ndim
                    lo[axis], hi[axis] = slice(None, -k), slice(k, None)
                    near[tuple(lo)] |= other[tuple(hi)]
                    near[tuple(hi)] |= other[tuple(lo)]
            self._near[name] = near
        return self._near[name]

    def bounding(self, mask: np.ndarray) -> dict[str, int]:
        """Per used polynomial: the samples of ``mask`` within two grid steps (along one
        axis) of a sample where it has the sign opposite to home's: its locus passes within
        two steps of the component.  Two, because the sample on the locus itself is usually
        excluded (the IK is singular there) and its computed sign is rounding noise; samples
        where a polynomial is undefined (0) are not taken as evidence."""
        return {name: int(np.count_nonzero(mask & self.near(name))) for name in self.used}


def home_component(res: ScanResult, signs: Mapping[str, np.ndarray],
                   home: Mapping[str, float], sides: SignSides | None = None
                   ) -> HomeComponent:
    """Restrict ``res`` (a scan that kept its mask) to the samples connected to ``home``
    without a sign change of any polynomial of ``signs`` (:func:`signs_near_reachable`,
    or :func:`.singular_loci.polynomial_signs`, on at least the reachable samples).
    ``sides``: ``SignSides(signs, home's sample)`` where already built."""
    if res.mask is None:
        raise ValueError(f"{res.mechanism}: the scan kept no mask (keep_mask=False)")
    at = nearest_index(res, home)
    if not res.mask[at]:
        raise HomeNotReachable(f"{res.mechanism}: the home pose {dict(home)} is not reachable "
                         "on this grid")
    if sides is None:
        sides = SignSides(signs, at)
    elif sides.signs is not signs or sides.at != at:
        raise ValueError(f"{res.mechanism}: sides were built for other signs or another "
                         f"home sample ({sides.at}, not {at})")
    allowed = res.mask if sides.agree is None else res.mask & sides.agree
    labels, _ = ndimage.label(allowed, structure=_faces(allowed.ndim))
    mask = labels == labels[at]
    ranges = {}
    for k, a in enumerate(res.grid.axes):
        other = tuple(j for j in range(mask.ndim) if j != k)
        hit = np.nonzero(mask.any(axis=other) if other else mask)[0]
        ranges[a.name] = (float(a.values()[hit[0]]), float(a.values()[hit[-1]]))
    count = int(np.count_nonzero(mask))
    return HomeComponent(replace(res, mask=mask, count=count, ranges=ranges), at,
                         sides.used, sides.skipped, int(res.count - count), sides)
