"""The immutable results the pipeline's stages hand on (``pipeline.stages``).

Each stage takes the results of the stages before it and returns new frozen objects; a
:class:`Derivation` is filled stage by stage with :func:`dataclasses.replace`, never
mutated.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType, ModuleType
from typing import Any

import sympy as sp

from ..chains.joints import Leg
from ..declaration.closures import Closure
from ..declaration.mechanism import InputFunction, Limit, Mechanism, PoseFunction
from ..elimination.problem import (
    EliminationProblem,
    EliminationResult,
    ParametricProblem,
    ParametricResult,
)
from ..kinematics.ik_plan import IKStep, mode_count
from ..kinematics.singularities import FactoredPolynomial
from ..verification import Verdict

EMPTY: Mapping = MappingProxyType({})


def frozen_map(d: Mapping) -> Mapping:
    return MappingProxyType(dict(d))


@dataclass(frozen=True)
class LegIdeal:
    """One leg: its chain product, its closure problem, and the generators of its ideal.

    ``method`` names the solver that produced the ideal (``solvers.legs``): an elimination,
    or a certified closed form (``certificate`` says why no elimination was run).
    ``generators`` are in ``keep``, each a sum of monomials (expanded); for a mounted leg
    they are the eliminated frame's reduced basis carried back to the platform's
    coordinates."""

    closure: Closure
    leg: Leg
    product: tuple[sp.Expr, ...]
    problem: EliminationProblem
    result: EliminationResult
    generators: tuple[sp.Expr, ...]
    keep: tuple[sp.Symbol, ...]
    method: str
    certificate: str = ""


@dataclass(frozen=True)
class ClosureVelocity:
    """Ji = dG/dq and Jo = dG/dy of one closure (004 eq. 19-20), rows = IK generators."""

    closure: str
    joints: tuple[sp.Symbol, ...]
    pose: tuple[sp.Symbol, ...]
    ji: sp.ImmutableMatrix
    jo: sp.ImmutableMatrix


@dataclass(frozen=True)
class ClosureFK:
    """Forward kinematics of one closure, from the solver that recognized it
    (``solvers.closures``): a triangular lex basis over Q(joints, geometry) and its
    back-substitution plan, or an eliminant system solved per configuration (``system``)
    whose solution count is certified by a Groebner basis at ``count_at``."""

    closure: str
    solver: str
    problem: ParametricProblem
    result: ParametricResult | None
    dimension: int
    solutions: int | None
    steps: tuple[IKStep, ...]
    system: Any = None  # e.g. kinematics.rps_forward.RPSSystem
    count_at: Mapping | None = None
    singularity: FactoredPolynomial | None = None
    # plans from the lex bases in other orders of the unknowns, regular where a pivot of
    # ``steps`` vanishes (``solvers.closures.TriangularLexBasis._alternates``)
    alternates: tuple[tuple[IKStep, ...], ...] = ()


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one mechanism, symbolic; filled stage by stage."""

    mechanism: Mechanism
    derivation_hash: str
    legs: tuple[LegIdeal, ...] = ()
    steps: tuple[IKStep, ...] = ()
    extra_generators: tuple[tuple[str, sp.Expr], ...] = ()
    velocity: tuple[ClosureVelocity, ...] = ()
    singularities: tuple[FactoredPolynomial, ...] = ()
    fk: tuple[ClosureFK, ...] = ()
    fk_note: str = ""
    passive: tuple = ()  # kinematics.passive.LegRecovery per leg of the actuated closures
    analyses: Mapping[str, Any] = field(default_factory=lambda: EMPTY)
    pose_to_study: Mapping[sp.Symbol, sp.Expr] = field(default_factory=lambda: EMPTY)
    limits: tuple[Limit, ...] = ()
    pose_functions: tuple[PoseFunction, ...] = ()
    functions: tuple[InputFunction, ...] = ()
    timings: Mapping[str, float] = field(default_factory=lambda: EMPTY)
    branches: tuple = ()  # kinematics.branches.Branch per declared joint of home_joints

    @property
    def constants(self) -> dict[sp.Symbol, sp.Expr]:
        return {c.symbol: c.value for c in self.mechanism.constants}

    def leg(self, name: str) -> LegIdeal:
        return next(r for r in self.legs if r.leg.name == name)

    def closure_generators(self, point: str) -> list[sp.Expr]:
        """The union of the leg ideals of the closure on ``point`` (in leg order)."""
        return list(dict.fromkeys(g for r in self.legs if r.closure.point == point
                                  for g in r.generators))

    def singularity(self, name: str) -> FactoredPolynomial:
        return next(s for s in self.singularities if s.name == name)

    @property
    def modes(self) -> int:
        return mode_count(self.steps)

    def ik_expressions(self, mode: int = 0) -> dict[sp.Symbol, sp.Expr]:
        """The IK of every joint as one sympy expression of the pose (constants inserted):
        the reference the generated code is checked and benchmarked against."""
        sub = {k: sp.sympify(v).subs(self.constants) for k, v in self.pose_to_study.items()}
        out: dict[sp.Symbol, sp.Expr] = {}
        bit = 0
        for st in self.steps:
            a, b, c = (sp.sympify(e).subs(self.constants).xreplace(sub)
                       for e in (st.A, st.B, st.C))
            if st.degree == 1:
                out[st.joint] = -c / b
                continue
            sign = -1 if (mode >> bit) & 1 else 1
            bit += 1
            out[st.joint] = (-b + sign * sp.sqrt(b**2 - 4 * a * c)) / (2 * a)
        return out


@dataclass(frozen=True)
class GeneratedModule:
    """The generated module's source, its operation counts, and the module imported from
    that source (never from disk)."""

    name: str
    source: str
    operations: Mapping[str, int]
    module: ModuleType | None = None
    c_source: str = ""  # generated/<name>.c, the compiled fast path

    @property
    def total_operations(self) -> int:
        return sum(self.operations.values())


@dataclass(frozen=True)
class Study:
    """The result of a paper study run on the generated module (``bonered_alg.studies``):
    its data (read by the paper checks), the files it writes beside the report, and its
    report sections (LaTeX)."""

    name: str
    data: Mapping[str, Any] = field(default_factory=lambda: EMPTY)
    files: Mapping[str, str | bytes] = field(default_factory=lambda: EMPTY)
    report: tuple[str, ...] = ()


@dataclass(frozen=True)
class Record:
    """Everything a mechanism's derivation produces: the derivation, the generated module,
    the studies and the verdicts (``outputs.files`` renders the report from them)."""

    derivation: Derivation
    generated: GeneratedModule
    studies: Mapping[str, Study] = field(default_factory=dict)
    verification: tuple[Verdict, ...] = ()
