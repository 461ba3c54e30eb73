"""Assemble a generated numpy module (DESIGN.md section 4) from derived symbolic results.

The module text comes from ``templates/module.py.j2`` (rendered strictly); its kernels from
:mod:`.kernels` (one common-subexpression elimination per kernel); its algorithms are the
runtime's (:mod:`bonered_alg.runtime`), which the module imports.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from ..algebra import polyring as pr
from ..declaration.parameters import Parameter
from ..kinematics.ik_plan import IKStep
from ..kinematics.rps_forward import DEGREE_BOUND, RPSSystem
from ..solvers.closures import RPSEliminant
from .c_module import c_module
from .kernels import (
    Kernel,
    Program,
    kernel,
    leaner_outputs,
    numpy_function,
    shareable_functions,
    shared_functions,
)
from .template import render


@dataclass(frozen=True)
class IKModuleSpec:
    """Everything a generated IK module needs; symbolic, built by the pipeline."""

    name: str
    title: str
    source: str
    derivation_hash: str
    generator: str
    parameters: Sequence[Parameter]
    pose: Sequence[sp.Symbol]
    pose_units: Sequence[str]
    pose_to_study: dict[sp.Symbol, sp.Expr]
    joints: Sequence[sp.Symbol]
    joint_units: Sequence[str]
    steps: Sequence[IKStep]
    singularities: Sequence[tuple[str, sp.Expr, str]]
    fk_steps: Sequence[IKStep] = ()
    fk_unknowns: Sequence[sp.Symbol] = ()
    # other plans for the same fk_unknowns (lex bases in other elimination orders)
    fk_charts: Sequence[Sequence[IKStep]] = ()
    study_to_pose: dict[sp.Symbol, sp.Expr] | None = None
    fk_system: Sequence[sp.Expr] = ()  # leg generators, for Gauss-Newton polishing of fk
    constants: dict[sp.Symbol, sp.Expr] | None = None  # algebraic constants -> exact values
    fk_note: str = ""  # why there is no forward kinematics, when there is none
    # (name, expression in POSE/JOINTS/parameters, lower, upper, kind, unit, source)
    limits: Sequence[tuple] = ()
    # mechanism-specific functions of the pose: (name, output names, expressions, doc)
    pose_functions: Sequence[tuple] = ()
    # mechanism-specific functions of other inputs: (name, input symbols, output names,
    # expressions, doc), e.g. the Study point of a platform from the closures' points
    functions: Sequence[tuple] = ()
    # a 3-RPS closure solved through its eliminant (kinematics.rps_forward.RPSSystem) and the
    # closure's Study coordinates (chart x0 = 1), which come first in the arguments of _fk_pose
    rps: RPSSystem | None = None
    rps_unknowns: Sequence[sp.Symbol] = ()
    # passive-joint recovery per leg (kinematics.passive.LegRecovery)
    passive: Sequence = ()
    # the end effector's Study point in the pose coordinates (for the twist), or None
    end_effector: Sequence[sp.Expr] | None = None
    # helical couplings (chains.joints.HelicalCoupling) of the legs
    helical: Sequence = ()
    # the joints' names for users (an angle joint's, whose algebra variable is tan(q/2))
    public_joints: Sequence[str] = ()
    # unit of each passive joint variable
    passive_units: dict | None = None
    # legs of the actuated closures: (closure base body, leg) for the link poses, and the
    # algebraic constants their factors use
    link_legs: Sequence = ()
    # the declared home pose (POSE order) or None, and (joint, value) of the physical branch
    home: tuple | None = None
    physical_branch: tuple = ()
    link_constants: dict | None = None
    # link weights for the static model (declaration.weights.LinkWeight)
    link_weights: Sequence = ()
    # IK steps of distance legs in their geometric form (joint -> sphere_leg.CompactSphere),
    # proved equal to the step's generator: the kernels evaluate these, not the expansions
    compact: dict | None = None
    # IK steps whose stroke is proved to be the distance between two points of its leg
    # (joint -> kinematics.leg_lines.LegLine): their Jacobian rows come from the leg's line
    leg_lines: dict | None = None


def _literal(value) -> str:
    return "None" if value is None else repr(float(value))


def _abs(e: sp.Expr) -> sp.Expr:
    """``|e|`` without sympy's simplification attempts (minutes on large expressions)."""
    return sp.Integer(0) if e == 0 else sp.Abs(e, evaluate=False)


def pose_map_rates(outputs: Sequence[sp.Expr], pose: Sequence[sp.Symbol], program: Program
                   ) -> tuple[list[sp.Expr], list[list[sp.Expr]]]:
    """``(values, rates)``: the ``outputs`` and ``d outputs_i / d pose_m`` (rows per output)
    as names of ``program``, by forward-mode differentiation of the outputs' common-
    subexpression program: each temporary is an entry, and so is each of its rates, the
    chain rule over the arguments of its own (small) expression.  The same derivatives as
    ``diff`` of the whole expression, the shared factors of a rational pose map shared,
    and nothing multiplied out: tripod_planar's Study map and its rates are about 820
    operations after CSE against 989 with the temporaries put back in (and 1,257 with
    ``diff`` of each output)."""
    pose = list(pose)
    subs, reduced = sp.cse([sp.sympify(e) for e in outputs], symbols=sp.numbered_symbols("_w"),
                           order="canonical")
    zero = sp.Integer(0)
    rates: dict[sp.Symbol, list[sp.Expr]] = {
        x: [sp.Integer(int(x == y)) for y in pose] for x in pose}
    value: dict[sp.Symbol, sp.Expr] = {}

    def named(e: sp.Expr) -> sp.Expr:
        """``e`` (over the pose and earlier entries) as an entry, with its rates."""
        sym = program.name(e)
        if sym.is_Symbol and sym not in rates:
            out = [zero] * len(pose)
            for a in sorted(e.free_symbols & rates.keys(), key=sp.default_sort_key):
                partial = None
                for m, r in enumerate(rates[a]):
                    if r != 0:
                        if partial is None:
                            partial = sp.diff(e, a)
                        out[m] += partial * r
            rates[sym] = [program.name(r) for r in out]
        return sym

    for sym, e in subs:
        value[sym] = named(e.xreplace(value))
    values = [named(sp.sympify(r).xreplace(value)) for r in reduced]
    return values, [rates.get(v, [zero] * len(pose)) for v in values]


