"""The derivation's fixed stages; data flows one way, each stage returns new frozen results.

    build -> eliminate -> plan -> analyses -> specify -> generate -> import -> studies
          -> verify -> artifacts, report

* :func:`build`: the validated declaration (``bonered_alg.declaration``);
* :func:`eliminate`: the ideal of every leg (``solvers.legs``);
* :func:`plan`: inverse kinematics (back-substitution through the ideals), velocity model
  and singularity polynomials, forward kinematics (``solvers.closures``), passive-joint
  recovery (``kinematics.passive``);
* :func:`analyse`: the declaration's further derivations (``bonered_alg.analyses``);
* :func:`specify`: the pose map, limits and generated functions, from the results so far;
* :func:`generate`: the generated module's source (``bonered_alg.codegen``) and
  :func:`import_generated`, the module imported from that source;
* :func:`run_studies`, :func:`verify`: the paper studies and the paper checks, handed the
  generated module;
* :mod:`.outputs`: the report, the verification record and the files beside them.

No stage reads another's side effects; mechanisms never import this module.
"""

from __future__ import annotations

import importlib
import math
import time
from dataclasses import replace
from types import ModuleType

import sympy as sp

from .. import __version__
from ..algebra import polyring as pr
from ..declaration.mechanism import (
    ExtraGenerator,
    InputFunction,
    Limit,
    Mechanism,
    PoseFunction,
    load_declaration,
)
from ..errors import MechanismDefinitionError, NonClosingMechanismError
from ..kinematics.branches import negate_rows, orient
from ..kinematics.ik_plan import IKStep, joint_value_at
from ..kinematics.ik_plan import plan as plan_steps
from ..kinematics.passive import recover as recover_passive
from ..kinematics.singularities import FactoredPolynomial, discriminant, factored, large_product
from ..solvers.closures import forward_kinematics
from ..solvers.legs import leg_ideal
from ..verification import Verdict, in_ideal
from .algebra import Algebra
from .results import ClosureVelocity, Derivation, GeneratedModule, Study, frozen_map

GENERATOR = f"bonered_alg {__version__}"


# ------------------------------------------------------------------ build
def build(module: ModuleType) -> Mechanism:
    """The mechanism module's declaration, validated before any algebra."""
    return load_declaration(module)


# ------------------------------------------------------------------ eliminate
def eliminate(d: Derivation, algebra: Algebra) -> Derivation:
    """The ideal of every leg of every closure."""
    mech = d.mechanism
    legs, timings = [], dict(d.timings)
    for closure in mech.closures:
        for leg in closure.legs:
            t0 = time.perf_counter()
            r = leg_ideal(mech, closure, leg, algebra)
            what = "certify distance leg" if r.certificate else f"eliminate ({algebra.engine.name})"
            timings[f"{what} {leg.name}"] = time.perf_counter() - t0
            legs.append(r)
    return replace(d, legs=tuple(legs), timings=frozen_map(timings))


# ------------------------------------------------------------------ plan
def _extra_generators(d: Derivation) -> tuple[tuple[str, sp.Expr], ...]:
    """The declaration's extra IK generators, each proved to lie in its leg's ideal: its
    normal form modulo the leg's reduced grevlex basis is 0 (Cox-Little-O'Shea, Ch. 2
    Sect. 6, Corollary 2)."""
    mech = d.mechanism
    declared = mech.ik_generators(d) if callable(mech.ik_generators) else mech.ik_generators
    out = []
    as_symbols = {c.value: c.symbol for c in mech.constants}
    for extra in declared:
        if not isinstance(extra, ExtraGenerator):
            raise MechanismDefinitionError(mech.name, "ik_generators must give ExtraGenerator "
                                                      f"objects, got {type(extra).__name__}")
        r = d.leg(extra.leg)
        if not in_ideal(extra.generator.subs(as_symbols), r.result.generators,
                        r.problem.keep):
            raise NonClosingMechanismError(
                mech.name, f"an extra IK generator for leg {extra.leg!r} ({extra.note}) is "
                "not in the leg's ideal: its normal form is not 0")
        out.append((f"{r.closure.point}/{extra.leg} ({extra.note})", extra.generator))
    return tuple(out)


