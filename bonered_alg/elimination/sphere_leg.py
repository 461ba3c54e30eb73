"""Closed-form ideal of a leg that only fixes a distance (U-P-S and S-P-S legs).

A leg ``T(A) R1 T_axis(q) R2 T(-B)`` (``R1``, ``R2`` passive rotations, ``q`` the active
stroke) keeps the platform point ``B`` at distance ``|q|`` from the base point ``A``.  With
``M = T(-A) X T(B)`` (linear in the platform's Study point ``X``) the translation ``t`` of
``M = R1 T(q) R2`` has ``|t| = |q|``, and from ``y = -1/2 t x`` (004 eq. 13)

    S(X, q) = q^2 (x0^2 + x1^2 + x2^2 + x3^2) - 4 (y0'^2 + y1'^2 + y2'^2 + y3'^2) = 0,

Husty's sphere condition pulled back by the two translations.  Eliminating the passive
joints of such a leg with a Groebner basis is expensive (a 6-UPS leg: more than 600 s in
Singular), and unnecessary: :func:`certify` proves that ``<Study quadric, S>`` is the leg's
ideal up to radical, i.e. that both define the closure of the leg's configurations:

1. ``S`` vanishes identically on the leg's chain product (symbolic substitution), and so
   does the Study quadric: the leg's configurations lie on ``V(quadric, S)``;
2. in the chart ``x0 = 1`` the quadric is linear in ``y0``; with ``y0`` substituted, ``S``
   is a quadratic polynomial in ``(y1, y2, y3, q)`` whose quadratic part has full rank 4
   over the field of the other symbols and whose coefficients have no common factor, so
   it is irreducible over the algebraic closure (:func:`_irreducible`), and
   ``V(quadric, S)`` is an irreducible variety of dimension 6 in (pose, q);
3. the chain's map (passive joints, q) -> pose has rank 6 at a random rational point
   (50-digit singular values), so the leg's configurations fill a 6-dimensional set.

An irreducible variety contains no other closed set of its own dimension, so the two agree
(Cox-Little-O'Shea, Ch. 9 Sect. 4).  A leg that fails a step (e.g. an R-P-S leg, rank 5)
is not a distance leg, and the pipeline eliminates it instead.
"""

from __future__ import annotations

import functools
import random
from dataclasses import dataclass

import mpmath
import sympy as sp

from ..algebra import polyring as pr
from ..algebra import study_symbolic as ss
from ..chains.joints import Leg, Role

RANK_DIGITS = 50
RANK_TOL = mpmath.mpf(10) ** -30


class NotADistanceLeg(Exception):
    """A certificate step failed: the leg's ideal is not the sphere condition."""


@dataclass(frozen=True)
class DistanceLeg:
    """A leg recognized as ``T(A) R1 T(q) R2 T(-B)``: base point, platform point, stroke."""

    leg: str
    base: tuple[sp.Expr, sp.Expr, sp.Expr]
    platform: tuple[sp.Expr, sp.Expr, sp.Expr]
    stroke: sp.Symbol


def _vector(f) -> tuple[sp.Expr, ...] | None:
    if f.kind != "translation" or f.role is not Role.GEOMETRIC:
        return None
    if f.axis is None:
        return tuple(f.args)
    out = [sp.Integer(0)] * 3
    out[ss.AXES[f.axis]] = f.args[0]
    return tuple(out)


def recognize(leg: Leg, signed: bool = False) -> DistanceLeg | None:
    """The shape ``[T(A)] R... T(q) R... [T(-B)]`` with ``q`` the only active parameter and
    only passive rotations in between; None for any other leg.  With ``signed`` the stroke
    may also be ``T(-q)`` (the same distance ``|q|``; the sphere condition is even in
    ``q``)."""
    fs = list(leg.factors)
    base = plat = (sp.Integer(0),) * 3
    if fs and (v := _vector(fs[0])) is not None:
        base, fs = v, fs[1:]
    if fs and (v := _vector(fs[-1])) is not None:
        plat, fs = tuple(-c for c in v), fs[:-1]
    active = [i for i, f in enumerate(fs) if f.role is Role.ACTIVE]
    if len(active) != 1:
        return None
    i = active[0]
    stroke = fs[i]
    if stroke.kind != "translation" or stroke.axis is None:
        return None
    length = stroke.args[0]
    if signed and (-length).is_Symbol:
        length = -length
    if not length.is_Symbol:
        return None
    others = fs[:i] + fs[i + 1:]
    if not others or any(f.role is not Role.PASSIVE or f.kind not in ("rotation", "quaternion")
                         for f in others):
        return None
    return DistanceLeg(leg.name, base, plat, length)