# A leg line's frame (R, t and their rates) is built from its platform's Study point in the
# pose coordinates, each entry a reduced fraction.  Where that point is small (a Stewart
# platform's: 246 operations, planar_tripod's tripod on MP1: 173) the rows are far shorter
# than the chain rule through the generator (planar_tripod's Jacobian kernel: 308
# operations against 415); where it is a large rational function of the pose (tripod_planar's
# tripod, below the planar stage the pose describes: 6332) the chain rule through the named
# Study coordinates and their rates is shorter (that kernel: 1,291 operations; a frame built
# from those named values and their rates instead, tried: 1,570).
LEG_LINE_MAX_OPS = 1000


def _triangular_jacobian(steps: Sequence[IKStep], gens: Sequence[sp.Expr],
                         joints: Sequence[sp.Symbol], pose: Sequence[sp.Symbol],
                         sub: dict, lines: dict | None = None) -> tuple[list, Program]:
    """Pivots, row scales and ``dq/dX`` by forward substitution (004 eq. 19-21), and the
    program of named values (:class:`.kernels.Program`) they read.

    Generator ``k`` involves only joints solved at steps ``<= k``, so ``dG/dq`` in the solve
    order is lower triangular: ``dq_k/dX = -(dg_k/dX + sum_{j<k} dg_k/dq_j dq_j/dX) / d_k``
    with the pivot ``d_k = dg_k/dq_k``; ``det Ji = prod d_k``.  The generators are written in
    the Study coordinates ``sub`` maps to the pose, and ``dg/dX`` is taken by the chain rule,
    ``sum_i dg/ds_i ds_i/dX``, with the Study coordinates and their rates named values of
    the program (:func:`pose_map_rates`): differentiating the substituted generator instead
    multiplies out the pose map into every partial (the Stewart platform's kernel was 4x
    larger).  A step in ``lines`` (a stroke that is the distance between two points of its
    leg, whose generator involves its own stroke only) takes its row from the leg's line
    (:mod:`..kinematics.leg_lines`), with the same ratio of pivot to row scale, where its
    platform's Study point is a small function of the pose (``LEG_LINE_MAX_OPS``).
    """
    from ..kinematics import leg_lines

    program = Program()
    study = list(sub)
    values, ds = pose_map_rates([sub[s] for s in study], pose, program)
    at = dict(zip(study, values))

    def chain(partials: dict[int, sp.Expr], m: int) -> sp.Expr:
        """``sum_i partials[i] ds_i/dX_m``."""
        return sp.Add(*[a * ds[i][m] for i, a in partials.items() if ds[i][m] != 0])

    def partials(e: sp.Expr) -> dict[int, sp.Expr]:
        """``{i: de/ds_i}`` at the named Study coordinates, the non-zero ones."""
        out = {}
        for i, s in enumerate(study):
            if e.has(s):
                out[i] = sp.diff(e, s).xreplace(at)
        return out

    frames: dict[tuple, leg_lines.PlatformFrame | None] = {}
    rows: dict[sp.Symbol, list[sp.Expr]] = {}
    pivots, scales = [], []
    for st, g in zip(steps, gens):
        form = (lines or {}).get(st.joint)
        if form is not None and form.platform not in frames:
            point = [sp.sympify(c).xreplace(sub) for c in form.platform]
            frames[form.platform] = (leg_lines.platform_frame(point, pose)
                                     if pr.count_ops(point) <= LEG_LINE_MAX_OPS else None)
        if form is not None and frames[form.platform] is not None:
            d, scale, row = leg_lines.distance_row(frames[form.platform], form.base,
                                                   form.point, st.joint)
            rows[st.joint] = row
            pivots.append(d)
            scales.append(scale)
            continue
        d = sp.diff(g, st.joint).xreplace(at)
        dgs = partials(g)
        dgx = [chain(dgs, m) for m in range(len(pose))]
        row = []
        for m in range(len(pose)):
            acc = dgx[m] + sum(sp.diff(g, prev.joint).xreplace(at) * rows[prev.joint][m]
                               for prev in steps[: steps.index(st)])
            row.append(-acc / d)
        rows[st.joint] = row
        pivots.append(d)
        scales.append(_abs(d) + sum(_abs(e) for e in dgx))
    return pivots + scales + [e for q in joints for e in rows[q]], program


# A pose map of at most this many operations (the Study coordinates in the pose) may also
# be written out into the Jacobian's rows, and CSE finds the shorter program then (the
# Stewart platform's, planar_tripod's, the RCM's); a larger one is only named
# (tripod_planar's, about 20,000 operations: 1,291 operations named against 1,509 written
# out, and 0.6 s of CSE against 3.3 s).
WRITTEN_OUT_MAX_OPS = 2000


def _jacobian_kernel(spec: IKModuleSpec, gens: Sequence[sp.Expr], lean: dict,
                     args: Sequence[sp.Symbol], par: Sequence[sp.Symbol]) -> Kernel:
    """The kernel ``_jac`` of :func:`_triangular_jacobian`'s outputs, with the pose map's
    values and rates as named values of its program or, where the map is small
    (``WRITTEN_OUT_MAX_OPS``), written out into the outputs if that gives fewer operations
    after CSE."""
    doc = ("Pivots dG_k/dq_k, row scales, then dq/dX row-major (forward substitution: Ji "
           "is triangular in the solve order).")
    tri, program = _triangular_jacobian(spec.steps, gens, spec.joints, spec.pose, lean,
                                        spec.leg_lines)
    named = kernel("_jac", args, tri, doc, c=True, scalars=par, program=program.entries)
    if sum(pr.count_ops(e) for e in lean.values()) > WRITTEN_OUT_MAX_OPS:
        return named
    written = kernel("_jac", args, program.written_out(tri), doc, c=True, scalars=par)
    return written if written.operations <= named.operations else named


