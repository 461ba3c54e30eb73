"""Inverse kinematics by back-substitution through generators of the constraint ideal.

For each active joint ``q`` we pick a generator ``g`` of the elimination ideal whose only
unknown joints are ``q`` and joints already solved, and which has degree 1 or 2 in ``q``; then
``g = A q^2 + B q + C`` (or ``B q + C``) is solved in closed form.  The two roots of each
quadratic step are the working modes of that step (004 Sect. 3.4).  When no generator of
degree <= 2 exists we stop with ``NotImplementedError`` rather than guess.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from ..algebra import polyring as pr


@dataclass(frozen=True)
class IKStep:
    """Solve ``generator`` (``A q^2 + B q + C`` or ``B q + C``) for ``joint``."""

    joint: sp.Symbol
    generator: sp.Expr
    degree: int
    A: sp.Expr
    B: sp.Expr
    C: sp.Expr
    source: str  # which ideal/leg the generator comes from

    @property
    def branches(self) -> int:
        return 2 if self.degree == 2 else 1

    def roots(self) -> list[sp.Expr]:
        """Symbolic roots; the first uses ``+sqrt`` (mode bit 0), the second ``-sqrt``."""
        if self.degree == 1:
            return [-self.C / self.B]
        disc = self.B**2 - 4 * self.A * self.C
        return [(-self.B + s * sp.sqrt(disc)) / (2 * self.A) for s in (1, -1)]


def plan(generators: Sequence[tuple[str, sp.Expr]], joints: Sequence[sp.Symbol],
         context: str, constants: dict | None = None, probe: dict | None = None,
         declared: dict | None = None) -> list[IKStep]:
    """Order of solution and the generator used for each joint (see module docstring).

    ``constants`` maps algebraic constants (``s3``) to their values for the test that a
    leading coefficient cannot vanish.  ``probe`` (numbers for the Study coordinates and
    parameters at the declared home pose) demotes a generator that vanishes identically in
    its joint there -- every coefficient zero, the joint undetermined at home (a
    combination of other generators that degenerates on a special plane of the pose
    space); the joints solved before it take their value at home, the root nearest
    ``declared`` or the ``+sqrt`` one."""
    constants = constants or {}
    probe = dict(probe) if probe else None
    declared = declared or {}
    solved: list[sp.Symbol] = []
    steps: list[IKStep] = []
    remaining = list(joints)
    jset = set(joints)
    # (rank, operation count, degree) of generator i in joint q, computed once each:
    # re-deriving them in every round took minutes on the large Stewart generators
    ranks: dict[tuple[int, sp.Symbol], tuple | None] = {}

    def rank_of(i: int, g: sp.Expr, q: sp.Symbol):
        if (i, q) not in ranks:
            deg = _degree(g, q)
            if deg not in (1, 2):
                ranks[i, q] = None
            else:
                rank = 0 if deg == 1 else (1 if _definite(
                    _coefficient(g, q, 2).subs(constants)) else 2)
                ranks[i, q] = (rank, pr.count_ops(g), deg)
        return ranks[i, q]

    free = [g.free_symbols & jset for _, g in generators]
    while remaining:
        cands = []
        for q in remaining:
            for i, (src, g) in enumerate(generators):
                if free[i] - set(solved) != {q}:
                    continue
                info = rank_of(i, g, q)
                if info is None:
                    continue
                rank, ops, deg = info
                cands.append((rank, ops, str(q), i, src, q, g, deg))
        if not cands:
            raise NotImplementedError(
                f"{context}: no generator of degree 1 or 2 in any of "
                f"{[str(q) for q in remaining]} once {[str(q) for q in solved]} are known")
        cands.sort(key=lambda c: c[:4])
        best = cands[0]
        if probe is not None:
            best = next((c for c in cands if not _vanishes_at(c[6], c[5], probe)), best)
        _, _, _, _, src, q, g, deg = best
        coeff = pr.coefficients(pr.expanded(g), q)  # sp.expand's result
        steps.append(IKStep(q, g, deg, *(_compact(coeff.get(k, sp.Integer(0)))
                                          for k in (2, 1, 0)), src))
        if probe is not None:
            value = joint_value_at(steps[-1], probe, declared.get(q))
            if value is None:  # not real at home: no further probing
                probe = None
            else:
                probe[q] = value
        solved.append(q)
        remaining.remove(q)
    return steps


PROBE_DIGITS = 30


def _vanishes_at(g: sp.Expr, q: sp.Symbol, probe: dict) -> bool:
    """True when every coefficient of ``g`` in ``q`` is zero at ``probe`` (relative to
    the size of its terms there, at PROBE_DIGITS digits)."""
    at = {s: v for s, v in probe.items() if s != q}
    if g.free_symbols - set(at) - {q}:
        return False  # not decidable at the probe
    terms = sp.Add.make_args(sp.expand(g))
    size = sum(abs(sp.N(t.xreplace(at).xreplace({q: 1}), PROBE_DIGITS)) for t in terms)
    if size == 0:
        return True
    poly = sp.Poly(sp.N(sp.expand(g).xreplace(at), PROBE_DIGITS), q)
    return all(abs(c) <= sp.Float(10) ** (-20) * size for c in poly.coeffs())


def joint_value_at(step: IKStep, probe: dict, declared) -> sp.Expr | None:
    """The step's joint at ``probe``: its root nearest ``declared``, else the +sqrt one
    (None when not real or not finite)."""
    a, b, c = (sp.N(sp.sympify(x).xreplace(probe), PROBE_DIGITS)
               for x in (step.A, step.B, step.C))
    if step.degree == 1:
        return None if b == 0 else -c / b
    if a == 0:
        return None if b == 0 else -c / b
    disc = b * b - 4 * a * c
    if not (disc.is_real and disc >= 0):
        return None
    roots = [(-b + sgn * sp.sqrt(disc)) / (2 * a) for sgn in (1, -1)]
    if declared is None:
        return roots[0]
    return min(roots, key=lambda r: abs(float(r) - float(declared)))


def _degree(g: sp.Expr, q: sp.Symbol) -> int:
    """Degree of the polynomial ``g`` in ``q``, read off its terms (``sp.degree`` builds a
    Poly over all other symbols first: seconds on a generator of 800 terms)."""
    terms = sp.Add.make_args(sp.expand(g)) if not g.is_Add else g.args
    return max((int(t.as_powers_dict().get(q, 0)) for t in terms), default=0)


def _coefficient(g: sp.Expr, q: sp.Symbol, k: int) -> sp.Expr:
    """Coefficient of ``q**k`` in the polynomial ``g``, read off its terms."""
    terms = sp.Add.make_args(sp.expand(g)) if not g.is_Add else g.args
    return sp.Add(*[t / q**k for t in terms if int(t.as_powers_dict().get(q, 0)) == k])


def _compact(c: sp.Expr, max_terms: int = 40) -> sp.Expr:
    """Factored when small (readable reports, fewer operations); large coefficients are left
    expanded: multivariate factorization (Wang's algorithm) can take minutes on them."""
    c = pr.expanded(c)  # sp.expand's result, without its pass over a sum of monomials
    return pr.factor(c) if len(sp.Add.make_args(c)) <= max_terms else c


def _definite(a: sp.Expr) -> bool:
    """True when ``a`` is visibly positive for all real values: a positive constant plus
    even monomials with positive coefficients (e.g. ``1 + x**2``), or a positive constant
    plus a positive semidefinite quadratic form (e.g. ``1 + (x + sqrt(3) y)**2``).
    Quadratic steps whose leading coefficient cannot vanish are preferred: they never
    degenerate inside the workspace.  A sum of monomials with rational coefficients that is
    not a quadratic form is decided on its terms (the same test, without building a Poly
    of a long singularity factor)."""
    if a.free_symbols:
        gens = sorted(a.free_symbols, key=str)
        terms = pr.terms_of(pr.expanded(a), gens)
        if terms and max(map(sum, terms)) != 2:
            return ((0,) * len(gens) in terms
                    and all(c > 0 and all(e % 2 == 0 for e in m) for m, c in terms.items()))
    poly = sp.Poly(sp.expand(a), *sorted(a.free_symbols, key=str)) if a.free_symbols else None
    if poly is None:
        return bool(a.is_positive)
    terms = poly.terms()
    if poly.total_degree() == 2 and not any(sum(m) == 1 for m, _ in terms):
        # c + x^T Q x with c > 0 and Q positive semidefinite (e.g. 1 + (x1 + sqrt3 x2)^2)
        const = poly.coeff_monomial(1)
        n = len(poly.gens)
        quad = sp.Matrix(n, n, lambda i, j: poly.coeff_monomial(poly.gens[i] * poly.gens[j])
                         * (1 if i == j else sp.Rational(1, 2)))
        if const.is_positive and quad.is_positive_semidefinite:
            return True
    has_const = any(all(e == 0 for e in m) for m, _ in terms)
    return has_const and all(c > 0 and all(e % 2 == 0 for e in m) for m, c in terms)


def mode_count(steps: Sequence[IKStep]) -> int:
    """Number of working modes: the product of the branch counts."""
    n = 1
    for s in steps:
        n *= s.branches
    return n
