"""Chunked, parallel workspace scans: reachable set, ranges per coordinate, volume.

:func:`scan` classifies every sample of a :class:`~.grid.Grid` with
:func:`~.membership.classify`, one chunk at a time, and keeps only running totals (count,
per-axis extremes, reasons) and, optionally, a bit-packed mask (one bit per sample: 10^8
samples are 12.5 MB).  Chunks run on a local process pool (all cores by default, its
workers kept for the next scan of the process; :func:`shutdown_pools` stops them) or, for
scans that outgrow one machine, on a dask cluster (``client=`` a ``distributed.Client``,
or ``"local"`` for a ``LocalCluster``); at most ``2 x workers`` chunks are in flight, so
memory stays bounded at any resolution.
"""

from __future__ import annotations

import itertools
import os
import queue
import threading
import time
from collections import Counter
from collections.abc import Callable, Mapping
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from multiprocessing import get_context
from types import ModuleType

import numpy as np

from .grid import Grid
from .membership import DEFAULT_CRITERIA, IN_WORKSPACE, Criteria, classify, load_module

DEFAULT_CHUNK = 1 << 13  # 8192: arrays of 64 KB stay in cache (1.5x faster per core than 65536)
# with the compiled fast path: fewer, larger chunks (the per-chunk Python work, which holds
# the GIL, is then small against the compiled call, which does not; bonered_scan never
# splits a chunk over threads itself).  On a 160^3 grid, medians of 5 interleaved rounds on
# two cores: planar_tripod 87.7 -> 81.3 ms, tripod_planar 95.6 -> 90.4 ms from 2^15 to 2^16
# samples a chunk, stewart 131 -> 133 ms; 2^17 no better
COMPILED_CHUNK = 1 << 16
MASK_LIMIT = 2 * 10**8  # samples beyond which the mask is not kept unless asked


@dataclass(frozen=True)
class ChunkResult:
    start: int
    count: int
    lo: tuple[float, ...]  # per axis, over the chunk's reachable samples (inf if none)
    hi: tuple[float, ...]
    reasons: dict[int, int]
    packed: bytes | None


@dataclass
class ScanResult:
    """Totals of a scan (internal units: mm, rad)."""

    mechanism: str
    grid: Grid
    criteria: Criteria
    params: dict
    count: int = 0
    ranges: dict[str, tuple[float, float]] = field(default_factory=dict)
    reasons: dict[int, int] = field(default_factory=dict)
    mask: np.ndarray | None = None
    seconds: float = 0.0

    @property
    def samples(self) -> int:
        return self.grid.size

    @property
    def volume(self) -> float:
        """Reachable samples x cell volume (mm^k rad^l of the grid's axes)."""
        return self.count * self.grid.cell_volume

    @property
    def rate(self) -> float:
        return self.samples / self.seconds if self.seconds > 0 else float("nan")

    def extent(self, name: str) -> float:
        lo, hi = self.ranges.get(name, (np.nan, np.nan))
        return hi - lo


def compiled_scan(module, criteria: Criteria, params: Mapping):
    """``(fast path, parameters)`` where a chunk can be classified and reduced in one
    compiled call (:meth:`bonered_alg.runtime.compiled.FastPath.scan`): the module's fast
    path is available for these parameters and the criteria are the module's own limits
    without a singularity margin; else None (:func:`~.membership.classify` in numpy around
    the IK, compiled or not)."""
    if criteria.limits or criteria.min_margin > 0:
        return None
    model = getattr(module, "_MODEL", None)
    if model is None or getattr(model, "fast", None) is None:
        return None
    from ..runtime import inputs

    par = inputs.parameters(model, "scan", dict(params))
    fast = model._fast_path("scan", None, par)  # noqa: SLF001
    return None if fast is None else (fast, par)


def scan_chunk(mechanism: str | ModuleType, grid: Grid, start: int, stop: int, criteria: Criteria,
               params: Mapping, keep_mask: bool) -> ChunkResult:
    """Classify samples ``start:stop`` of ``grid`` (runs in a worker): in one compiled call
    where :func:`compiled_scan` allows it, else with :func:`~.membership.classify`."""
    module = load_module(mechanism)
    compiled = compiled_scan(module, criteria, params)
    if compiled is not None:
        fast, par = compiled
        names = list(grid.pose_names)
        fixed = np.zeros(len(names))
        for name, value in grid.fixed.items():
            fixed[names.index(name)] = value
        axes = [(names.index(a.name), a.lo, a.step, a.n) for a in grid.axes]
        count, lo, hi, reasons, packed = fast.scan(start, stop, axes, fixed, criteria.modes,
                                                   par, keep_mask)
        return ChunkResult(start, count, tuple(float(v) for v in lo),
                           tuple(float(v) for v in hi), reasons, packed)
    axis_values = grid.axis_values(start, stop)
    code = classify(mechanism, grid.poses(start, stop, axis_values), criteria, **params)
    inside = code == IN_WORKSPACE
    lo, hi = [], []
    for v in axis_values:  # on the contiguous axis values, with where=: no copies
        lo.append(float(np.min(v, where=inside, initial=np.inf)))
        hi.append(float(np.max(v, where=inside, initial=-np.inf)))
    if code.size and code.min() >= 0:  # status codes: small non-negative integers
        counts = np.bincount(code)
        codes = np.flatnonzero(counts)
        counts = counts[codes]
    else:
        codes, counts = np.unique(code, return_counts=True)
    packed = np.packbits(inside).tobytes() if keep_mask else None
    return ChunkResult(start, int(inside.sum()), tuple(lo), tuple(hi),
                       {int(v): int(c) for v, c in zip(codes, counts)}, packed)