def _with_constants(spec: IKModuleSpec) -> IKModuleSpec:
    """The spec with every algebraic constant replaced by its exact value."""
    c = spec.constants

    def step(st: IKStep) -> IKStep:
        return IKStep(st.joint, sp.expand(sp.sympify(st.generator).xreplace(c)), st.degree,
                      sp.sympify(st.A).xreplace(c), sp.sympify(st.B).xreplace(c),
                      sp.sympify(st.C).xreplace(c), st.source)

    return IKModuleSpec(
        **{**spec.__dict__,
           "steps": [step(st) for st in spec.steps],
           "fk_steps": [step(st) for st in spec.fk_steps],
           "fk_charts": [[step(st) for st in chart] for chart in spec.fk_charts],
           "fk_system": [sp.sympify(g).xreplace(c) for g in spec.fk_system],
           "singularities": [(n, sp.sympify(e).xreplace(c), m) for n, e, m in spec.singularities],
           "limits": [(lim[0], sp.sympify(lim[1]).xreplace(c), *lim[2:]) for lim in spec.limits],
           "pose_functions": [(f[0], f[1], [sp.sympify(e).xreplace(c) for e in f[2]], f[3])
                              for f in spec.pose_functions],
           "functions": [(f[0], f[1], f[2], [sp.sympify(e).xreplace(c) for e in f[3]], f[4])
                         for f in spec.functions],
           "pose_to_study": {k: sp.sympify(v).xreplace(c) for k, v in spec.pose_to_study.items()},
           "study_to_pose": ({k: sp.sympify(v).xreplace(c) for k, v in spec.study_to_pose.items()}
                             if spec.study_to_pose else None),
           "rps": _rps_with_constants(spec.rps, c) if spec.rps else None,
           "passive": [_recovery_with_constants(r, c) for r in spec.passive],
           "end_effector": (tuple(sp.sympify(e).xreplace(c) for e in spec.end_effector)
                            if spec.end_effector else None),
           "constants": None})


def _recovery_with_constants(rec, c: dict):
    from dataclasses import replace

    from ..kinematics.passive import LinearStep, QuadraticStep, SphericalStep

    steps = []
    for st in rec.steps:
        if isinstance(st, LinearStep):
            steps.append(LinearStep(st.variable, tuple((sp.sympify(b).xreplace(c),
                                                        sp.sympify(k).xreplace(c))
                                                       for b, k in st.candidates)))
        elif isinstance(st, QuadraticStep):
            steps.append(QuadraticStep(st.variable, tuple(sp.sympify(e).xreplace(c)
                                                          for e in st.coefficients)))
        else:
            steps.append(SphericalStep(st.variables, tuple(sp.sympify(e).xreplace(c)
                                                           for e in st.rotation)))
    return replace(rec, steps=tuple(steps))


def _rps_with_constants(rps: RPSSystem, c: dict) -> RPSSystem:
    def sub(e):
        return sp.sympify(e).xreplace(c)

    return RPSSystem(
        rps.closure, rps.angles, rps.joints,
        tuple(tuple(sub(e) for e in p) for p in rps.centres),
        tuple(tuple(sub(e) for e in p) for p in rps.platform),
        tuple(sub(e) for e in rps.equations),
        tuple(tuple(tuple(sub(e) for e in row) for row in m) for m in rps.coefficients))


# a quadratic step is tried in its half-angle form (:func:`_half_angle_split`) where A and
# C have at most this many operations together (larger ones are never of that shape here)
HALF_ANGLE_MAX_OPS = 400


def _half_angle_split(coeffs: Sequence[sp.Expr], program: Program
                      ) -> tuple[list[sp.Expr], list] | None:
    """A quadratic step's ``[A, B, C]`` as ``[P - Q, B, P + Q]`` with ``P = (A + C)/2`` and
    ``Q = (C - A)/2`` named values of ``program`` (its new entries returned beside), where
    that has fewer operations; else None.  A revolute joint's generator in its
    tan-half-angle ``t`` comes from ``a cos + b sin + c`` with ``cos = (1 - t^2)/(1 +
    t^2)``: then ``A = c - a`` and ``C = c + a`` share every term but those of ``a``
    (lamina_milling's theta1: ``lAF^2 - lOA^2 - x^2 - y^2 -+ 2 lOA x``, 20 operations
    against 11)."""
    a, c = (sp.expand(sp.sympify(e)) for e in (coeffs[0], coeffs[2]))
    before = pr.count_ops(a) + pr.count_ops(c)
    if before > HALF_ANGLE_MAX_OPS:
        return None
    p, q = sp.expand((a + c) / 2), sp.expand((c - a) / 2)
    if p == 0 or q == 0 or pr.count_ops(p) + pr.count_ops(q) + 2 >= before:
        return None
    start = len(program.entries)
    ps, qs = program.name(p), program.name(q)
    return [ps - qs, coeffs[1], ps + qs], program.entries[start:]


def _step_kernels(prefix: str, steps: Sequence[IKStep], inputs: Sequence[sp.Symbol],
                  par: Sequence[sp.Symbol], sub: dict, c: bool = False,
                  compact: dict | None = None, uses: list | None = None,
                  coefficients: list | None = None
                  ) -> tuple[list[Kernel], list[str], list]:
    """One kernel per back-substitution step; the ``(degree, kernel, mode bit)`` table rows.
    A step in ``compact`` (a distance leg's geometric form) is evaluated in that form, a
    quadratic one in its half-angle form where that is smaller (:func:`_half_angle_split`).
    ``uses`` (a list) receives, per step, the indices of the earlier steps whose unknowns
    its coefficients contain (a kernel takes every earlier unknown as an argument);
    ``coefficients`` (a list) each step's ``([A, B, C], program entries)`` as its kernel
    evaluates them."""
    kernels, rows, mode_bits = [], [], []
    solved: list[sp.Symbol] = []
    bit = 0
    program = Program("_h")
    for k, st in enumerate(steps):
        coeffs = [sp.sympify(c).subs(sub) for c in (st.A, st.B, st.C)]
        form = (compact or {}).get(st.joint)
        if form is not None and st.degree == 2 and coeffs[1] == 0:
            coeffs = [form.scale * form.rotation, sp.Integer(0), -4 * form.scale * form.dual]
        if uses is not None:
            free = set().union(*(sp.sympify(e).free_symbols for e in coeffs))
            uses.append(tuple(j for j, q in enumerate(solved) if q in free))
        name = f"_{prefix}{k}_{st.joint}"
        doc = (f"Coefficients (A, B, C) of the generator solved for {st.joint} "
               f"(from {st.source}).")
        kern = kernel(name, [*inputs, *solved, *par], coeffs, doc, c=c, scalars=par)
        entries: list = []
        split = _half_angle_split(coeffs, program) if st.degree == 2 else None
        if split is not None:
            alt = kernel(name, [*inputs, *solved, *par], split[0], doc, c=c, scalars=par,
                         program=split[1])
            if alt.operations < kern.operations:
                kern, coeffs, entries = alt, split[0], split[1]
        if coefficients is not None:
            coefficients.append((coeffs, entries))
        kernels.append(kern)
        if st.degree == 2:
            mode_bits.append((str(st.joint), bit))
            rows.append(f"    (2, {kern.name}, {bit}),")
            bit += 1
        else:
            rows.append(f"    (1, {kern.name}, None),")
        solved.append(st.joint)
    return kernels, rows, mode_bits


