"""The derivation pipeline: mechanism -> elimination -> IK/Jacobians/singularities -> files.

:func:`derive` computes everything in memory; :func:`write` then writes
``generated/<name>.py``, ``derivations/<name>.tex`` and ``derivations/<name>.verification.json``
atomically, only after every step has succeeded, so a failing derivation leaves both folders
untouched.  :func:`derive_all` skips a mechanism whose outputs already carry its current
derivation hash.
"""

from __future__ import annotations

import ast
import hashlib
import json
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType

import sympy as sp

from . import __version__
from .algebra.study_symbolic import quadric
from .chains.joints import Leg
from .chains.mechanism import Closure, Mechanism
from .codegen.ik_module import IKModuleSpec, write_ik_module
from .elimination import polyterms as pt
from .elimination import sphere_leg
from .elimination.cache import eliminate, lex_basis
from .elimination.closure import MU, leg_problem
from .elimination.engines import DEFAULT_BUDGET_S, Engine, get_engine
from .elimination.problem import (
    EliminationProblem,
    EliminationResult,
    ParametricProblem,
    ParametricResult,
)
from .errors import EngineTimeoutError, NonClosingMechanismError
from .fileio import atomic_write_bytes, atomic_write_text
from .kinematics.ik_plan import IKStep, mode_count, plan
from .kinematics.rps_forward import (
    DEGREE_BOUND,
    RPSSystem,
    angles_from_platform,
    count_solutions,
    forward_singularity,
    rps_system,
)
from .kinematics.singularities import (
    FactoredPolynomial,
    discriminant,
    factored,
    large_product,
)
from .mechanisms import REGISTRY, load
from .verification import Verdict, algebra_verdicts, in_ideal

PACKAGE_DIR = Path(__file__).resolve().parent
GENERATOR = f"bonered_alg {__version__}"


@dataclass
class LegResult:
    """One leg: its chain product, closure equations and elimination result."""

    closure: Closure
    leg: Leg
    product: tuple[sp.Expr, ...]
    problem: EliminationProblem
    result: EliminationResult
    certificate: str = ""  # closed-form leg ideal (sphere_leg): why no elimination was run


@dataclass(frozen=True)
class ClosureVelocity:
    """Ji = dG/dq and Jo = dG/dy of one closure (004 eq. 19-20), rows = IK generators."""

    closure: str
    joints: tuple[sp.Symbol, ...]
    pose: tuple[sp.Symbol, ...]
    ji: sp.Matrix
    jo: sp.Matrix


@dataclass(frozen=True)
class ClosureFK:
    """Forward kinematics of one closure: lex basis over Q(joints, geometry) and its plan, or
    (3-RPS closures) the circle-distance system solved through its eliminant, with the
    solution count certified by a Groebner basis at a generic configuration."""

    closure: str
    problem: ParametricProblem
    result: ParametricResult
    dimension: int
    solutions: int | None
    steps: tuple[IKStep, ...]
    rps: RPSSystem | None = None
    count_at: dict | None = None  # the generic configuration of the RPS solution count
    singularity: FactoredPolynomial | None = None  # RPS: where two assembly modes merge


@dataclass
class Derivation:
    """Everything derived for one mechanism (symbolic; nothing written yet)."""

    mechanism: Mechanism
    module: ModuleType
    derivation_hash: str
    legs: list[LegResult]
    steps: list[IKStep]
    singularities: list[FactoredPolynomial]
    velocity: list[ClosureVelocity] = field(default_factory=list)
    fk: list[ClosureFK] = field(default_factory=list)
    verification: list[Verdict] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    fk_note: str = ""
    extra: dict = field(default_factory=dict)  # mechanism-specific analyses (module.analyses)
    pose_to_study: dict = field(default_factory=dict)

    @property
    def constants(self) -> dict[sp.Symbol, sp.Expr]:
        return {c.symbol: c.value for c in self.mechanism.constants}

    def leg(self, name: str) -> LegResult:
        return next(r for r in self.legs if r.leg.name == name)

    @property
    def modes(self) -> int:
        return mode_count(self.steps)

    def ik_expressions(self, mode: int = 0) -> dict[sp.Symbol, sp.Expr]:
        """The IK of every joint as one sympy expression of the pose (constants inserted):
        the reference the generated code is checked and benchmarked against."""
        sub = {k: sp.sympify(v).subs(self.constants) for k, v in self.pose_to_study.items()}
        out: dict[sp.Symbol, sp.Expr] = {}
        bit = 0
        for st in self.steps:
            a, b, c = (sp.sympify(e).subs(self.constants).xreplace(sub)
                       for e in (st.A, st.B, st.C))
            if st.degree == 1:
                out[st.joint] = -c / b
                continue
            sign = -1 if (mode >> bit) & 1 else 1
            bit += 1
            out[st.joint] = (-b + sign * sp.sqrt(b**2 - 4 * a * c)) / (2 * a)
        return out


