"""Passive-joint recovery: every passive joint variable of every leg as a function of the
pose (through the closure's Study coordinates) and the actuated joints.

For each leg the ideal of its closure equations is computed with the passive variables
kept (only the chart's scale eliminated), so it contains polynomials linear in a passive
variable once the others are known (Cox-Little-O'Shea, Ch. 3 Sect. 1); each passive
variable gets all such generators as candidates, and the runtime takes, per configuration,
the candidate whose pivot is largest relative to the generator (a pivot that vanishes on a
locus of one candidate does not stop the recovery there).

A spherical joint is recovered in two steps: its centre is known from the platform side
(the leg's trailing factors are fixed offsets), which gives the passive joints before it
from three point equations (written in the frame of the leg's leading fixed offsets, so
that the geometry drops out of the Groebner basis); then its rotation is what remains of
the chain, ``conj(before) X conj(after)`` (primal parts), normalized in the runtime.

Where a passive variable is fixed only by a quadratic (a universal joint: the angles
``(a, b)`` and ``(a + pi, pi - b)`` point a leg the same way), the recovery takes the root
of smaller magnitude, the joint angle within +-90 degrees of its zero: the assembly the
chain is drawn in.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..algebra import convention as cv
from ..algebra import polyring as pr
from ..algebra import study_symbolic as ss
from ..chains.joints import Role
from ..elimination.closure import leg_problem
from ..elimination.problem import EliminationProblem
from ..errors import EngineTimeoutError

MAX_CANDIDATES = 4  # the simplest linear generators kept per passive variable
CENTRE = sp.symbols("c_x c_y c_z", real=True)


@dataclass(frozen=True)
class LinearStep:
    """``B v + C = 0`` for ``variable``, from any of ``candidates`` ``(B, C)``."""

    variable: sp.Symbol
    candidates: tuple[tuple[sp.Expr, sp.Expr], ...]


@dataclass(frozen=True)
class QuadraticStep:
    """``A v^2 + B v + C = 0`` for ``variable``; the root of smaller magnitude."""

    variable: sp.Symbol
    coefficients: tuple[sp.Expr, sp.Expr, sp.Expr]


@dataclass(frozen=True)
class SphericalStep:
    """The rotation quaternion (up to scale) of a spherical joint's Euler parameters."""

    variables: tuple[sp.Symbol, ...]
    rotation: tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]


@dataclass(frozen=True)
class LegRecovery:
    """How the passive joints of one leg follow from the pose and the actuated joints;
    ``note`` says why some could not be recovered (then ``steps`` is empty)."""

    closure: str
    leg: str
    steps: tuple[LinearStep | QuadraticStep | SphericalStep, ...]
    note: str = ""

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        out: list[sp.Symbol] = []
        for s in self.steps:
            out += list(s.variables) if isinstance(s, SphericalStep) else [s.variable]
        return tuple(out)


def _numerator(e: sp.Expr) -> sp.Expr:
    return sp.expand(sp.fraction(sp.together(sp.expand(e)))[0])


def _spherical_split(leg):
    """(factors before, the spherical factor, factors after) when the leg has exactly one
    spherical joint followed by fixed offsets only; else None."""
    fs = list(leg.factors)
    kinds = [f.kind for f in fs]
    if kinds.count("quaternion") != 1:
        return None
    k = kinds.index("quaternion")
    after = fs[k + 1:]
    if any(f.role is not Role.GEOMETRIC for f in after) or leg.mount is not None:
        return None
    return fs[:k], fs[k], after


def _vanishes(coefficients, points) -> bool:
    """True when the coefficients of a candidate vanish at every sample point of the leg's
    configurations: the generator is a multiple of the leg's own constraint there (e.g.
    ``(u^2 + 1) (|c|^2 - q^2)``) and says nothing about the variable."""
    for point in points:
        if any(sp.expand(sp.sympify(c).xreplace(point)) != 0 for c in coefficients):
            return False
    return True


