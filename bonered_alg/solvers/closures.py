"""Forward kinematics of each closure: the first solver of :data:`CLOSURE_SOLVERS` that
recognizes the closure derives it; a closure none can solve leaves the mechanism without
generated forward kinematics, and the reason is reported.

* :class:`RPSEliminant`: a closure of three R-P-S legs.  The lex basis of its
  circle-distance system over Q(joints, geometry) is out of reach, so the eliminant of
  degree 16 is formed per configuration in the runtime (:mod:`bonered_alg.runtime.rps`);
  the solution count at a generic rational configuration, from a Groebner basis, certifies
  that degree (:mod:`bonered_alg.kinematics.rps_forward`).
* :class:`TriangularLexBasis`: the union of the leg ideals has a lex basis over
  Q(joints, geometry) that is zero-dimensional and triangular with steps of degree <= 2,
  solved by back-substitution (all assembly modes at once).
"""

from __future__ import annotations

import dataclasses
import itertools

import sympy as sp

from ..algebra import convention as cv
from ..codegen.kernels import kernel
from ..elimination import polyterms as pt
from ..elimination.problem import ParametricProblem
from ..errors import EngineTimeoutError
from ..kinematics.ik_plan import plan
from ..kinematics.rps_forward import (
    DEGREE_BOUND,
    angles_from_platform,
    count_solutions,
    forward_jacobian,
    forward_singularity,
    is_rps_closure,
    rps_system,
)
from ..kinematics.singularities import evaluation_form, factored
from ..pipeline.results import ClosureFK

FK_BUDGET_S = 120.0
# back-substitution plans from other elimination orders kept per closure (at most)
MAX_ALTERNATES = 2


class NotSolvable(Exception):
    """A solver recognized the closure but cannot solve it (the message says why)."""


class NotTriangular(NotSolvable):
    """The lex basis in one order of the unknowns has a step of degree > 2 (another order
    may not)."""


class RPSEliminant:
    name = "3-RPS eliminant"

    def recognize(self, mech, closure, legs) -> bool:
        return is_rps_closure(closure)

    def derive(self, mech, closure, legs, algebra) -> ClosureFK:
        rps = rps_system(mech, closure)
        if tuple(closure.platform) != (1, *closure.pose):
            raise NotSolvable(f"the {closure.name} is a 3-RPS closure, but its point is not "
                              "in the chart x0 = 1 the 3-RPS forward kinematics writes")
        budget = dataclasses.replace(algebra, budget_s=min(algebra.budget_s, FK_BUDGET_S))
        count, at = count_solutions(rps, mech, budget)
        if count != DEGREE_BOUND:
            raise NotSolvable(f"the {closure.name} has {count} forward-kinematics solutions "
                              f"at a generic configuration, not the {DEGREE_BOUND} of the "
                              "iterated resultant: its eliminant would carry extraneous roots")
        problem = ParametricProblem(
            f"mechanism {mech.name!r}, closure {closure.name!r}: forward kinematics "
            "(circle-distance system)", rps.equations, rps.angles, rps.joints)
        det = forward_singularity(rps)
        # evaluated from the Jacobian's entries where that is shorter (planar_tripod: 3,026
        # operations after CSE expanded, 375 from the entries); the angles from the pose in
        # one simultaneous replacement (no angle appears in another's value)
        form = evaluation_form(det, forward_jacobian(rps))
        sing = factored(
            f"det_forward_{closure.point}", det,
            f"forward (type II) singularity of the {closure.name}: det d(e12, e23, e31)/d("
            + ", ".join(map(str, rps.angles)) + "), zero where two assembly modes merge "
            "and the platform moves infinitesimally with the legs locked",
            evaluate=(det if form is None else form).xreplace(
                angles_from_platform(rps, closure.platform)))
        return ClosureFK(closure.name, self.name, problem, None, 0, count, (), rps, at, sing)

    def kernels(self, rps, joints, par) -> list:
        """The kernels of the runtime step (``runtime.rps``): coefficients, equations and
        Jacobian, centres, platform points, Study point from (R, t); rational functions,
        also printed as C (the compiled fast path's twins, ``codegen.c_module``)."""
        u = list(rps.angles)
        eqs = sp.Matrix(list(rps.equations))
        rot = sp.Matrix(3, 3, sp.symbols("r0:9", real=True))
        trans = sp.symbols("t0:3", real=True)
        x = cv.rotation_ratios(rot.tolist())[0]
        study = tuple(x) + cv.dual_part_from_translation(trans, x)
        return [
            kernel("_rps_coefficients", [*joints, *par],
                   [e for m in rps.coefficients for row in m for e in row],
                   "Coefficients C_ij[a][b] of u_i^a u_j^b in e12, e23, e31 (row-major).",
                   c=True),
            kernel("_rps_equations", [*u, *joints, *par], list(eqs) + list(eqs.jacobian(u)),
                   "e12, e23, e31 and their Jacobian in the revolute tan-half angles.",
                   c=True),
            kernel("_rps_centres", [*u, *joints, *par], [e for p in rps.centres for e in p],
                   "Spherical joint centres B_k in the closure's base frame.", c=True),
            kernel("_rps_platform", list(par), [e for p in rps.platform for e in p],
                   "Spherical joint centres P_k in the platform frame.", c=True),
            kernel("_rps_study", [*rot, *trans], [e / study[0] for e in study[1:]],
                   "Study coordinates (chart x0 = 1) of the platform from R (row-major) and t.",
                   c=True),
        ]


