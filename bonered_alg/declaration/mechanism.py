"""The mechanism contract: what a module in ``bonered_alg/mechanisms/`` declares.

A mechanism module defines ``MECHANISM = declare(...)``, a frozen :class:`Mechanism`:
parameters (with their sources), the actuated joints, the closures (legs, platform point,
chart), the pose map, and optional parts with defaults (limits, analyses, generated
functions, the module checking the paper's printed equations, the studies).  The pipeline
(``bonered_alg.pipeline``) reads nothing else; :func:`declare` rejects unknown field names
and :func:`validate` every inconsistency it can see, before any algebra runs.
"""

from __future__ import annotations

import difflib
import importlib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import MISSING, dataclass, field, fields
from types import ModuleType
from typing import Any, Protocol

import sympy as sp

from ..chains.joints import Role
from ..errors import MechanismDefinitionError, UndefinedParameterError
from .closures import Closure, UnitCoordinate, UnitRotation, infer_chart
from .parameters import DOMAINS, Constant, Parameter
from .weights import PLATFORM, LinkWeight, body_names


@dataclass(frozen=True)
class PoseMap:
    """The user-facing pose and its map to the closures' Study coordinates.

    ``to_study`` maps each closure pose symbol to an expression in ``coordinates`` (a
    mapping, or a function of the derivation for maps that use derived results, e.g. a
    parasitic motion); ``from_study`` maps each pose coordinate back (forward kinematics);
    ``description`` says how the map is built (for the report); ``end_effector`` is the
    end effector's Study point in the pose coordinates, for its spatial twist
    (``pose_twist``, ``twist_jacobian``), where the pose is a rigid body's."""

    coordinates: tuple[sp.Symbol, ...]
    units: tuple[str, ...]
    to_study: Mapping[sp.Symbol, sp.Expr] | Callable[[Any], Mapping[sp.Symbol, sp.Expr]]
    from_study: Mapping[sp.Symbol, sp.Expr] | None = None
    description: str = "004 eq. 13 with x = [1:0:0:0]"
    end_effector: tuple[sp.Expr, ...] | None = None


@dataclass(frozen=True)
class Limit:
    """A range a quantity of the pose and joints must stay in (a stroke, a passive angle)."""

    name: str
    expression: sp.Expr
    lower: float
    upper: float
    kind: str  # "stroke" | "passive"
    unit: str
    source: str


@dataclass(frozen=True)
class PoseFunction:
    """A generated function of the pose: ``name(pose) -> (..., len(outputs))``."""

    name: str
    outputs: tuple[str, ...]
    expressions: tuple[sp.Expr, ...]
    doc: str


@dataclass(frozen=True)
class InputFunction:
    """A generated function of other inputs: ``name(values) -> (..., len(outputs))``."""

    name: str
    inputs: tuple[sp.Symbol, ...]
    outputs: tuple[str, ...]
    expressions: tuple[sp.Expr, ...]
    doc: str


@dataclass(frozen=True)
class ExtraGenerator:
    """A polynomial the IK planner may use for ``leg``, proved to lie in its ideal first."""

    leg: str
    generator: sp.Expr
    note: str


class Analysis(Protocol):
    """A further derivation step of a mechanism (``bonered_alg.analyses``)."""

    name: str

    def check(self, mechanism: Mechanism) -> None: ...

    def run(self, derivation, algebra) -> Any: ...

    def report(self, result) -> list[str]: ...


Derived = Callable[[Any], Sequence]  # a function of the derivation


