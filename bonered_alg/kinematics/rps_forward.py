"""Forward kinematics of a 3-RPS closure: three spherical centres on three circles.

Each leg of a 3-RPS closure is ``offsets, revolute (u_k), prismatic (q_k), spherical,
offsets``: the revolute joint turns the leg of active length ``q_k`` in a plane, so the
spherical centre ``B_k(u_k, q_k)`` (the product of the factors before the spherical joint,
applied to the origin) runs on a circle.  The platform is rigid, so
``|B_i - B_j|^2 = |P_i - P_j|^2`` for the platform points ``P_k`` (the trailing offsets,
inverted).  Cleared of the denominators ``1 + u_k^2`` each condition is biquadratic,
``e_ij = sum_{a, b <= 2} C_ij[a][b] u_i^a u_j^b`` with ``C_ij`` polynomial in the joints and
the geometry.

The lex basis of ``<e12, e23, e31>`` over ``Q(q, geometry)`` is out of reach (Singular: more
than 600 s, measured), so the eliminant of ``u2, u3`` is formed per configuration, in the
generated code, as the iterated resultant ``Res_u3(Res_u2(e12, e23), e31)``: a polynomial of
degree at most ``2*4 + 4*2 = 16`` in ``u1`` that lies in the ideal (Cox-Little-O'Shea, Ch. 3
Sect. 6).  Its degree is certified by a Groebner basis: :func:`count_solutions` counts the
solutions of the ideal at a generic rational configuration (vdim); 16 means the eliminant
has no extraneous factor and misses no assembly mode.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

import sympy as sp

from ..algebra import convention as cv
from ..algebra import polyring as pr
from ..algebra import study_symbolic as ss
from ..chains.joints import Leg, Role
from ..elimination import polyterms as pt
from ..elimination.problem import ParametricProblem
from ..errors import NonClosingMechanismError

PAIRS = ((0, 1), (1, 2), (2, 0))
DEGREE_BOUND = 16  # of the iterated resultant in u1: 2 * 4 + 4 * 2


@dataclass(frozen=True)
class RPSSystem:
    """The circle-distance system of one 3-RPS closure."""

    closure: str
    angles: tuple[sp.Symbol, sp.Symbol, sp.Symbol]  # revolute tan-half angles u_k
    joints: tuple[sp.Symbol, sp.Symbol, sp.Symbol]  # active leg lengths q_k
    centres: tuple[tuple[sp.Expr, ...], ...]  # B_k(u_k, q_k) in the closure's base frame
    platform: tuple[tuple[sp.Expr, ...], ...]  # P_k in the platform frame
    equations: tuple[sp.Expr, ...]  # e12, e23, e31 (denominators cleared)
    coefficients: tuple[tuple[tuple[sp.Expr, ...], ...], ...]  # C_ij[a][b], pairs in PAIRS


def _translation(study) -> tuple[sp.Expr, ...]:
    n = cv.rotation_norm(study)
    return tuple(sp.cancel(c / n) for c in cv.translation_times_norm(study))


def _split(leg: Leg):
    """(u, q, factors before the spherical joint, factors after) or None if not R-P-S."""
    kinds = [f.kind for f in leg.factors]
    if kinds.count("quaternion") != 1:
        return None
    k = kinds.index("quaternion")
    before, after = leg.factors[:k], leg.factors[k + 1:]
    moving = [f for f in before if f.role is not Role.GEOMETRIC]
    if (len(moving) != 2 or moving[0].kind != "rotation" or moving[0].role is not Role.PASSIVE
            or moving[1].kind != "translation" or moving[1].role is not Role.ACTIVE
            or any(f.role is not Role.GEOMETRIC for f in after)):
        return None
    q = [s for s in moving[1].free_symbols]
    if len(q) != 1:
        return None
    return moving[0].args[0], q[0], before, after


def _reduce_constants(expr: sp.Expr, mech) -> sp.Expr:
    for c in mech.constants:
        if expr.has(c.symbol):
            expr = sp.rem(sp.expand(expr), c.minimal_polynomial, c.symbol)
    return sp.expand(expr)


def _clear(expr: sp.Expr, mech, ui: sp.Symbol, uj: sp.Symbol) -> sp.Expr:
    """Numerator of ``expr`` free of the factors ``1 + u^2`` (no real zeros) and of content."""
    num = _reduce_constants(pr.reduced_numerator(expr), mech)
    for u in (ui, uj):
        while True:
            quo, rem = sp.div(num, u**2 + 1, u)
            if rem != 0 or quo == 0:
                break
            num = sp.expand(quo)
    _, primitive = sp.Poly(num, ui, uj).primitive()
    return sp.expand(primitive.as_expr())


def _rps_parts(closure) -> list | None:
    """Each leg's :func:`_split`, or None if ``closure`` is not a 3-RPS closure."""
    if len(closure.legs) != 3:
        return None
    parts = [_split(leg) for leg in closure.legs]
    return None if any(p is None for p in parts) else parts


def is_rps_closure(closure) -> bool:
    """Whether ``closure`` has three R-P-S legs (the shape :func:`rps_system` reads),
    without forming the system."""
    return _rps_parts(closure) is not None