def _step_rows(prefix_rows: list[str]) -> list[str]:
    return [r.strip().rstrip(",") for r in prefix_rows]


def write_ik_module(spec: IKModuleSpec) -> tuple[str, dict[str, int], str]:
    """Source text of ``generated/<name>.py`` (deterministic for equal inputs), the
    operation count of each kernel, and the source of ``generated/<name>.c`` (the compiled
    fast path of the IK, its limits and its Jacobian)."""
    from .. import runtime

    if spec.constants:
        spec = _with_constants(spec)
    par = [sp.Symbol(p.name, real=True) for p in spec.parameters]
    sub = dict(spec.pose_to_study)
    study = list(sub)
    # the pose is converted to Study coordinates once per call; the IK steps are polynomial
    # in those coordinates
    # the pose map in its leanest form (polynomial part plus proper fraction where that
    # is smaller), for the Study map's kernel and the Jacobian's chain rule alike
    lean = dict(zip(study, leaner_outputs([sub[y] for y in study], [*spec.pose, *par], par)))
    kernels = [kernel("_study", [*spec.pose, *par], [lean[y] for y in study],
                      "Study coordinates STUDY_POSE of the pose (POSE).", c=True,
                      scalars=par)]
    step_uses: list = []
    step_coeffs: list = []
    step_kernels, steps_src, mode_bits = _step_kernels("step", spec.steps, study, par, {},
                                                       c=True, compact=spec.compact,
                                                       uses=step_uses,
                                                       coefficients=step_coeffs)
    kernels += step_kernels
    # where no step reads an earlier root, every step's coefficients from one CSE program:
    # what the steps share (the rotation of a Stewart platform's six legs, x^2 + y^2 of
    # lamina_milling's two bottom chains) computed once; the numpy runtime takes it in
    # place of the step kernels (the C module inlines those, and its compiler shares)
    fused = None
    if len(spec.steps) > 1 and not any(step_uses):
        fused = kernel("_step_coefficients", [*study, *par],
                       [e for coeffs, _ in step_coeffs for e in coeffs],
                       "Coefficients (A, B, C) of every IK step in order, of the Study "
                       "coordinates alone (no step reads an earlier root).", scalars=par,
                       program=[e for _, entries in step_coeffs for e in entries])
        kernels.append(fused)
    bit = len(mode_bits)
    # forward kinematics' polynomial kernels, also in C (the compiled fast path calls them
    # row by row: c_module's row_kernels)
    fk_kernels, fk_src, fk_bits = _step_kernels("fkstep", spec.fk_steps, spec.joints, par, {},
                                                c=True)
    kernels += fk_kernels
    row_kernels = list(fk_kernels)
    fk_charts = []
    for c, chart in enumerate(spec.fk_charts, start=1):
        chart_kernels, chart_src, _ = _step_kernels(f"fkchart{c}_step", chart, spec.joints,
                                                    par, {}, c=True)
        kernels += chart_kernels
        row_kernels += chart_kernels
        fk_charts.append((_step_rows(chart_src),
                          tuple(list(spec.fk_unknowns).index(st.joint) for st in chart)))
    has_fk = bool(spec.fk_steps or spec.rps)
    if spec.rps:
        rps_kernels = RPSEliminant().kernels(spec.rps, spec.joints, par)
        kernels += rps_kernels
        row_kernels += rps_kernels
    if has_fk:
        kernels.append(kernel("_fk_pose", [*spec.rps_unknowns, *spec.fk_unknowns, *par],
                              [spec.study_to_pose[x] for x in spec.pose],
                              "Pose coordinates (POSE) from the solved Study coordinates."))
    if spec.fk_steps:
        system = sp.Matrix(list(spec.fk_system))
        kernels.append(kernel(
            "_fk_newton", [*spec.fk_unknowns, *spec.joints, *par],
            list(system) + list(pr.jacobian(list(system), spec.fk_unknowns)),
            "Residuals of the leg generators and their Jacobian in FK_UNKNOWNS (row-major).",
            c=True, scalars=par))
        row_kernels.append(kernels[-1])
    compact = spec.compact or {}
    gens = [compact[st.joint].generator() if st.joint in compact else sp.expand(st.generator)
            for st in spec.steps]
    args = [*spec.pose, *spec.joints, *par]
    g_pose = [g.xreplace(sub) for g in gens]
    ji = sp.Matrix(g_pose).jacobian(sp.Matrix(spec.joints))
    jo_study = pr.jacobian(gens, study).xreplace(sub)
    # pivots of linear steps that can vanish (a constant pivot never does)
    linear = [k for k, st in enumerate(spec.steps)
              if st.degree == 1 and not sp.diff(gens[k], st.joint).is_number]
    piv = [sp.diff(gens[k], spec.steps[k].joint) for k in linear]
    piv_scale = [sp.Abs(pv, evaluate=False) + sum(sp.Abs(sp.diff(gens[k], y)) for y in study)
                 for k, pv in zip(linear, piv)]
    if linear:
        kernels.append(kernel("_pivots", [*study, *spec.joints, *par], piv + piv_scale,
                              "Pivots dG_k/dq_k of the linear IK steps and their row scales "
                              "(in Study coordinates).", c=True, scalars=par))
    kernels.append(_jacobian_kernel(spec, gens, lean, args, par))
    kernels.append(kernel("_ji", args, list(ji), "Input Jacobian dG/dq, row-major.",
                          scalars=par))
    kernels.append(kernel("_jo_study", args, list(jo_study),
                          "Output Jacobian dG/dy in Study coordinates, row-major.",
                          scalars=par))
    if spec.limits:
        kernels.append(kernel("_limit_values", args, [sp.sympify(lim[1]) for lim in spec.limits],
                              "Quantities bounded by LIMITS (joint strokes, passive angles).",
                              c=True, scalars=par))
    pose_functions, functions = [], []
    for fname, outs, exprs, doc in spec.pose_functions:
        kern = kernel(f"_pf_{fname}", [*spec.pose, *par], list(exprs), doc)
        kernels.append(kern)
        pose_functions.append({"name": fname, "outputs": tuple(outs), "doc": doc,
                               "kernel": kern.name})
    for fname, inputs, outs, exprs, doc in spec.functions:
        kern = kernel(f"_fn_{fname}", [*inputs, *par], list(exprs), doc)
        kernels.append(kern)
        functions.append({"name": fname, "inputs": tuple(str(v) for v in inputs),
                          "outputs": tuple(outs), "doc": doc, "kernel": kern.name})
    sing_kernels, sing_matrices = [], []
    for name, expr, meaning in spec.singularities:
        # in the Study coordinates of the pose (computed once by _study), not in the pose:
        # composed with the pose map, a large polynomial makes CSE slow and the kernel long
        if isinstance(expr, sp.MatrixBase):  # a determinant, evaluated numerically
            kern = kernel(f"_sing_{name}", [*study, *spec.joints, *par], list(expr),
                          f"Entries (row-major) of the matrix whose determinant is {name}: "
                          f"{meaning}", scalars=par)
            kernels.append(kern)
            sing_matrices.append((name, kern.name, expr.rows))
            continue
        expr = sp.sympify(expr)
        stray = expr.free_symbols - set(study) - set(spec.joints) - set(par)
        if stray:
            raise ValueError(f"{spec.name}: singularity {name} has symbols "
                             f"{sorted(map(str, stray))} outside the Study coordinates, "
                             "joints and parameters")
        kern = kernel(f"_sing_{name}", [*study, *spec.joints, *par], [expr], meaning,
                      scalars=par)
        kernels.append(kern)
        sing_kernels.append((name, kern.name))
    passive_table, passive_names, passive_units, passive_notes = _passive_kernels(
        spec, study, par, kernels)
    link_rows, link_names, link_frames = _link_kernels(spec, study, par, passive_names,
                                                       kernels)
    statics = (_static_kernels(spec, study, par, passive_names, link_names, kernels)
               if spec.link_weights else None)
    has_twist = spec.end_effector is not None
    if has_twist:
        from ..kinematics.twist import pose_twist

        kernels.append(kernel("_pose_twist", [*spec.pose, *par],
                              list(pose_twist(spec.end_effector, spec.pose)),
                              "Spatial twist (omega; v) per unit rate of each pose coordinate, "
                              "6 x len(POSE) row-major."))
    helical = [h for h in spec.helical]
    if helical:
        known = set(spec.joints) | {sp.Symbol(n, real=True) for n in passive_names}
        for h in helical:
            if not {h.rotation, h.translation} <= known:
                raise ValueError(f"{spec.name}: the helical joint of {h.translation} needs "
                                 "its turn and slide recovered")
        kernels.append(kernel(
            "_helical", [*[sp.Symbol(n, real=True) for n in passive_names], *spec.joints, *par],
            [h.translation - h.pitch * 2 * sp.atan(h.rotation) for h in helical],
            "Residuals s - pitch * theta of the helical joints (zero where the algebra's "
            "cylindrical joint is the helical one)."))
    by_name = {k.name: k for k in kernels}  # as the C module takes them
    kernels, pose_kernels = _pose_sharing(kernels, spec.pose, par)
    total = sum(k.operations for k in kernels if k.name not in pose_kernels)  # no wrappers
    rps_kernels = ("_runtime.RPSKernels(coefficients=_rps_coefficients, "
                   "equations=_rps_equations, centres=_rps_centres, platform=_rps_platform, "
                   "study=_rps_study)") if spec.rps else "None"
    names = ["ik", "ik_all", "ik_status", "ik_and_status", "ik_joint_status", "ik_explain",
             "fk", "fk_status", "jacobian",
             "jacobian_status", "jacobian_and_status", "ik_and_jacobian", "input_jacobian",
             "output_jacobian",
             "singularities", "limit_values"]
    if passive_names:
        names.append("passive_joints")
    if link_names:
        names.append("link_poses")
    if has_twist:
        names += ["pose_twist", "twist_jacobian"]
    if helical:
        names.append("helical_residuals")
    if statics:
        names.append("static_efforts")
    names += [f["name"] for f in pose_functions + functions]
    public = list(spec.public_joints or [str(q) for q in spec.joints])
    context = {
        "title": spec.title, "generator": spec.generator,
        "declaration": f"bonered_alg/mechanisms/{spec.name}.py", "source": spec.source,
        "derivation_hash": spec.derivation_hash, "total_operations": total,
        "contract": ", ".join(names), "api_version": runtime.API_VERSION, "name": spec.name,
        "operations": [(k.name, k.operations) for k in kernels
                       if k.name not in pose_kernels],
        "parameters": [{"name": p.name, "value": p.value, "unit": p.unit, "domain": p.domain,
                        "note": p.description + "; " + p.source} for p in spec.parameters],
        "pose": [str(s) for s in spec.pose], "pose_units": list(spec.pose_units),
        "study_pose": [str(s) for s in study], "joints": [str(s) for s in spec.joints],
        "public_joints": public, "joint_angles": tuple(
            i for i, (q, name) in enumerate(zip(spec.joints, public)) if str(q) != name),
        "joint_units": list(spec.joint_units), "modes": 2**bit,
        "mode_bits": tuple((public[[str(q) for q in spec.joints].index(j)], b)
                           for j, b in mode_bits),
        "fk_unknowns": [str(u) for u in spec.fk_unknowns],
        "rps_unknowns": [str(u) for u in spec.rps_unknowns],
        "rps_modes": DEGREE_BOUND if spec.rps else 0,
        "fk_modes": (DEGREE_BOUND if spec.rps else 1) * 2 ** len(fk_bits) if has_fk else 0,
        "fk_note": spec.fk_note if not has_fk else "", "fk_mode_bits": tuple(fk_bits),
        "fk_generators": [(str(st.joint), sp.sstr(sp.expand(st.generator)))
                          for st in spec.fk_steps],
        "ik_generators": [(str(st.joint), sp.sstr(sp.expand(st.generator)))
                          for st in spec.steps],
        "limits": [(lim[0], float(lim[2]), float(lim[3]), lim[4], lim[5], lim[6])
                   for lim in spec.limits],
        "singularity_meanings": [(n, m) for n, _, m in spec.singularities],
        "kernels": kernels, "steps": _step_rows(steps_src), "fk_steps": _step_rows(fk_src),
        "step_uses": tuple(step_uses),
        "step_coefficients_kernel": fused.name if fused else "None",
        "singularity_kernels": sing_kernels, "singularity_matrices": sing_matrices,
        "pivot_steps": tuple(linear),
        "home": None if spec.home is None else tuple(float(v) for v in spec.home),
        "physical_branch": tuple((str(j), float(v)) for j, v in spec.physical_branch),
        "solve_index": tuple(list(spec.joints).index(st.joint) for st in spec.steps),
        "pivots_kernel": "_pivots" if linear else "None",
        "limit_kernel": pose_kernels.get("_limit_values", "_limit_values") if spec.limits
        else "None",
        "study_kernel": pose_kernels.get("_study", "_study"),
        "jac_kernel": pose_kernels.get("_jac", "_jac"),
        "shared_kernel": "_shared" if pose_kernels else "None",
        "rps_kernels": rps_kernels,
        "fk_index": tuple(list(spec.fk_unknowns).index(st.joint) for st in spec.fk_steps),
        "fk_charts": fk_charts,
        "fk_newton": "_fk_newton" if spec.fk_steps else "None",
        "fk_pose": "_fk_pose" if has_fk else "None",
        "pose_functions": pose_functions, "functions": functions,
        "passive_names": passive_names, "passive_units": passive_units,
        "passive_notes": passive_notes, "passive_table": passive_table,
        "twist_kernel": "_pose_twist" if has_twist else "None",
        "link_names": link_names, "link_frames": link_frames, "link_kernels": link_rows,
        "helical": [(str(h.rotation), str(h.translation), sp.sstr(h.pitch)) for h in helical],
        "helical_kernel": "_helical" if helical else "None",
        "statics": statics,
    }
    numpy_ops = {k.name: k.operations for k in kernels}

    def ops(name: str) -> int:  # of the numpy kernel the runtime calls
        return numpy_ops[pose_kernels.get(name, name)]
    step_names = [fused.name] if fused else [k.name for k in step_kernels]
    ik_ops = (sum(ops(n) for n in ["_study", *step_names]
                  + [n for n in ("_pivots", "_limit_values") if n in by_name])
              + numpy_ops.get("_shared", 0))
    context["function_operations"] = [("ik", ik_ops), ("ik_and_jacobian", ik_ops + ops("_jac"))]
    c_source = c_module(
        name=spec.name, derivation_hash=spec.derivation_hash, generator=spec.generator,
        pose=context["pose"], study_pose=context["study_pose"], joints=context["joints"],
        parameters=[p.name for p in spec.parameters], study=by_name["_study"],
        steps=[(st.degree, k, b) for st, k, b in zip(
            spec.steps, step_kernels, _bits(spec.steps))],
        step_uses=context["step_uses"],
        solve_index=context["solve_index"], pivots=by_name.get("_pivots"),
        jac=by_name["_jac"], limits_kernel=by_name.get("_limit_values"),
        limits=[(float(lim[2]), float(lim[3]), lim[4]) for lim in spec.limits],
        angles=context["joint_angles"], row_kernels=row_kernels)
    return (render("module.py.j2", context), {k.name: k.operations for k in kernels},
            c_source)


