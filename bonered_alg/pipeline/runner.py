"""Running the stages: one mechanism in memory (:func:`derive`), or every registered one
whose outputs are out of date, written to disk (:func:`derive_all`)."""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path
from types import ModuleType

from ..elimination.engines import DEFAULT_BUDGET_S, Engine, get_engine
from ..registry import REGISTRY, load, module_path
from . import outputs, stages, toolchain
from .algebra import Algebra
from .provenance import derivation_hash
from .results import Derivation, Record, frozen_map


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
    ``progress`` (e.g. ``print``) is told each stage and its time as it ends."""
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


def derive_all(root: Path, names: list[str] | None = None, force: bool = False,
               engine: Engine | None = None, log=print, progress=None) -> dict[str, str]:
    """Derive and write each mechanism whose outputs are missing or out of date, and the
    record of the Study-parameter framework (``papers/study_algebra.py``); where anything
    was derived, the record of the engine and packages used (:mod:`.toolchain`)."""
    from ..papers import study_algebra

    status = {}
    if not names:
        status["study_algebra"] = study_algebra.write_record(root, force, log)
    for name in names or list(REGISTRY):
        current = current_hash(name)
        if not force and outputs.recorded_hash(root, name) == current:
            log(f"{name}: up to date ({current[:12]})")
            status[name] = "up to date"
            continue
        t0 = time.perf_counter()
        record = derive(name, engine=engine, progress=progress)
        changed = write(record, root)
        log(f"{name}: derived in {time.perf_counter() - t0:.1f} s; wrote "
            + (", ".join(str(p.relative_to(root)) for p in changed) or "nothing new"))
        status[name] = "derived"
    if "derived" in status.values() or toolchain.recorded(root) is None:
        toolchain.write(root, engine or get_engine())
    return status
