"""Where the singularity polynomials vanish inside a scanned workspace.

For each polynomial of the generated module (``SINGULARITY_MEANING``), evaluated at the
grid's samples with their IK: two grid neighbours that are both reachable and where the
polynomial has opposite signs (or is zero) bracket a point of the singularity locus inside
the workspace, to the grid's resolution.  No such pair means the locus does not cross the
reachable set at this resolution (001 Sect. 3: "all the singular configurations identified
in Sect. 2.3 remain outside of the mechanism workspace").
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .membership import load_module
from .scan import ScanResult

CHUNK = 1 << 15


def polynomial_signs(res: ScanResult, mode: int = 0, params: Mapping | None = None,
                     where: np.ndarray | None = None, workers: int | None = None
                     ) -> dict[str, np.ndarray]:
    """Sign (-1, 0, 1; 0 also where undefined) of each singularity polynomial on every
    grid sample (kinematics only, limits off), shaped like the grid; with ``where`` (a
    boolean array of the grid's shape) only there, 0 elsewhere: :func:`crossings` and
    :func:`signs_on_reachable` read the reachable samples only, :mod:`.components` also
    their neighbours.  The grid's chunks are evaluated on ``workers`` threads (default:
    all cores; numpy releases the GIL inside each operation on a chunk, so two threads
    take about half the time of one), each writing its own samples: the same signs for
    any number of threads."""
    module = load_module(res.mechanism)
    params = dict(params if params is not None else res.params)
    if where is not None and where.shape != res.grid.shape:
        raise ValueError(f"{res.mechanism}: where has shape {where.shape}, the grid "
                         f"{res.grid.shape}")
    flat = None if where is None else where.reshape(-1)
    out = {name: np.zeros(res.grid.size, dtype=np.int8) for name in module.SINGULARITY_MEANING}

    def chunk(bounds: tuple[int, int]) -> None:
        a, b = bounds
        pick = slice(None) if flat is None else np.nonzero(flat[a:b])[0]
        if flat is not None and pick.size == 0:
            return
        poses = res.grid.poses(a, b)[pick]
        q = module.ik(poses, mode, False, **params)
        values = module.singularities(poses, q, **params)
        for name, v in values.items():
            s = np.zeros(v.shape, dtype=np.int8)  # NaN (undefined): 0
            s[v > 0], s[v < 0] = 1, -1
            out[name][a:b][pick] = s

    bounds = list(res.grid.chunks(CHUNK))
    workers = min(workers or os.cpu_count() or 1, len(bounds))
    if workers <= 1:
        for ab in bounds:
            chunk(ab)
    else:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            for _ in pool.map(chunk, bounds):  # raises the first error
                pass
    return {k: v.reshape(res.grid.shape) for k, v in out.items()}


def crossings(res: ScanResult, signs: Mapping[str, np.ndarray]) -> dict[str, int]:
    """Per polynomial: the number of pairs of reachable grid neighbours (along any axis)
    across which it changes sign or vanishes."""
    if res.mask is None:
        raise ValueError(f"{res.mechanism}: the scan kept no mask (keep_mask=False)")
    out = {}
    for name, s in signs.items():
        n = 0
        for axis in range(res.mask.ndim):
            lo = [slice(None)] * res.mask.ndim
            hi = [slice(None)] * res.mask.ndim
            lo[axis], hi[axis] = slice(None, -1), slice(1, None)
            both = res.mask[tuple(lo)] & res.mask[tuple(hi)]
            flip = (s[tuple(lo)] * s[tuple(hi)]) <= 0
            n += int(np.count_nonzero(both & flip))
        out[name] = n
    return out


def signs_on_reachable(res: ScanResult, signs: Mapping[str, np.ndarray]) -> dict[str, dict]:
    """Per polynomial: how many reachable samples it is positive, negative and zero on.
    Both signs on the reachable set mean the locus crosses it, or separates parts of it
    (a locus on an excluded grid plane, e.g. an input singularity where the IK status is
    INPUT_SINGULAR, is not seen by :func:`crossings`)."""
    if res.mask is None:
        raise ValueError(f"{res.mechanism}: the scan kept no mask (keep_mask=False)")
    return {name: {"positive": int(np.count_nonzero(res.mask & (s > 0))),
                   "negative": int(np.count_nonzero(res.mask & (s < 0))),
                   "zero_or_undefined": int(np.count_nonzero(res.mask & (s == 0)))}
            for name, s in signs.items()}