class TriangularLexBasis:
    name = "triangular lex basis"

    def recognize(self, mech, closure, legs) -> bool:
        return True

    def derive(self, mech, closure, legs, algebra) -> ClosureFK:
        gens = [g for r in legs if r.closure is closure for g in r.generators]
        syms = set().union(*(g.free_symbols for g in gens))
        # rotation coordinates last: for fixed rotation the closure equations are mostly
        # linear in the dual part, so the univariate polynomial of the lex basis is in the
        # rotation and the translation follows linearly (with pivots that do not vanish at
        # symmetric configurations such as equal strokes, which the reverse order gave)
        # within each class, an unknown that fewer generators contain is solved later
        # (e.g. the height z of 003 eq. 9, in one sphere only: from x, y, not the other way,
        # whose univariate quartic in z took 90 s)
        primal = set().union(*(sp.sympify(c).free_symbols for c in closure.platform[:4]))
        pose_unknowns = tuple(sorted((y for y in closure.pose if y in syms),
                                     key=lambda y: (y in primal,
                                                    sum(y in g.free_symbols for g in gens))))
        problem, result, steps, count, pose_unknowns = self._first_triangular(
            mech, closure, gens, syms, pose_unknowns, algebra)
        return ClosureFK(closure.name, self.name, problem, result, 0, count, tuple(steps),
                         alternates=self._alternates(mech, closure, gens, syms, pose_unknowns,
                                                     steps, algebra))

    def _first_triangular(self, mech, closure, gens, syms, pose_unknowns, algebra):
        """The lex basis in the preferred order of the pose unknowns, or, where its steps
        are not all of degree <= 2, in the first other order whose steps are (e.g. three
        distance equations in (x, y, z) with z in only one: z must be solved last, from
        x, y, which two circles give by a quadratic and their linear radical axis, 003
        eq. 9).  The first order's reason is the one reported when none is triangular."""
        first: NotSolvable | None = None
        for order in (pose_unknowns, *(o for o in itertools.permutations(pose_unknowns)
                                       if o != pose_unknowns)):
            try:
                return (*self._order(mech, closure, gens, syms, order, algebra), order)
            except NotTriangular as exc:
                first = first or exc
        raise first

    def _order(self, mech, closure, gens, syms, pose_unknowns, algebra):
        """The lex basis with the pose unknowns in the given order (the first is solved
        last), its solution count and its back-substitution steps."""
        # algebraic constants are the last (lowest) unknowns, bound by their minimal
        # polynomials; they are not solved for but substituted (generators stay valid)
        consts = [c for c in mech.constants if c.symbol in syms]
        unknowns = pose_unknowns + tuple(c.symbol for c in consts)
        params = tuple(s for s in (*mech.active, *mech.geometric) if s in syms)
        problem = ParametricProblem(
            f"mechanism {mech.name!r}, closure {closure.name!r}: forward kinematics",
            tuple(dict.fromkeys(gens + [sp.expand(c.minimal_polynomial) for c in consts])),
            unknowns, params)
        budget = min(algebra.budget_s, FK_BUDGET_S)
        try:
            result = algebra.lex_basis(problem, budget)
        except EngineTimeoutError:
            raise NotSolvable(f"the lex basis of the {closure.name} exceeded its budget of "
                              f"{budget:g} s") from None
        n = len(unknowns)
        leading = [max(e[:n] for e, _ in p) for p in result.basis]
        dim = pt.dimension_from_leading_monomials(leading, n)
        if dim != 0:
            raise NotSolvable(f"the ideal of the {closure.name} has dimension {dim} over the "
                              "field of joints and geometry: no finite set of assembly modes")
        count = pt.count_standard_monomials(leading, n)
        for c in consts:
            count //= int(sp.degree(c.minimal_polynomial, c.symbol))
        const_syms = {c.symbol for c in consts}
        pool = [(f"lex basis of the {closure.name}", g) for g in result.generators
                if not g.free_symbols <= const_syms | set(params)]
        try:
            steps = plan(pool, pose_unknowns, problem.context)
        except NotImplementedError as exc:
            raise NotTriangular(f"{exc} ({count} solutions; univariate steps of higher degree "
                              "are not generated yet)") from None
        return problem, result, steps, count

    def _alternates(self, mech, closure, gens, syms, pose_unknowns, steps, algebra):
        """Back-substitution plans from the lex bases in the other orders of the pose
        unknowns, where a linear step of ``steps`` divides by a pivot that can vanish
        (Pro-Hep-LCT's lower closure: 8 l1 (t1^2 - w1^2) with l1 = l3).  The runtime solves
        through them where the first plan's solution fails its check; an order whose plan
        is not triangular, or whose pivots share a factor with the first plan's, is
        skipped (it would fail at the same points), and so is an order that puts an
        unknown before one of its class that fewer generators contain (such an order's
        univariate polynomial is in the rarer unknown, of higher degree: 003 eq. 9's
        quartic in z took 90 s and gives no new plan)."""
        primal = set().union(*(sp.sympify(c).free_symbols for c in closure.platform[:4]))

        def admissible(order) -> bool:
            counts = [(y in primal, sum(y in g.free_symbols for g in gens)) for y in order]
            return all(not (a[0] == b[0] and a[1] > b[1])
                       for i, a in enumerate(counts) for b in counts[i + 1:])

        pivots = [sp.factor_list(st.B)[1] for st in steps
                  if st.degree == 1 and st.B.free_symbols]
        if not pivots:
            return ()
        bad = {f for factors in pivots for f, _ in factors if f.free_symbols}
        out = []
        for order in itertools.permutations(pose_unknowns):
            if order == pose_unknowns or not admissible(order):
                continue
            try:
                _, _, alt, _ = self._order(mech, closure, gens, syms, order, algebra)
            except NotSolvable:
                continue
            alt_factors = {f for st in alt if st.degree == 1 and st.B.free_symbols
                           for f, _ in sp.factor_list(st.B)[1] if f.free_symbols}
            if not any(sp.gcd(f, g) != 1 for f in bad for g in alt_factors):
                out.append(tuple(alt))
            if len(out) == MAX_ALTERNATES:
                break
        return tuple(out)


CLOSURE_SOLVERS = (RPSEliminant(), TriangularLexBasis())


def forward_kinematics(mech, legs, algebra) -> tuple[tuple[ClosureFK, ...], str]:
    """Every actuated closure's forward kinematics, or ``((), reason)`` when one closure
    cannot be solved (the generated ``fk`` needs all of them)."""
    out: list[ClosureFK] = []
    for closure in mech.actuated_closures:
        solver = next(s for s in CLOSURE_SOLVERS if s.recognize(mech, closure, legs))
        if isinstance(solver, RPSEliminant) and any(f.solver == solver.name for f in out):
            return (), "more than one 3-RPS closure: the code generator solves one per mechanism"
        try:
            out.append(solver.derive(mech, closure, legs, algebra))
        except NotSolvable as exc:
            return (), str(exc)
    return tuple(out), ""