def moved(d: DistanceLeg, platform: tuple) -> tuple[sp.Expr, ...]:
    """``M = T(-A) X T(B)``: linear in the platform's Study point ``X``."""
    return ss.product(ss.translation_vector(tuple(-c for c in d.base)), tuple(platform),
                      ss.translation_vector(d.platform))


def _cleared_sphere(d: DistanceLeg, platform: tuple, minimal_polynomials: dict,
                    extra: set = frozenset()):
    """``(S'', gens, D)``: the sphere condition in the ring Q[platform coordinates and
    stroke (``gens``), geometry, algebraic constants, ``extra`` symbols] with the layout's
    denominators cleared: with ``D`` the lcm of the denominators of ``A`` and ``B``,
    ``2D T(-A) X 2D T(B) = 4 D^2 M`` is polynomial and gives ``S'' = 16 D^4 S``."""
    gens = tuple(sorted(set().union(*(sp.sympify(c).free_symbols for c in platform))
                        | {d.stroke}, key=str))
    layout = [sp.sympify(c) for c in (*d.base, *d.platform)]
    geometry = set().union(*(c.free_symbols for c in layout)) | set(minimal_polynomials)
    ring = pr.ring_over((*gens, *sorted((geometry | set(extra)) - set(gens), key=str)))
    fractions = [pr.fraction(ring, c) for c in layout]
    dens = [den for _, den in fractions]
    if any(set(minimal_polynomials) & {ring.symbols[i] for m in den.monoms()
                                       for i, e in enumerate(m) if e} for den in dens):
        raise ValueError(f"leg {d.leg}: a denominator of the layout holds an algebraic "
                         "constant; the sphere condition is written over Q(parameters)")
    common = pr.lcm(dens)
    scaled = [num * common.exquo(den) for num, den in fractions]
    two_d, zero = 2 * common, ring.zero
    left = (two_d, zero, zero, zero, zero, *scaled[:3])  # 2D T(-A) = [2D:0:0:0:0:D A]
    right = (two_d, zero, zero, zero, zero, *(-c for c in scaled[3:]))
    m = pr.study_product(left, tuple(pr.polynomial(ring, c) for c in platform), right)
    q = ring.gens[gens.index(d.stroke)]
    expr = q**2 * sum((c**2 for c in m[:4]), zero) - 4 * sum((c**2 for c in m[4:]), zero)
    return expr, gens, common


def _sphere_ring(d: DistanceLeg, platform: tuple, minimal_polynomials: dict | None
                 ) -> tuple[pr.PolyElement, tuple[sp.Symbol, ...]]:
    """The sphere condition of :func:`_cleared_sphere` reduced by the algebraic constants'
    minimal polynomials and made primitive in the platform's coordinates and the stroke.
    Returns it and those coordinates; kept for the last few arguments (certify and the
    leg's ideal ask for the same leg's, each about 0.2 s on a Stewart leg; the polynomial
    is not modified by its readers)."""
    return _sphere_ring_of(d, tuple(platform), tuple((minimal_polynomials or {}).items()))


@functools.lru_cache(maxsize=16)
def _sphere_ring_of(d: DistanceLeg, platform: tuple, minpolys: tuple):
    expr, gens, _ = _cleared_sphere(d, platform, dict(minpolys))
    ring = expr.ring
    expr = pr.reduce_modulo(expr, [pr.polynomial(ring, mp) for _, mp in minpolys])
    return pr.primitive_in(expr, gens), gens