def _pose_sharing(kernels: list[Kernel], pose: Sequence[sp.Symbol], par: Sequence[sp.Symbol]
                  ) -> tuple[list[Kernel], dict[str, str]]:
    """``kernels`` with the elementary functions of the pose that the Study map, the
    Jacobian and the limits each compute (tan(alpha/2), sin(beta), ...) computed once, by a
    kernel ``_shared``, and passed to variants of those kernels (``_study_of``, ...) that
    read them, as the C module does; each kernel under its old name is kept as a wrapper of
    the two (for callers of one kernel).  Also ``{kernel: its variant}``, empty where
    nothing is shared."""
    names = {str(v) for v in [*pose, *par]}
    pose_kernels = [k for k in kernels if k.name in ("_study", "_jac", "_limit_values")]
    found = {k.name: shareable_functions(k, names) for k in pose_kernels}
    shared = shared_functions(list(found.values()))
    if not shared:
        return kernels, {}
    fsyms = {f: sp.Symbol(f"_f{i}") for i, f in enumerate(shared)}
    out = [kernel("_shared", [*pose, *par], shared,
                  "Elementary functions of the pose that several kernels take "
                  f"({', '.join(map(str, fsyms.values()))}), computed once per call.")]
    variants = {}
    for k in kernels:
        if k.name not in found:
            out.append(k)
            continue
        variant = numpy_function(k, f"{k.name}_of", fsyms, found[k.name])
        args = ", ".join(k.arguments)
        wrapper = (f"def {k.name}({args}):\n    \"\"\"{k.doc}\"\"\"\n"
                   f"    return {variant.name}(*_shared({', '.join(map(str, [*pose, *par]))}), "
                   f"{args})\n")
        out += [variant, Kernel(k.name, wrapper, k.operations, "", k.arguments, k.outputs,
                                (), k.doc, k.scalars)]
        variants[k.name] = variant.name
    return out, variants