def _velocity_and_singularities(mech: Mechanism, steps: tuple[IKStep, ...]):
    out: list[FactoredPolynomial] = []
    velocity: list[ClosureVelocity] = []
    for closure in mech.actuated_closures:
        syms = set().union(*(leg.free_symbols for leg in closure.legs),
                           *(c.equation.free_symbols for c in closure.couplings))
        csteps = [s for s in steps if s.joint in syms]
        if not csteps:
            continue
        gens = sp.Matrix([s.generator for s in csteps])
        joints = sp.Matrix([s.joint for s in csteps])
        pose = [p for p in closure.pose if any(p in s.generator.free_symbols for s in csteps)]
        ji = pr.jacobian(list(gens), list(joints))  # Matrix.jacobian's expressions
        jo = pr.jacobian(list(gens), pose)
        velocity.append(ClosureVelocity(closure.name, tuple(joints), tuple(pose),
                                        sp.ImmutableMatrix(ji), sp.ImmutableMatrix(jo)))
        diag = [ji[i, i] for i in range(ji.shape[0])]
        det_ji = (sp.Mul(*diag, evaluate=False) if (ji.is_lower or ji.is_upper)
                  and large_product(diag) else ji.det(method="berkowitz"))
        out.append(factored(f"det_Ji_{closure.point}", det_ji,
                            f"input singularity of the {closure.name}: det dG/d("
                            + ", ".join(map(str, joints)) + ")", matrix=ji))
        if jo.shape[0] == jo.shape[1]:
            out.append(factored(f"det_Jo_{closure.point}", jo.det(method="berkowitz"),
                                f"output singularity of the {closure.name}: det dG/d("
                                + ", ".join(map(str, pose)) + ")", matrix=jo))
        else:
            out += _forward_matrix(closure, jo, pose)
        for s in csteps:
            if s.degree == 2:
                out.append(factored(
                    f"boundary_{s.joint}", discriminant(s.generator, s.joint),
                    f"discriminant of the generator in {s.joint}: the boundary of the "
                    f"reach of the leg driven by {s.joint} (two working modes merge)"))
    return tuple(velocity), tuple(out)


def _forward_matrix(closure, jo: sp.Matrix, pose: list) -> list[FactoredPolynomial]:
    """The forward (type II) singularity of a closure whose IK generators are one fewer
    than its Study coordinates (a 6-UPS in the chart x0 = 1: six legs, seven coordinates):
    Jo with the gradient of the Study quadric as a last row.  Its determinant vanishes
    where a velocity tangent to the Study quadric leaves every generator unchanged, i.e.
    where the leg lines are linearly dependent; it is a polynomial of high degree, so the
    generated code evaluates the matrix and its determinant numerically."""
    from ..algebra.study_symbolic import quadric

    quad = sp.expand(quadric(closure.platform))
    if jo.shape[1] != jo.shape[0] + 1 or not quad.free_symbols or not (
            quad.free_symbols <= set(pose)):
        return []
    m = sp.ImmutableMatrix(jo.col_join(sp.Matrix([[sp.diff(quad, y) for y in pose]])))
    return [FactoredPolynomial(
        f"det_forward_{closure.point}", m, sp.Integer(1), (),
        f"forward (type II) singularity of the {closure.name}: det of dG/d("
        + ", ".join(map(str, pose)) + ") with the Study quadric's gradient as last row "
        "(zero where the leg lines are linearly dependent and the platform gains a motion "
        "with the actuators locked)")]


def _home_probe(mech: Mechanism) -> tuple[dict | None, dict]:
    """The Study coordinates and parameters at the declared home pose (for the planner's
    test that a generator does not vanish identically there), and the declared joint
    values in the algebra's variables; no probe where the pose map needs the derivation."""
    declared = {q: (math.tan(v / 2) if q in mech.angle_joints else v)
                for q, v in mech.home_joints.items()}
    if not mech.home or callable(mech.pose.to_study):
        return None, declared
    at = {s: sp.nsimplify(v) for s, v in zip(mech.pose.coordinates, mech.home)}
    values = {p.symbol: sp.nsimplify(p.value) for p in mech.parameters}
    values |= {c.symbol: c.value for c in mech.constants}
    probe = {k: sp.sympify(v).xreplace(at).xreplace(values)
             for k, v in mech.pose.to_study.items()}
    return probe | values, declared


def _joints_at(steps, probe, declared) -> dict | None:
    """``probe`` with the joints at home (the declared roots, else the +sqrt ones), or
    None where a step has no real finite root there."""
    if probe is None:
        return None
    out = dict(probe)
    for st in steps:
        value = joint_value_at(st, out, declared.get(st.joint))
        if value is None:
            return None
        out[st.joint] = value
    return out


