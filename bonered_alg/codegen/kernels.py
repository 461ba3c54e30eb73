"""Numpy kernels from sympy expressions, with common subexpressions eliminated.

A kernel is a plain function of scalar-or-array arguments returning a tuple of arrays; it
contains only arithmetic and ``numpy`` calls, so it broadcasts over any leading shape.  The
kernels of the compiled fast path (:mod:`.c_module`) are printed as C from the same
common-subexpression program, so both evaluate the same operations in the same order.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import sympy as sp
from sympy.core.function import _coeff_isneg
from sympy.core.mul import _keep_coeff
from sympy.printing.c import C99CodePrinter
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import PRECEDENCE, precedence

from ..algebra import polyring as pr


def _float_literal(value: float) -> str:
    """A float as a literal valid in Python and C, negative ones parenthesized."""
    text = repr(float(value))
    return f"({text})" if text.startswith("-") else text


def _number(expr) -> str | None:
    """A constant irrational subexpression (``sqrt(3)``, ``2**(1/3)``) as a float literal,
    folded at generation time instead of evaluated on every call; None for anything else."""
    if expr.is_number and not expr.is_Rational:
        try:
            return _float_literal(float(expr))
        except TypeError:  # complex
            return None
    return None


def _print_mul_scalars_first(printer, expr, scalars: frozenset) -> str | None:
    """``expr`` (a Mul) written with its factors that are one number per call (``scalars``:
    the parameters and the hoisted ``_k``/``_s`` values) before its array factors: the
    product is evaluated left to right, so ``2.0*rb*_c3`` is one array operation where
    sympy's order, ``2.0*_c3*rb`` (the temporaries sort first), is two.  Written as
    sympy's code printers write a product (``CodePrinter._print_Mul``); None where the
    order stays sympy's."""
    c, e = expr.as_coeff_Mul()
    sign = ""
    if c < 0:
        expr, sign = _keep_coeff(-c, e), "-"
    factors = expr.as_ordered_factors()
    first = [f for f in factors if f.is_Number or (
        f.free_symbols and {v.name for v in f.free_symbols} <= scalars)]
    args = first + [f for f in factors if f not in first]
    if args == factors:  # nothing to move: sympy's own printing
        return None
    prec = precedence(expr)
    a, b, pow_paren = [], [], []  # numerator, denominator, as there
    for item in args:
        if item.is_commutative and item.is_Pow and item.exp.is_Rational and item.exp.is_negative:
            if item.exp != -1:
                b.append(sp.Pow(item.base, -item.exp, evaluate=False))
            else:
                if len(item.args[0].args) != 1 and isinstance(item.base, sp.Mul):
                    pow_paren.append(item)
                b.append(sp.Pow(item.base, -item.exp))
        else:
            a.append(item)
    a = a or [sp.S.One]
    if len(a) == 1 and sign == "-":
        a_str = [printer.parenthesize(a[0], 0.5 * (PRECEDENCE["Pow"] + PRECEDENCE["Mul"]))]
    else:
        a_str = [printer.parenthesize(x, prec) for x in a]
    b_str = [printer.parenthesize(x, prec) for x in b]
    for item in pow_paren:
        if item.base in b:
            b_str[b.index(item.base)] = f"({b_str[b.index(item.base)]})"
    if not b:
        return sign + "*".join(a_str)
    if len(b) == 1:
        return sign + "*".join(a_str) + "/" + b_str[0]
    return sign + "*".join(a_str) + "/(" + "*".join(b_str) + ")"


