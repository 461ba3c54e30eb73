"""Assemble a generated numpy module (DESIGN.md section 4) from derived symbolic results."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from ..algebra import convention as cv
from ..chains.mechanism import Parameter
from ..kinematics.ik_plan import IKStep
from ..kinematics.rps_forward import DEGREE_BOUND, RPSSystem
from .kernels import Kernel, kernel
from .runtime_template import RUNTIME


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


def _literal(value) -> str:
    return "None" if value is None else repr(float(value))


def _abs(e: sp.Expr) -> sp.Expr:
    """``|e|`` without sympy's simplification attempts (minutes on large expressions)."""
    return sp.Integer(0) if e == 0 else sp.Abs(e, evaluate=False)


def _triangular_jacobian(steps: Sequence[IKStep], gens: Sequence[sp.Expr],
                         joints: Sequence[sp.Symbol], pose: Sequence[sp.Symbol],
                         sub: dict) -> list:
    """Pivots, row scales and ``dq/dX`` by forward substitution (004 eq. 19-21).

    Generator ``k`` involves only joints solved at steps ``<= k``, so ``dG/dq`` in the solve
    order is lower triangular: ``dq_k/dX = -(dg_k/dX + sum_{j<k} dg_k/dq_j dq_j/dX) / d_k``
    with the pivot ``d_k = dg_k/dq_k``; ``det Ji = prod d_k``.  The generators are written in
    the Study coordinates ``sub`` maps to the pose, and ``dg/dX`` is taken by the chain rule,
    ``sum_i dg/ds_i ds_i/dX``: differentiating the substituted generator instead multiplies
    out the pose map into every partial (the Stewart platform's kernel was 4x larger).
    """
    study = list(sub)
    ds = [[sp.diff(sub[s], x) for x in pose] for s in study]
    rows: dict[sp.Symbol, list[sp.Expr]] = {}
    pivots, scales = [], []
    for st, g in zip(steps, gens):
        d = sp.diff(g, st.joint).subs(sub)
        dgs = [sp.diff(g, s).subs(sub) for s in study]
        dgx = [sp.Add(*[a * ds[i][m] for i, a in enumerate(dgs) if a != 0 and ds[i][m] != 0])
               for m in range(len(pose))]
        row = []
        for m in range(len(pose)):
            acc = dgx[m] + sum(sp.diff(g, prev.joint).subs(sub) * rows[prev.joint][m]
                               for prev in steps[: steps.index(st)])
            row.append(-acc / d)
        rows[st.joint] = row
        pivots.append(d)
        scales.append(_abs(d) + sum(_abs(e) for e in dgx))
    return pivots + scales + [e for q in joints for e in rows[q]]


def _with_constants(spec: IKModuleSpec) -> IKModuleSpec:
    """The spec with every algebraic constant replaced by its exact value."""
    c = spec.constants

    def step(st: IKStep) -> IKStep:
        return IKStep(st.joint, sp.expand(sp.sympify(st.generator).subs(c)), st.degree,
                      sp.sympify(st.A).subs(c), sp.sympify(st.B).subs(c),
                      sp.sympify(st.C).subs(c), st.source)

    return IKModuleSpec(
        **{**spec.__dict__,
           "steps": [step(st) for st in spec.steps],
           "fk_steps": [step(st) for st in spec.fk_steps],
           "fk_system": [sp.sympify(g).subs(c) for g in spec.fk_system],
           "singularities": [(n, sp.sympify(e).subs(c), m) for n, e, m in spec.singularities],
           "limits": [(lim[0], sp.sympify(lim[1]).subs(c), *lim[2:]) for lim in spec.limits],
           "pose_functions": [(f[0], f[1], [sp.sympify(e).subs(c) for e in f[2]], f[3])
                              for f in spec.pose_functions],
           "functions": [(f[0], f[1], f[2], [sp.sympify(e).subs(c) for e in f[3]], f[4])
                         for f in spec.functions],
           "pose_to_study": {k: sp.sympify(v).subs(c) for k, v in spec.pose_to_study.items()},
           "study_to_pose": ({k: sp.sympify(v).subs(c) for k, v in spec.study_to_pose.items()}
                             if spec.study_to_pose else None),
           "rps": _rps_with_constants(spec.rps, c) if spec.rps else None,
           "constants": None})


def _rps_with_constants(rps: RPSSystem, c: dict) -> RPSSystem:
    def sub(e):
        return sp.sympify(e).subs(c)

    return RPSSystem(
        rps.closure, rps.angles, rps.joints,
        tuple(tuple(sub(e) for e in p) for p in rps.centres),
        tuple(tuple(sub(e) for e in p) for p in rps.platform),
        tuple(sub(e) for e in rps.equations),
        tuple(tuple(tuple(sub(e) for e in row) for row in m) for m in rps.coefficients))