def sphere_condition(d: DistanceLeg, platform: tuple,
                     minimal_polynomials: dict | None = None) -> sp.Expr:
    """``q^2 |x|^2 - 4 |y'|^2`` (module docstring), expanded.  A layout rational in the
    geometric parameters gives the numerator, divided by its content in those parameters
    (a non-zero constant for a given mechanism), so the result is primitive in the
    platform's coordinates and the stroke, with integer coefficients of gcd 1 and a positive
    leading coefficient; algebraic constants (``minimal_polynomials``: symbol -> its minimal
    polynomial) are reduced.  Computed on typed polynomials (:func:`_sphere_ring`)."""
    return pr.as_expr(_sphere_ring(d, platform, minimal_polynomials)[0])


def _irreducible(poly: pr.PolyElement, quadratic: tuple[sp.Symbol, ...],
                 geometry: set[sp.Symbol]) -> bool:
    """True when ``poly``, of degree 2 in ``quadratic`` with coefficients in the other
    symbols, is irreducible over the algebraic closure: a quadratic polynomial factors only
    when its homogenized form has rank <= 2 (the rank of its quadratic part, a determinant
    over the field of the other symbols, is a lower bound; it is required to be full here),
    and by Gauss's lemma only when its coefficients have a common factor; a common factor
    in the ``geometry`` symbols alone (the ring's ``(1 + t^2)`` of a rational layout) is a
    non-zero constant for a given mechanism and allowed."""
    coeffs = pr.coefficients_in(poly, quadratic)
    if max(map(sum, coeffs)) != 2:
        return False
    n, zero = len(quadratic), poly.ring.zero
    hessian = [[zero] * n for _ in range(n)]
    for e, c in coeffs.items():
        if sum(e) == 2:
            i, j = [k for k in range(n) for _ in range(e[k])]
            hessian[i][j] = hessian[j][i] = 2 * c if i == j else c
    if not pr.determinant(hessian):
        return False  # rank of the quadratic part < 4: not certified here
    content = pr.gcd(list(coeffs.values()))
    return {poly.ring.symbols[i] for m in content.monoms() for i, k in enumerate(m) if k} \
        <= geometry


def _rank(leg: Leg, d: DistanceLeg, passive: tuple, params: dict, seed: int,
          points: int = 3) -> int:
    """Rank of d(chart coordinates)/d(passive, q), the largest over ``points`` random
    rational points (the generic rank; a point can be special, e.g. a universal joint at
    90 deg), from singular values at 50 digits.  The Jacobian is evaluated factor by factor
    (product rule: a variable's column is the chain product with its factor differentiated),
    each factor's value and derivative from its exact value at the point to 60 digits."""
    variables = [*passive, d.stroke]
    studies = [tuple(sp.sympify(c).xreplace(params) for c in f.study()) for f in leg.factors]
    if leg.mount is not None:
        studies.insert(0, tuple(sp.sympify(c).xreplace(params) for c in leg.mount))
    derivatives = [{v: tuple(sp.diff(c, v) for c in f) for v in variables
                    if any(c.has(v) for c in f)} for f in studies]
    rng = random.Random(seed)
    best = 0
    for _ in range(points):
        point = {v: sp.Rational(rng.randint(-1000, 1000), 1009) for v in variables}
        point[d.stroke] = sp.Rational(rng.randint(150_000, 300_000), 1009)
        with mpmath.workdps(RANK_DIGITS):
            def value(e, point=point):
                return mpmath.mpf(sp.N(e.xreplace(point), RANK_DIGITS + 10))

            at = [tuple(value(c) for c in f) for f in studies]
            chain = pr.study_product(*at)
            rows = []
            for v in variables:
                column = [mpmath.mpf(0)] * 8
                for j, dj in enumerate(derivatives):
                    if v in dj:
                        term = pr.study_product(*at[:j], [value(c) for c in dj[v]], *at[j + 1:])
                        column = [a + b for a, b in zip(column, term)]
                rows.append([(column[i] * chain[0] - chain[i] * column[0]) / chain[0] ** 2
                             for i in range(1, 8)])
            m = mpmath.matrix(rows).T
            sv = mpmath.svd_r(m, compute_uv=False)
            top = max(abs(x) for x in sv)
            best = max(best, sum(1 for s in sv if abs(s) > RANK_TOL * top))
    return best