@dataclass(frozen=True)
class Mechanism:
    """A mechanism declaration (the fields after ``pose`` are optional)."""

    name: str
    title: str
    source: str
    summary: str
    parameters: tuple[Parameter, ...]
    joints: tuple[sp.Symbol, ...]
    joint_units: tuple[str, ...]
    closures: tuple[Closure, ...]
    pose: PoseMap
    constants: tuple[Constant, ...] = ()
    limits: Sequence[Limit] | Derived = ()
    analyses: tuple[Analysis, ...] = ()
    pose_functions: Sequence[PoseFunction] | Derived = ()
    functions: Sequence[InputFunction] | Derived = ()
    ik_generators: Sequence[ExtraGenerator] | Derived = ()
    forward_kinematics: str = ""  # empty: derive it; else why it is not generated
    singularity_notes: Mapping[str, str] = field(default_factory=dict)
    reading_notes: tuple[str, ...] = ()
    checks: str = ""  # module with verify(derivation, generated, studies) -> [Verdict]
    studies: tuple[str, ...] = ()  # modules with run(derivation, generated) -> Study
    # the home pose (pose coordinates, in their units) and the joint values there of the
    # physical branch: mode 0 of the IK is the root nearest each declared value
    home: tuple[float, ...] = ()
    home_joints: Mapping[sp.Symbol, float] = field(default_factory=dict)
    # actuated revolute joints the generated functions take and return as angles: the
    # algebra's tan-half-angle symbol -> the user's name, angle = 2 atan(symbol) in rad
    # (home_joints gives their values as angles)
    angle_joints: Mapping[sp.Symbol, str] = field(default_factory=dict)
    # the weights of the links for the static model (generated ``static_efforts``)
    link_weights: tuple[LinkWeight, ...] = ()

    def public_joint(self, q: sp.Symbol) -> str:
        """The name users see for the actuated joint ``q`` (its angle's, for an angle
        joint)."""
        return self.angle_joints.get(q, str(q))

    # ------------------------------------------------------------- derived views
    @property
    def geometric(self) -> tuple[sp.Symbol, ...]:
        return tuple(p.symbol for p in self.parameters)

    @property
    def parameter_map(self) -> dict[str, Parameter]:
        return {p.name: p for p in self.parameters}

    @property
    def active(self) -> tuple[sp.Symbol, ...]:
        return tuple(self.joints)

    def passive_factor_symbols(self) -> list[sp.Symbol]:
        """The symbols of the passive factors of every leg, in order of appearance."""
        out: list[sp.Symbol] = []
        for closure in self.closures:
            for leg in closure.legs:
                for f in leg.factors:
                    if f.role is Role.PASSIVE:
                        out += [s for s in sorted(f.free_symbols, key=str) if s not in out]
        return out

    @property
    def passive(self) -> tuple[sp.Symbol, ...]:
        """Passive joint variables: the symbols of passive factors and coupling-only
        unknowns, in order of appearance."""
        fixed = set(self.joints) | set(self.geometric) | self._pose_symbols()
        fixed |= {c.symbol for c in self.constants}
        out = [s for s in self.passive_factor_symbols() if s not in fixed]
        for closure in self.closures:
            for cp in closure.couplings:
                for s in sorted(sp.sympify(cp.equation).free_symbols, key=str):
                    if s not in out and s not in fixed:
                        out.append(s)
        return tuple(out)

    def _pose_symbols(self) -> set[sp.Symbol]:
        return {s for c in self.closures for s in c.pose} | set(self.pose.coordinates)

    def declared(self) -> set[sp.Symbol]:
        consts = {c.symbol for c in self.constants}
        return (set(self.geometric) | set(self.joints) | set(self.passive)
                | self._pose_symbols() | consts)

    @property
    def actuated_closures(self) -> tuple[Closure, ...]:
        return tuple(c for c in self.closures if not c.driven)

    def closure(self, point: str) -> Closure:
        """The closure on the body ``point``."""
        return next(c for c in self.closures if c.point == point)

    def closure_named(self, name: str) -> Closure:
        return next(c for c in self.closures if c.name == name)


FIELDS = tuple(f.name for f in fields(Mechanism))


def declare(**kwargs) -> Mechanism:
    """A :class:`Mechanism` from keyword fields; an unknown or missing field name is a
    :class:`MechanismDefinitionError` naming the mechanism (and the nearest valid name)."""
    name = kwargs.get("name", "?")
    for key in kwargs:
        if key not in FIELDS:
            near = difflib.get_close_matches(key, FIELDS, n=1)
            raise MechanismDefinitionError(
                name, f"unknown declaration field {key!r}"
                + (f" (did you mean {near[0]!r}?)" if near else "")
                + f"; the fields are {', '.join(FIELDS)}")
    missing = [f.name for f in fields(Mechanism) if f.name not in kwargs
               and f.default is MISSING and f.default_factory is MISSING]
    if missing:
        raise MechanismDefinitionError(name, f"the declaration lacks the required field(s) "
                                             f"{', '.join(missing)}")
    conv = dict(kwargs)
    for key in ("parameters", "joints", "joint_units", "closures", "constants", "analyses",
                "reading_notes", "studies", "home", "link_weights"):
        if key in conv and not callable(conv[key]):
            conv[key] = tuple(conv[key])
    return Mechanism(**conv)