def plan(d: Derivation, algebra: Algebra) -> Derivation:
    """Inverse kinematics, velocity model, singularity polynomials, forward kinematics."""
    mech = d.mechanism
    t0 = time.perf_counter()
    extra = _extra_generators(d)
    pool = [(f"{r.closure.point}/{r.leg.name}", g) for r in d.legs
            if not r.closure.driven for g in r.generators]
    pool += list(extra)
    probe, declared = _home_probe(mech)
    steps = tuple(plan_steps(pool, mech.joints, f"mechanism {mech.name!r}: inverse "
                             "kinematics", {c.symbol: c.value for c in mech.constants},
                             probe, declared))
    velocity, sing = _velocity_and_singularities(mech, steps)
    timings = dict(d.timings)
    timings["ik plan, Jacobians, singularities"] = time.perf_counter() - t0
    t1 = time.perf_counter()
    if mech.forward_kinematics:
        fk, fk_note = (), mech.forward_kinematics
    else:
        fk, fk_note = forward_kinematics(mech, d.legs, algebra)
    timings["forward kinematics"] = time.perf_counter() - t1
    sing += tuple(f.singularity for f in fk if f.singularity is not None)
    t2 = time.perf_counter()
    passive = recover_passive(mech, algebra, _joints_at(steps, probe, declared))
    timings["passive-joint recovery"] = time.perf_counter() - t2
    return replace(d, steps=steps, extra_generators=extra, velocity=velocity,
                   singularities=sing, fk=fk, fk_note=fk_note, passive=passive,
                   timings=frozen_map(timings))


# ------------------------------------------------------------------ analyses
def analyse(d: Derivation, algebra: Algebra) -> Derivation:
    """The declaration's analyses, in order (each sees the results before it)."""
    timings = dict(d.timings)
    for a in d.mechanism.analyses:
        t0 = time.perf_counter()
        result = a.run(d, algebra)
        d = replace(d, analyses=frozen_map({**d.analyses, a.name: result}))
        timings[f"analysis {a.name}"] = time.perf_counter() - t0
    return replace(d, timings=frozen_map(timings))


# ------------------------------------------------------------------ specify
def _derived(value, d):
    return tuple(value(d) if callable(value) else value)


def driven_closure_functions(d: Derivation) -> tuple[InputFunction, ...]:
    """Generated functions of each driven closure's ideal G: its input and output Jacobians
    (as in 004 eq. 21), the dual part of its point where G's linear generators give it, and
    every generator (the residuals, zero on the closure's configurations)."""
    out = []
    for closure in d.mechanism.closures:
        if not closure.driven:
            continue
        px, inputs, name = tuple(closure.pose), tuple(closure.inputs), closure.point
        g = d.closure_generators(closure.point)
        rows = len(g)
        src = f" ({closure.source})" if closure.source else ""
        ji = sp.Matrix(g).jacobian(sp.Matrix(inputs))
        jo = sp.Matrix(g).jacobian(sp.Matrix(px))
        out += [
            InputFunction(f"{name}_input_jacobian", inputs + px, tuple(
                f"dg{i + 1}/d{v}" for i in range(rows) for v in inputs), tuple(ji),
                f"Ji = dG/d({', '.join(map(str, inputs))}) of the {closure.name}'s ideal "
                f"G{src}, row-major ({rows} x {len(inputs)})."),
            InputFunction(f"{name}_output_jacobian", inputs + px, tuple(
                f"dg{i + 1}/d{v}" for i in range(rows) for v in px), tuple(jo),
                f"Jo = dG/d({', '.join(map(str, px))}) of the {closure.name}'s ideal G{src}, "
                f"row-major ({rows} x {len(px)})."),
        ]
        lin = [e for e in g if sp.Poly(e, *px).total_degree() == 1]
        sol = sp.solve(lin, px[4:], dict=True) if lin else []
        if len(sol) == 1 and set(sol[0]) == set(px[4:]):
            dual = tuple(sp.expand(sol[0][y]) for y in px[4:])
            used = [s for s in inputs if any(e.has(s) for e in dual)]
            out.append(InputFunction(
                f"{name}_dual", (*px[:4], *used), tuple(str(y) for y in px[4:]), dual,
                f"Dual part ({', '.join(map(str, px[4:]))}) of the {closure.name}'s Study "
                f"point from its rotation ({', '.join(map(str, px[:4]))}) and "
                f"({', '.join(map(str, used))}): the linear generators of G solved{src}."))
        out.append(InputFunction(
            f"{name}_residuals", inputs + px, tuple(f"g{k}" for k in range(1, rows + 1)),
            tuple(g), f"Generators of the {closure.name}'s ideal G{src} at the inputs and a "
            "Study point: all zero on its configurations."))
    return tuple(out)