def _merge(result: ScanResult, parts: list[ChunkResult], keep_mask: bool) -> None:
    lo = [np.inf] * len(result.grid.axes)
    hi = [-np.inf] * len(result.grid.axes)
    reasons: Counter = Counter()
    for p in parts:
        result.count += p.count
        lo = [min(a, b) for a, b in zip(lo, p.lo)]
        hi = [max(a, b) for a, b in zip(hi, p.hi)]
        reasons.update(p.reasons)
    result.ranges = {a.name: (lo[i], hi[i]) for i, a in enumerate(result.grid.axes)
                     if lo[i] <= hi[i]}
    result.reasons = dict(sorted(reasons.items()))
    if keep_mask:
        parts = sorted(parts, key=lambda p: p.start)
        # unpacked straight to 0/1 bytes and viewed as bool: no second array of the grid's
        # size (4 ms of the 2-core scan's 110 on a 160^3 grid, after every chunk is done)
        bits = np.unpackbits(np.frombuffer(b"".join(p.packed for p in parts), dtype=np.uint8),
                             count=result.grid.size)
        result.mask = bits.view(bool).reshape(result.grid.shape)


def compiled_path(module, params: Mapping) -> bool:
    """Whether ``module``'s IK runs through its compiled fast path with these parameters
    (then chunks run on threads: the compiled call releases the GIL, and threads cost no
    process start-up and no pickling)."""
    model = getattr(module, "_MODEL", None)
    if model is None or getattr(model, "fast", None) is None:
        return False
    par = [np.asarray(v) for v in params.values()]
    return model._fast_path("scan", None, par) is not None  # noqa: SLF001


# the spawned worker processes, kept for the next scan of this process: starting two costs
# about 0.3 s (the interpreter, numpy, the runtime and the generated module), more than a
# scan of half a million samples takes on one core; the comparison study scans 19 grids
_POOLS: dict[tuple[int, int], ProcessPoolExecutor] = {}  # (this process's id, workers)
_POOLS_LOCK = threading.Lock()


def process_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of ``workers`` spawned processes, started on first use and kept (a broken one,
    e.g. after a worker was killed, is replaced).  Kept per process: a forked child starts
    its own and never touches its parent's."""
    key = (os.getpid(), workers)
    with _POOLS_LOCK:
        pool = _POOLS.get(key)
        if pool is None or getattr(pool, "_broken", False):
            if pool is not None:
                pool.shutdown(wait=False, cancel_futures=True)
            pool = ProcessPoolExecutor(max_workers=workers, mp_context=get_context("spawn"))
            _POOLS[key] = pool
        return pool


def shutdown_pools() -> None:
    """Stop this process's kept worker processes (they also stop when it exits)."""
    with _POOLS_LOCK:
        for key in [k for k in _POOLS if k[0] == os.getpid()]:
            _POOLS.pop(key).shutdown(wait=True, cancel_futures=True)


def _run_local(tasks, workers, progress, threads=False):
    if workers == 1 or len(tasks) <= 1:  # one task: in this process
        out = []
        for i, t in enumerate(tasks):
            out.append(scan_chunk(*t))
            if progress:
                progress(i + 1, len(tasks))
        return out
    if threads:
        return _run_threads(tasks, workers, progress)
    out, pending = [], set()
    pool = process_pool(workers)
    try:
        for t in tasks:
            pending.add(pool.submit(scan_chunk, *t))
            if len(pending) >= 2 * workers:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                out += [f.result() for f in done]
                if progress:
                    progress(len(out), len(tasks))
        for f in pending:
            out.append(f.result())
            if progress:
                progress(len(out), len(tasks))
    finally:  # an error (or an interrupt) leaves no chunk of this scan running
        for f in pending:
            f.cancel()
        wait(pending)
    return out


