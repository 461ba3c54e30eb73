"""On-disk cache of elimination results, keyed by a hash of the problem and the engine."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from ..fileio import atomic_write_text
from . import polyterms as pt
from .engines import DEFAULT_BUDGET_S, Engine, get_engine, timed_eliminate
from .problem import EliminationProblem, EliminationResult, ParametricProblem, ParametricResult


def cache_dir() -> Path:
    """``$BONERED_CACHE_DIR`` or ``.cache/elimination`` in the current directory."""
    return Path(os.environ.get("BONERED_CACHE_DIR", ".cache/elimination"))


def eliminate(problem: EliminationProblem, engine: Engine | None = None,
              budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True) -> EliminationResult:
    """Solve ``problem`` with ``engine`` (default: :func:`get_engine`), through the cache."""
    engine = engine or get_engine()
    path = cache_dir() / f"{problem.key(engine.name)}.json"
    if use_cache and path.is_file():
        try:
            data = json.loads(path.read_text())
            basis = pt.from_json(data["basis"])
            return EliminationResult(problem, basis, int(data["dimension"]), engine.name,
                                     float(data["seconds"]), cached=True)
        except (ValueError, KeyError, TypeError):
            pass  # a damaged cache entry is recomputed
    basis, seconds = timed_eliminate(engine, problem, budget_s)
    dim = pt.dimension_from_leading_monomials([p[0][0] for p in basis], len(problem.keep))
    if not basis:
        dim = len(problem.keep)
    if use_cache:
        atomic_write_text(path, json.dumps({"basis": pt.to_json(basis), "dimension": dim,
                                            "seconds": seconds, "context": problem.context}))
    return EliminationResult(problem, basis, dim, engine.name, seconds)


def lex_basis(problem: ParametricProblem, engine: Engine | None = None,
              budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True) -> ParametricResult:
    """Lex basis over Q(parameters) of ``problem`` (:class:`ParametricProblem`), cached."""
    engine = engine or get_engine()
    path = cache_dir() / f"{problem.key(engine.name)}.json"
    if use_cache and path.is_file():
        try:
            data = json.loads(path.read_text())
            return ParametricResult(problem, pt.from_json(data["basis"]), engine.name,
                                    float(data["seconds"]), cached=True)
        except (ValueError, KeyError, TypeError):
            pass
    t0 = time.perf_counter()
    basis = engine.lex_basis(problem, budget_s)
    seconds = time.perf_counter() - t0
    if use_cache:
        atomic_write_text(path, json.dumps({"basis": pt.to_json(basis), "seconds": seconds,
                                            "context": problem.context}))
    return ParametricResult(problem, basis, engine.name, seconds)
