"""On-disk cache of engine results, keyed by a hash of the problem and the engine."""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable
from pathlib import Path

from ..fileio import atomic_write_text
from . import polyterms as pt
from .engines import DEFAULT_BUDGET_S, Engine, get_engine
from .problem import EliminationProblem, EliminationResult, ParametricProblem, ParametricResult


def cache_dir() -> Path:
    """``$BONERED_CACHE_DIR`` or ``.cache/elimination`` in the current directory."""
    return Path(os.environ.get("BONERED_CACHE_DIR", ".cache/elimination"))


def _cached(problem, engine: Engine, use_cache: bool,
            compute: Callable[[], tuple[tuple, float]]) -> tuple[tuple, float, bool]:
    """(basis, seconds, cached) from the cache, or from ``compute()`` (then stored)."""
    who = engine.identity if engine.available() else engine.name
    path = cache_dir() / f"{problem.key(who)}.json"
    if use_cache and path.is_file():
        try:
            data = json.loads(path.read_text())
            return pt.from_json(data["basis"]), float(data["seconds"]), True
        except (ValueError, KeyError, TypeError):
            pass  # a damaged cache entry is recomputed
    t0 = time.perf_counter()
    basis = compute()
    seconds = time.perf_counter() - t0
    if use_cache:
        atomic_write_text(path, json.dumps({"basis": pt.to_json(basis), "seconds": seconds,
                                            "context": problem.context}))
    return basis, seconds, False


def eliminate(problem: EliminationProblem, engine: Engine | None = None,
              budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True) -> EliminationResult:
    """Solve ``problem`` with ``engine`` (default: :func:`get_engine`), through the cache."""
    engine = engine or get_engine()
    basis, seconds, cached = _cached(problem, engine, use_cache,
                                     lambda: engine.eliminate(problem, budget_s))
    dim = pt.dimension_from_leading_monomials([p[0][0] for p in basis], len(problem.keep))
    if not basis:
        dim = len(problem.keep)
    return EliminationResult(problem, basis, dim, engine.name, seconds, cached=cached)


def lex_basis(problem: ParametricProblem, engine: Engine | None = None,
              budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True) -> ParametricResult:
    """Lex basis over Q(parameters) of ``problem`` (:class:`ParametricProblem`), cached."""
    engine = engine or get_engine()
    basis, seconds, cached = _cached(problem, engine, use_cache,
                                     lambda: engine.lex_basis(problem, budget_s))
    return ParametricResult(problem, basis, engine.name, seconds, cached=cached)