def _rps_kernels(rps: RPSSystem, joints: Sequence[sp.Symbol],
                 par: Sequence[sp.Symbol]) -> list[Kernel]:
    """Kernels of the 3-RPS forward kinematics (see ``kinematics.rps_forward``)."""
    u = list(rps.angles)
    eqs = sp.Matrix(list(rps.equations))
    rot = sp.Matrix(3, 3, sp.symbols("r0:9", real=True))
    trans = sp.symbols("t0:3", real=True)
    x = cv.rotation_ratios(rot.tolist())[0]
    study = tuple(x) + cv.dual_part_from_translation(trans, x)
    return [
        kernel("_rps_coefficients", [*joints, *par],
               [e for m in rps.coefficients for row in m for e in row],
               "Coefficients C_ij[a][b] of u_i^a u_j^b in e12, e23, e31 (row-major)."),
        kernel("_rps_equations", [*u, *joints, *par], list(eqs) + list(eqs.jacobian(u)),
               "e12, e23, e31 and their Jacobian in the revolute tan-half angles."),
        kernel("_rps_centres", [*u, *joints, *par], [e for p in rps.centres for e in p],
               "Spherical joint centres B_k in the closure's base frame."),
        kernel("_rps_platform", list(par), [e for p in rps.platform for e in p],
               "Spherical joint centres P_k in the platform frame."),
        kernel("_rps_study", [*rot, *trans], [e / study[0] for e in study[1:]],
               "Study coordinates (chart x0 = 1) of the platform from R (row-major) and t."),
    ]


def _step_kernels(prefix: str, steps: Sequence[IKStep], inputs: Sequence[sp.Symbol],
                  par: Sequence[sp.Symbol], sub: dict) -> tuple[list[Kernel], list[str], list]:
    """One kernel per back-substitution step; the ``(degree, kernel, mode bit)`` table rows."""
    kernels, rows, mode_bits = [], [], []
    solved: list[sp.Symbol] = []
    bit = 0
    for k, st in enumerate(steps):
        coeffs = [sp.sympify(c).subs(sub) for c in (st.A, st.B, st.C)]
        kern = kernel(f"_{prefix}{k}_{st.joint}", [*inputs, *solved, *par], coeffs,
                      f"Coefficients (A, B, C) of the generator solved for {st.joint} "
                      f"(from {st.source}).")
        kernels.append(kern)
        if st.degree == 2:
            mode_bits.append((str(st.joint), bit))
            rows.append(f"    (2, {kern.name}, {bit}),")
            bit += 1
        else:
            rows.append(f"    (1, {kern.name}, None),")
        solved.append(st.joint)
    return kernels, rows, mode_bits


_FUNCTION_HELPER = '''def _function(func, kern, values, names, params):
    values = numpy.asarray(values, dtype=float)
    if values.ndim == 0 or values.shape[-1] != len(names):
        raise ValueError(f"{MECHANISM}.{func}: values must have shape (..., {len(names)}) "
                         f"with coordinates {names}, got shape {values.shape}")
    par = _params(func, params)
    shape = values.shape[:-1]
    with numpy.errstate(all="ignore"):
        out = kern(*[values[..., i] for i in range(len(names))], *par)
    return numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                        for v in out], axis=-1)
'''