# ------------------------------------------------------------------ validation
def _fail(mech: Mechanism, detail: str, error=MechanismDefinitionError):
    raise error(mech.name, detail)


def validate(mech: Mechanism) -> None:
    """Raise a specific :class:`MechanismDefinitionError` for any inconsistency visible in
    the declaration (before any algebra)."""
    if not mech.name.isidentifier():
        _fail(mech, "the name must be a Python identifier (it names the generated module)")
    _check_parameters(mech)
    if len(mech.joint_units) != len(mech.joints):
        _fail(mech, f"{len(mech.joints)} joints but {len(mech.joint_units)} joint units")
    if len(set(mech.joints)) != len(mech.joints):
        _fail(mech, f"a joint is listed twice in joints {list(map(str, mech.joints))}")
    _check_roles(mech)
    declared = mech.declared()
    names = [str(s) for s in declared]
    if len(set(names)) != len(names):
        dup = sorted({n for n in names if names.count(n) > 1})
        _fail(mech, f"symbol name(s) {dup} are declared twice (with different assumptions "
                    "or roles)")
    if not mech.closures:
        _fail(mech, "no closure")
    used: set[sp.Symbol] = set()
    for closure in mech.closures:
        _check_closure(mech, closure, declared)
        for leg in closure.legs:
            used |= leg.free_symbols
        for cp in closure.couplings:
            used |= sp.sympify(cp.equation).free_symbols
    unused = [str(q) for q in mech.joints if q not in used]
    if unused:
        _fail(mech, f"joint(s) {unused} appear in no leg and no coupling")
    _check_pose(mech)
    names_seen = set()
    for a in mech.analyses:
        if a.name in names_seen:
            _fail(mech, f"two analyses are named {a.name!r}")
        names_seen.add(a.name)
        a.check(mech)
    for ref in (*((mech.checks,) if mech.checks else ()), *mech.studies):
        _check_module_reference(mech, ref, "verify" if ref == mech.checks else "run")
    _check_home(mech)
    _check_angle_joints(mech)
    _check_link_weights(mech)
    if mech.forward_kinematics and not isinstance(mech.forward_kinematics, str):
        _fail(mech, "forward_kinematics must be a string (why it is not generated) or ''")


def _finite_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _check_home(mech: Mechanism) -> None:
    n = len(mech.pose.coordinates)
    if mech.home and (len(mech.home) != n or not all(map(_finite_number, mech.home))):
        _fail(mech, f"home must be {n} finite numbers, one per pose coordinate "
                    f"{tuple(map(str, mech.pose.coordinates))}, got {mech.home!r}")
    if mech.home_joints and not mech.home:
        _fail(mech, "home_joints (the physical branch) needs the home pose it holds at: "
                    "declare home=(...)")
    for q, v in mech.home_joints.items():
        if q not in mech.joints:
            _fail(mech, f"home_joints names {q!r}, which is not an actuated joint (joints: "
                        f"{list(map(str, mech.joints))})")
        if not _finite_number(v):
            _fail(mech, f"home_joints[{q}] must be a finite number, got {v!r}")