def _covering(cands, probe) -> tuple:
    """The simplest MAX_CANDIDATES linear candidates ``(ops, B, C)``; where every one of
    them has ``B = 0`` at the home configuration ``probe`` (numbers for the Study
    coordinates, joints, parameters and the passive variables solved before: the home
    pose often lies on a coordinate plane where combinations of generators degenerate),
    also the simplest candidate that does not vanish there."""
    chosen = list(cands[:MAX_CANDIDATES])
    if probe is not None and all(_zero_at(c[1], probe) for c in chosen):
        extra = next((c for c in cands if not _zero_at(c[1], probe)), None)
        if extra is not None:
            chosen.append(extra)
    return tuple((b, c) for _, b, c in chosen)


def _zero_at(expr, probe, digits: int = 30) -> bool:
    """``expr`` vanishes at ``probe`` relative to the size of its terms there."""
    expr = sp.expand(sp.sympify(expr))
    if expr.free_symbols - set(probe):
        return False  # not decidable at the probe (e.g. a spherical centre's coordinates)
    size = sum(abs(sp.N(t.xreplace(probe), digits)) for t in sp.Add.make_args(expr))
    return size == 0 or abs(sp.N(expr.xreplace(probe), digits)) <= 1e-20 * size


def _value_at(step, probe, digits: int = 30):
    """A linear step's variable at ``probe``: ``-C/B`` of its candidate with the largest
    relative pivot, as the runtime chooses (None where every pivot vanishes)."""
    best, value = 0, None
    for b, c in step.candidates:
        bv = sp.N(sp.sympify(b).xreplace(probe), digits)
        cv_ = sp.N(sp.sympify(c).xreplace(probe), digits)
        if bv == 0 or not (bv.is_real and cv_.is_real):
            continue
        score = abs(bv) / (abs(bv) + abs(cv_))
        if score > best:
            best, value = score, -cv_ / bv
    return value


def _steps(basis, unknowns, context, points=(),
           eliminated=None, probe=None) -> tuple[LinearStep | QuadraticStep, ...]:
    """The solve order and, per passive variable, its linear candidates in the basis (or,
    where there is none, the simplest quadratic); candidates that vanish on the leg's
    configurations (the exact sample ``points``) are dropped.  Where the basis has no usable
    generator for any remaining variable, ``eliminated(v, others)`` (the basis with the other
    unsolved variables eliminated) is tried for each."""
    solved: list[sp.Symbol] = []
    steps: list[LinearStep | QuadraticStep] = []
    remaining = list(unknowns)
    memo: dict = {}
    while remaining:
        best, quadratic = _best(basis, remaining, points, {}, memo)
        if best is None and quadratic is None and eliminated is not None:
            bases = {v: eliminated(v, [w for w in remaining if w != v]) for v in remaining}
            best, quadratic = _best(None, remaining, points, bases, memo)
        if best is not None:
            v, cands = best
            steps.append(LinearStep(v, _covering(cands, probe)))
            if probe is not None:
                value = _value_at(steps[-1], probe)
                probe = None if value is None else {**probe, v: value}
        elif quadratic is not None:
            _, v, coeffs = quadratic
            steps.append(QuadraticStep(v, coeffs))
            probe = None  # the runtime's root choice is not followed here
        else:
            raise NotImplementedError(f"{context}: no generator of degree 1 or 2 in any of "
                                      f"{[str(v) for v in remaining]} once "
                                      f"{[str(v) for v in solved]} are known")
        solved.append(v)
        remaining.remove(v)
    return tuple(steps)


def _without_spurious_factors(g: sp.Expr, v: sp.Symbol) -> sp.Expr:
    """``g`` without its factors free of ``v`` and its factors ``v^2 + 1``, which vanish for
    no real ``v`` (the tan-half-angle denominators).  FLINT factors (the same factors as
    ``sympy.factor_list``, in another order, which the product does not see)."""
    _, factors = pr.factor_list(g)
    keep = [f**k for f, k in factors if f.has(v) and sp.expand(f - (v**2 + 1)) != 0]
    return sp.expand(sp.Mul(*keep)) if keep else g


