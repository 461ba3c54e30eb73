"""Verdicts of the checks against the papers' printed equations (DESIGN.md section 5).

Each :class:`Verdict` becomes one row of the report's verification section and one entry of
``derivations/<name>.verification.json``.  The helpers compare a derived result with a printed
one *without* adapting either: a mismatch is reported with the exact differing terms.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass

import sympy as sp

VERDICTS = ("confirmed-symbolic", "confirmed-numeric", "erratum", "not-checkable")


@dataclass(frozen=True)
class Verdict:
    """One checked printed equation or table row."""

    ref: str
    quantity: str
    verdict: str
    max_error: float | None
    detail: str
    evidence: str = ""  # LaTeX shown in the report (not in the JSON)

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict must be one of {VERDICTS}, got {self.verdict!r}")

    def as_json(self) -> dict:
        d = asdict(self)
        d.pop("evidence")
        return d


def rounded(value: float, digits: int = 3) -> float:
    """``value`` to ``digits`` significant digits: numeric errors and measured values are
    recorded at a resolution that floating-point noise does not reach, so the record is the
    same on every machine."""
    return float(f"{value:.{digits}g}")


NOISE_FLOOR = 1e-9  # errors below it are floating-point noise, recorded as this bound


def noise_bound(value: float, floor: float = NOISE_FLOOR) -> float:
    """An error at floating-point noise level (below ``floor``) recorded as ``floor``: a
    bound, "at most floor".  The noise itself differs between machines, and so does its
    power of ten (002 Sect. 4.3's J_q error is 7.5e-15 on one machine and above 1e-14 on
    another), so no finer figure is the same bytes everywhere."""
    if value >= floor:
        return rounded(value)
    return floor


def constant_ratio(printed: sp.Expr, derived: sp.Expr) -> sp.Expr | None:
    """``lambda`` with ``printed = lambda * derived`` if it is a non-zero constant, else None."""
    printed, derived = sp.expand(printed), sp.expand(derived)
    if derived == 0:
        return sp.Integer(1) if printed == 0 else None
    ratio = sp.cancel(printed / derived)
    if ratio.free_symbols or ratio == 0:
        return None
    return ratio


def leading_ratio(printed: sp.Expr, derived: sp.Expr, gens: Sequence[sp.Symbol]) -> sp.Expr:
    """Ratio of the coefficients of the derived polynomial's leading monomial (grevlex)."""
    pd = sp.Poly(sp.expand(derived), *gens)
    pp = sp.Poly(sp.expand(printed), *gens)
    lm = pd.monoms(order="grevlex")[0]
    coeff = dict(zip(pp.monoms(), pp.coeffs())).get(lm, 0)
    return sp.Rational(coeff) / pd.coeff_monomial(lm) if coeff else sp.Integer(1)


def term_difference(printed: sp.Expr, derived: sp.Expr, gens: Sequence[sp.Symbol]) -> sp.Expr:
    """``printed - lambda * derived`` with lambda from the leading monomial: the differing terms."""
    lam = leading_ratio(printed, derived, gens)
    return sp.expand(printed - lam * derived)


def in_ideal(expr: sp.Expr, basis: Sequence[sp.Expr], gens: Sequence[sp.Symbol]) -> bool:
    """True when ``expr`` reduces to 0 modulo the Groebner basis ``basis`` (grevlex)."""
    if not basis:
        return sp.expand(expr) == 0
    _, rem = sp.reduced(sp.expand(expr), list(basis), *gens, order="grevlex")
    return sp.expand(rem) == 0


# the functions of one argument whose values an mpmath evaluation keeps (huge derived
# expressions repeat tan(alpha/2), sqrt(3) and mpf(1)/mpf(2) thousands of times)
_MEMO_FUNCTIONS = ("mpf", "tan", "sin", "cos", "atan", "sqrt")


def mpmath_function(args, expr):
    """``sympy.lambdify(args, expr, "mpmath")`` that computes each repeated subexpression
    once and whose functions of one argument (``tan``, ``sqrt``, the constants ``mpf(1)``,
    ...) remember their values: the same numbers, operation for operation (mpmath rounds
    each operation correctly, so a value computed once equals the value computed again),
    without recomputing the subtrees that derivatives of composed expressions repeat
    thousands of times.  The values of the functions are those of the working precision at
    their first call: call the function at one precision only."""
    import mpmath

    namespace = {name: _remembering(getattr(mpmath, name)) for name in _MEMO_FUNCTIONS}
    shared = _shared_subtrees(expr)
    names = {node: sp.Symbol(f"_shared{k}") for k, node in enumerate(shared)}
    # the printer lambdify would make for these modules, printing each subexpression once
    printer = _remembering_printer()({"fully_qualified_modules": False, "inline": True,
                                      "allow_unknown_functions": True,
                                      "user_functions": {k: k for k in namespace}})
    printer.names = {node: str(name) for node, name in names.items()}
    return sp.lambdify(args, expr, modules=[namespace, "mpmath"], printer=printer,
                       cse=lambda e: ([(names[node], node) for node in shared], e))


def _shared_subtrees(expr) -> list:
    """The compound subexpressions of ``expr`` (an expression, a list or a matrix of them)
    that occur more than once, each after the ones it contains; none where a ``Piecewise``
    or other conditional would make computing a branch ahead of time wrong."""
    roots = list(expr) if isinstance(expr, (list, tuple, sp.MatrixBase)) else [expr]
    if not all(isinstance(r, sp.Expr) for r in roots) or any(
            r.has(sp.Piecewise) for r in roots):
        return []
    seen: set = set()
    repeated: set = set()
    order: list = []

    def visit(node):
        if not node.args or not isinstance(node, sp.Expr):
            return
        if node in seen:
            repeated.add(node)
            return
        seen.add(node)
        for arg in node.args:
            visit(arg)
        order.append(node)

    for root in roots:
        visit(root)
    return [node for node in order if node in repeated]


def _remembering_printer():
    """sympy's ``MpmathPrinter`` with the text of each subexpression kept, and the
    subexpressions in ``names`` printed as their names except where they are defined (the
    expression ``doprint`` is given).  A printed subexpression depends on it and the
    settings only (the parentheses are added around it by its parent), and a name stands
    for a value that its parent's code evaluates as a unit (the one case that differs, a
    term ``-u`` printed as ``a - u`` where the name gives ``a + (-u)``, is the same number:
    negation is exact and mpmath subtracts by adding the negation)."""
    from sympy.printing.pycode import MpmathPrinter

    class RememberingMpmathPrinter(MpmathPrinter):
        def __init__(self, settings=None):
            super().__init__(settings)
            self._printed: dict = {}
            self.names: dict = {}
            self._defining = False

        def doprint(self, expr, *args, **kwargs):
            self._defining = True
            return super().doprint(expr, *args, **kwargs)

        def _print(self, expr, **kwargs):
            defining, self._defining = self._defining, False
            if kwargs or not isinstance(expr, sp.Basic):
                return super()._print(expr, **kwargs)
            if expr in self.names:
                return super()._print(expr) if defining else self.names[expr]
            text = self._printed.get(expr)
            if text is None:
                text = self._printed[expr] = super()._print(expr)
            return text

    return RememberingMpmathPrinter


def _remembering(func):
    """``func`` of one argument with its values kept (keyed by the argument's value: mpmath
    turns equal ints, floats and mpf into the same number)."""
    values = {}

    def call(a):
        v = values.get(a)
        if v is None:
            v = values[a] = func(a)
        return v

    return call