def _bits(steps: Sequence[IKStep]) -> list:
    """The mode bit of each step (quadratic steps in order), None for a linear one."""
    out, bit = [], 0
    for st in steps:
        out.append(bit if st.degree == 2 else None)
        bit += st.degree == 2
    return out


def module_source(d, generator: str):
    """The generated module of derivation ``d`` (:class:`..pipeline.results.GeneratedModule`)."""
    from ..pipeline.results import GeneratedModule, frozen_map

    m = d.mechanism
    rps_fk = next((f for f in d.fk if f.system is not None), None)
    compact = compact_steps(d)
    boundaries = compact_boundaries(compact)
    spec = IKModuleSpec(
        name=m.name, title=m.title, source=m.source, derivation_hash=d.derivation_hash,
        generator=generator, parameters=list(m.parameters), pose=m.pose.coordinates,
        pose_units=m.pose.units, pose_to_study=dict(d.pose_to_study), joints=m.joints,
        joint_units=m.joint_units, steps=list(d.steps),
        singularities=[(s.name, boundaries.get(s.name, s.expression if s.evaluate is None
                                               else s.evaluate), s.meaning)
                       for s in d.singularities],
        fk_steps=[s for f in d.fk for s in f.steps],
        rps=rps_fk.system if rps_fk else None,
        rps_unknowns=m.closure_named(rps_fk.closure).pose if rps_fk else (),
        fk_unknowns=[s.joint for f in d.fk for s in f.steps],
        fk_charts=[[s for g in d.fk for s in (alt if g is f else g.steps)]
                   for f in d.fk for alt in f.alternates],
        fk_system=[g for f in d.fk if f.system is None for g in f.problem.equations],
        study_to_pose=dict(m.pose.from_study) if m.pose.from_study else None,
        constants=d.constants, fk_note=d.fk_note,
        limits=[(lim.name, lim.expression, lim.lower, lim.upper, lim.kind, lim.unit,
                 lim.source) for lim in d.limits],
        pose_functions=[(f.name, f.outputs, list(f.expressions), f.doc)
                        for f in d.pose_functions],
        functions=[(f.name, f.inputs, f.outputs, list(f.expressions), f.doc)
                   for f in d.functions],
        passive=list(d.passive), end_effector=m.pose.end_effector,
        helical=[h for c in m.actuated_closures for leg in c.legs for h in leg.couplings],
        passive_units=_passive_units(m),
        link_legs=[(c.base, leg) for c in m.actuated_closures for leg in c.legs],
        link_weights=list(m.link_weights),
        link_constants=d.constants,
        home=tuple(m.home) if m.home else None,
        physical_branch=tuple(
            (m.public_joint(b.joint), 2 * math.atan(b.declared) if b.joint in m.angle_joints
             else b.declared) for b in d.branches),
        public_joints=tuple(m.public_joint(q) for q in m.joints),
        compact=compact, leg_lines=leg_line_steps(d, compact))
    source, ops, c_source = write_ik_module(spec)
    return GeneratedModule(m.name, source, frozen_map(ops), c_source=c_source)