class _ScalarsFirst:
    """Printer mixin: ``scalars`` (symbol names) written first in a product
    (:func:`_print_mul_scalars_first`)."""

    def __init__(self, settings=None, scalars: frozenset = frozenset()):
        super().__init__(settings or {})
        self.scalars = scalars

    def _print_Mul(self, expr):  # noqa: N802 - sympy printer protocol
        out = _print_mul_scalars_first(self, expr, self.scalars) if self.scalars else None
        return super()._print_Mul(expr) if out is None else out

    def _as_ordered_terms(self, expr, order=None):
        """A sum's terms in sympy's order (the printers' ``_print_Add`` writes them left to
        right), except that a negative first term followed by a positive one goes after
        it: ``-_c0 + x + y`` is written ``x - _c0 + y``.  The same numbers (the first two
        terms of a sum commute, and IEEE negation is exact), and numpy saves the pass that
        negates the array ``_c0``."""
        terms = super()._as_ordered_terms(expr, order=order)
        if len(terms) > 1 and _coeff_isneg(terms[0]) and not _coeff_isneg(terms[1]):
            terms = [terms[1], terms[0], *terms[2:]]
        return terms


class _Printer(_ScalarsFirst, NumPyPrinter):
    """NumPyPrinter writing ``numpy.<fn>`` calls and exact rationals as float literals;
    ``scalars`` (symbol names) are written first in a product."""

    def _print_Rational(self, expr):  # noqa: N802 - sympy printer protocol
        return repr(float(expr.p) / float(expr.q)) if expr.q != 1 else f"{expr.p}.0"

    def _print_Integer(self, expr):  # noqa: N802
        return f"{int(expr)}.0" if abs(int(expr)) < 2**53 else repr(float(expr))

    def _print_Float(self, expr):  # noqa: N802
        return _float_literal(float(expr))

    def _print_Pow(self, expr, rational=False):  # noqa: N802
        # integer powers stay integer (numpy's fast paths); x**2 becomes (x*x), parenthesized
        # because the printer gives a Pow the precedence of a power: unparenthesized,
        # a/x**2 would print as a/x*x
        out = _small_power(self, expr)
        if out is not None:
            return out
        if expr.exp.is_Integer:
            base = self.parenthesize(expr.base, PRECEDENCE["Pow"], strict=False)
            return f"{base}**{int(expr.exp)}"
        return super()._print_Pow(expr, rational=rational)


# integer powers up to this are written as products, in numpy and C alike: numpy.power
# (on AVX-512 machines numpy's own vector pow, elsewhere libm's, which differ in the last
# bit for about 2.6 % of x**4) is then out of the kernels, so that their numbers are the
# same on every machine, and C's program is numpy's operation for operation (the compiled
# twins of forward kinematics' kernels, bit for bit); x**4 costs three multiplications
SMALL_POWER = 8


def _small_power(printer, expr) -> str | None:
    """What both printers write alike: a constant folded, ``x^k`` for ``|k| <= 8`` as a
    product, left to right (SMALL_POWER; numpy.power with a negative exponent is several
    times slower than a division); None for any other power."""
    folded = _number(expr)
    if folded is not None:
        return folded
    base, exp = expr.base, expr.exp
    b = printer.parenthesize(base, PRECEDENCE["Pow"], strict=False)
    if exp.is_Integer and int(exp) == 1:
        return b
    if exp.is_Integer and 1 < int(exp) <= SMALL_POWER:
        return "(" + "*".join([b] * int(exp)) + ")"
    if exp.is_Integer and -SMALL_POWER <= int(exp) < 0:
        return "(1.0/(" + "*".join([b] * -int(exp)) + "))"
    return None


class _CPrinter(_ScalarsFirst, C99CodePrinter):
    """C99 for the fast path: the same literals and integer powers as :class:`_Printer`;
    every variable prefixed ``v_`` (no clash with ``gamma``, ``y1`` or ``j0`` of libm);
    ``scalars`` first in a product, as there (the compiler then hoists ``2.0*v_rb`` out of
    the loop over poses)."""

    def _print_Symbol(self, expr):  # noqa: N802
        return f"v_{expr.name}"

    def _print_Rational(self, expr):  # noqa: N802
        return _Printer._print_Rational(self, expr)

    def _print_Integer(self, expr):  # noqa: N802
        return _Printer._print_Integer(self, expr)

    def _print_Float(self, expr):  # noqa: N802
        return _float_literal(float(expr))

    def _print_Pow(self, expr, rational=False):  # noqa: N802
        out = _small_power(self, expr)
        if out is not None:
            return out
        base, exp = expr.base, expr.exp
        if exp == sp.Rational(1, 2):
            return f"sqrt({self._print(base)})"
        if exp == sp.Rational(-1, 2):  # as numpy's printer writes it: no pow() call
            return f"(1.0/sqrt({self._print(base)}))"
        return f"pow({self._print(base)}, {self._print(exp)})"


