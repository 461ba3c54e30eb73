"""A remote centre of motion proved from the ideal: a line of the platform passes through
the base origin O in every configuration (002 Sect. 2.4, eq. 1-6).

The claim is proved on a *general* platform, not on a parametrization that has the centre
built in.  Each leg ends in a frame whose z axis is the line (trailing rotations about z and
translations along z, such as a collar's spin and slide on a shaft, are dropped: they leave
that line where it is).  For each leg:

1. the leg closes on a general Study point ``X = [1:X1:X2:X3:Y0:Y1:Y2:Y3]`` (chart
   ``x0 = 1``, every rotation but the half-turns); every joint of the leg except those of a
   declared plane normal ``n`` is eliminated (Cox-Little-O'Shea, Ch. 3 Sect. 1);
2. ``n . u`` and ``n . p`` lie in the elimination ideal (reduction to 0 by its Groebner
   basis), where ``u |x|^2`` is the frame's z axis and ``p |x|^2`` its origin: the line lies
   in the plane through O normal to ``n`` (002 eq. 4), and so its moment ``m = p x u`` obeys
   ``m x n = u (p . n) - p (u . n)``, in the ideal.

With two legs whose frames share the line, the identity (checked by expansion)

    |N|^2 m = |n2|^2 (n1 x C1) + (n1 . n2)(C1 x n2) + (C2 . N) n1,
    C_i = m x n_i,  N = n1 x n2,

puts ``|N|^2 m`` in the sum of the two ideals, and ``u x N = n1 (u . n2) - n2 (u . n1)``
does the same for the direction (002 eq. 6, up to sign): the line passes through O and
is parallel to ``n1 x n2`` wherever the two planes differ (``N != 0``).  Where they coincide
the certificate says nothing, and the report says so.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_symbolic as ss
from ..declaration.closures import MU, UnitCoordinate
from ..elimination.problem import EliminationProblem, EliminationResult
from ..errors import MechanismDefinitionError
from ..report.latex_util import latex, tex_escape
from ..verification import in_ideal

GENERAL = (sp.Integer(1),) + tuple(sp.Symbol(f"rc_{k}", real=True)
                                   for k in ("x1", "x2", "x3", "y0", "y1", "y2", "y3"))


def _z_line_factor(f) -> bool:
    """A factor that keeps its frame's z axis in place: a rotation about z or a
    translation along z."""
    return f.kind in ("rotation", "translation") and f.axis == "z"


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def line_of(point) -> tuple[tuple, tuple]:
    """``(u, p)`` times ``|x|^2``: the z axis and the origin of the frame ``point``."""
    rows = cv.rotation_matrix_times_norm(point)
    return tuple(r[2] for r in rows), cv.translation_times_norm(point)


def certificate_holds() -> bool:
    """The two identities of the module docstring, for symbolic vectors (exact)."""
    m, u, n1, n2 = (sp.symbols(f"{c}0:3", real=True) for c in ("m", "u", "n", "k"))
    c1, c2, big = cv.cross(m, n1), cv.cross(m, n2), cv.cross(n1, n2)
    lhs = [_dot(big, big) * mk for mk in m]
    t1, t2 = cv.cross(n1, c1), cv.cross(c1, n2)
    rhs = [_dot(n2, n2) * a + _dot(n1, n2) * b + _dot(c2, big) * n
           for a, b, n in zip(t1, t2, n1)]
    ok = all(sp.expand(x - y) == 0 for x, y in zip(lhs, rhs))
    dirs = [x - (n1[k] * _dot(u, n2) - n2[k] * _dot(u, n1))
            for k, x in enumerate(cv.cross(u, big))]
    return ok and all(sp.expand(x) == 0 for x in dirs)


@dataclass(frozen=True)
class LegPlane:
    """One leg's proof: its elimination on the general platform and the memberships."""

    leg: str
    dropped: tuple[str, ...]  # trailing factors about/along the line
    normal: tuple[sp.Expr, ...]
    result: EliminationResult
    direction_in_plane: bool  # n . u in the ideal
    origin_in_plane: bool  # n . p in the ideal


@dataclass(frozen=True)
class RemoteCentreResult:
    legs: tuple[LegPlane, ...]
    certificate: bool
    degenerate: tuple[sp.Expr, ...]  # N = n1 x n2, zero where the planes coincide

    @property
    def proved(self) -> bool:
        return self.certificate and all(g.direction_in_plane and g.origin_in_plane
                                        for g in self.legs)