def _candidate(g: sp.Expr, v: sp.Symbol, memo: dict):
    """``(ops, degree, coefficients)`` of ``g`` as a polynomial in ``v`` (coefficients of
    ``v, 1`` for degree 1, of ``v^2, v, 1`` for degree 2; ops and coefficients None for
    another degree), after removing the factors that vanish for no real ``v``; computed
    once per generator and variable (a ``Poly`` of a large generator takes long, and
    :func:`_steps` asks again in every round)."""
    key = (g, v)
    if key not in memo:
        coeffs = _coefficients_in(g, v)
        if len(coeffs) - 1 > 2:  # a factor 1 + v^2 (no real zero) or a content may hide one
            g = _without_spurious_factors(g, v)
            coeffs = _coefficients_in(g, v)
        degree = len(coeffs) - 1
        if degree in (1, 2):  # the operation count ranks candidates of these degrees only
            out = (pr.count_ops(g), degree, tuple(coeffs[k] for k in range(degree, -1, -1)))
        else:
            out = (None, degree, None)
        memo[key] = out
    return memo[key]


def _coefficients_in(g: sp.Expr, v: sp.Symbol) -> list[sp.Expr]:
    """The coefficients of ``v^0, v^1, ...`` of the polynomial ``g``, each expanded: read
    off the terms of a sum of monomials (a ``Poly`` in ``v`` over the other symbols took a
    fifth of a derivation on 002's generators; ``as_coeff_exponent``, which collects, half
    of what was left); through ``Poly`` for anything else."""
    by_power = pr.coefficients(g, v)
    return [pr.expanded(by_power.get(k, sp.S.Zero)) for k in range(max(by_power, default=0) + 1)]


def _vanishes_memo(coefficients, points, memo: dict) -> bool:
    """:func:`_vanishes`, once per coefficients (``memo`` belongs to one set of points)."""
    key = ("vanishes", coefficients)
    if key not in memo:
        memo[key] = _vanishes(coefficients, points)
    return memo[key]


def _best(basis, remaining, points, bases, memo=None):
    """The variable with the most linear candidates, and the simplest quadratic."""
    memo = {} if memo is None else memo
    best, quadratic = None, None
    for v in remaining:
        cands = []
        for g in (bases[v] if bases else basis):
            if not g.has(v) or (g.free_symbols & set(remaining)) - {v}:
                continue
            ops, degree, coeffs = _candidate(g, v, memo)
            if degree == 1:
                if not _vanishes_memo(coeffs[:1], points, memo):
                    cands.append((ops, *coeffs))
            elif degree == 2 and (quadratic is None or ops < quadratic[0]):
                if not _vanishes_memo(coeffs[:2], points, memo):
                    quadratic = (ops, v, coeffs)
        if cands and (best is None or len(cands) > len(best[1])):
            best = (v, sorted(cands, key=lambda t: (t[0], sp.srepr(t[1]))))
    return best, quadratic


def _sample_points(mech, leg, variables, point_of, count=2, seed=20261202):
    """Exact points of the leg's configurations: random rational values of the leg's
    variables and the geometry, and the coordinates ``point_of`` derives from them."""
    import random

    rng = random.Random(seed + sum(map(ord, leg.name)))
    consts = {c.symbol: c.value for c in mech.constants}
    out = []
    for _ in range(count):
        values = {v: sp.Rational(rng.randint(-900, 900), 997) for v in variables}
        values.update({p.symbol: sp.Rational(rng.randint(500, 1500), 7) for p in mech.parameters})
        values.update(consts)
        values.update(point_of(values))
        out.append(values)
    return out