@dataclass(frozen=True)
class Kernel:
    """Source of one generated function and its operation count after CSE; ``c_source``
    the same program as a C function (empty unless asked for)."""

    name: str
    source: str
    operations: int
    c_source: str = ""
    arguments: tuple[str, ...] = ()
    outputs: int = 0
    # the common-subexpression program (temporaries, outputs) of a C kernel, which
    # :func:`c_function` prints again with shared values passed in
    program: tuple = field(default=(), compare=False, repr=False)
    doc: str = ""
    # the names of its one-number-per-call values (parameters, hoisted coefficients)
    scalars: frozenset = field(default=frozenset(), compare=False, repr=False)


def scalar_coefficients(expr: sp.Expr, scalars: set[sp.Symbol],
                        hoisted: dict[sp.Expr, sp.Symbol] | None = None) -> sp.Expr:
    """``expr`` with the terms of every sum grouped by their factors that are not
    ``scalars`` (the geometric parameters, one number per call): ``a*x + b*x`` becomes
    ``(a + b)*x``, so that the kernel does one array multiplication instead of two (a
    Stewart leg's sphere in Study coordinates: 96 array operations to 41).

    With ``hoisted`` (filled in: a compound scalar coefficient -> its placeholder symbol
    ``_s<k>``), each compound coefficient, the sum of a sum's scalar terms included, is
    replaced by a placeholder: computed once per call, it costs one array operation where
    it is used (printed inline, ``a*b*x/c`` is three, and sympy would spread a sum of
    scalar terms among the array ones)."""
    memo: dict[sp.Expr, sp.Expr] = {}
    known = set(scalars)
    defs: dict[sp.Symbol, sp.Expr] = {}
    if hoisted is not None:
        for e, sym in hoisted.items():
            known.add(sym)
            defs[sym] = e

    scalar_memo: dict[sp.Expr, bool] = {}

    def scalar(f: sp.Expr) -> bool:
        """``f.free_symbols <= known``, bottom-up with a memo: sympy computes
        ``free_symbols`` anew on every call, which on a large kernel's nested sums took a
        quarter of a derivation (tripod_planar)."""
        out = scalar_memo.get(f)
        if out is None:
            if f.is_Symbol:
                out = f in known
            elif f.is_Atom:
                out = not f.free_symbols
            else:
                out = all(scalar(a) for a in f.args)
            scalar_memo[f] = out
        return out

    def name(c: sp.Expr) -> sp.Expr:
        """A compound scalar ``c`` as its placeholder (a number or a symbol as it is)."""
        if hoisted is None or c.is_Number or c.is_Symbol or (
                c.is_Mul and len(c.args) == 2 and c.args[0].is_Number and c.args[1].is_Symbol):
            return c
        full = c.xreplace(defs) if defs else c
        if full not in hoisted:
            sym = sp.Symbol(f"_s{len(hoisted)}", real=True)
            hoisted[full] = sym
            defs[sym] = full
            known.add(sym)
        return hoisted[full]

    def split(term: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
        if term.is_Mul:
            coeff, rest = [], []
            for f in term.args:
                (coeff if scalar(f) else rest).append(f)
            return sp.Mul(*coeff), sp.Mul(*rest)
        if not scalar(term):
            return sp.Integer(1), term
        return term, sp.Integer(1)

    def walk(e: sp.Expr) -> sp.Expr:
        if e.is_Atom:
            return e
        if e in memo:
            return memo[e]
        args = tuple(walk(a) for a in e.args)
        out = e
        if args != e.args:  # Abs kept unevaluated (sympy's simplification takes minutes)
            out = sp.Abs(args[0], evaluate=False) if isinstance(e, sp.Abs) else e.func(*args)
        if out.is_Add and not scalar(out):
            groups: dict[sp.Expr, list[sp.Expr]] = {}
            for term in out.args:
                coeff, rest = split(term)
                groups.setdefault(rest, []).append(coeff)
            if hoisted is not None or any(len(v) > 1 for v in groups.values()):
                out = sp.Add(*[name(sp.Add(*cs)) * rest for rest, cs in groups.items()])
        elif out.is_Mul and hoisted is not None and not scalar(out):
            coeff, rest = split(out)
            out = name(coeff) * rest
        memo[e] = out
        return out

    return walk(sp.sympify(expr))


def polynomial_part(expr: sp.Expr) -> sp.Expr | None:
    """``expr = N/D`` as ``P + R/D``: the polynomial part ``P`` and the remainder ``R`` of
    dividing ``N`` by ``D`` as polynomials in the elementary-function applications of
    ``expr`` (its tan-half-angles) and the symbols of ``D``; None where ``D`` is a
    number.  A pose map is often such a fraction whose numerator carries the whole
    denominator as a factor of most terms (000's platform point: ``-(x + g y)/2 - 2 rb
    t_a t_b / ((1 + t_a^2)(1 + t_b^2))``, 9 terms over the denominator before)."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    if den.is_number:
        return None
    fns = sorted(expr.atoms(sp.tan, sp.sin, sp.cos), key=sp.default_sort_key)
    inner = set().union(*[f.free_symbols for f in fns]) if fns else set()
    gens = fns + sorted(den.free_symbols - inner, key=sp.default_sort_key)
    if not gens:
        return None
    try:
        q, r = sp.div(sp.Poly(num, *gens), sp.Poly(den, *gens))
    except sp.PolynomialError:
        return None
    return q.as_expr() + sp.factor(r.as_expr()) / sp.factor(den)


def leaner_outputs(outputs: Sequence[sp.Expr], args: Sequence[sp.Symbol],
                   scalars: Sequence[sp.Symbol] = (), small: int = 200) -> list[sp.Expr]:
    """``outputs`` with each small fraction (at most ``small`` operations written out)
    replaced by its :func:`polynomial_part` form where that has fewer operations, and all
    of them kept as they are unless the kernel's operation count after CSE falls."""
    lean = []
    for e in outputs:
        e = sp.sympify(e)
        alt = polynomial_part(e) if pr.count_ops(e) <= small else None
        lean.append(alt if alt is not None and pr.count_ops(alt) < pr.count_ops(e) else e)
    if lean == [sp.sympify(e) for e in outputs]:
        return list(outputs)
    before = kernel("_probe", args, outputs, "", scalars=scalars).operations
    after = kernel("_probe", args, lean, "", scalars=scalars).operations
    return lean if after < before else list(outputs)


def kernel(name: str, args: Sequence[sp.Symbol], outputs: Sequence[sp.Expr], doc: str,
           c: bool = False, scalars: Sequence[sp.Symbol] = (),
           program: Sequence[tuple[sp.Symbol, sp.Expr]] = ()) -> Kernel:
    """Emit ``def name(*args): ... return (out0, out1, ...)`` with CSE; with ``c``, also
    ``BF_INLINE void name(double v_arg, ..., double *restrict out)`` from the same program.
    ``scalars``: the arguments that are one number per call (:func:`scalar_coefficients`).
    ``program``: named values ``(symbol, expression)`` in dependency order that the outputs
    (and later entries) read, such as a forward-mode derivative's values and rates
    (:class:`Program`); one CSE runs over the entries and the outputs together, and only
    the entries the outputs need are computed (:func:`_scheduled`)."""
    program = list(program)
    exprs = [sp.sympify(e) for _, e in program] + [sp.sympify(o) for o in outputs]
    first: list = []  # the scalar coefficients, computed before the array program
    if scalars:
        hoisted: dict[sp.Expr, sp.Symbol] = {}
        exprs = [scalar_coefficients(e, set(scalars), hoisted) for e in exprs]
        if hoisted:
            ksubs, kred = sp.cse(list(hoisted), symbols=sp.numbered_symbols("_k"),
                                 order="canonical")
            first = list(ksubs) + list(zip(hoisted.values(), kred))
    scalar_names = frozenset([str(a) for a in scalars] + [sym.name for sym, _ in first])
    subs, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_c"), order="canonical")
    if program:
        subs, reduced = _scheduled([sym for sym, _ in program], subs, reduced)
    subs, reduced = _scaled_temporaries_inlined(subs, reduced, scalar_names)
    subs = first + list(subs)
    source, ops = _numpy_function(name, args, subs, reduced, doc, scalar_names)
    c_source = _c_function(name, args, subs, reduced, doc, scalar_names) if c else ""
    return Kernel(name, source, ops, c_source,
                  tuple(str(a) for a in args), len(reduced),
                  (tuple(args), tuple(subs), tuple(reduced)) if c else (), doc, scalar_names)


class Program:
    """A straight-line program under construction: each non-trivial expression given to
    :meth:`name` becomes an entry ``(symbol, expression)`` that later expressions read by
    its symbol, so that a value shared by many outputs (a pose map's temporaries and their
    rates) is written once instead of being multiplied out into each; :func:`kernel` takes
    the entries as its ``program``."""

    def __init__(self, prefix: str = "_p"):
        self.entries: list[tuple[sp.Symbol, sp.Expr]] = []
        self._symbols = sp.numbered_symbols(prefix, real=True)

    def name(self, expr) -> sp.Expr:
        """``expr`` as a symbol of the program; a number or a symbol as it is."""
        expr = sp.sympify(expr)
        if expr.is_Atom:
            return expr
        sym = next(self._symbols)
        self.entries.append((sym, expr))
        return sym

    def written_out(self, exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
        """``exprs`` with every entry's symbol replaced by its expression, recursively (an
        unevaluated ``Abs`` kept unevaluated: xreplace would drop the sign of its
        argument)."""
        full: dict[sp.Expr, sp.Expr] = {}

        def put(e: sp.Expr) -> sp.Expr:
            if e.is_Atom:
                return full.get(e, e)
            if e not in full:
                args = [put(a) for a in e.args]
                full[e] = (sp.Abs(args[0], evaluate=False) if isinstance(e, sp.Abs)
                           else e.func(*args) if args != list(e.args) else e)
            return full[e]

        for sym, e in self.entries:
            full[sym] = put(sp.sympify(e))
        return [put(sp.sympify(e)) for e in exprs]


def _scheduled(named: Sequence[sp.Symbol], subs: Sequence[tuple[sp.Symbol, sp.Expr]],
               reduced: Sequence[sp.Expr]
               ) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The CSE program of ``[*program entries, *outputs]`` (``subs``, ``reduced``; the
    first ``len(named)`` of ``reduced`` are the entries' expressions, ``named`` their
    symbols) as one straight-line program: the outputs' expressions, and before them, in
    depth-first order from the outputs, every temporary and entry they need, each after
    the values it reads (an entry that is a number or a symbol is put in its readers'
    places).  The temporaries are then numbered ``_c0, _c1, ...`` in that order."""
    values = list(reduced[: len(named)])
    outputs = list(reduced[len(named):])
    rep: dict[sp.Symbol, sp.Expr] = {}
    defs: dict[sp.Symbol, sp.Expr] = {}
    rank: dict[sp.Symbol, int] = {}
    for k, (sym, e) in enumerate(subs):
        defs[sym], rank[sym] = e, k
    for k, (sym, e) in enumerate(zip(named, values)):
        if e.is_Atom:
            rep[sym] = e
        else:
            defs[sym], rank[sym] = e, len(subs) + k
    if rep:  # an atom entry read by a later atom entry: resolved in order
        for sym in named:
            if sym in rep:
                rep[sym] = rep[sym].xreplace(rep)
        defs = {s: sp.sympify(e).xreplace(rep) for s, e in defs.items()}
        outputs = [sp.sympify(e).xreplace(rep) for e in outputs]
    order: list[sp.Symbol] = []
    seen: set[sp.Symbol] = set()
    for out in outputs:
        stack = [(s, False) for s in sorted(sp.sympify(out).free_symbols & defs.keys(),
                                            key=rank.__getitem__, reverse=True)]
        while stack:
            sym, done = stack.pop()
            if done:
                order.append(sym)
                continue
            if sym in seen:
                continue
            seen.add(sym)
            stack.append((sym, True))
            stack += [(s, False) for s in sorted(
                sp.sympify(defs[sym]).free_symbols & defs.keys() - seen,
                key=rank.__getitem__, reverse=True)]
    renamed = {s: sp.Symbol(f"_c{k}") for k, s in enumerate(order)}
    return ([(renamed[s], sp.sympify(defs[s]).xreplace(renamed)) for s in order],
            [sp.sympify(e).xreplace(renamed) for e in outputs])


def _power_of_two(c: sp.Expr) -> bool:
    """``c`` a rational number +-2^k (k any integer): multiplying by it is exact."""
    if not c.is_Rational or c == 0:
        return False
    p, q = abs(int(c.p)), int(c.q)
    return p & (p - 1) == 0 and q & (q - 1) == 0


def _scaled_temporaries_inlined(subs, reduced, scalars: frozenset):
    """The CSE program ``(subs, reduced)`` with each temporary ``_c = 2^k * X`` (X an
    array) put back into its readers where every reader multiplies it by a scalar (a
    parameter or a hoisted ``_s``): CSE shares ``2.0*x`` between ``lOA*2.0*x`` and
    ``lOB*2.0*x``, which costs an array operation more than the two products printed
    scalars first (``2.0*lOA*x``: one each).  Each product is the same number (scaling by
    a power of two is exact, so ``lOA*(2x)`` and ``(2 lOA)*x`` round alike; a product with
    another array factor, or a scalar divided by, keeps the temporary), but a sum that
    reads it may then order its terms differently, and round differently in the last
    bits.  The temporaries are then numbered in order again."""
    def scalar(f: sp.Expr) -> bool:
        return not f.is_Number and bool(f.free_symbols) and {
            v.name for v in f.free_symbols} <= scalars

    candidates = {sym: e for sym, e in subs
                  if e.is_Mul and len(e.args) == 2 and _power_of_two(e.args[0])
                  and (e.args[1].is_Symbol or e.args[1].is_Pow) and not scalar(e.args[1])}
    if not candidates:
        return subs, reduced
    keep: set[sp.Symbol] = set()
    seen: set = set()

    def visit(e: sp.Expr) -> None:
        if e.is_Atom or e in seen:
            return
        seen.add(e)
        # a product of scalars and the temporary alone, no scalar divided by (another
        # array factor would be multiplied in another order once the factors are printed
        # scalars first, and a division by a scalar is printed after the array)
        scaled = False
        if e.is_Mul:
            arrays = [a for a in e.args if not a.is_Number and not scalar(a)]
            others = [a for a in e.args if a not in arrays]
            scaled = (len(arrays) == 1 and any(not a.is_Number for a in others)
                      and not any(a.is_Pow and a.exp.is_negative for a in others))
        for a in e.args:
            if a in candidates:
                if not scaled:
                    keep.add(a)
            else:
                visit(a)

    for e in [e for _, e in subs] + list(reduced):
        if e in candidates:  # a candidate that is a whole value (an alias) stays
            keep.add(e)
        visit(e)
    inline = {s: e for s, e in candidates.items() if s not in keep}
    if not inline:
        return subs, reduced
    subs = [(s, e.xreplace(inline)) for s, e in subs if s not in inline]
    reduced = [sp.sympify(e).xreplace(inline) for e in reduced]
    temps = [s for s, _ in subs if s.name.startswith("_c")]
    renamed = {s: sp.Symbol(f"_c{k}") for k, s in enumerate(temps)}
    return ([(renamed.get(s, s), e.xreplace(renamed)) for s, e in subs],
            [e.xreplace(renamed) for e in reduced])


def _numpy_function(name, args, subs, reduced, doc, scalars: frozenset) -> tuple[str, int]:
    """The numpy source of a common-subexpression program and its operation count."""
    printer = _Printer({"fully_qualified_modules": True, "allow_unknown_functions": False},
                       scalars=scalars)
    lines = [f"def {name}({', '.join(str(a) for a in args)}):", f'    """{doc}"""']
    ops = 0
    # each array temporary is released after its last use: the kernel's working set is then
    # the live temporaries, not all of them (planar_tripod's Jacobian 20 % faster on chunks
    # of 16384 poses)
    last = _last_uses(subs, reduced)
    for k, (sym, expr) in enumerate(subs):
        lines.append(f"    {sym} = {printer.doprint(expr)}")
        ops += pr.count_ops(expr)
        dead = sorted(last.get(k, ()), key=lambda t: int(t.name[2:]))
        if dead:
            lines.append(f"    del {', '.join(t.name for t in dead)}")
    outs = []
    for expr in reduced:
        outs.append(printer.doprint(expr))
        ops += pr.count_ops(expr)
    lines.append(f"    return ({', '.join(outs)},)")
    return "\n".join(lines) + "\n", ops


def _last_uses(subs, reduced) -> dict[int, list[sp.Symbol]]:
    """The array temporaries (``_c<k>``) of a CSE program by the index of the temporary
    whose line uses them last (none of those used by the outputs)."""
    temps = {sym for sym, _ in subs if sym.name.startswith("_c")}
    last: dict[sp.Symbol, int] = {}
    for k, (_, expr) in enumerate(subs):
        for t in sp.sympify(expr).free_symbols & temps:
            last[t] = k
    for expr in reduced:
        for t in sp.sympify(expr).free_symbols & temps:
            last.pop(t, None)
            temps.discard(t)
    out: dict[int, list[sp.Symbol]] = {}
    for t, k in last.items():
        if t in temps:
            out.setdefault(k, []).append(t)
    return out


# elementary functions worth computing once per pose for several C kernels
_SHAREABLE = (sp.tan, sp.sin, sp.cos)


def shareable_functions(k: Kernel, names: set[str]) -> dict[sp.Expr, list[sp.Expr]]:
    """The applications of tan, sin and cos in the C program of ``k`` whose arguments, with
    the temporaries written out, involve only the variables ``names`` (the pose and the
    parameters): ``{written-out application: [its forms in the program]}``.  Only small
    arguments are followed (``tan(gamma/2)``, not the sine of a long expression)."""
    args, subs, reduced = k.program
    temps = dict(subs)
    memo: dict[sp.Symbol, sp.Expr | None] = {}

    def written_out(e: sp.Expr) -> sp.Expr | None:
        if pr.count_ops(e) > 4:
            return None
        rep = {}
        for s in e.free_symbols:
            if s in temps:
                if s not in memo:
                    memo[s] = written_out(temps[s])
                if memo[s] is None:
                    return None
                rep[s] = memo[s]
        return e.xreplace(rep) if rep else e

    out: dict[sp.Expr, list[sp.Expr]] = {}
    for expr in [e for _, e in subs] + list(reduced):
        for a in sp.sympify(expr).atoms(*_SHAREABLE):
            arg = written_out(a.args[0])
            if arg is not None and {str(v) for v in arg.free_symbols} <= names:
                forms = out.setdefault(a.func(arg), [])
                if a not in forms:
                    forms.append(a)
    return out


def shared_functions(found: Sequence[dict[sp.Expr, list[sp.Expr]]]) -> list[sp.Expr]:
    """tan, sin and cos of the pose that two or more kernels compute (``found``: each
    kernel's :func:`shareable_functions`; the Study map, the Jacobian and the limits all
    take tan(angle/2) of the pose's angles), in a deterministic order."""
    count: dict[sp.Expr, int] = {}
    for applications in found:
        for full in applications:
            count[full] = count.get(full, 0) + 1
    return sorted((f for f, c in count.items() if c > 1), key=sp.srepr)


def _with_shared(k: Kernel, shared: dict[sp.Expr, sp.Symbol],
                 found: dict[sp.Expr, list[sp.Expr]]):
    """The program of ``k`` with the applications ``shared`` maps read from its symbols,
    and the symbols it then takes: ``(extra arguments, temporaries, outputs)``."""
    args, subs, reduced = k.program
    rep, extra = {}, []
    for full, sym in shared.items():
        if full in found:
            extra.append(sym)
            for form in found[full]:
                rep[form] = sym
    if not rep:
        return [], list(subs), list(reduced)
    return (extra, [(s, sp.sympify(e).xreplace(rep)) for s, e in subs],
            [sp.sympify(e).xreplace(rep) for e in reduced])


def numpy_function(k: Kernel, name: str, shared: dict[sp.Expr, sp.Symbol],
                   found: dict[sp.Expr, list[sp.Expr]]) -> Kernel:
    """``k`` as a numpy function ``name`` taking every value of ``shared`` (in its order)
    before its own arguments, those it computed itself read from them instead (``found``:
    the kernel's :func:`shareable_functions`)."""
    args, _, _ = k.program
    _, subs, reduced = _with_shared(k, shared, found)
    new_args = [*shared.values(), *args]
    source, ops = _numpy_function(name, new_args, subs, reduced, k.doc, k.scalars)
    return Kernel(name, source, ops, "", tuple(str(a) for a in new_args), k.outputs, (),
                  k.doc, k.scalars)


def c_function(k: Kernel, shared: dict[sp.Expr, sp.Symbol],
               found: dict[sp.Expr, list[sp.Expr]]) -> tuple[str, tuple[str, ...]]:
    """The C source of ``k`` with the written-out applications ``shared`` maps taken as
    arguments (placed first) instead of computed, and its argument names; ``found``: the
    kernel's :func:`shareable_functions`."""
    args = k.program[0]
    extra, subs, reduced = _with_shared(k, shared, found)
    if not extra:
        return k.c_source, k.arguments
    new_args = [*extra, *args]
    return (_c_function(k.name, new_args, subs, reduced, k.doc, k.scalars),
            tuple(str(a) for a in new_args))


def c_values(name: str, args: Sequence[sp.Symbol], values: Sequence[sp.Expr], doc: str) -> str:
    """A C function computing ``values`` of ``args`` as written (no CSE)."""
    return _c_function(name, args, [], list(values), doc)


def _c_function(name, args, subs, reduced, doc, scalars: frozenset = frozenset()) -> str:
    cp = _CPrinter(scalars=scalars)
    params = ", ".join([f"double v_{a}" for a in args] + ["double *restrict out"])
    lines = [f"/* {doc.replace('*/', '* /')} */", f"BF_INLINE void {name}({params})", "{"]
    for sym, expr in subs:
        lines.append(f"    const double v_{sym} = {cp.doprint(expr)};")
    for k, expr in enumerate(reduced):
        lines.append(f"    out[{k}] = {cp.doprint(expr)};")
    lines.append("}")
    return "\n".join(lines) + "\n"