@dataclass(frozen=True)
class RemoteCentre:
    """The line common to the end frames' z axes of the legs of closure ``closure`` passes
    through O; ``normals`` gives, per leg name, the normal of the plane through O that
    holds the leg's line (an expression in that leg's actuated joints: a hypothesis that
    the ideal must confirm)."""

    name: str
    closure: str
    normals: Mapping[str, tuple[sp.Expr, sp.Expr, sp.Expr]]
    title: str = "Remote centre of motion from the ideal"

    def check(self, mech) -> None:
        if self.closure not in {c.point for c in mech.closures}:
            raise MechanismDefinitionError(mech.name, f"analysis {self.name!r}: no closure on "
                                                      f"{self.closure!r}")
        legs = {leg.name: leg for leg in mech.closure(self.closure).legs}
        if sorted(self.normals) != sorted(legs) or len(legs) != 2:
            raise MechanismDefinitionError(
                mech.name, f"analysis {self.name!r}: needs a plane normal for each of the "
                f"closure's two legs {sorted(legs)}, got {sorted(self.normals)}")
        for name, n in self.normals.items():
            stray = set().union(*(sp.sympify(c).free_symbols for c in n)) - (
                set(mech.active) & legs[name].free_symbols)
            if len(n) != 3 or stray:
                raise MechanismDefinitionError(
                    mech.name, f"analysis {self.name!r}: leg {name!r}'s normal must be three "
                    f"expressions in the leg's actuated joints (stray: "
                    f"{sorted(map(str, stray))})")

    def _leg(self, mech, leg, algebra) -> LegPlane:
        factors = list(leg.factors)
        dropped = []
        while factors and _z_line_factor(factors[-1]):
            dropped.insert(0, factors.pop().label)
        chain = ss.product(*[f.study() for f in factors])
        normal = tuple(sp.sympify(c) for c in self.normals[leg.name])
        plane_joints = set().union(*(c.free_symbols for c in normal))
        syms = set().union(*(c.free_symbols for c in chain))
        geometric = tuple(s for s in mech.geometric if s in syms)
        joints = tuple(s for s in mech.passive + mech.active if s in syms)
        chart = UnitCoordinate(0)
        problem = EliminationProblem(
            context=f"mechanism {mech.name!r}, analysis {self.name!r}, leg {leg.name!r} on "
                    "a general platform",
            equations=tuple(chart.equations(chain, GENERAL)),
            eliminate=tuple(s for s in joints if s not in plane_joints) + (MU,),
            keep=GENERAL[1:] + tuple(s for s in joints if s in plane_joints) + geometric)
        result = algebra.eliminate(problem)
        u, p = line_of(GENERAL)
        gens, keep = result.generators, problem.keep
        return LegPlane(leg.name, tuple(dropped), normal, result,
                        in_ideal(sp.expand(_dot(normal, u)), gens, keep),
                        in_ideal(sp.expand(_dot(normal, p)), gens, keep))

    def run(self, d, algebra) -> RemoteCentreResult:
        mech = d.mechanism
        legs = tuple(self._leg(mech, leg, algebra) for leg in mech.closure(self.closure).legs)
        big = tuple(sp.factor(c) for c in cv.cross(legs[0].normal, legs[1].normal))
        return RemoteCentreResult(legs, certificate_holds(), big)

    def report(self, result: RemoteCentreResult) -> list[str]:
        out = [rf"\section{{{tex_escape(self.title)}}}",
               r"Each leg closes on a general platform $X = [1:X_1:X_2:X_3:Y_0:Y_1:Y_2:Y_3]$ "
               r"(the chart $x_0 = 1$: every rotation but the half-turns), with the "
               r"rotations about and translations along the line at its end dropped (they "
               r"leave the line in place). Its joints other than those of the plane's normal "
               r"$n$ are eliminated, and the line's direction $u$ and a point $p$ of it (the "
               r"end frame's $z$ axis and origin, times $|x|^2$: polynomials in $X$) are "
               r"reduced by the Groebner basis of the elimination ideal $I$:",
               r"\begin{center}\begin{tabular}{lllrcc}\hline leg & dropped & normal $n$ & "
               r"generators, dim & $n\cdot u \in I$ & $n\cdot p \in I$\\\hline"]
        for g in result.legs:
            out.append(
                f"{tex_escape(g.leg)} & {tex_escape(', '.join(g.dropped) or '--')} & "
                f"$({', '.join(latex(c) for c in g.normal)})$ & "
                f"{len(g.result.basis)}, {g.result.dimension} & "
                f"{'yes' if g.direction_in_plane else 'no'} & "
                f"{'yes' if g.origin_in_plane else 'no'}\\\\")
        out.append(r"\hline\end{tabular}\end{center}")
        n = ", ".join(latex(c) for c in result.degenerate)
        out.append(
            r"So each leg's line lies in the plane through $O$ normal to its $n$, and its "
            r"moment $m = p\times u$ about $O$ satisfies $m\times n = u\,(p\cdot n) - "
            r"p\,(u\cdot n) \in I$. With $C_i = m\times n_i$ and $N = n_1\times n_2$, the "
            r"identities $|N|^2 m = |n_2|^2 (n_1\times C_1) + (n_1\cdot n_2)(C_1\times n_2) "
            r"+ (C_2\cdot N)\, n_1$ and $u\times N = n_1 (u\cdot n_2) - n_2 (u\cdot n_1)$ "
            + ("(checked by expansion) " if result.certificate else
               "(FAIL when expanded) ")
            + r"put $|N|^2 m$ and $u\times N$ in the sum of the two ideals: "
            + (r"the line passes through $O$, along $n_1\times n_2$, in every "
               r"configuration where the two planes differ." if result.proved else
               r"the proof does not go through (see the table).")
            + f" Here $N = ({n})$, which vanishes only where the planes coincide; there the "
              "certificate says nothing.")
        return out