def _between_the_points(leg: Leg, d: DistanceLeg) -> tuple[DistanceLeg, tuple]:
    """``(d0, M)`` with ``sphere_condition(d0, M) = sphere_condition(d, leg.product())``:
    ``T(-A) X T(B)`` for the chain ``X = T(A) Mid T(-B)`` is ``Mid`` (the product is
    associative and ``T(-A) T(A) = T(B) T(-B) = 1``, checked here exactly), so the sphere
    condition is taken on ``Mid`` and the points ``A = B = 0`` (``d0``), without expanding
    the layout's coordinates into every term (a Stewart leg: a fifth of its derivation)."""
    fs = [f.study() for f in leg.factors]
    ends = []
    zero = (sp.Integer(0),) * 3
    if fs and _vector(leg.factors[0]) is not None and tuple(d.base) != zero:
        ends.append(ss.product(ss.translation_vector(tuple(-c for c in d.base)), fs[0]))
        fs = fs[1:]
    if fs and _vector(leg.factors[-1]) is not None and tuple(d.platform) != zero:
        ends.append(ss.product(fs[-1], ss.translation_vector(d.platform)))
        fs = fs[:-1]
    one = (sp.Integer(1),) + (sp.Integer(0),) * 7
    if any(tuple(sp.expand(c) for c in e) != one for e in ends):  # pragma: no cover
        return d, leg.product()  # not the shape recognize() read: the full product
    return DistanceLeg(d.leg, zero, zero, d.stroke), ss.product(*fs)


def distance_on_chain(leg: Leg, constants: dict | None = None) -> DistanceLeg | None:
    """The leg's base point, platform point and stroke where the stroke is proved to be
    the distance between them on *every* configuration of the leg: the shape of
    :func:`recognize` (either sign of the stroke) and the sphere condition vanishing on the
    chain product (step 1 of :func:`certify`), whatever the dimension of the chain's image
    (an R-P-S leg, whose ideal is not the sphere condition, qualifies).  Then ``q^2 = |R B
    + t - A|^2`` wherever the platform is at ``(R, t)``; None otherwise."""
    d = recognize(leg, signed=True)
    if d is None:
        return None
    try:
        gen = sphere_condition(*_between_the_points(leg, d),
                               minimal_polynomials(dict(constants or {})))
    except ValueError:
        return None
    return d if gen == 0 else None


def minimal_polynomials(constants: dict) -> dict:
    """symbol -> minimal polynomial over Q of each algebraic constant's value."""
    return {c: sp.minimal_polynomial(v, c) for c, v in constants.items()}


def certify(leg: Leg, d: DistanceLeg, platform: tuple, passive: tuple, params: dict,
            constants: dict) -> str:
    """Run the three steps of the module docstring; returns their record, or raises
    :class:`NotADistanceLeg` naming the step that failed.  ``params`` are numeric values
    of the geometry for the rank test, ``constants`` the algebraic constants' values."""
    # the rank test first: it is what rules out legs with fewer joints (R-P-S: rank 5)
    rank = _rank(leg, d, passive, {**params, **constants}, seed=sum(map(ord, leg.name)))
    if rank != 6:
        raise NotADistanceLeg(f"leg {leg.name}: the chain's image has dimension {rank}, not 6")
    chain = leg.product()
    minpolys = minimal_polynomials(constants)
    try:
        gen = sphere_condition(*_between_the_points(leg, d), minpolys)
        xs = tuple(platform)
        sphere, _ = _sphere_ring(d, xs, minpolys)
    except ValueError as exc:
        raise NotADistanceLeg(str(exc)) from None
    if gen != 0:
        raise NotADistanceLeg(f"leg {leg.name}: the sphere condition does not vanish on the "
                              "chain product")
    if ss.quadric(chain) != 0:  # pragma: no cover - holds for every chain
        raise NotADistanceLeg(f"leg {leg.name}: the chain product is off the Study quadric")
    y0 = xs[4]
    solved = sp.solve(ss.quadric(xs), y0)
    if len(solved) != 1 or xs[0] != 1:
        raise NotADistanceLeg(f"leg {leg.name}: the platform point is not in the chart x0 = 1")
    ring = sphere.ring
    reduced = sphere.compose(ring.gens[ring.symbols.index(y0)], pr.polynomial(ring, solved[0]))
    geometry = set(params) | set(constants)
    if not _irreducible(reduced, (*xs[5:], d.stroke), geometry):
        raise NotADistanceLeg(f"leg {leg.name}: the sphere condition factors on the quadric")
    return (f"leg {leg.name}: distance |{d.stroke}| between base point A = "
            f"{tuple(map(str, d.base))} and platform point B = {tuple(map(str, d.platform))}; "
            "the sphere condition vanishes on the chain product, is irreducible on the Study "
            f"quadric, and the chain's image has dimension {rank} (rank test, "
            f"{RANK_DIGITS} digits)")