def rps_system(mech, closure) -> RPSSystem | None:
    """The circle-distance system of ``closure``, or None if it is not a 3-RPS closure."""
    parts = _rps_parts(closure)
    if parts is None:
        return None
    centres, platform = [], []
    for _u, _q, before, after in parts:
        centres.append(_translation(ss.product(*[f.study() for f in before])))
        tail = ss.product(*[f.study() for f in after]) if after else (1, 0, 0, 0, 0, 0, 0, 0)
        platform.append(_translation(ss.conjugate(tail)))
    angles = tuple(p[0] for p in parts)
    equations, coefficients = [], []
    for i, j in PAIRS:
        d2 = (sum((centres[i][k] - centres[j][k]) ** 2 for k in range(3))
              - sum((platform[i][k] - platform[j][k]) ** 2 for k in range(3)))
        e = _clear(d2, mech, angles[i], angles[j])
        poly = sp.Poly(e, angles[i], angles[j])
        if poly.degree(angles[i]) != 2 or poly.degree(angles[j]) != 2:
            raise NonClosingMechanismError(
                mech.name, f"{closure.name}: the distance condition of legs {i + 1} and {j + 1} "
                f"has degrees {poly.degree_list()} in ({angles[i]}, {angles[j]}); the 3-RPS "
                "forward kinematics expects (2, 2)")
        equations.append(e)
        coefficients.append(tuple(tuple(poly.coeff_monomial(angles[i] ** a * angles[j] ** b)
                                        for b in range(3)) for a in range(3)))
    return RPSSystem(closure.name, angles, tuple(p[1] for p in parts), tuple(centres),
                     tuple(platform), tuple(equations), tuple(coefficients))


def generic_configuration(system: RPSSystem, mech,
                          seed: int = 20261122) -> dict[sp.Symbol, sp.Rational]:
    """Rational joints (and the default geometry) for the solution count; fixed seed."""
    rng = random.Random(seed)
    geometry = {p.symbol: sp.Rational(str(p.value)) for p in mech.parameters}
    scale = max([abs(v) for v in geometry.values()] + [1])
    joints = {q: sp.Rational(rng.randint(900, 1400), 1000) * scale for q in system.joints}
    return {**geometry, **joints}


def count_solutions(system: RPSSystem, mech, algebra) -> tuple[int, dict]:
    """Number of complex solutions of ``<e12, e23, e31>`` at a generic rational
    configuration, from the standard monomials of its lex Groebner basis."""
    values = generic_configuration(system, mech)
    eqs = [sp.expand(e.subs(values)) for e in system.equations]
    consts = [c for c in mech.constants if any(e.has(c.symbol) for e in eqs)]
    unknowns = (*system.angles, *(c.symbol for c in consts))
    problem = ParametricProblem(
        f"mechanism {mech.name!r}, {system.closure}: forward-kinematics solution count",
        tuple(eqs) + tuple(sp.expand(c.minimal_polynomial) for c in consts), unknowns, ())
    result = algebra.lex_basis(problem)
    n = len(unknowns)
    leading = [max(e[:n] for e, _ in p) for p in result.basis]
    count = pt.count_standard_monomials(leading, n)
    if count is None:
        raise NonClosingMechanismError(
            mech.name, f"{system.closure}: the distance system is not zero-dimensional at a "
            "generic configuration; the 3-RPS forward kinematics has no finite set of modes")
    for c in consts:
        count //= int(sp.degree(c.minimal_polynomial, c.symbol))
    return count, values


def forward_jacobian(system: RPSSystem) -> sp.Matrix:
    """``d(e12, e23, e31)/d(u1, u2, u3)``, the matrix of :func:`forward_singularity`."""
    return pr.jacobian(system.equations, system.angles)


def forward_singularity(system: RPSSystem) -> sp.Expr:
    """``det d(e12, e23, e31)/d(u1, u2, u3)``: zero where two assembly modes merge, the
    forward (type II) singularity of the tripod; in the leg angles and lengths."""
    return pr.jacobian_determinant(system.equations, system.angles)


def angles_from_platform(system: RPSSystem, platform_study: tuple) -> dict[sp.Symbol, sp.Expr]:
    """Each leg's revolute tan-half angle from the platform pose (a Study point) and the leg
    length: ``u_k = (d . s_k)/(q_k + d . c_k)``, ``d = B_k - A_k``, where the leg direction is
    ``cos(theta) c_k + sin(theta) s_k`` (``c_k`` at ``u = 0``, ``s_k`` at ``u = 1``); valid
    wherever the leg is not turned to ``theta = pi``."""
    n = cv.rotation_norm(platform_study)
    rot = sp.Matrix(cv.rotation_matrix_times_norm(platform_study))
    trans = sp.Matrix(cv.translation_times_norm(platform_study))
    out = {}
    for u, q, centre, p in zip(system.angles, system.joints, system.centres, system.platform):
        centre = sp.Matrix(centre)
        base = centre.subs(q, 0).applyfunc(sp.cancel)
        if base.free_symbols & {u}:
            raise ValueError(f"{system.closure}: the base point of the leg of {q} moves with "
                             f"{u}; no tan-half angle formula")
        direction = sp.diff(centre, q)
        c, s = direction.subs(u, 0), direction.subs(u, 1)
        # the identity behind the formula, on the chain itself
        check = (q * direction).dot(s) / (q + (q * direction).dot(c)) - u
        if pr.simplified(check) != 0:
            raise ValueError(f"{system.closure}: leg of {q} does not turn its direction as "
                             "cos(theta) c + sin(theta) s; no tan-half angle formula")
        d = (rot * sp.Matrix(p) + trans) / n - base
        out[u] = d.dot(s) / (q + d.dot(c))
    return out