def compact_steps(d) -> dict:
    """The IK steps that a distance leg's generator solves, in the geometric form of
    :func:`..elimination.sphere_leg.compact_sphere` (proved equal to the generator there):
    joint -> CompactSphere.  Steps of other legs are evaluated as expanded."""
    from ..elimination import sphere_leg
    from ..solvers.legs import DistanceLeg

    consts = dict(d.constants or {})
    out = {}
    for st in d.steps:
        if st.degree != 2:
            continue
        leg = next((r for r in d.legs if f"{r.closure.point}/{r.leg.name}" == st.source
                    and r.method == DistanceLeg.name), None)
        dl = sphere_leg.recognize(leg.leg) if leg is not None else None
        if dl is None or dl.stroke != st.joint:
            continue
        form = sphere_leg.compact_sphere(dl, tuple(leg.closure.platform), st.generator, consts)
        if form is not None:
            out[st.joint] = form
    return out


def compact_boundaries(compact: dict) -> dict[str, sp.Expr]:
    """``boundary_<joint>`` of each step in ``compact`` (:func:`compact_steps`) in the
    geometric form: the generator is ``scale (q^2 R - 4 D)`` (proved in
    :func:`..elimination.sphere_leg.compact_sphere`), so its discriminant in ``q``, ``-4 A
    C`` of the expanded coefficients, is ``16 scale^2 R D`` with ``R`` and ``D`` left as
    sums of squares: the same polynomial, which the kernel evaluates in a few dozen
    operations (a Stewart leg's expanded ``-4 A C``: about 2,400)."""
    return {f"boundary_{q}": 16 * form.scale**2 * form.rotation * form.dual
            for q, form in compact.items()}


def leg_line_steps(d, compact: dict) -> dict:
    """The IK steps whose Jacobian row is taken from the leg's line
    (:func:`_triangular_jacobian`): joint -> :class:`..kinematics.leg_lines.LegLine`.  A
    step in ``compact`` (:func:`compact_steps`) qualifies with its form's points; any other
    quadratic step ``A q^2 + C`` (no linear term, no other joint) qualifies where its leg's
    stroke is proved to be the distance between a base point and a platform point on every
    configuration of the leg (:func:`..elimination.sphere_leg.distance_on_chain`: an R-P-S
    leg too).  Then the step's roots are ``+-|l|`` of the leg vector ``l`` at the pose, and
    ``q dq/dX = l . dl/dX`` is the derivative of the IK solution whichever generator
    gives it."""
    from ..elimination import sphere_leg
    from ..kinematics.leg_lines import LegLine

    consts = dict(d.constants or {})
    joints = set(d.mechanism.joints)
    out = {}
    for st in d.steps:
        form = compact.get(st.joint)
        if form is not None:
            if form.platform:
                out[st.joint] = LegLine(form.base, form.point, form.platform)
            continue
        if (st.degree != 2 or sp.sympify(st.B) != 0
                or sp.sympify(st.generator).free_symbols & joints != {st.joint}):
            continue
        leg = next((r for r in d.legs if f"{r.closure.point}/{r.leg.name}" == st.source), None)
        dl = sphere_leg.distance_on_chain(leg.leg, consts) if leg is not None else None
        if dl is None or dl.stroke != st.joint:
            continue
        out[st.joint] = LegLine(*(tuple(sp.sympify(c).subs(consts) for c in pts)
                                  for pts in (dl.base, dl.platform, leg.closure.platform)))
    return out


def _passive_kernels(spec, study, par, kernels):
    """Kernels of the passive-joint recovery and the runtime table: per leg, its steps
    ``(kind, kernel, output indices)`` (``kinematics.passive``).  A candidate generator that
    uses a Study coordinate the pose map does not give is dropped; a leg left without a
    complete recovery is reported in PASSIVE_NOTES."""
    from ..kinematics.passive import LinearStep, QuadraticStep

    names, units, notes, table = [], [], [], []
    have = set(study) | set(spec.joints) | set(par)
    for rec in spec.passive:
        if rec.note:
            notes.append(f"{rec.leg}: {rec.note}")
            continue
        rows, solved, ok, offset = [], [], True, len(names)
        for st in rec.steps:
            args = [*study, *spec.joints, *solved, *par]
            allowed = have | set(solved)
            if isinstance(st, LinearStep):
                cands = [(b, c) for b, c in st.candidates
                         if (sp.sympify(b).free_symbols | sp.sympify(c).free_symbols) <= allowed]
                if not cands:
                    ok = False
                    break
                kern = kernel(f"_passive_{rec.leg}_{st.variable}", args,
                              [e for b, c in cands for e in (b, c, _term_scale(b, c))],
                              f"Candidates (B, C, S) of B {st.variable} + C = 0, leg "
                              f"{rec.leg}; S, the sum of the terms' magnitudes, says how far "
                              "B is from zero relative to rounding.", scalars=par)
                rows.append(("linear", kern, (len(solved),)))
                solved.append(st.variable)
            elif isinstance(st, QuadraticStep):
                if not set().union(*(sp.sympify(e).free_symbols for e in st.coefficients)) \
                        <= allowed:
                    ok = False
                    break
                kern = kernel(f"_passive_{rec.leg}_{st.variable}", args, list(st.coefficients),
                              f"(A, B, C) of A {st.variable}^2 + B {st.variable} + C = 0, "
                              f"leg {rec.leg} (the root of smaller magnitude).", scalars=par)
                rows.append(("quadratic", kern, (len(solved),)))
                solved.append(st.variable)
            else:
                if not set().union(*(sp.sympify(e).free_symbols for e in st.rotation)) <= allowed:
                    ok = False
                    break
                kern = kernel(f"_passive_{rec.leg}_sphere", args, list(st.rotation),
                              f"Rotation quaternion (up to scale) of the spherical joint of "
                              f"leg {rec.leg}.", scalars=par)
                rows.append(("spherical", kern, tuple(range(len(solved), len(solved) + 4))))
                solved += list(st.variables)
        if not ok:
            notes.append(f"{rec.leg}: a step needs Study coordinates the pose map does not give")
            continue
        kernels += [k for _, k, _ in rows]
        table.append(tuple((kind, k.name, tuple(offset + i for i in idx))
                           for kind, k, idx in rows))
        for v in solved:
            names.append(str(v))
            units.append((spec.passive_units or {}).get(v, "1"))
    return table, names, units, notes


