"""Running the stages: one mechanism in memory (:func:`derive`), or every registered one
whose outputs are out of date, written to disk (:func:`derive_all`)."""

from __future__ import annotations

import json
import multiprocessing
import os
import time
from collections.abc import Callable, Collection
from concurrent.futures import ProcessPoolExecutor, wait
from dataclasses import replace
from pathlib import Path
from types import ModuleType

from ..elimination.cache import cache_dir
from ..elimination.engines import DEFAULT_BUDGET_S, Engine, get_engine
from ..fileio import atomic_write_text
from ..registry import EXPECTED_SECONDS, REGISTRY, load, module_path
from . import outputs, stages, toolchain
from .algebra import Algebra
from .provenance import derivation_hash
from .results import Derivation, Record, frozen_map
from .seeding import seeded_sympy_random
from .sympy_memo import remembered_structure


def current_hash(target: str | ModuleType) -> str:
    """The derivation hash of a registered mechanism or of a declaration module."""
    if isinstance(target, str):
        return derivation_hash(module_path(target), stages.GENERATOR)
    file = getattr(target, "__file__", None)
    return derivation_hash(target.__name__, stages.GENERATOR,
                           module_file=Path(file) if file else None)


def derive(target: str | ModuleType, engine: Engine | None = None,
           budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True,
           algebra: Algebra | None = None, progress=None) -> Record:
    """Every stage for one mechanism (registered name, or a declaration module), in memory;
    ``progress`` (e.g. ``print``) is told each stage and its time as it ends.  sympy's
    random numbers are seeded for the derivation (:mod:`.seeding`), and its node counts
    and free symbols remembered (:mod:`.sympy_memo`)."""
    with seeded_sympy_random(), remembered_structure():
        return _derive(target, engine, budget_s, use_cache, algebra, progress)


def _derive(target, engine, budget_s, use_cache, algebra, progress) -> Record:
    t0 = time.perf_counter()
    module = load(target) if isinstance(target, str) else target
    mech = stages.build(module)
    algebra = algebra or Algebra.default(engine, budget_s, use_cache)
    d = Derivation(mech, current_hash(target))
    clock = [time.perf_counter()]

    def done(stage: str) -> None:
        now = time.perf_counter()
        if progress is not None:
            progress(f"  {mech.name}: {stage} {now - clock[0]:.1f} s "
                     f"(elapsed {now - t0:.1f} s)", flush=True)
        clock[0] = now

    for name, stage in (("elimination", stages.eliminate), ("IK plan", stages.plan),
                        ("analyses", stages.analyse)):
        d = stage(d, algebra)
        done(name)
    d = stages.specify(d)
    t1 = time.perf_counter()
    gm = stages.import_generated(stages.generate(d))
    done("code generation")
    t2 = time.perf_counter()
    studies = stages.run_studies(d, gm)
    verdicts = stages.verify(d, gm, studies)
    done("studies and verification")
    t3 = time.perf_counter()
    d = replace(d, timings=frozen_map({**d.timings, "code generation": t2 - t1,
                                       "studies and verification": t3 - t2, "total": t3 - t0}))
    return Record(d, gm, studies, verdicts)


def write(record: Record, root: Path) -> list[Path]:
    """Render every output of ``record``, then write them atomically under ``root``."""
    return outputs.write(outputs.files(record), root)


def default_jobs() -> int:
    """Processes for :func:`derive_all`: ``$BONERED_ALG_JOBS``, else the usable cores."""
    env = os.environ.get("BONERED_ALG_JOBS")
    if env:
        try:
            jobs = int(env)
        except ValueError:
            jobs = 0
        if jobs < 1:
            raise ValueError(f"BONERED_ALG_JOBS must be a positive integer, got {env!r}")
        return jobs
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
               else (os.cpu_count() or 1))


def _derive_and_write(name: str, root: Path, engine: Engine | None, progress
                      ) -> tuple[str, float]:
    """Derive ``name`` and write its outputs: the log line and the seconds it took."""
    t0 = time.perf_counter()
    record = derive(name, engine=engine, progress=progress)
    changed = write(record, root)
    seconds = time.perf_counter() - t0
    return (f"{name}: derived in {seconds:.1f} s; wrote "
            + (", ".join(str(p.relative_to(root)) for p in changed) or "nothing new"),
            seconds)


def _derive_in_worker(name: str, root: Path, engine: Engine | None, progress: bool
                      ) -> tuple[str, float]:
    """:func:`_derive_and_write` in a worker process (the engine pickled: its class and
    executable)."""
    return _derive_and_write(name, root, engine, print if progress else None)


def _times_file() -> Path:
    """This machine's record of the last derivation time of each mechanism, beside the
    elimination cache (not an output: it only orders the work)."""
    return cache_dir().parent / "derive_seconds.json"


