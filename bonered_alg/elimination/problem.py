"""An elimination problem and its result, independent of the engine that solves it."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp

from ..algebra import polyring as pr
from . import polyterms as pt


class _PolynomialProblem:
    """Shared parts: exact term lists of the equations over ``gens``, canonical text, key."""

    context: str
    equations: tuple[sp.Expr, ...]

    @property
    def gens(self) -> tuple[sp.Symbol, ...]:  # pragma: no cover - overridden
        raise NotImplementedError

    def equation_terms(self) -> list[pt.PolyTerms]:
        """Equations as exact term lists over ``gens`` (rational coefficients only), each in
        ``Poly.terms()``'s order (lex, descending); computed once per problem (the cache key,
        the engine's script and its stages each ask)."""
        memo = self.__dict__.get("_equation_terms")
        if memo is None or memo[0] is not self.equations:
            memo = (self.equations, tuple(_terms(eq, self.gens) for eq in self.equations))
            self.__dict__["_equation_terms"] = memo
        return list(memo[1])

    def canonical_text(self) -> str:
        names = ",".join(map(str, self.gens))
        eqs = pt.canonical_text([pt.normal_form(t) for t in self.equation_terms()])
        return f"{type(self).__name__};split={self.split};vars={names};eqs={eqs}"

    @property
    def split(self) -> int:  # pragma: no cover - overridden
        raise NotImplementedError

    def key(self, engine: str) -> str:
        return hashlib.sha256(f"{engine}|{self.canonical_text()}".encode()).hexdigest()


@dataclass(frozen=True)
class ParametricProblem(_PolynomialProblem):
    """Lex Groebner basis of ``equations`` in ``unknowns`` over the field Q(``parameters``).

    For a zero-dimensional ideal the basis is triangular (Cox-Little-O'Shea, Ch. 3 Sect. 1-2,
    and the Shape Lemma), so the unknowns follow by back-substitution: this is how forward
    kinematics is solved for all assembly modes at once.  Denominators are cleared and each
    generator is made primitive over Z[parameters], which makes the answer unique.
    """

    context: str
    equations: tuple[sp.Expr, ...]
    unknowns: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]

    @property
    def gens(self) -> tuple[sp.Symbol, ...]:
        return self.unknowns + self.parameters

    @property
    def split(self) -> int:
        return len(self.unknowns)


def _terms(eq: sp.Expr, gens: tuple[sp.Symbol, ...]) -> pt.PolyTerms:
    """``eq`` as exact terms over ``gens`` in lex order, descending: read off the monomials
    of the expanded sum (:func:`..algebra.polyring.terms_of`, several times faster), through
    ``sympy.Poly`` over QQ where that does not apply (the same terms)."""
    found = pr.terms_of(pr.expanded(eq), gens)
    if found is not None:
        return tuple(sorted(found.items(), reverse=True))
    poly = sp.Poly(sp.expand(eq), *gens, domain=sp.QQ)
    return tuple((e, pt.parse_rational(str(c))) for e, c in poly.terms())


def as_expressions(basis, gens) -> list[sp.Expr]:
    """Term lists -> sympy expressions in ``gens`` (:func:`..algebra.polyring.expression`)."""
    powers: dict = {}
    return [pr.expression(terms, gens, powers) for terms in basis]


def _expressions(result, gens) -> tuple[sp.Expr, ...]:
    """``as_expressions(result.basis, gens)``, kept on ``result`` after the first call."""
    memo = result.__dict__.get("_expressions")
    if memo is None or memo[0] is not result.basis or memo[1] != gens:
        memo = (result.basis, gens, tuple(as_expressions(result.basis, gens)))
        result.__dict__["_expressions"] = memo
    return memo[2]


def normal_parametric_basis(polys, unknowns, parameters) -> tuple[pt.PolyTerms, ...]:
    """Primitive over Z[parameters], positive leading coefficient, sorted (deterministic).

    Each generator (terms over ``unknowns + parameters``, rational coefficients) is made an
    integer polynomial and divided by the gcd of its coefficients as a polynomial in the
    unknowns (Gauss's lemma: the content in Z[parameters]), with FLINT's multivariate gcd
    and exact division; then :func:`_signed`.  The same generators as
    :func:`normal_parametric_basis_sympy` (the primitive part is unique up to its sign,
    which :func:`_signed` fixes), without sympy's expression arithmetic: pro_hep_lct's and
    tripod_planar's lex bases took seconds there."""
    try:
        import flint
    except ImportError:  # pragma: no cover - python-flint is a dependency
        return normal_parametric_basis_sympy(polys, unknowns, parameters)
    n = len(unknowns)
    nvars = n + len(parameters)
    ctx = flint.fmpz_mpoly_ctx.get(tuple(f"v{i}" for i in range(nvars)), "lex")
    out = []
    for terms in polys:
        # equal monomials merged, integer coefficients (the integer content and the sign
        # go too, which the division below and _signed settle anyway)
        ints = {e: int(c) for e, c in pt.normal_form(terms)}
        if not ints:
            continue
        groups: dict[tuple[int, ...], dict] = {}
        for e, c in ints.items():
            groups.setdefault(e[:n], {})[(0,) * n + e[n:]] = c
        parts = sorted((ctx.from_dict(g) for g in groups.values()), key=len)
        content = parts[0]
        for part in parts[1:]:
            if content.is_constant() and abs(int(content.coeffs()[0])) == 1:
                break
            content = content.gcd(part)
        poly = ctx.from_dict(ints) / content  # exact: DomainError otherwise
        out.append(_signed(pt.normal_form(
            (tuple(int(k) for k in e), Fraction(int(c))) for e, c in poly.to_dict().items()),
            n))
    return _sorted_basis(out, n)