def write_ik_module(spec: IKModuleSpec) -> str:
    """Source text of ``generated/<name>.py`` (deterministic for equal inputs)."""
    if spec.constants:
        spec = _with_constants(spec)
    par = [sp.Symbol(p.name, real=True) for p in spec.parameters]
    sub = dict(spec.pose_to_study)
    study = list(sub)
    # the pose is converted to Study coordinates once per call; the IK steps are polynomial
    # in those coordinates
    kernels = [kernel("_study", [*spec.pose, *par], [sub[y] for y in study],
                      "Study coordinates STUDY_POSE of the pose (POSE).")]
    step_kernels, steps_src, mode_bits = _step_kernels("step", spec.steps, study, par, {})
    kernels += step_kernels
    bit = len(mode_bits)
    fk_kernels, fk_src, fk_bits = _step_kernels("fkstep", spec.fk_steps, spec.joints, par, {})
    kernels += fk_kernels
    has_fk = bool(spec.fk_steps or spec.rps)
    if spec.rps:
        kernels += _rps_kernels(spec.rps, spec.joints, par)
    if has_fk:
        kernels.append(kernel("_fk_pose", [*spec.rps_unknowns, *spec.fk_unknowns, *par],
                              [spec.study_to_pose[x] for x in spec.pose],
                              "Pose coordinates (POSE) from the solved Study coordinates."))
    if spec.fk_steps:
        system = sp.Matrix(list(spec.fk_system))
        kernels.append(kernel(
            "_fk_newton", [*spec.fk_unknowns, *spec.joints, *par],
            list(system) + list(system.jacobian(sp.Matrix(list(spec.fk_unknowns)))),
            "Residuals of the leg generators and their Jacobian in FK_UNKNOWNS (row-major)."))
    gens = [sp.expand(st.generator) for st in spec.steps]
    args = [*spec.pose, *spec.joints, *par]
    g_pose = [g.subs(sub) for g in gens]
    ji = sp.Matrix(g_pose).jacobian(sp.Matrix(spec.joints))
    jo = sp.Matrix(g_pose).jacobian(sp.Matrix(spec.pose))
    jo_study = sp.Matrix(gens).jacobian(sp.Matrix(study)).subs(sub)
    tri = _triangular_jacobian(spec.steps, gens, spec.joints, spec.pose, sub)
    # pivots of linear steps that can vanish (a constant pivot never does)
    linear = [k for k, st in enumerate(spec.steps)
              if st.degree == 1 and not sp.diff(gens[k], st.joint).is_number]
    piv = [sp.diff(gens[k], spec.steps[k].joint) for k in linear]
    piv_scale = [sp.Abs(pv, evaluate=False) + sum(sp.Abs(sp.diff(gens[k], y)) for y in study)
                 for k, pv in zip(linear, piv)]
    if linear:
        kernels.append(kernel("_pivots", [*study, *spec.joints, *par], piv + piv_scale,
                              "Pivots dG_k/dq_k of the linear IK steps and their row scales "
                              "(in Study coordinates)."))
    kernels.append(kernel("_jac", args, tri,
                          "Pivots dG_k/dq_k, row scales, then dq/dX row-major (forward "
                          "substitution: Ji is triangular in the solve order)."))
    kernels.append(kernel("_ji", args, list(ji), "Input Jacobian dG/dq, row-major."))
    kernels.append(kernel("_jo", args, list(jo), "dG/dX for the pose coordinates, row-major."))
    kernels.append(kernel("_jo_study", args, list(jo_study),
                          "Output Jacobian dG/dy in Study coordinates, row-major."))
    if spec.limits:
        kernels.append(kernel("_limit_values", args, [sp.sympify(lim[1]) for lim in spec.limits],
                              "Quantities bounded by LIMITS (joint strokes, passive angles)."))
    pf_src = []
    for fname, outs, exprs, doc in spec.pose_functions:
        kern = kernel(f"_pf_{fname}", [*spec.pose, *par], list(exprs), doc)
        kernels.append(kern)
        pf_src += [
            "",
            "",
            f"def {fname}(pose, **params):",
            f'    """{doc} Returns (..., {len(outs)}): {", ".join(outs)}."""',
            f"    return _pose_function({fname!r}, {kern.name}, pose, params)",
        ]
    for fname, inputs, outs, exprs, doc in spec.functions:
        kern = kernel(f"_fn_{fname}", [*inputs, *par], list(exprs), doc)
        kernels.append(kern)
        names = tuple(str(v) for v in inputs)
        pf_src += [
            "",
            "",
            f"def {fname}(values, **params):",
            f'    """{doc} ``values``: (..., {len(names)}) = {", ".join(names)}; returns '
            f'(..., {len(outs)}): {", ".join(outs)}."""',
            f"    return _function({fname!r}, {kern.name}, values, {names!r}, params)",
        ]
    if spec.functions:
        pf_src += ["", "", _FUNCTION_HELPER.rstrip("\n")]
    sing_src = []
    for name, expr, meaning in spec.singularities:
        # in the Study coordinates of the pose (computed once by _study), not in the pose:
        # composed with the pose map, a large polynomial makes CSE slow and the kernel long
        expr = sp.sympify(expr)
        stray = expr.free_symbols - set(study) - set(spec.joints) - set(par)
        if stray:
            raise ValueError(f"{spec.name}: singularity {name} has symbols "
                             f"{sorted(map(str, stray))} outside the Study coordinates, "
                             "joints and parameters")
        kern = kernel(f"_sing_{name}", [*study, *spec.joints, *par], [expr], meaning)
        kernels.append(kern)
        sing_src.append(f"    {name!r}: {kern.name},")
    ops = {k.name: k.operations for k in kernels}
    total = sum(ops.values())
    n_modes = 2**bit
    lines = [
        f'"""{spec.title}: generated numeric kinematics.  DO NOT EDIT.',
        "",
        f"Generated by {spec.generator} from bonered_alg/mechanisms/{spec.name}.py;",
        "regenerate with `make derive`.",
        f"Source: {spec.source}.",
        f"Derivation hash: {spec.derivation_hash}",
        f"Operation count after common-subexpression elimination: {total}.",
        "",
        "Contract (DESIGN.md section 4): ik, ik_all, ik_status, ik_and_status, fk, fk_status,",
        "jacobian, jacobian_status, jacobian_and_status, input_jacobian, output_jacobian,",
        "singularities; all vectorized",
        "over leading axes.",
        "Imports numpy only.",
        '"""',
        "",
        "import numpy",
        "",
        f"MECHANISM = {spec.name!r}",
        f"SOURCE = {spec.source!r}",
        f"DERIVATION_HASH = {spec.derivation_hash!r}",
        f"GENERATOR = {spec.generator!r}",
        f"OPERATION_COUNT = {total}",
        "PARAMETERS = {",
        *[f"    {p.name!r}: {_literal(p.value)}," for p in spec.parameters],
        "}",
        "PARAMETER_UNITS = {",
        *[f"    {p.name!r}: {p.unit!r}," for p in spec.parameters],
        "}",
        "PARAMETER_NOTES = {",
        *[f"    {p.name!r}: {(p.description + '; ' + p.source)!r}," for p in spec.parameters],
        "}",
        f"POSE = {tuple(str(s) for s in spec.pose)!r}",
        f"POSE_UNITS = {tuple(spec.pose_units)!r}",
        f"STUDY_POSE = {tuple(str(s) for s in study)!r}",
        f"JOINTS = {tuple(str(s) for s in spec.joints)!r}",
        f"JOINT_UNITS = {tuple(spec.joint_units)!r}",
        f"MODES = {n_modes}",
        "# working mode m takes the '-sqrt' root of a joint's quadratic when bit b of m is set",
        f"MODE_BITS = {tuple(mode_bits)!r}",
        f"_SOLVE_ORDER = {tuple(str(st.joint) for st in spec.steps)!r}",
        f"_SOLVE_INDEX = {tuple(list(spec.joints).index(st.joint) for st in spec.steps)!r}",
        f"_CHECK_PIVOTS = {bool(linear)!r}",
        f"FK_UNKNOWNS = {tuple(str(u) for u in spec.fk_unknowns)!r}",
        "# Study coordinates of the 3-RPS closure solved through its eliminant (if any)",
        f"RPS_UNKNOWNS = {tuple(str(u) for u in spec.rps_unknowns)!r}",
        f"RPS_MODES = {DEGREE_BOUND if spec.rps else 0}",
        f"FK_MODES = {(DEGREE_BOUND if spec.rps else 1) * 2 ** len(fk_bits) if has_fk else 0}",
        f"FK_NOTE = {spec.fk_note if not has_fk else ''!r}",
        f"FK_MODE_BITS = {tuple(fk_bits)!r}",
        f"_FK_INDEX = {tuple(list(spec.fk_unknowns).index(st.joint) for st in spec.fk_steps)!r}",
        "# the generators of the lex basis solved for each Study coordinate in fk",
        "FK_GENERATORS = (",
        *[f"    ({str(st.joint)!r}, {sp.sstr(sp.expand(st.generator))!r}),"
          for st in spec.fk_steps],
        ")",
        "# the generator of the constraint ideal solved for each joint (rows of Ji, Jo)",
        "IK_GENERATORS = (",
        *[f"    ({str(st.joint)!r}, {sp.sstr(sp.expand(st.generator))!r}),"
          for st in spec.steps],
        ")",
        "# (name, lower, upper, kind, unit, source); kind 'stroke' or 'passive'",
        "LIMITS = (",
        *[f"    ({lim[0]!r}, {float(lim[2])!r}, {float(lim[3])!r}, {lim[4]!r}, {lim[5]!r}, "
          f"{lim[6]!r})," for lim in spec.limits],
        ")",
        "SINGULARITY_MEANING = {",
        *[f"    {name!r}: {meaning!r}," for name, _, meaning in spec.singularities],
        "}",
        "",
        "",
    ]
    for kern in kernels:
        lines.append(kern.source)
        lines.append("")
    lines += ["_STEPS = (", *steps_src, ")", "_FK_STEPS = (", *fk_src, ")",
              "_SINGULARITIES = {", *sing_src, "}", ""]
    return "\n".join(lines) + RUNTIME + ("\n".join(pf_src) + "\n" if pf_src else "")