# package folders that shape only the mechanisms naming them in ``USES_PACKAGES``
OPTIONAL_PACKAGES = ("surgical",)


def declared_packages(module_path: Path) -> set[str]:
    """The optional package folders a mechanism module names in ``USES_PACKAGES`` (read
    with ``ast``, without importing the module)."""
    if not module_path.is_file():
        return set()
    for node in ast.parse(module_path.read_text()).body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "USES_PACKAGES" for t in node.targets):
            return set(ast.literal_eval(node.value))
    return set()


def derivation_hash(name: str, package_dir: Path = PACKAGE_DIR,
                    module_file: str | None = None) -> str:
    """SHA-256 of every source file that shapes ``name``'s outputs (engine excluded).

    That is the whole package except the command line, the workspace tool (it reads the
    generated modules, it does not shape them), the *other* mechanism modules, so editing
    one mechanism re-derives only that one, and the optional packages (``OPTIONAL_PACKAGES``)
    the mechanism does not name in ``USES_PACKAGES``.  The engine is excluded on purpose:
    both engines return the same normalized basis (``tests/test_engines_agree.py``).
    ``module_file`` adds a mechanism module that lives outside the package.
    """
    h = hashlib.sha256(f"{GENERATOR}\n".encode())
    uses = declared_packages(package_dir / "mechanisms" / f"{name}.py")
    if module_file and not Path(module_file).resolve().is_relative_to(package_dir):
        h.update(Path(module_file).read_bytes())
        uses |= declared_packages(Path(module_file))
    for path in sorted(package_dir.rglob("*.py")):
        rel = path.relative_to(package_dir).as_posix()
        if rel.startswith("mechanisms/") and rel not in ("mechanisms/__init__.py",
                                                          f"mechanisms/{name}.py"):
            continue
        if rel in ("cli.py",) or rel.startswith("workspace/"):
            continue
        if any(rel.startswith(f"{p}/") and p not in uses for p in OPTIONAL_PACKAGES):
            continue
        h.update(rel.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def _velocity_and_singularities(mech: Mechanism, steps: list[IKStep]):
    out: list[FactoredPolynomial] = []
    velocity: list[ClosureVelocity] = []
    for closure in mech.closures:
        syms = set().union(*(leg.free_symbols for leg in closure.legs),
                           *(c.equation.free_symbols for c in closure.couplings))
        csteps = [s for s in steps if s.joint in syms]
        if not csteps:
            continue
        gens = sp.Matrix([s.generator for s in csteps])
        joints = sp.Matrix([s.joint for s in csteps])
        pose = [p for p in closure.pose if any(p in s.generator.free_symbols for s in csteps)]
        ji = gens.jacobian(joints)
        jo = gens.jacobian(sp.Matrix(pose))
        velocity.append(ClosureVelocity(closure.name, tuple(joints), tuple(pose), ji, jo))
        diag = [ji[i, i] for i in range(ji.shape[0])]
        det_ji = (sp.Mul(*diag, evaluate=False) if (ji.is_lower or ji.is_upper)
                  and large_product(diag) else ji.det(method="berkowitz"))
        out.append(factored(f"det_Ji_{closure.point}", det_ji,
                            f"input singularity of the {closure.name}: det dG/d("
                            + ", ".join(map(str, joints)) + ")"))
        if jo.shape[0] == jo.shape[1]:
            out.append(factored(f"det_Jo_{closure.point}", jo.det(method="berkowitz"),
                                f"output singularity of the {closure.name}: det dG/d("
                                + ", ".join(map(str, pose)) + ")"))
        for s in csteps:
            if s.degree == 2:
                out.append(factored(
                    f"boundary_{s.joint}", discriminant(s.generator, s.joint),
                    f"discriminant of the generator in {s.joint}: the boundary of the "
                    f"reach of the leg driven by {s.joint} (two working modes merge)"))
    return velocity, out


FK_BUDGET_S = 120.0


def _forward_kinematics(mech: Mechanism, legs: list[LegResult], engine: Engine,
                        budget_s: float, use_cache: bool) -> tuple[list[ClosureFK], str]:
    """Per closure: lex basis of the union of its leg ideals in the pose unknowns over
    Q(active joints, geometry); zero-dimensional -> finitely many assembly modes, solved by
    back-substitution.  Returns ([], reason) when some closure cannot be solved that way."""
    out = []
    for closure in mech.closures:
        gens = [g for r in legs if r.closure is closure for g in r.result.generators]
        rps = rps_system(mech, closure)
        if rps is not None and any(f.rps for f in out):
            return [], "more than one 3-RPS closure: the code generator solves one per mechanism"
        if rps is not None:
            if tuple(closure.platform) != (1, *closure.pose):
                return [], (f"the {closure.name} is a 3-RPS closure, but its point is not in "
                            "the chart x0 = 1 the 3-RPS forward kinematics writes")
            count, at = count_solutions(rps, mech, engine, min(budget_s, FK_BUDGET_S),
                                        use_cache)
            if count != DEGREE_BOUND:
                return [], (f"the {closure.name} has {count} forward-kinematics solutions at "
                            f"a generic configuration, not the {DEGREE_BOUND} of the iterated "
                            "resultant: its eliminant would carry extraneous roots")
            problem = ParametricProblem(
                f"mechanism {mech.name!r}, closure {closure.name!r}: forward kinematics "
                "(circle-distance system)", rps.equations, rps.angles, rps.joints)
            det = forward_singularity(rps)
            sing = factored(
                f"det_forward_{closure.point}", det,
                f"forward (type II) singularity of the {closure.name}: det d(e12, e23, e31)/d("
                + ", ".join(map(str, rps.angles)) + "), zero where two assembly modes merge "
                "and the platform moves infinitesimally with the legs locked",
                evaluate=det.subs(angles_from_platform(rps, closure.platform)))
            out.append(ClosureFK(closure.name, problem, None, 0, count, (), rps, at, sing))
            continue
        syms = set().union(*(g.free_symbols for g in gens))
        # rotation coordinates last: for fixed rotation the closure equations are mostly
        # linear in the dual part, so the univariate polynomial of the lex basis is in the
        # rotation and the translation follows linearly (with pivots that do not vanish at
        # symmetric configurations such as equal strokes, which the reverse order gave)
        primal = set().union(*(sp.sympify(c).free_symbols for c in closure.platform[:4]))
        pose_unknowns = tuple(sorted((y for y in closure.pose if y in syms),
                                     key=lambda y: y in primal))
        # algebraic constants are the last (lowest) unknowns, bound by their minimal
        # polynomials; they are not solved for but substituted (generators stay valid)
        consts = [c for c in mech.constants if c.symbol in syms]
        unknowns = pose_unknowns + tuple(c.symbol for c in consts)
        params = tuple(s for s in (*mech.active, *mech.geometric) if s in syms)
        problem = ParametricProblem(
            f"mechanism {mech.name!r}, closure {closure.name!r}: forward kinematics",
            tuple(dict.fromkeys(gens + [sp.expand(c.minimal_polynomial) for c in consts])),
            unknowns, params)
        try:
            result = lex_basis(problem, engine, min(budget_s, FK_BUDGET_S), use_cache)
        except EngineTimeoutError:
            return [], (f"the lex basis of the {closure.name} exceeded its budget of "
                        f"{min(budget_s, FK_BUDGET_S):g} s")
        n = len(unknowns)
        leading = [max(e[:n] for e, _ in p) for p in result.basis]
        dim = pt.dimension_from_leading_monomials(leading, n)
        if dim != 0:
            return [], (f"the ideal of the {closure.name} has dimension {dim} over the field "
                        "of joints and geometry: no finite set of assembly modes")
        count = pt.count_standard_monomials(leading, n)
        for c in consts:
            count //= int(sp.degree(c.minimal_polynomial, c.symbol))
        const_syms = {c.symbol for c in consts}
        pool = [(f"lex basis of the {closure.name}", g) for g in result.generators
                if not g.free_symbols <= const_syms | set(params)]
        try:
            steps = plan(pool, pose_unknowns, problem.context)
        except NotImplementedError as exc:
            return [], (f"{exc} ({count} solutions; univariate steps of higher degree are "
                        "not generated yet)")
        out.append(ClosureFK(closure.name, problem, result, dim, count, tuple(steps)))
    return out, ""


def _extra_ik_generators(module: ModuleType, mech: Mechanism,
                         legs: list[LegResult]) -> list[tuple[str, sp.Expr]]:
    """Generators a mechanism module adds to the IK pool (``extra_ik_generators``), each
    proved to lie in its leg's ideal: its normal form modulo the leg's reduced grevlex
    basis must be 0 (Cox-Little-O'Shea, Ch. 2 Sect. 6, Corollary 2)."""
    if not callable(getattr(module, "extra_ik_generators", None)):
        return []
    out = []
    for leg_name, gen, note in module.extra_ik_generators(legs):
        r = next(r for r in legs if r.leg.name == leg_name)
        keep = r.problem.keep
        as_symbols = {c.value: c.symbol for c in mech.constants}
        if not in_ideal(gen.subs(as_symbols), r.result.generators, keep):
            raise NonClosingMechanismError(
                mech.name, f"an extra IK generator for leg {leg_name!r} ({note}) is not in "
                "the leg's ideal: its normal form is not 0")
        out.append((f"{r.closure.point}/{leg_name} ({note})", gen))
    return out


def _distance_leg_problem(mech: Mechanism, closure: Closure,
                          leg: Leg) -> tuple[EliminationProblem | None, str]:
    """For a leg that only fixes a distance (U-P-S, S-P-S), the problem whose reduced basis
    is its ideal ``<Study quadric, sphere condition>`` without eliminating anything, and the
    certificate that this is the leg's ideal (:mod:`.elimination.sphere_leg`); (None, "")
    for any other leg, which is eliminated."""
    d = sphere_leg.recognize(leg)
    if d is None:
        return None, ""
    full = leg_problem(mech, closure, leg)
    passive = tuple(s for s in full.eliminate if s != MU)
    params = {sp.Symbol(n, real=True): sp.nsimplify(p.value)
              for n, p in mech.parameters.items() if p.value is not None}
    consts = {c.symbol: c.value for c in mech.constants}
    try:
        note = sphere_leg.certify(leg, d, closure.platform, passive, params, consts)
    except sphere_leg.NotADistanceLeg:
        return None, ""
    eqs = (quadric(closure.platform),
           sphere_leg.sphere_condition(d, closure.platform,
                                       sphere_leg.minimal_polynomials(consts)))
    eqs += tuple(sp.expand(c.minimal_polynomial) for c in mech.constants
                 if c.symbol in full.keep)
    return EliminationProblem(full.context + " (closed-form distance-leg ideal)", eqs, (),
                              full.keep), note


def derive(name: str | ModuleType, engine: Engine | None = None,
           budget_s: float = DEFAULT_BUDGET_S, use_cache: bool = True) -> Derivation:
    """Derive a mechanism (registered name, or a mechanism module) completely, in memory."""
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    module = load(name) if isinstance(name, str) else name
    name = module.NAME
    mech = module.build()
    mech.validate()
    engine = engine or get_engine()
    legs: list[LegResult] = []
    for closure in mech.closures:
        for leg in closure.legs:
            t_leg = time.perf_counter()
            problem, certificate = _distance_leg_problem(mech, closure, leg)
            if certificate:
                timings[f"certify distance leg {leg.name}"] = time.perf_counter() - t_leg
            problem = problem or leg_problem(mech, closure, leg)
            result = eliminate(problem, engine, budget_s, use_cache)
            if result.is_unit_ideal:
                raise NonClosingMechanismError(
                    mech.name, f"leg {leg.name!r} cannot close on the platform point "
                    f"{closure.point} of the {closure.name}: its elimination ideal is <1> "
                    "(no pose satisfies the closure equations)")
            timings[f"eliminate {leg.name} ({engine.name})"] = result.seconds
            legs.append(LegResult(closure, leg, leg.product(), problem, result, certificate))
    pool = [(f"{r.closure.point}/{r.leg.name}", g) for r in legs for g in r.result.generators]
    pool += _extra_ik_generators(module, mech, legs)
    t1 = time.perf_counter()
    steps = plan(pool, module.JOINTS, f"mechanism {mech.name!r}: inverse kinematics",
                 {c.symbol: c.value for c in mech.constants})
    velocity, sing = _velocity_and_singularities(mech, steps)
    timings["ik plan, Jacobians, singularities"] = time.perf_counter() - t1
    t_fk = time.perf_counter()
    if getattr(module, "FORWARD_KINEMATICS_PENDING", ""):
        fk, fk_note = [], module.FORWARD_KINEMATICS_PENDING
    else:
        fk, fk_note = _forward_kinematics(mech, legs, engine, budget_s, use_cache)
    timings["forward kinematics (lex bases)"] = time.perf_counter() - t_fk
    dhash = derivation_hash(name, module_file=module.__file__)
    sing += [f.singularity for f in fk if f.singularity is not None]
    d = Derivation(mech, module, dhash, legs, steps, sing, velocity, fk, timings=timings,
                   fk_note=fk_note)
    if hasattr(module, "analyses"):
        t_extra = time.perf_counter()
        d.extra = module.analyses(d, engine, budget_s, use_cache)
        timings["mechanism-specific analyses"] = time.perf_counter() - t_extra
    d.pose_to_study = (module.pose_to_study(d) if callable(getattr(module, "pose_to_study", None))
                       else dict(module.POSE_TO_STUDY))
    t2 = time.perf_counter()
    d.verification = algebra_verdicts() + module.verify(d)
    timings["verification"] = time.perf_counter() - t2
    timings["total"] = time.perf_counter() - t0
    return d


def ik_module_source(d: Derivation) -> str:
    m = d.module
    spec = IKModuleSpec(
        name=d.mechanism.name, title=d.mechanism.title, source=d.mechanism.source,
        derivation_hash=d.derivation_hash, generator=GENERATOR,
        parameters=list(d.mechanism.parameters.values()), pose=m.POSE,
        pose_units=m.POSE_UNITS, pose_to_study=d.pose_to_study, joints=m.JOINTS,
        joint_units=m.JOINT_UNITS, steps=d.steps,
        singularities=[(s.name, s.expression if s.evaluate is None else s.evaluate, s.meaning)
                       for s in d.singularities],
        fk_steps=[s for f in d.fk for s in f.steps],
        rps=next((f.rps for f in d.fk if f.rps), None),
        rps_unknowns=next((_closure(d, f.closure).pose for f in d.fk if f.rps), ()),
        fk_unknowns=[s.joint for f in d.fk for s in f.steps],
        fk_system=[g for f in d.fk if not f.rps for g in f.problem.equations],
        study_to_pose=getattr(m, "STUDY_TO_POSE", None), constants=d.constants,
        fk_note=d.fk_note,
        limits=m.limits(d) if callable(getattr(m, "limits", None)) else (),
        pose_functions=(m.pose_functions(d) if callable(getattr(m, "pose_functions", None))
                        else ()),
        functions=m.functions(d) if callable(getattr(m, "functions", None)) else ())
    return write_ik_module(spec)


def _closure(d: Derivation, name: str) -> Closure:
    return next(c for c in d.mechanism.closures if c.name == name)


def verification_json(d: Derivation) -> str:
    return json.dumps([v.as_json() for v in d.verification], indent=2, sort_keys=True) + "\n"


def write(d: Derivation, root: Path) -> list[Path]:
    """Render every output first, then write them atomically; returns the changed files."""
    from .report.latex_report import render_report

    source = ik_module_source(d)
    outputs: dict[Path, str | bytes] = {
        root / "generated" / f"{d.mechanism.name}.py": source,
        root / "derivations" / f"{d.mechanism.name}.tex": render_report(d),
        root / "derivations" / f"{d.mechanism.name}.verification.json": verification_json(d),
    }
    if hasattr(d.module, "artifacts"):
        generated = load_generated(source, d.mechanism.name)
        for rel, content in d.module.artifacts(d, generated).items():
            outputs[root / "derivations" / rel] = content
    return [p for p, content in outputs.items()
            if (atomic_write_bytes if isinstance(content, bytes) else atomic_write_text)(
                p, content)]


def load_generated(source: str, name: str) -> ModuleType:
    """Import generated module source (our own output) without writing it anywhere."""
    module = ModuleType(f"bonered_alg.generated.{name}")
    exec(compile(source, f"<generated {name}>", "exec"), module.__dict__)  # noqa: S102
    return module


_HASH_RE = re.compile(r"^DERIVATION_HASH = '([0-9a-f]{64})'$", re.M)


def recorded_hash(root: Path, name: str) -> str | None:
    """The derivation hash recorded in ``generated/<name>.py`` and the report, if they agree."""
    gen = root / "generated" / f"{name}.py"
    tex = root / "derivations" / f"{name}.tex"
    js = root / "derivations" / f"{name}.verification.json"
    if not (gen.is_file() and tex.is_file() and js.is_file()):
        return None
    m = _HASH_RE.search(gen.read_text())
    if not m or m.group(1) not in tex.read_text():
        return None
    return m.group(1)


def derive_all(root: Path, names: list[str] | None = None, force: bool = False,
               engine: Engine | None = None, log=print) -> dict[str, str]:
    """Derive and write each mechanism whose outputs are missing or out of date."""
    status = {}
    for name in names or list(REGISTRY):
        current = derivation_hash(name)
        if not force and recorded_hash(root, name) == current:
            log(f"{name}: up to date ({current[:12]})")
            status[name] = "up to date"
            continue
        t0 = time.perf_counter()
        d = derive(name, engine=engine)
        changed = write(d, root)
        log(f"{name}: derived in {time.perf_counter() - t0:.1f} s; wrote "
            + (", ".join(str(p.relative_to(root)) for p in changed) or "nothing new"))
        status[name] = "derived"
    return status
