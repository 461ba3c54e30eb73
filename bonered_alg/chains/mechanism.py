"""A mechanism: named parameters, legs closing on platforms, and its topology graph.

A :class:`Mechanism` is what a module in ``bonered_alg/mechanisms/`` defines.  Its
:meth:`Mechanism.validate` catches definition errors before any algebra runs (unknown joint
types, symbols used in a chain but never declared, a topology whose legs do not close).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import networkx as nx
import sympy as sp

from ..errors import MechanismDefinitionError, UndefinedParameterError, UnknownJointTypeError
from .joints import JOINT_DOF, JOINT_TYPES, Factor, Leg, Role


@dataclass(frozen=True)
class Parameter:
    """A geometric parameter: name, value (``None`` where the paper gives none), unit, source."""

    name: str
    value: float | None
    unit: str
    description: str
    source: str = ""


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


@dataclass(frozen=True)
class Coupling:
    """An extra polynomial relation of a leg (e.g. an actuation linkage), and what it frees."""

    equation: sp.Expr
    description: str
    source: str = ""


@dataclass(frozen=True)
class Closure:
    """Legs that close on one platform point, each eliminated separately (004 Sect. 3.2.2).

    ``platform`` is the platform's Study point in the pose symbols ``pose``; one coordinate
    must be the constant 1 (the normalization chosen by the paper, e.g. ``x0 = 1``).
    """

    name: str
    point: str
    legs: tuple[Leg, ...]
    platform: tuple[sp.Expr, ...]
    pose: tuple[sp.Symbol, ...]
    couplings: tuple[Coupling, ...] = ()
    note: str = ""


@dataclass
class Mechanism:
    """Parameters, joint variables, closures and the body/joint graph of one mechanism."""

    name: str
    title: str
    source: str
    parameters: dict[str, Parameter]
    active: tuple[sp.Symbol, ...]
    passive: tuple[sp.Symbol, ...]
    closures: tuple[Closure, ...]
    topology: nx.MultiGraph
    planar: bool = False
    extra_constraints: int = 0
    extra_constraints_note: str = ""
    units: dict[str, str] = field(default_factory=dict)
    constants: tuple[Constant, ...] = ()
    # Kutzbach-Gruebler lambda per subsystem (edge attribute "subsystem"); default planar/6
    subsystem_lambda: dict[str, int] = field(default_factory=dict)

    # ----------------------------------------------------------------- symbols
    @property
    def geometric(self) -> tuple[sp.Symbol, ...]:
        return tuple(sp.Symbol(n, real=True) for n in self.parameters)

    def declared(self) -> set[sp.Symbol]:
        pose = {s for c in self.closures for s in c.pose}
        consts = {c.symbol for c in self.constants}
        return set(self.geometric) | set(self.active) | set(self.passive) | pose | consts

    # ----------------------------------------------------------------- checks
    def validate(self) -> None:
        """Raise a specific :class:`MechanismDefinitionError` for any inconsistency."""
        declared = self.declared()
        names = [str(s) for s in declared]
        if len(set(names)) != len(names):
            raise MechanismDefinitionError(
                self.name, f"a symbol is declared twice: {sorted(names)}")
        roles = {Role.ACTIVE: set(self.active), Role.PASSIVE: set(self.passive),
                 Role.GEOMETRIC: set(self.geometric)}
        for closure in self.closures:
            if not closure.legs:
                raise MechanismDefinitionError(self.name, f"closure {closure.name!r} has no leg")
            if len(closure.platform) != 8:
                raise MechanismDefinitionError(
                    self.name, f"closure {closure.name!r}: the platform Study point needs 8 "
                    f"coordinates, got {len(closure.platform)}")
            if not any(sp.sympify(c) == 1 for c in closure.platform):
                raise MechanismDefinitionError(
                    self.name, f"closure {closure.name!r}: one platform coordinate must be the "
                    "constant 1 (the normalization, e.g. x0 = 1)")
            for leg in closure.legs:
                for f in leg.factors:
                    self._check_factor(leg, f, declared, roles)
            for cp in closure.couplings:
                extra = cp.equation.free_symbols - declared
                if extra:
                    raise UndefinedParameterError(
                        self.name, f"coupling {cp.description!r} uses undefined "
                        f"{sorted(map(str, extra))}")
        self._check_topology()

    def _check_factor(self, leg: Leg, f: Factor, declared, roles) -> None:
        undefined = f.free_symbols - declared
        if undefined:
            raise UndefinedParameterError(
                self.name, f"leg {leg.name!r}, factor {f.label}: parameter(s) "
                f"{sorted(map(str, undefined))} are not declared (declared: "
                f"{sorted(map(str, declared))})")
        own = f.free_symbols & (roles[Role.ACTIVE] | roles[Role.PASSIVE])
        if f.role is not Role.GEOMETRIC and not own <= roles[f.role]:
            raise MechanismDefinitionError(
                self.name, f"leg {leg.name!r}, factor {f.label}: marked {f.role.value} but "
                f"uses {sorted(map(str, own - roles[f.role]))}")
        if f.role is Role.GEOMETRIC and own:
            raise MechanismDefinitionError(
                self.name, f"leg {leg.name!r}, factor {f.label}: a geometric factor uses joint "
                f"variables {sorted(map(str, own))}")

    def _check_topology(self) -> None:
        g = self.topology
        for node in ("base",):
            if node not in g:
                raise MechanismDefinitionError(self.name, f"topology has no {node!r} body")
        for a, b, data in g.edges(data=True):
            kind = data.get("joint")
            if kind not in JOINT_TYPES:
                raise UnknownJointTypeError(
                    self.name, f"joint {data.get('label', '?')} between {a!r} and {b!r} has "
                    f"unknown type {kind!r}; expected one of {sorted(JOINT_TYPES)}")
        if not nx.is_connected(g):
            parts = [sorted(c) for c in nx.connected_components(g)]
            raise MechanismDefinitionError(
                self.name, f"topology is not connected; components: {parts}")

    # ----------------------------------------------------------------- topology
    def loops(self) -> list[list[str]]:
        """Independent loops (a cycle basis of the body/joint graph, parallel joints included)."""
        simple = nx.Graph()
        loops: list[list[str]] = []
        for a, b, _key in self.topology.edges(keys=True):
            if simple.has_edge(a, b):
                loops.append([a, b])
            else:
                simple.add_edge(a, b)
        loops.extend(sorted(sorted(c) for c in nx.cycle_basis(simple, root="base")))
        return loops

    def mobility(self) -> int:
        """Kutzbach-Gruebler mobility ``sum_s lambda_s (n_s - 1 - j_s) + f_s - extra``.

        Each subsystem (edge attribute ``subsystem``) is counted with its own ``lambda`` (3 for
        a planar one, 6 for a spatial one), since the spatial formula over-counts the
        constraints of planar loops; without subsystems the whole graph uses 3 or 6.
        """
        groups: dict[str, list] = {}
        for a, b, d in self.topology.edges(data=True):
            groups.setdefault(d.get("subsystem", ""), []).append((a, b, d))
        total = 0
        for name, edges in groups.items():
            lam = self.subsystem_lambda.get(name, 3 if self.planar else 6)
            nodes = {x for a, b, _ in edges for x in (a, b)}
            f = sum(JOINT_DOF[d["joint"]] for _, _, d in edges)
            total += lam * (len(nodes) - 1 - len(edges)) + f
        return total - self.extra_constraints

    def parameter_values(self) -> dict[str, float | None]:
        return {k: p.value for k, p in self.parameters.items()}


def joint(mechanism: str, kind: str, *args, **kwargs) -> list[Factor]:
    """Factors of a joint of type ``kind``; unknown types raise :class:`UnknownJointTypeError`."""
    try:
        make = JOINT_TYPES[kind]
    except KeyError:
        raise UnknownJointTypeError(
            mechanism, f"unknown joint type {kind!r}; expected one of {sorted(JOINT_TYPES)}"
        ) from None
    return make(*args, **kwargs)


def leg(name: str, *factor_lists: Sequence[Factor]) -> Leg:
    """A leg from joint factor lists, in base-to-platform order."""
    return Leg(name, tuple(f for fl in factor_lists for f in fl))