def _signed(terms_out: pt.PolyTerms, n: int) -> pt.PolyTerms:
    """The sign that makes the lex-leading coefficient (a polynomial in the parameters)
    have a positive grevlex-leading coefficient."""
    lead_u = max(e[:n] for e, _ in terms_out)
    lead_terms = [(e[n:], c) for e, c in terms_out if e[:n] == lead_u]
    _, c_lead = max(lead_terms, key=lambda t: pt.grevlex_key(t[0]))
    return tuple((e, -c) for e, c in terms_out) if c_lead < 0 else terms_out


def _sorted_basis(out: list[pt.PolyTerms], n: int) -> tuple[pt.PolyTerms, ...]:
    return tuple(sorted(set(out), key=lambda p: (sorted((e[:n] for e, _ in p), reverse=True),
                                                 [pt.grevlex_key(e) for e, _ in p])))


def normal_parametric_basis_sympy(polys, unknowns, parameters) -> tuple[pt.PolyTerms, ...]:
    """:func:`normal_parametric_basis` with sympy's expressions (together, Poly, gcd_list,
    cancel): the reference the tests hold the FLINT form to, and the form used where
    python-flint is missing."""
    gens = tuple(unknowns) + tuple(parameters)
    out = []
    for expr in as_expressions(polys, gens):
        if expr == 0:
            continue
        expr, _ = sp.together(expr).as_numer_denom()
        poly = sp.Poly(sp.expand(expr), *unknowns)
        content = sp.gcd_list(poly.coeffs()) if len(poly.coeffs()) > 1 else poly.coeffs()[0]
        expr = sp.expand(sp.cancel(poly.as_expr() / content))
        full = sp.Poly(expr, *gens)
        out.append(_signed(pt.normal_form(
            (e, pt.parse_rational(str(c))) for e, c in full.terms()), len(unknowns)))
    return _sorted_basis(out, len(unknowns))


@dataclass(frozen=True)
class EliminationProblem(_PolynomialProblem):
    """Eliminate ``eliminate`` from the ideal of ``equations``; keep ``keep``.

    The answer is the reduced Groebner basis of the elimination ideal
    ``<equations> ∩ Q[keep]`` in the grevlex order on ``keep`` (in the given order), normalized by
    :func:`polyterms.normal_basis` (Cox-Little-O'Shea, Ch. 3 Sect. 1, Elimination Theorem).
    ``context`` names the mechanism and step for error messages.
    """

    context: str
    equations: tuple[sp.Expr, ...]
    eliminate: tuple[sp.Symbol, ...]
    keep: tuple[sp.Symbol, ...]

    @property
    def gens(self) -> tuple[sp.Symbol, ...]:
        return self.eliminate + self.keep

    @property
    def split(self) -> int:
        return len(self.eliminate)


@dataclass
class ParametricResult:
    """Normalized lex basis over Q(parameters), with provenance."""

    problem: ParametricProblem
    basis: tuple[pt.PolyTerms, ...]
    engine: str
    seconds: float
    cached: bool = field(default=False)

    @property
    def generators(self) -> list[sp.Expr]:
        return list(_expressions(self, self.problem.gens))


@dataclass
class EliminationResult:
    """Normalized reduced Groebner basis of the elimination ideal, with provenance."""

    problem: EliminationProblem
    basis: tuple[pt.PolyTerms, ...]
    dimension: int
    engine: str
    seconds: float
    cached: bool = field(default=False)

    @property
    def generators(self) -> list[sp.Expr]:
        """The generators as sympy expressions in ``problem.keep`` (built once: a large
        basis takes seconds, and a derivation asks for it many times)."""
        return list(_expressions(self, self.problem.keep))

    @property
    def is_unit_ideal(self) -> bool:
        return self.dimension == -1
