"""Closures: legs meeting on one platform point, with the chart that normalizes it.

A leg closes on the platform when its chain product ``C`` and the platform's Study point
``X`` are the same projective point, ``C = lambda X``.  The chart fixes the scale of ``X``
and so decides the closure equations (:meth:`Chart.equations`):

* :class:`UnitCoordinate` (``X_p = 1``, e.g. ``x0 = 1``): ``C_k - C_p X_k = 0`` for
  ``k != p`` and ``1 - mu C_p = 0`` with a Rabinowitsch variable ``mu`` that excludes
  ``C_p = 0`` (Cox-Little-O'Shea, Ch. 4 Sect. 4, saturation);
* :class:`UnitRotation` (``|x|^2 = 1``, 004 eq. 2): ``X_k - lambda C_k = 0`` for all ``k``
  and ``x0^2 + x1^2 + x2^2 + x3^2 - 1 = 0``, with the scale ``lambda`` eliminated; every
  rotation, half-turns included, is in this chart.

A pure translation is the chart ``x0 = 1`` with ``x1 = x2 = x3 = 0`` in the platform point.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from ..chains.joints import Leg

MU = sp.Symbol("mu_sat")
LAMBDA = sp.Symbol("lambda_p", real=True)


@dataclass(frozen=True)
class UnitCoordinate:
    """The chart ``X_index = 1`` (``index`` 0..7)."""

    index: int

    @property
    def name(self) -> str:
        return f"{('x0 x1 x2 x3 y0 y1 y2 y3'.split())[self.index]} = 1"

    @property
    def scale(self) -> sp.Symbol:
        return MU

    def equations(self, chain: Sequence[sp.Expr], platform: Sequence[sp.Expr]) -> list[sp.Expr]:
        """``C_k - C_p X_k`` for ``k != p`` and ``1 - mu C_p``, where ``X_p = 1``."""
        p = self.index
        eqs = [sp.expand(chain[k] - chain[p] * platform[k]) for k in range(8) if k != p]
        eqs.append(sp.expand(1 - MU * chain[p]))
        return [e for e in eqs if e != 0]

    def normalize(self, point: Sequence) -> tuple:
        """A Study point scaled into the chart (symbolic division)."""
        return tuple(c / point[self.index] for c in point)


@dataclass(frozen=True)
class UnitRotation:
    """The chart ``|x|^2 = 1`` of 004 eq. (2) (every displacement, up to the sign of X)."""

    @property
    def name(self) -> str:
        return "x0^2 + x1^2 + x2^2 + x3^2 = 1"

    @property
    def scale(self) -> sp.Symbol:
        return LAMBDA

    def equations(self, chain: Sequence[sp.Expr], platform: Sequence[sp.Expr]) -> list[sp.Expr]:
        eqs = [sp.expand(platform[k] - LAMBDA * chain[k]) for k in range(8)]
        eqs.append(sp.expand(sum(c**2 for c in platform[:4]) - 1))
        return [e for e in eqs if e != 0]

    def normalize(self, point: Sequence) -> tuple:
        n = sp.sqrt(sum(c**2 for c in point[:4]))
        return tuple(c / n for c in point)


Chart = UnitCoordinate | UnitRotation


def infer_chart(platform: Sequence) -> UnitCoordinate | None:
    """The first coordinate of ``platform`` equal to the constant 1, as a chart."""
    for i, c in enumerate(platform):
        if sp.sympify(c) == 1:
            return UnitCoordinate(i)
    return None


@dataclass(frozen=True)
class Coupling:
    """An extra polynomial relation of a closure (e.g. an actuation linkage), what it
    stands for, and the joints of the linkage it replaces (``(body, body, kind, label)``
    edges, for the topology and the mobility count)."""

    equation: sp.Expr
    description: str
    source: str = ""
    linkage: tuple[tuple[str, str, str, str], ...] = ()


@dataclass(frozen=True)
class Closure:
    """Legs that close on one platform point, each eliminated separately (004 Sect. 3.2.2).

    ``platform`` is the platform's Study point in the closure's ``pose`` symbols (its Study
    coordinates); ``chart`` normalizes it (default: the first coordinate equal to 1).
    ``base`` is the body the legs stand on and ``point`` the body they close on (the names
    of the topology).  ``motion`` is the motion space of the closure's loops for the
    Kutzbach-Gruebler count (``"planar"``: lambda = 3, ``"spatial"``: 6) and
    ``extra_constraints`` what that count misses (``constraints_note`` says why).
    ``inputs`` makes it a driven closure: its legs carry no actuated joint but depend on
    these pose coordinates of the mechanism (the outputs of other closures); its ideal is
    derived and generated as functions, but it is not part of the inverse kinematics.
    """

    name: str
    point: str
    legs: tuple[Leg, ...]
    platform: tuple[sp.Expr, ...]
    pose: tuple[sp.Symbol, ...]
    chart: Chart | None = None
    couplings: tuple[Coupling, ...] = ()
    note: str = ""
    base: str = "base"
    motion: str = "spatial"
    extra_constraints: int = 0
    constraints_note: str = ""
    inputs: tuple[sp.Symbol, ...] = ()
    source: str = ""

    @property
    def normalization(self) -> Chart:
        """The chart (explicit, or inferred from the platform point)."""
        chart = self.chart or infer_chart(self.platform)
        if chart is None:  # pragma: no cover - rejected by the validator
            raise ValueError(f"closure {self.name!r} has no chart")
        return chart

    @property
    def driven(self) -> bool:
        return bool(self.inputs)

    @property
    def lam(self) -> int:
        return 3 if self.motion == "planar" else 6