def _check_link_weights(mech: Mechanism) -> None:
    """Each weight a declared parameter, its points on known bodies in parameters only, the
    shares summing to 1; the legs free of closure coordinates (their rates would not be
    joint rates)."""
    if not mech.link_weights:
        return
    if mech.pose.end_effector is None:
        _fail(mech, "link_weights need the pose map's end_effector (the load acts at its "
                    "origin)")
    closures = mech.actuated_closures
    if len(closures) != 1 or any(c.base != "base" or leg.base not in (None, "base")
                                 or leg.mount is not None
                                 for c in closures for leg in c.legs):
        _fail(mech, "link_weights: the static model handles one actuated closure whose legs "
                    "stand on the fixed base (stacked closures and mounted legs are not "
                    "supported yet)")
    bodies = set(body_names(mech)) | {PLATFORM}
    geometric = set(mech.geometric)
    coords = {s for c in mech.actuated_closures for s in c.pose}
    for c in mech.actuated_closures:
        for leg in c.legs:
            if leg.free_symbols & coords:
                _fail(mech, f"link_weights: leg {leg.name!r} depends on the closure's "
                            "coordinates; the static model needs legs of joints only")
    for w in mech.link_weights:
        if w.weight not in geometric:
            _fail(mech, f"link weight {w.name}: {w.weight} is not a declared parameter")
        if not w.points:
            _fail(mech, f"link weight {w.name}: no point")
        for pt in w.points:
            if pt.body not in bodies:
                _fail(mech, f"link weight {w.name}: unknown body {pt.body!r}; the bodies are "
                            f"{sorted(bodies)}")
            stray = set().union(*(sp.sympify(c).free_symbols for c in (*pt.local, pt.share)))
            if len(pt.local) != 3 or stray - geometric:
                _fail(mech, f"link weight {w.name}: a point needs three coordinates in the "
                            f"parameters (stray: {sorted(map(str, stray - geometric))})")
        if sp.simplify(sum(sp.sympify(pt.share) for pt in w.points) - 1) != 0:
            _fail(mech, f"link weight {w.name}: the shares of its points must sum to 1")


def _check_angle_joints(mech: Mechanism) -> None:
    names = [str(q) for q in mech.joints]
    for q, public in mech.angle_joints.items():
        if q not in mech.joints:
            _fail(mech, f"angle_joints names {q!r}, which is not an actuated joint (joints: "
                        f"{names})")
        if not isinstance(public, str) or not public.isidentifier():
            _fail(mech, f"angle_joints[{q}] must be an identifier (the joint's name for "
                        f"users), got {public!r}")
        unit = mech.joint_units[mech.joints.index(q)]
        if unit != "rad":
            _fail(mech, f"angle joint {public} (2 atan({q})) must have the unit 'rad', got "
                        f"{unit!r}")
    public = [mech.public_joint(q) for q in mech.joints]
    if len(set(public)) != len(public):
        _fail(mech, f"the joints' public names {public} are not distinct")


def _check_roles(mech: Mechanism) -> None:
    """A symbol has one role: actuated joint, passive joint, parameter, closure Study
    coordinate, pose coordinate or algebraic constant (sympy symbols with the same name are
    the same symbol, so a passive ``v1`` and a Study coordinate ``v1`` would be one)."""
    roles = {"actuated joint": set(mech.joints), "parameter": set(mech.geometric),
             "closure Study coordinate": {s for c in mech.closures for s in c.pose},
             "pose coordinate": set(mech.pose.coordinates),
             "algebraic constant": {c.symbol for c in mech.constants}}
    roles["passive joint"] = set(mech.passive_factor_symbols()) - roles["actuated joint"]
    names = list(roles)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            both = roles[a] & roles[b]
            if a == "closure Study coordinate" and b == "pose coordinate":
                continue  # a pose given directly in Study coordinates
            if both:
                _fail(mech, f"symbol(s) {sorted(map(str, both))} are both {a} and {b}; give "
                            "them different names")


def _check_parameters(mech: Mechanism) -> None:
    seen = set()
    for p in mech.parameters:
        if not isinstance(p, Parameter):
            _fail(mech, f"parameters must be Parameter objects, got {type(p).__name__}")
        if p.name in seen:
            _fail(mech, f"parameter {p.name!r} is declared twice")
        seen.add(p.name)
        if not _finite_number(p.value):
            _fail(mech, f"parameter {p.name!r} has value {p.value!r}; expected a finite number "
                        f"in {p.unit or 'its unit'} (where the paper gives none, choose one "
                        "and say so in its source)")
        if not p.name.isidentifier():
            _fail(mech, f"parameter name {p.name!r} is not an identifier")
        if p.domain not in DOMAINS:
            _fail(mech, f"parameter {p.name!r} has domain {p.domain!r}; expected one of "
                        f"{DOMAINS}")
        if (p.domain == "positive" and not p.value > 0) or (
                p.domain == "nonnegative" and not p.value >= 0):
            _fail(mech, f"parameter {p.name!r} is declared {p.domain} but its value is "
                        f"{p.value}")


