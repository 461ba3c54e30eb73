"""The Groebner engine as the stages see it: one engine, one time budget, one cache."""

from __future__ import annotations

from dataclasses import dataclass

from ..elimination import cache
from ..elimination.engines import DEFAULT_BUDGET_S, Engine, get_engine
from ..elimination.problem import (
    EliminationProblem,
    EliminationResult,
    ParametricProblem,
    ParametricResult,
)


@dataclass(frozen=True)
class Algebra:
    """Eliminations and lex bases through ``engine`` with ``budget_s`` per call, cached on
    disk unless ``use_cache`` is off."""

    engine: Engine
    budget_s: float = DEFAULT_BUDGET_S
    use_cache: bool = True

    @classmethod
    def default(cls, engine: Engine | None = None, budget_s: float = DEFAULT_BUDGET_S,
                use_cache: bool = True) -> Algebra:
        return cls(engine or get_engine(), budget_s, use_cache)

    def eliminate(self, problem: EliminationProblem,
                  budget_s: float | None = None) -> EliminationResult:
        return cache.eliminate(problem, self.engine, budget_s or self.budget_s, self.use_cache)

    def lex_basis(self, problem: ParametricProblem,
                  budget_s: float | None = None) -> ParametricResult:
        return cache.lex_basis(problem, self.engine, min(budget_s or self.budget_s,
                                                         self.budget_s), self.use_cache)