def _term_scale(*exprs) -> sp.Expr:
    """The sum of the magnitudes of the terms of ``exprs`` (expanded): a candidate's scale,
    against which its pivot is judged (a pivot below DET_RTOL of it is rounding)."""
    terms = [t for e in exprs for t in sp.Add.make_args(sp.expand(e))]
    return sp.Add(*[sp.Abs(t, evaluate=False) for t in terms]) if terms else sp.Integer(0)


def _link_kernels(spec, study, par, passive_names, kernels):
    """One kernel per leg whose joints are all known: the Study point of the body after each
    moving joint (the partial products of the leg), in the frame of the body the leg's
    closure stands on.  Returns the runtime table ``(kernel, first link index, count)``,
    the link names (those of the topology, ``<leg>.<k>``, the last one the platform seen
    from that leg) and each link's frame."""
    from ..algebra import study_symbolic as ss

    # the Study coordinates are inputs too (a leg may end in an offset along the
    # platform's coordinates, e.g. a collar's position on a shaft)
    known = set(spec.joints) | {sp.Symbol(n, real=True) for n in passive_names} | set(study)
    psyms = [sp.Symbol(n, real=True) for n in passive_names]
    rows, names, frames = [], [], []
    consts = spec.link_constants or {}
    for base, leg in spec.link_legs:
        moving = [k for k, j in enumerate(leg.joints) if j.kind != "offset"]
        if not moving or not leg.free_symbols - set(par) <= known | set(consts):
            continue
        outs, labels = [], []
        for n_body, k in enumerate(moving, 1):
            factors = [f.study() for j in leg.joints[:k + 1] for f in j.factors]
            point = ss.product(*factors)
            outs += [sp.sympify(c).subs(consts) for c in point]
            labels.append(f"{leg.name}.{n_body}")
        kern = kernel(f"_links_{leg.name}", [*study, *spec.joints, *psyms, *par], outs,
                      f"Study points of the bodies of leg {leg.name} (frame {base}).",
                      scalars=par)
        kernels.append(kern)
        rows.append((kern.name, len(names), len(labels)))
        names += labels
        frames += [base or "base"] * len(labels)
    return rows, names, frames


def _static_kernels(spec, study, par, passive_names, link_names, kernels):
    """The kernels of the static model (``runtime.statics``): per leg the derivatives of
    its bodies' Study points by each of its joint variables (the same partial products as
    the link poses), the weights and their points from the parameters, and the end
    effector's Study point.  Returns the runtime table (rates, points, names)."""
    from ..algebra import study_symbolic as ss
    from ..chains.joints import Role
    from ..declaration.weights import PLATFORM

    psyms = [sp.Symbol(n, real=True) for n in passive_names]
    consts = spec.link_constants or {}
    rates = []
    for _, leg in spec.link_legs:
        if f"{leg.name}.1" not in link_names:
            continue
        if leg.couplings:
            raise ValueError(f"{spec.name}: the static model does not handle the helical "
                             f"joint of leg {leg.name}")
        variables = []
        for f in leg.factors:
            if f.role is not Role.GEOMETRIC:
                variables += [v for v in sorted(f.free_symbols, key=str) if v not in variables]
        moving = [k for k, j in enumerate(leg.joints) if j.kind != "offset"]
        outs = []
        for k in moving:
            point = ss.product(*[f.study() for j in leg.joints[:k + 1] for f in j.factors])
            outs += [sp.expand(sp.diff(c, v)).subs(consts) for v in variables for c in point]
        # each variable's joint (the body after it, within the leg) and its actuated joint
        owner = []
        for v in variables:
            body = next(b for b, k in enumerate(moving) if v in leg.joints[k].free_symbols)
            owner.append((body, list(spec.joints).index(v) if v in spec.joints else -1))
        kern = kernel(f"_rates_{leg.name}", [*study, *spec.joints, *psyms, *par], outs,
                      f"d(Study point)/d({', '.join(map(str, variables))}) of each body of "
                      f"leg {leg.name} (body-major, 8 coordinates each).", scalars=par)
        kernels.append(kern)
        rates.append((kern.name, link_names.index(f"{leg.name}.1"), len(moving),
                      len(variables), tuple(owner)))
    outs, points = [], []
    for w in spec.link_weights:
        for pt in w.points:
            if pt.body != PLATFORM and pt.body not in link_names:
                raise ValueError(f"{spec.name}: link weight {w.name} is on body {pt.body}, "
                                 "whose pose is not generated")
            outs += [w.weight * pt.share, *pt.local]
            points.append(-1 if pt.body == PLATFORM else link_names.index(pt.body))
    kernels.append(kernel("_weights", list(par), outs,
                          "(G * share, cx, cy, cz) of each point of the link weights."))
    kernels.append(kernel("_end_effector", [*spec.pose, *par], list(spec.end_effector),
                          "The end effector's Study point (the load acts at its origin)."))
    return {"rates": rates, "points": tuple(points),
            "names": tuple(w.name for w in spec.link_weights)}


def _passive_units(mech) -> dict:
    """The unit of each passive variable, from the kind of the factor it moves."""
    out = {}
    for closure in mech.closures:
        for leg in closure.legs:
            for f in leg.factors:
                for v in f.free_symbols:
                    out.setdefault(v, {"rotation": "1 (tan(theta/2))", "translation": "mm",
                                       "quaternion": "1 (Euler parameter, normalized)"}[f.kind])
    return out