@dataclass(frozen=True)
class CompactSphere:
    """A distance leg's IK generator in its geometric form ``scale (q^2 R - 4 D)``, with
    ``R = |x'|^2`` and ``D = |y'|^2`` of ``M = T(-A) X T(B)`` left unexpanded: the sums of
    squares of eight linear forms in the platform's Study point, about a tenth of the
    operations of the expanded polynomial (a Stewart leg: 60 against 620)."""

    stroke: sp.Symbol
    scale: sp.Expr
    rotation: sp.Expr  # R = x0'^2 + ... + x3'^2
    dual: sp.Expr  # D = y0'^2 + ... + y3'^2
    # the leg's geometry, constants substituted: base point A, platform point B, and the
    # platform's Study point X (in the Study coordinates) of M = T(-A) X T(B)
    base: tuple = ()
    point: tuple = ()
    platform: tuple = ()

    def generator(self) -> sp.Expr:
        return self.scale * (self.stroke**2 * self.rotation - 4 * self.dual)


def compact_sphere(d: DistanceLeg, platform: tuple, generator: sp.Expr,
                   constants: dict | None = None) -> CompactSphere | None:
    """The leg's generator (as the ideal holds it: expanded, primitive, perhaps negated) as
    a constant multiple of the unexpanded sphere condition, or None where it is not one.
    Proved, not assumed, on typed polynomials with the constants as symbols: with ``S'' =
    16 D^4 S`` (:func:`_cleared_sphere`) and ``c_g``, ``c_s`` the coefficients (in the
    geometry) of the generator's lex-leading monomial in the platform's coordinates and the
    stroke in the generator and in ``S''``, ``c_s generator - c_g S''`` must vanish modulo
    the constants' minimal polynomials (irreducible over Q(parameters), so exactly where it
    vanishes at the constants' values).  Then ``generator = scale S`` with ``scale = 16 D^4
    c_g / c_s``; ``constants`` (symbol -> exact value) are substituted in what is returned."""
    sub = constants or {}
    minpolys = minimal_polynomials(sub)
    generator = sp.sympify(generator)
    try:
        cleared, gens, common = _cleared_sphere(d, platform, minpolys, generator.free_symbols)
        target = pr.polynomial(cleared.ring, generator)
    except ValueError:
        return None
    if not cleared or not target:
        return None
    lead = max(pr.coefficients_in(target, gens))
    c_g = pr.coefficients_in(target, gens)[lead]
    c_s = pr.coefficients_in(cleared, gens).get(lead)
    if not c_s:
        return None
    ring = cleared.ring
    reduce = [pr.polynomial(ring, mp) for mp in minpolys.values()]
    if pr.reduce_modulo(c_s * target - c_g * cleared, reduce):
        return None
    value = (lambda p: pr.as_expr(p).subs(sub)) if sub else pr.as_expr
    other = value(c_s) / (16 * value(common) ** 4)
    scale = sp.cancel(value(c_g) / other)
    m = [sp.sympify(c).subs(sub) for c in moved(d, platform)]
    rot, dual = sum(c**2 for c in m[:4]), sum(c**2 for c in m[4:])
    return CompactSphere(d.stroke, scale, rot, dual,
                         tuple(sp.sympify(c).subs(sub) for c in d.base),
                         tuple(sp.sympify(c).subs(sub) for c in d.platform),
                         tuple(sp.sympify(c).subs(sub) for c in platform))