def _check_closure(mech: Mechanism, closure: Closure, declared: set) -> None:
    label = f"closure {closure.name!r}"
    if not closure.legs:
        _fail(mech, f"{label} has no leg")
    if len(closure.platform) != 8:
        _fail(mech, f"{label}: the platform Study point needs 8 coordinates, got "
                    f"{len(closure.platform)}")
    chart = closure.chart or infer_chart(closure.platform)
    if chart is None:
        _fail(mech, f"{label}: give a chart (UnitRotation()) or set one platform coordinate "
                    "to the constant 1 (the normalization, e.g. x0 = 1)")
    if isinstance(chart, UnitCoordinate) and sp.sympify(closure.platform[chart.index]) != 1:
        _fail(mech, f"{label}: the chart {chart.name} needs that coordinate to be 1 in the "
                    "platform point")
    if not isinstance(chart, (UnitCoordinate, UnitRotation)):
        _fail(mech, f"{label}: unknown chart {chart!r}")
    if closure.motion not in ("planar", "spatial"):
        _fail(mech, f"{label}: motion must be 'planar' or 'spatial', got {closure.motion!r}")
    stray = set().union(*(sp.sympify(c).free_symbols for c in closure.platform)) - set(
        closure.pose) - set(mech.geometric)
    if stray:
        _fail(mech, f"{label}: the platform point uses {sorted(map(str, stray))}, which are "
                    "not the closure's pose symbols")
    bad_inputs = [str(s) for s in closure.inputs if s not in set(mech.pose.coordinates)]
    if bad_inputs:
        _fail(mech, f"{label}: inputs {bad_inputs} are not pose coordinates of the mechanism")
    roles = {Role.ACTIVE: set(mech.joints), Role.PASSIVE: set(mech.passive),
             Role.GEOMETRIC: set(mech.geometric)}
    for leg in closure.legs:
        if leg.mount is not None:
            _check_mount(mech, closure, leg)
        for f in leg.factors:
            undefined = f.free_symbols - declared
            if undefined:
                _fail(mech, f"leg {leg.name!r}, factor {f.label}: parameter(s) "
                            f"{sorted(map(str, undefined))} are not declared (declared: "
                            f"{sorted(map(str, declared))})", UndefinedParameterError)
            own = f.free_symbols & (roles[Role.ACTIVE] | roles[Role.PASSIVE])
            if f.role is not Role.GEOMETRIC and not own <= roles[f.role]:
                _fail(mech, f"leg {leg.name!r}, factor {f.label}: marked {f.role.value} but "
                            f"uses {sorted(map(str, own - roles[f.role]))}")
            if f.role is Role.GEOMETRIC and own:
                _fail(mech, f"leg {leg.name!r}, factor {f.label}: a geometric factor uses "
                            f"joint variables {sorted(map(str, own))}")
            if f.role is Role.GEOMETRIC and closure.inputs == () and (
                    f.free_symbols & set(mech.pose.coordinates)):
                _fail(mech, f"leg {leg.name!r}, factor {f.label}: uses pose coordinates; "
                            "only a driven closure (inputs=...) may")
        if closure.driven and any(f.role is Role.ACTIVE for f in leg.factors):
            _fail(mech, f"{label} is driven by {list(map(str, closure.inputs))} but leg "
                        f"{leg.name!r} has an actuated joint")
    for cp in closure.couplings:
        extra = sp.sympify(cp.equation).free_symbols - declared
        if extra:
            _fail(mech, f"coupling {cp.description!r} uses undefined "
                        f"{sorted(map(str, extra))}", UndefinedParameterError)
        for a, b, kind, lab in cp.linkage:
            from ..chains.joints import JOINT_TYPES

            if kind not in JOINT_TYPES:
                from ..errors import UnknownJointTypeError

                _fail(mech, f"coupling {cp.description!r}: joint {lab} between {a!r} and "
                            f"{b!r} has unknown type {kind!r}; expected one of "
                            f"{sorted(JOINT_TYPES)}", UnknownJointTypeError)


