"""Numpy kernels from sympy expressions, with common subexpressions eliminated.

A kernel is a plain function of scalar-or-array arguments returning a tuple of arrays; it
contains only arithmetic and ``numpy`` calls, so it broadcasts over any leading shape.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import PRECEDENCE


class _Printer(NumPyPrinter):
    """NumPyPrinter writing ``numpy.<fn>`` calls and exact rationals as float literals."""

    def _print_Rational(self, expr):  # noqa: N802 - sympy printer protocol
        return repr(float(expr.p) / float(expr.q)) if expr.q != 1 else f"{expr.p}.0"

    def _print_Integer(self, expr):  # noqa: N802
        return f"{int(expr)}.0" if abs(int(expr)) < 2**53 else repr(float(expr))

    def _print_Pow(self, expr, rational=False):  # noqa: N802
        # integer powers stay integer (numpy's fast paths); x**2 becomes (x*x), parenthesized
        # because the printer gives a Pow the precedence of a power: unparenthesized,
        # a/x**2 would print as a/x*x
        base, exp = expr.base, expr.exp
        b = self.parenthesize(base, PRECEDENCE["Pow"], strict=False)
        if exp.is_Integer and int(exp) == 1:
            return b
        if exp.is_Integer and 1 < int(exp) <= 3:
            return "(" + "*".join([b] * int(exp)) + ")"
        if exp.is_Integer and -3 <= int(exp) < 0:
            # numpy.power with a negative exponent is several times slower than a division
            return "(1.0/(" + "*".join([b] * -int(exp)) + "))"
        if exp.is_Integer:
            return f"{b}**{int(exp)}"
        return super()._print_Pow(expr, rational=rational)


@dataclass(frozen=True)
class Kernel:
    """Source of one generated function and its operation count after CSE."""

    name: str
    source: str
    operations: int


def kernel(name: str, args: Sequence[sp.Symbol], outputs: Sequence[sp.Expr], doc: str) -> Kernel:
    """Emit ``def name(*args): ... return (out0, out1, ...)`` with CSE."""
    printer = _Printer({"fully_qualified_modules": True, "allow_unknown_functions": False})
    subs, reduced = sp.cse([sp.sympify(o) for o in outputs],
                           symbols=sp.numbered_symbols("_c"), order="canonical")
    lines = [f"def {name}({', '.join(str(a) for a in args)}):", f'    """{doc}"""']
    ops = 0
    for sym, expr in subs:
        lines.append(f"    {sym} = {printer.doprint(expr)}")
        ops += int(sp.count_ops(expr))
    outs = []
    for expr in reduced:
        outs.append(printer.doprint(expr))
        ops += int(sp.count_ops(expr))
    lines.append(f"    return ({', '.join(outs)},)")
    return Kernel(name, "\n".join(lines) + "\n", ops)