def _recorded_seconds() -> dict[str, float]:
    """This machine's record, or nothing where there is none or it is damaged."""
    try:
        recorded = json.loads(_times_file().read_text())
        return {k: float(v) for k, v in recorded.items() if isinstance(v, (int, float))}
    except (OSError, ValueError, AttributeError):
        return {}


def expected_seconds() -> dict[str, float]:
    """How long each mechanism's derivation is expected to take: this machine's last times
    where recorded, else :data:`..registry.EXPECTED_SECONDS`."""
    return {**EXPECTED_SECONDS, **_recorded_seconds()}


def _record_seconds(seconds: dict[str, float]) -> None:
    """Add ``seconds`` to this machine's record (best effort: a read-only cache directory
    leaves the registry's figures in use)."""
    if not seconds:
        return
    merged = {**_recorded_seconds(), **{k: round(v, 1) for k, v in seconds.items()}}
    try:
        _times_file().parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(_times_file(), json.dumps(merged, indent=1, sort_keys=True) + "\n")
    except OSError:
        pass


def longest_first(names: list[str]) -> list[str]:
    """``names`` by expected derivation time, the longest first (the registry's order
    among equals and for names without an estimate, which go first): handed to the
    workers in this order, the last mechanism to start is a short one and the workers
    finish at nearly the same time (in registry order a long one could start last)."""
    expected = expected_seconds()
    return sorted(names, key=lambda n: -expected.get(n, float("inf")))


def derive_all(root: Path, names: list[str] | None = None, force: bool = False,
               engine: Engine | None = None, log=print, progress=None,
               jobs: int | None = None,
               then: tuple[Collection[str], Callable[[], None]] | None = None
               ) -> dict[str, str]:
    """Derive and write each mechanism whose outputs are missing or out of date, and the
    record of the Study-parameter framework (``papers/study_algebra.py``); where anything
    was derived, the record of the engine and packages used (:mod:`.toolchain`).

    With ``jobs`` > 1 (default :func:`default_jobs`) the mechanisms are derived in that many
    worker processes, each mechanism in one process from start to finish: every output is
    the same bytes as a serial run (each depends on its own mechanism only and is written
    atomically); the log lines come in registry order, the progress lines as they happen.

    ``then``: ``(mechanisms, run)``; ``run()`` is called in this process once every
    mechanism of ``mechanisms`` that is derived here has been written, while the workers
    go on with the others (those are handed out after them): a study of those modules
    (the comparison, ``cli derive --comparison``) then fills the cores that the last
    derivations leave idle.  Not called where one of them failed; an error of ``run`` is
    raised after the derivations have finished and been logged."""
    from ..papers import study_algebra

    status = {}
    todo, current_lines = [], []
    for name in names or list(REGISTRY):
        current = current_hash(name)
        if not force and outputs.recorded_hash(root, name) == current:
            current_lines.append(f"{name}: up to date ({current[:12]})")
            status[name] = "up to date"
        else:
            todo.append(name)
    jobs = min(len(todo), jobs or default_jobs())

    def framework_record():
        # the Study-parameter framework's record (under a second), logged first; in the
        # parallel case while the workers start
        if not names:
            status["study_algebra"] = study_algebra.write_record(root, force, log)
        for line in current_lines:
            log(line)

    seconds: dict[str, float] = {}
    needs = set(then[0]) if then is not None else set()
    failure: BaseException | None = None
    if jobs <= 1:
        framework_record()
        for name in todo:
            line, seconds[name] = _derive_and_write(name, root, engine, progress)
            log(line)
            status[name] = "derived"
        if then is not None:
            failure = _call(then[1])
    else:
        ctx = multiprocessing.get_context("spawn")  # no fork of a process with threads
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            order = (longest_first([n for n in todo if n in needs])
                     + longest_first([n for n in todo if n not in needs]))
            futures = {name: pool.submit(_derive_in_worker, name, root, engine,
                                         progress is not None)
                       for name in order}
            try:
                framework_record()
            except BaseException:
                for f in futures.values():  # the ones not started
                    f.cancel()
                raise
            if then is not None:
                needed = [futures[n] for n in todo if n in needs]
                wait(needed)
                if all(f.exception() is None for f in needed):
                    failure = _call(then[1])
            for name in todo:
                line, seconds[name] = futures[name].result()
                log(line)
                status[name] = "derived"
    _record_seconds(seconds)
    if "derived" in status.values() or toolchain.recorded(root) is None:
        toolchain.write(root, engine or get_engine())
    if failure is not None:
        raise failure
    return status


def _call(run: Callable[[], None]) -> Exception | None:
    """``run()``; its error returned (raised by :func:`derive_all` once the derivations
    are written and logged)."""
    try:
        run()
    except Exception as exc:
        return exc
    return None
