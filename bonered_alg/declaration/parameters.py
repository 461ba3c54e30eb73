"""Geometric parameters and algebraic constants of a mechanism."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

DOMAINS = ("real", "positive", "nonnegative")


@dataclass(frozen=True)
class Parameter:
    """A geometric parameter: its name, its value in ``unit``, what it is, where the value
    comes from (a paper's table or equation, a recovery, or a stated assumption).

    Every parameter has a finite value: the derivation checks the papers' numbers with it and
    the generated functions use it as their default (callers pass their own as keywords).
    Where a paper gives no value, choose one and say so in ``source``.  ``domain`` is what
    values a caller may pass (``"positive"`` for a length, ``"nonnegative"``, ``"real"``):
    the generated functions reject others with an error naming the parameter."""

    name: str
    value: float
    unit: str
    description: str
    source: str = ""
    domain: str = "real"

    @property
    def symbol(self) -> sp.Symbol:
        return sp.Symbol(self.name, real=True)


@dataclass(frozen=True)
class Constant:
    """An algebraic number used by a chain (e.g. sqrt(3) of an equilateral layout).

    It enters the ideals as a variable bound by its minimal polynomial, so elimination stays
    over Q; the generated code substitutes ``value``.
    """

    symbol: sp.Symbol
    minimal_polynomial: sp.Expr
    value: sp.Expr
    description: str = ""