def specify(d: Derivation) -> Derivation:
    """The pose map, limits and generated functions the declaration derives from results."""
    mech = d.mechanism
    to_study = mech.pose.to_study(d) if callable(mech.pose.to_study) else mech.pose.to_study
    needed = {s for st in d.steps for s in st.generator.free_symbols} & {
        s for c in mech.closures for s in c.pose}
    missing = sorted(map(str, needed - set(to_study)))
    if missing:
        raise MechanismDefinitionError(mech.name, f"the pose map gives no expression for the "
                                                  f"Study coordinate(s) {missing} the IK uses")
    d = replace(d, pose_to_study=frozen_map(to_study))
    limits = _derived(mech.limits, d)
    pose_functions = _derived(mech.pose_functions, d)
    functions = _derived(mech.functions, d) + driven_closure_functions(d)
    for obj, cls in [(x, Limit) for x in limits] + [(x, PoseFunction) for x in pose_functions] \
            + [(x, InputFunction) for x in functions]:
        if not isinstance(obj, cls):
            raise MechanismDefinitionError(mech.name, f"expected {cls.__name__} objects, got "
                                                      f"{type(obj).__name__}")
    names = [f.name for f in pose_functions + functions]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise MechanismDefinitionError(mech.name, f"generated function name(s) {dup} twice")
    known = {s.name for s in d.singularities}
    stray = sorted(set(mech.singularity_notes) - known)
    if stray:
        raise MechanismDefinitionError(mech.name, f"singularity_notes name {stray}, which are "
                                                  f"not derived (derived: {sorted(known)})")
    d = replace(d, limits=limits, pose_functions=pose_functions, functions=functions)
    return physical_branch(d)


def physical_branch(d: Derivation) -> Derivation:
    """Mode 0 as the declared physical branch (:mod:`..kinematics.branches`): negated
    generators where needed, and the matching rows of Ji and Jo."""
    mech = d.mechanism
    values = {p.symbol: p.value for p in mech.parameters} | d.constants
    declared = _home_probe(mech)[1]  # an angle joint's is its angle's tan-half
    steps, branches = orient(mech.name, d.steps, d.pose_to_study, mech.pose.coordinates,
                             mech.home, declared, values)
    flipped = {b.joint for b in branches if b.negated}
    velocity = tuple(
        replace(v, ji=negate_rows(v.ji, rows), jo=negate_rows(v.jo, rows))
        for v in d.velocity
        for rows in [[i for i, q in enumerate(v.joints) if q in flipped]])
    return replace(d, steps=steps, velocity=velocity, branches=branches)


# ------------------------------------------------------------------ generate, import
def generate(d: Derivation) -> GeneratedModule:
    """The generated module's source (``bonered_alg.codegen.module``)."""
    from ..codegen.module import module_source

    return module_source(d, GENERATOR)


def import_generated(gm: GeneratedModule) -> GeneratedModule:
    """The generated module imported from its source (our own output), not from disk."""
    module = ModuleType(f"bonered_alg.generated.{gm.name}")
    exec(compile(gm.source, f"<generated {gm.name}>", "exec"), module.__dict__)  # noqa: S102
    return replace(gm, module=module)


# ------------------------------------------------------------------ studies, verification
def run_studies(d: Derivation, gm: GeneratedModule) -> dict[str, Study]:
    """Each study module named by the declaration, run on the generated module."""
    out = {}
    if d.mechanism.home and getattr(gm.module, "LINKS", ()):
        from ..studies import configurations, mobility

        out["configurations"] = configurations.run(d, gm.module)
        out["mobility"] = mobility.run(d, gm.module)
    for ref in d.mechanism.studies:
        study = importlib.import_module(ref).run(d, gm.module)
        if not isinstance(study, Study):
            raise MechanismDefinitionError(d.mechanism.name, f"study {ref!r} returned "
                                                             f"{type(study).__name__}, not Study")
        out[study.name] = study
    return out


def verify(d: Derivation, gm: GeneratedModule, studies: dict[str, Study]) -> tuple[Verdict, ...]:
    """The paper checks of the declaration's ``checks`` module (DESIGN.md section 5)."""
    if not d.mechanism.checks:
        return ()
    verdicts = importlib.import_module(d.mechanism.checks).verify(d, gm.module, studies)
    bad = [v for v in verdicts if not isinstance(v, Verdict)]
    if bad:
        raise MechanismDefinitionError(d.mechanism.name, f"{d.mechanism.checks}.verify gave "
                                                         f"{type(bad[0]).__name__}, not Verdict")
    return tuple(verdicts)


def report_sections(d: Derivation, studies: dict[str, Study]) -> list[str]:
    """Report sections contributed by the analyses, the checks module and the studies."""
    out: list[str] = []
    for a in d.mechanism.analyses:
        out += a.report(d.analyses[a.name])
    if d.mechanism.checks:
        extra = getattr(importlib.import_module(d.mechanism.checks), "report_sections", None)
        if callable(extra):
            out += extra(d, studies)
    for s in studies.values():
        out += list(s.report)
    return out