def _run_threads(tasks, workers, progress):
    """``scan_chunk`` of every task on ``workers`` threads, each taking the next task when
    it is done with one (no future per chunk: with the compiled path, a pool's per-chunk
    scheduling held the two-core scan at 1.7x one core, against 1.9x for this); the main
    thread only reports progress.  The first error stops every thread and is raised."""
    lock = threading.Lock()
    it = iter(tasks)
    stop = threading.Event()
    events: queue.SimpleQueue = queue.SimpleQueue()

    def work() -> None:
        try:
            while not stop.is_set():
                with lock:
                    task = next(it, None)
                if task is None:
                    break
                events.put(scan_chunk(*task))
        except BaseException as exc:  # noqa: BLE001 - handed to the main thread, raised there
            stop.set()
            events.put(exc)
        finally:
            events.put(None)

    pool = [threading.Thread(target=work, name=f"bonered_scan_{i}", daemon=True)
            for i in range(workers)]
    # every thread started before any takes a task: a worker already running its chunk's
    # Python code holds the GIL that `start` needs for the next thread (measured on a 160^3
    # grid: the second thread began 0.7-4.5 ms after the first, of a scan's 90)
    with lock:
        for t in pool:
            t.start()
    out, error, running = [], None, workers
    while running:
        item = events.get()
        if item is None:
            running -= 1
        elif isinstance(item, BaseException):
            error = error or item
        else:
            out.append(item)
            if progress and error is None:
                progress(len(out), len(tasks))
    for t in pool:
        t.join()
    if error is not None:
        raise error
    return out


def _run_dask(tasks, client, workers, progress):
    from dask.distributed import Client, LocalCluster, as_completed

    own = None
    if client == "local":
        own = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None)
        client = Client(own)
    try:
        it = iter(tasks)
        futures = [client.submit(scan_chunk, *t, pure=False)
                   for t in itertools.islice(it, 2 * workers)]
        seq = as_completed(futures)
        out = []
        for fut in seq:
            out.append(fut.result())
            fut.release()
            nxt = next(it, None)
            if nxt is not None:
                seq.add(client.submit(scan_chunk, *nxt, pure=False))
            if progress:
                progress(len(out), len(tasks))
        return out
    finally:
        if own is not None:
            client.close()
            own.close()


def scan(mechanism: str | ModuleType, grid: Grid, criteria: Criteria = DEFAULT_CRITERIA, *,
         chunk: int | None = None, workers: int | None = None, client=None,
         keep_mask: bool | None = None, progress: Callable[[int, int], None] | None = None,
         **params) -> ScanResult:
    """Scan ``grid`` for ``mechanism`` (a generated module's name, or the module itself:
    then in this process or on threads only, e.g. a module just generated and not on disk).

    ``workers``: threads or processes (default: all cores); ``client``: None (local
    workers), a ``dask.distributed.Client``, or ``"local"``; ``chunk``: samples per task
    (default: DEFAULT_CHUNK, COMPILED_CHUNK with the compiled fast path); ``keep_mask``: keep
    the reachable mask (default: when the grid has at most 2e8 samples); ``progress(done,
    total)`` is called after each chunk; ``params``: geometric parameters passed to the
    generated functions.  Where the module's compiled fast path is used, local workers are
    threads; otherwise spawned processes, and a script that scans with ``workers > 1`` needs
    the usual ``if __name__ == "__main__":`` guard.
    """
    module = load_module(mechanism)
    in_memory = isinstance(mechanism, ModuleType)
    criteria.check(module)
    if tuple(grid.pose_names) != tuple(module.POSE):
        raise ValueError(f"{mechanism}: the grid's pose coordinates {grid.pose_names} are "
                         f"not the module's POSE {module.POSE}")
    threads = client is None and compiled_path(module, params)
    if chunk is None:
        chunk = COMPILED_CHUNK if threads else DEFAULT_CHUNK
    if chunk % 8:
        raise ValueError(f"chunk must be a multiple of 8 (the mask is bit-packed), got {chunk}")
    workers = workers or os.cpu_count() or 1
    keep = grid.size <= MASK_LIMIT if keep_mask is None else keep_mask
    if in_memory and (client is not None or (workers > 1 and not threads)):
        raise ValueError(f"{module.MECHANISM}: a module object is scanned in this process "
                         "or on threads only; pass the generated module's name for process "
                         "or dask workers (they import it)")
    target = module if in_memory else module.MECHANISM
    tasks = [(target, grid, a, b, criteria, dict(params), keep)
             for a, b in grid.chunks(chunk)]
    t0 = time.perf_counter()
    if client is None:
        parts = _run_local(tasks, workers, progress, threads)
    else:
        parts = _run_dask(tasks, client, workers, progress)
    result = ScanResult(module.MECHANISM, grid, criteria, dict(params))
    _merge(result, parts, keep)
    result.seconds = time.perf_counter() - t0
    return result
