"""Groebner engines behind one interface: sympy (always there) and Singular (the default).

Singular is GPL software and is driven as a separate program over a pipe (no linking), so the
BSD-licensed package stays free of GPL code.  Every call has a time budget; running out gives
:class:`EngineTimeoutError` naming the mechanism and step.

Both engines return the *reduced* Groebner basis of the elimination ideal in grevlex on the kept
variables; after :func:`polyterms.normal_basis` the two answers are identical, which
``tests/test_engines_agree.py`` checks.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import shutil
import subprocess
from abc import ABC, abstractmethod
from fractions import Fraction

import sympy as sp
from sympy.polys.orderings import ProductOrder, grevlex

from ..errors import EngineError, EngineTimeoutError, EngineUnavailableError
from . import polyterms as pt
from .problem import EliminationProblem, ParametricProblem, normal_parametric_basis

DEFAULT_BUDGET_S = 600.0


class Engine(ABC):
    """A Groebner engine: computes the normalized reduced basis of an elimination ideal."""

    name: str

    @abstractmethod
    def available(self) -> bool: ...

    @abstractmethod
    def version(self) -> str: ...

    @abstractmethod
    def _eliminate(self, problem: EliminationProblem, budget_s: float) -> list[list[pt.Term]]:
        """Raw reduced basis of the elimination ideal in grevlex on ``problem.keep``."""

    @abstractmethod
    def _lex_basis(self, problem: ParametricProblem, budget_s: float) -> list[list[pt.Term]]:
        """Raw lex basis over Q(parameters), denominators cleared, as terms over ``gens``."""

    @property
    def identity(self) -> str:
        """Name, version and method of the engine: the key of its cached results (a new
        Singular or another sympy method never reuses another's answers)."""
        cached = getattr(self, "_identity", None)
        if cached is None:
            cached = f"{self.name}|{self.version()}"
            object.__setattr__(self, "_identity", cached)
        return cached

    def _require(self, problem) -> None:
        if not self.available():
            raise EngineUnavailableError(
                f"{problem.context}: the {self.name} Groebner engine is not installed"
                + (" (Debian package 'singular')" if self.name == "singular" else "")
            )

    def eliminate(self, problem: EliminationProblem, budget_s: float = DEFAULT_BUDGET_S):
        """Normalized reduced basis; raises EngineUnavailableError / EngineTimeoutError."""
        self._require(problem)
        return pt.normal_basis(self._eliminate(problem, budget_s))

    def lex_basis(self, problem: ParametricProblem, budget_s: float = DEFAULT_BUDGET_S):
        """Normalized lex basis over Q(parameters) (see :class:`ParametricProblem`)."""
        self._require(problem)
        raw = self._lex_basis(problem, budget_s)
        return normal_parametric_basis(raw, problem.unknowns, problem.parameters)


# --------------------------------------------------------------------------- sympy


def _sympy_worker(func, problem, method: str, queue) -> None:  # pragma: no cover - child
    try:
        queue.put(("ok", func(problem, method)))
    except Exception as exc:  # noqa: BLE001 - reported to the parent verbatim
        queue.put(("error", f"{type(exc).__name__}: {exc}"))


def _terms(expr: sp.Expr, gens) -> list[pt.Term]:
    return [(e, Fraction(int(c.numerator), int(c.denominator)))
            for e, c in sp.Poly(expr, *gens, domain=sp.QQ).terms()]


def _sympy_lex(problem: ParametricProblem, method: str) -> list[list[pt.Term]]:
    domain = sp.QQ.frac_field(*problem.parameters) if problem.parameters else sp.QQ
    g = sp.groebner(list(problem.equations), *problem.unknowns, order="lex", domain=domain,
                    method=method)
    out = []
    for p in g.exprs:
        num, _ = sp.fraction(sp.together(p))
        out.append(_terms(sp.expand(num), problem.gens))
    return out


def _sympy_basis(problem: EliminationProblem, method: str) -> list[list[pt.Term]]:
    ne = len(problem.eliminate)
    gens = problem.gens
    order = ProductOrder((grevlex, lambda m: m[:ne]), (grevlex, lambda m: m[ne:]))
    g = sp.groebner(list(problem.equations), *gens, order=order, domain=sp.QQ, method=method)
    kept = [p for p in g.exprs if not (p.free_symbols & set(problem.eliminate))]
    if not kept:
        return []
    red = sp.groebner(kept, *problem.keep, order="grevlex", domain=sp.QQ, method=method)
    return [_terms(p, problem.keep) for p in red.exprs]


class SympyEngine(Engine):
    """sympy's ``groebner`` with a block (product) order; always installed.

    ``method="f5b"`` (Faugere's F5B, the default here) is measured 3.7 s / 8.3 s on the two
    lower chains of 004 with symbolic geometry, where ``"buchberger"`` exceeds 300 s
    (``bench/results.json``).
    """

    name = "sympy"
    METHODS = ("f5b", "buchberger")

    def __init__(self, method: str = "f5b"):
        if method not in self.METHODS:
            raise EngineUnavailableError(
                f"sympy Groebner method {method!r} unknown; expected one of {self.METHODS}")
        self.method = method

    def available(self) -> bool:
        return True

    def version(self) -> str:
        return f"sympy {sp.__version__} ({self.method})"

    def _eliminate(self, problem, budget_s):
        return self._run(_sympy_basis, problem, budget_s)

    def _lex_basis(self, problem, budget_s):
        return self._run(_sympy_lex, problem, budget_s)

    def _run(self, func, problem, budget_s):
        """Run ``func(problem, method)`` in a child process killed after ``budget_s``."""
        ctx = mp.get_context("fork")
        queue = ctx.Queue()
        proc = ctx.Process(target=_sympy_worker, args=(func, problem, self.method, queue),
                           daemon=True)
        proc.start()
        try:
            status, payload = queue.get(timeout=budget_s)
        except Exception:  # queue.Empty
            proc.kill()
            proc.join()
            raise EngineTimeoutError(self.name, problem.context, budget_s) from None
        proc.join()
        if status != "ok":
            raise EngineError(f"{problem.context}: sympy failed: {payload}")
        return payload


# --------------------------------------------------------------------------- Singular


def _singular_poly(terms: pt.PolyTerms, names: list[str]) -> str:
    out = []
    for e, c in terms:
        mono = "*".join(f"{n}^{k}" for n, k in zip(names, e) if k)
        coef = f"({c.numerator}/{c.denominator})" if c.denominator != 1 else f"({c.numerator})"
        out.append(f"{coef}*{mono}" if mono else coef)
    return "+".join(out) if out else "0"


# prints ideal E term by term ("T exponents coefficient", "END" per generator): parsed by
# SingularEngine._run without evaluating anything
_PRINT_TERMS = """poly g;
for (i = 1; i <= ncols(E); i++) {
  g = E[i];
  while (g != 0) {
    print("T " + string(leadexp(g)) + " " + string(leadcoef(g)));
    g = g - lead(g);
  }
  print("END");
}
print("DONE");
quit;
"""


def _algebraic_constant(problem: EliminationProblem,
                        terms: list[pt.PolyTerms]) -> tuple[int, int] | None:
    """(index in ``keep``, index of its equation) of the only kept variable bound by an
    irreducible univariate equation of degree >= 2, or None."""
    ne = len(problem.eliminate)
    found = []
    for j, t in enumerate(terms):
        used = {i for e, _ in t for i, k in enumerate(e) if k}
        if len(used) == 1 and (i := next(iter(used))) >= ne:
            poly = sp.Poly(problem.equations[j], problem.gens[i])
            if poly.degree() >= 2 and poly.is_irreducible:
                found.append((i - ne, j))
    return found[0] if len(found) == 1 else None


def _elimination_stages(terms: list[pt.PolyTerms], ne: int) -> list[list[int]]:
    """The eliminated variables (indices ``< ne``) in the order Singular removes them: first
    those that occur in one equation only, such as the variable ``w`` of a Rabinowitsch
    equation ``w d - 1`` (the saturation by ``d``), then the others together.  Both stages
    give ``<equations> ∩ Q[keep]`` (elimination ideals nest: ``I ∩ Q[y] = (I ∩ Q[x, y]) ∩
    Q[y]``); for urrh_rcm's second leg the staged form takes 2.7 s where one ``eliminate``
    of all four variables took 18 s, the same reduced basis."""
    occurs = [sum(1 for t in terms if any(e[i] for e, _ in t)) for i in range(ne)]
    first = [i for i in range(ne) if occurs[i] == 1]
    rest = [i for i in range(ne) if occurs[i] != 1]
    return [s for s in (first, rest) if s] if first and rest else [list(range(ne))]


def _eliminate_in_stages(stages: list[list[int]], names: list[str]) -> str:
    """Singular lines leaving ``E = <I> ∩ Q[kept variables]`` (``stages`` as from
    :func:`_elimination_stages`)."""
    lines, source = [], "I"
    for k, stage in enumerate(stages):
        target = "E" if k == len(stages) - 1 else f"E{k}"
        elim = "*".join(names[i] for i in stage) if stage else "1"
        lines.append(f"ideal {target} = eliminate({source}, {elim});")
        source = target
    return "\n".join(lines)


class SingularEngine(Engine):
    """Singular (``std``/``eliminate`` over Q), run as a separate program."""

    name = "singular"

    def __init__(self, executable: str | None = None):
        self.executable = executable or os.environ.get("BONERED_SINGULAR", "Singular")

    def _path(self) -> str | None:
        return shutil.which(self.executable)

    def available(self) -> bool:
        return self._path() is not None

    def version(self) -> str:
        out = subprocess.run([self._path(), "-v", "-q", "--no-rc"], input="quit;",
                             capture_output=True, text=True, timeout=30)
        first = (out.stdout or out.stderr).strip().splitlines()
        return first[0] if first else "Singular (unknown version)"

    def script(self, problem: EliminationProblem) -> str:
        """Elimination script; a kept algebraic constant becomes the ground field's extension.

        When exactly one kept variable ``c`` is bound by an irreducible univariate equation
        (an algebraic constant such as ``s3`` with ``s3^2 = 3``), the elimination runs over
        ``Q(c)`` (Singular ``minpoly``) instead of carrying ``c`` as a variable: for the
        3-RPS legs of 001 this takes 0.5 s instead of more than 60 s.  The result is mapped
        back to ``Q[keep]`` (``c`` a variable again) and reduced together with the minimal
        polynomial, which is the same ideal ``<equations> ∩ Q[keep]``: ideals of ``Q[x, c]``
        that contain the minimal polynomial correspond to ideals of ``Q(c)[x]``.

        The eliminated variables are removed in the stages of :func:`_elimination_stages`
        (the saturation variables first); the answer is the same reduced basis.
        """
        ne, nk = len(problem.eliminate), len(problem.keep)
        names = [f"e{i}" for i in range(ne)] + [f"k{i}" for i in range(nk)]
        keep_names = names[ne:]
        terms = problem.equation_terms()
        ext = _algebraic_constant(problem, terms)
        if ext is None:
            eqs = ",\n".join(_singular_poly(t, names) for t in terms)
            return f"""option(redSB); option(redTail);
ring r = 0, ({",".join(names)}), dp;
ideal I = {eqs};
{_eliminate_in_stages(_elimination_stages(terms, ne), names)}
ring s = 0, ({",".join(keep_names)}), dp;
ideal E = imap(r, E);
E = std(E);
int i;
""" + _PRINT_TERMS
        index, minpoly = ext
        par = names[ne + index]
        ring_vars = [n for n in names if n != par]
        eqs = ",\n".join(_singular_poly(t, names) for k, t in enumerate(terms) if k != minpoly)
        mp_text = _singular_poly(terms[minpoly], names)
        stages = _elimination_stages([t for k, t in enumerate(terms) if k != minpoly], ne)
        return f"""option(redSB); option(redTail);
ring r = (0,{par}), ({",".join(ring_vars)}), dp;
minpoly = {mp_text};
ideal I = {eqs};
{_eliminate_in_stages(stages, names)}
ring s = 0, ({",".join(keep_names)}), dp;
ideal E = imap(r, E);
E = std(E + ideal({mp_text}));
int i;
""" + _PRINT_TERMS

    def lex_script(self, problem: ParametricProblem) -> str:
        nu, npar = len(problem.unknowns), len(problem.parameters)
        unames = [f"u{i}" for i in range(nu)]
        pnames = [f"p{i}" for i in range(npar)]
        eqs = ",\n".join(_singular_poly(t, unames + pnames) for t in problem.equation_terms())
        coeffs = f"(0, {','.join(pnames)})" if npar else "0"
        return f"""option(redSB); option(redTail);
ring r = {coeffs}, ({",".join(unames)}), lp;
ideal I = {eqs};
ideal G = std(I);
int i;
for (i = 1; i <= ncols(G); i++) {{ G[i] = cleardenom(G[i]); }}
ring s = 0, ({",".join(unames + pnames)}), dp;
ideal E = imap(r, G);
""" + _PRINT_TERMS

    def _eliminate(self, problem, budget_s):
        return self._run(self.script(problem), problem, budget_s)

    def _lex_basis(self, problem, budget_s):
        return self._run(self.lex_script(problem), problem, budget_s)

    def _run(self, script: str, problem, budget_s):
        try:
            out = subprocess.run([self._path(), "-q", "--no-rc", "--no-warn"],
                                 input=script, capture_output=True, text=True,
                                 timeout=budget_s)
        except subprocess.TimeoutExpired:
            raise EngineTimeoutError(self.name, problem.context, budget_s) from None
        lines = out.stdout.splitlines()
        if out.returncode != 0 or "DONE" not in lines:
            raise EngineError(
                f"{problem.context}: Singular failed (exit {out.returncode}): "
                f"{(out.stderr or out.stdout)[-2000:]}"
            )
        polys: list[list[pt.Term]] = []
        current: list[pt.Term] = []
        for line in lines:
            if line.startswith("T "):
                _, exps, coef = line.split(" ")
                current.append((tuple(int(x) for x in exps.split(",")), pt.parse_rational(coef)))
            elif line == "END":
                polys.append(current)
                current = []
        return polys


ENGINES: dict[str, type[Engine]] = {"sympy": SympyEngine, "singular": SingularEngine}


def get_engine(name: str | None = None) -> Engine:
    """The named engine, or ``$BONERED_ENGINE``, or Singular when installed, else sympy."""
    name = name or os.environ.get("BONERED_ENGINE")
    if name is None:
        singular = SingularEngine()
        return singular if singular.available() else SympyEngine()
    try:
        return ENGINES[name]()
    except KeyError:
        raise EngineUnavailableError(
            f"unknown Groebner engine {name!r}; expected one of {sorted(ENGINES)}"
        ) from None