def _check_mount(mech: Mechanism, closure: Closure, leg) -> None:
    m = [sp.sympify(c) for c in leg.mount]
    if len(m) != 8 or m[0] != 1 or any(c != 0 for c in m[1:5]):
        _fail(mech, f"leg {leg.name!r}: the mount must be a pure translation "
                    "[1:0:0:0:0:-t/2] (its frame keeps the closure's chart)")
    allowed = set(mech.geometric) | set(closure.inputs)
    stray = set().union(*(c.free_symbols for c in m)) - allowed
    if stray:
        _fail(mech, f"leg {leg.name!r}: the mount uses {sorted(map(str, stray))}; only "
                    "geometric parameters and the closure's inputs may appear")


def _check_pose(mech: Mechanism) -> None:
    pose = mech.pose
    if len(pose.units) != len(pose.coordinates):
        _fail(mech, f"{len(pose.coordinates)} pose coordinates but {len(pose.units)} units")
    if not callable(pose.to_study):
        closure_syms = {s for c in mech.closures for s in c.pose}
        stray = sorted(map(str, set(pose.to_study) - closure_syms))
        if stray:
            _fail(mech, f"the pose map gives expressions for {stray}, which are not Study "
                        "coordinates of any closure")
    if pose.end_effector is not None:
        if len(pose.end_effector) != 8:
            _fail(mech, "the end effector's Study point needs 8 coordinates")
        stray = set().union(*(sp.sympify(c).free_symbols for c in pose.end_effector)) - set(
            pose.coordinates) - set(mech.geometric)
        if stray:
            _fail(mech, f"the end effector's Study point uses {sorted(map(str, stray))}, "
                        "which are not pose coordinates or parameters")
    if pose.from_study is not None:
        missing = sorted(map(str, set(pose.coordinates) - set(pose.from_study)))
        if missing:
            _fail(mech, f"from_study gives no expression for pose coordinate(s) {missing}")
    elif not mech.forward_kinematics:
        _fail(mech, "forward kinematics is derived (forward_kinematics='') but the pose map "
                    "has no from_study; give it, or say why forward kinematics is not "
                    "generated")


def _check_module_reference(mech: Mechanism, ref: str, function: str) -> ModuleType:
    try:
        module = importlib.import_module(ref)
    except ImportError as exc:
        _fail(mech, f"module {ref!r} cannot be imported: {exc}")
    if not callable(getattr(module, function, None)):
        _fail(mech, f"module {ref!r} defines no function {function}()")
    return module


# hooks of the former contract, read by nothing now: a module defining one is a mistake
FORMER_HOOKS = ("build", "verify", "analyses", "pose_to_study", "POSE_TO_STUDY", "limits",
                "pose_functions", "functions", "artifacts", "report_sections",
                "extra_ik_generators", "FORWARD_KINEMATICS_PENDING", "USES_PACKAGES",
                "SINGULARITY_NOTES", "STUDY_TO_POSE")


def load_declaration(module: ModuleType) -> Mechanism:
    """``module.MECHANISM``, validated; a clear error for a module that follows the former
    hook contract (a hook the declaration does not use is read by nothing) or defines no
    declaration."""
    name = getattr(module, "__name__", "?").rsplit(".", 1)[-1]
    mech = getattr(module, "MECHANISM", None)
    used = set()
    if isinstance(mech, Mechanism):
        used = {id(getattr(mech, f)) for f in FIELDS} | {id(mech.pose.to_study)}
    stale = [h for h in FORMER_HOOKS if hasattr(module, h) and id(getattr(module, h)) not in used]
    if not isinstance(mech, Mechanism):
        detail = f"module {module.__name__!r} defines no MECHANISM = declare(...)"
        if stale:
            detail += f" (it defines {stale}: the former hook names, read by nothing now)"
        raise MechanismDefinitionError(name, detail)
    if stale:
        raise MechanismDefinitionError(
            mech.name, f"module {module.__name__!r} defines {stale}, names of the former "
            "hook contract that the declaration does not use; the pipeline reads only "
            "MECHANISM = declare(...)")
    validate(mech)
    return mech
