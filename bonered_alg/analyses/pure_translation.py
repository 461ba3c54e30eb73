"""Pure translation proved from the ideal: the platform of a closure never turns (003 Sect.
2.1: "each chain contains only a torque constraint ... the robot could achieve translation
movement in 3D space").

The claim is proved on a *general* platform, not on the declared one (which has the claim
built in).  Each leg's rotation closes on a general rotation ``[X0:X1:X2:X3]`` in the chart
``|x|^2 = 1`` (004 eq. 2: every rotation, half-turns included), and all of its joints are
eliminated (Cox-Little-O'Shea, Ch. 3 Sect. 1).  The dual part is left out: with a general
dual part ``Y`` the equations ``Y = lambda C_dual`` only give ``Y`` and constrain no joint,
so the rotation ideal of the leg on the full general platform is this one.  Where the
rotation coordinates ``X1, X2, X3`` that lie in some leg's ideal (reduction to 0 by its
Groebner basis) are all three, the sum of the leg ideals contains ``X1, X2, X3`` and so,
with the chart, ``X0^2 - 1``: the platform's rotation is the identity in every
configuration of the closure, over the complex numbers and so over the reals.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..declaration.closures import LAMBDA
from ..elimination.problem import EliminationProblem, EliminationResult
from ..errors import MechanismDefinitionError
from ..report.latex_util import tex_escape
from ..verification import in_ideal

GENERAL = tuple(sp.Symbol(f"pt_x{k}", real=True) for k in range(4))
ROTATION = GENERAL[1:4]


@dataclass(frozen=True)
class LegOrientation:
    """One leg on the general platform: its elimination and the rotation coordinates in
    its ideal (each a constraint couple of the leg that holds in every configuration)."""

    leg: str
    result: EliminationResult
    fixed: tuple[int, ...]  # k with X_k in the leg's ideal (1..3)


@dataclass(frozen=True)
class PureTranslationResult:
    legs: tuple[LegOrientation, ...]

    @property
    def fixed(self) -> tuple[int, ...]:
        return tuple(sorted({k for g in self.legs for k in g.fixed}))

    @property
    def proved(self) -> bool:
        return self.fixed == (1, 2, 3)


@dataclass(frozen=True)
class PureTranslation:
    """The platform of closure ``closure`` (a point name) does not turn."""

    name: str
    closure: str
    title: str = "Pure translation from the ideal"

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")

    def _leg(self, mech, leg, algebra) -> LegOrientation:
        rotation = leg.product()[:4]
        syms = set().union(*(sp.sympify(c).free_symbols for c in rotation))
        geometric = tuple(s for s in mech.geometric if s in syms)
        joints = tuple(s for s in mech.passive + mech.active if s in syms)
        equations = [sp.expand(x - LAMBDA * c) for x, c in zip(GENERAL, rotation)]
        problem = EliminationProblem(
            context=f"mechanism {mech.name!r}, analysis {self.name!r}, leg {leg.name!r}'s "
                    "rotation on a general one",
            equations=tuple(e for e in equations if e != 0)
            + (sp.expand(sum(x**2 for x in GENERAL) - 1),),
            eliminate=joints + (LAMBDA,),
            keep=GENERAL + geometric)
        result = algebra.eliminate(problem)
        fixed = tuple(k for k, c in enumerate(ROTATION, start=1)
                      if in_ideal(c, result.generators, problem.keep))
        return LegOrientation(leg.name, result, fixed)

    def run(self, d, algebra) -> PureTranslationResult:
        mech = d.mechanism
        return PureTranslationResult(tuple(self._leg(mech, leg, algebra)
                                           for leg in mech.closure(self.closure).legs))

    def report(self, result: PureTranslationResult) -> list[str]:
        out = [rf"\section{{{tex_escape(self.title)}}}",
               r"Each leg's rotation closes on a general rotation $[X_0:X_1:X_2:X_3]$ with "
               r"$X_0^2 + X_1^2 + X_2^2 + X_3^2 = 1$ (every rotation, half-turns included; "
               r"the dual part is left out, as with a general dual part it only determines "
               r"$Y$), all of the leg's joints are eliminated, and the rotation coordinates "
               r"are reduced by the Groebner basis of the elimination ideal $I$ (a "
               r"coordinate in $I$ is zero in every configuration of the leg):",
               r"\begin{center}\begin{tabular}{lrl}\hline leg & generators, dim & "
               r"rotation coordinates in $I$\\\hline"]
        for g in result.legs:
            fixed = ", ".join(f"$X_{k}$" for k in g.fixed) or "none"
            out.append(f"{tex_escape(g.leg)} & {len(g.result.basis)}, "
                       f"{g.result.dimension} & {fixed}\\\\")
        out.append(r"\hline\end{tabular}\end{center}")
        out.append(
            r"The sum of the leg ideals contains $X_1, X_2, X_3$ and so $X_0^2 - 1$: the "
            r"platform keeps its orientation in every configuration, real or complex (a "
            r"pure translation)." if result.proved else
            "The rotation coordinates in the sum of the leg ideals are "
            + (", ".join(f"$X_{k}$" for k in result.fixed) or "none")
            + ": the platform is not proved to translate only.")
        return out