def recover_leg(mech, closure, leg, algebra, probe=None) -> LegRecovery:
    """The recovery of ``leg``'s passive joints (see the module docstring); ``probe``, the
    Study coordinates, joints and parameters at the home configuration (numbers), makes
    sure the candidates do not all degenerate there."""
    passive = [s for s in mech.passive if s in leg.free_symbols]
    context = f"mechanism {mech.name!r}, leg {leg.name!r}: passive joints"
    consts = tuple(c for c in mech.constants)
    split = _spherical_split(leg)
    spherical = ()
    if split is not None:
        before, sph, after = split
        lead = 0
        while lead < len(before) and before[lead].role is Role.GEOMETRIC:
            lead += 1
        head = ss.product(*[f.study() for f in before[:lead]])
        chain = ss.product(*[f.study() for f in before])
        rest = ss.product(*[f.study() for f in before[lead:]])
        tail = ss.product(*[f.study() for f in after]) if after else ss.product()
        n = cv.rotation_norm(rest)
        eqs = [_numerator(a - n * c) for a, c in zip(cv.translation_times_norm(rest), CENTRE)]
        unknowns = [s for s in passive if any(s in f.free_symbols for f in before)]
        # the centre from the platform side, in the frame of the leading offsets
        moved = ss.product(ss.conjugate(head), tuple(closure.platform), ss.conjugate(tail))
        nm = cv.rotation_norm(moved)
        centre = {c: t / nm for c, t in zip(CENTRE, cv.translation_times_norm(moved))}
        rot = cv.quaternion_product(cv.quaternion_product(
            cv.study_conjugate(chain)[:4], tuple(closure.platform[:4])),
            cv.study_conjugate(tail)[:4])
        spherical = (SphericalStep(tuple(sph.args), tuple(sp.expand(r) for r in rot)),)
        keep_extra = CENTRE
        eliminate = ()
        free = sorted(set().union(*(f.free_symbols for f in before[lead:])) - set(
            mech.geometric), key=str)

        def point_of(values):
            r = [sp.sympify(e).xreplace(values) for e in rest]
            nr = cv.rotation_norm(r)
            return {c: t / nr for c, t in zip(CENTRE, cv.translation_times_norm(r))}
    else:
        problem = leg_problem(mech, closure, leg)
        eqs, unknowns = list(problem.equations), passive
        keep_extra = tuple(s for s in problem.keep if s in set(closure.pose))
        eliminate = (closure.normalization.scale,)
        centre = {}
        free = sorted(leg.free_symbols - set(mech.geometric) - {c.symbol for c in consts},
                      key=str)

        def point_of(values):
            chain = [sp.sympify(e).xreplace(values) for e in leg.product()]
            p = closure.normalization.index
            return {s: chain[k] / chain[p] for k, s in enumerate(closure.platform)
                    if isinstance(s, sp.Symbol)}
    eqs += [sp.expand(c.minimal_polynomial) for c in consts
            if any(e.has(c.symbol) for e in eqs)]
    used = set().union(*(e.free_symbols for e in eqs))
    keep = tuple(unknowns) + tuple(keep_extra) + tuple(
        s for s in (*mech.joints, *mech.geometric, *(c.symbol for c in consts)) if s in used)
    problem = EliminationProblem(context, tuple(dict.fromkeys(eqs)), eliminate, keep)
    try:
        basis = algebra.eliminate(problem).generators
        points = _sample_points(mech, leg, free, point_of)

        def eliminated(v, others):
            sub = EliminationProblem(f"{context} ({v} alone)", problem.equations,
                                     problem.eliminate + tuple(others),
                                     tuple(s for s in keep if s not in others))
            return algebra.eliminate(sub).generators

        steps = _steps(basis, unknowns, context, points, eliminated, probe)
    except (NotImplementedError, EngineTimeoutError) as exc:
        return LegRecovery(closure.name, leg.name, (), str(exc))
    if centre:
        steps = tuple(_substituted(s, centre) for s in steps)
    return LegRecovery(closure.name, leg.name, steps + spherical)


def _substituted(step, sub):
    if isinstance(step, LinearStep):
        return LinearStep(step.variable, tuple((b.xreplace(sub), c.xreplace(sub))
                                               for b, c in step.candidates))
    return QuadraticStep(step.variable, tuple(c.xreplace(sub) for c in step.coefficients))


def recover(mech, algebra, probe=None) -> tuple[LegRecovery, ...]:
    """Every leg of every actuated closure (``probe``: see :func:`recover_leg`)."""
    return tuple(recover_leg(mech, closure, leg, algebra, probe)
                 for closure in mech.actuated_closures for leg in closure.legs)
