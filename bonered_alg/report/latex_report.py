"""The LaTeX derivation report ``derivations/<name>.tex`` (DESIGN.md section 5).

Every step a reviewer needs: parameters, topology, chain tables, chain products, closure
equations, elimination results, IK, Jacobians, singularities, and the verification section
with one row per printed equation or table row.  The text is deterministic (no dates, no
timings: those go to the benchmark results).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import polyring as pr
from ..chains.topology import loops, mobility_counts, topology
from ..kinematics.rps_forward import DEGREE_BOUND, PAIRS
from ..verification import NOISE_FLOOR
from .algebra_record import FULL_TERMS, degrees, is_long, terms
from .latex_util import broken_math, latex, matrix_math, prose, tex_escape

PREAMBLE = r"""\documentclass[10pt,a4paper]{article}
\usepackage[margin=2cm]{geometry}
\usepackage{amsmath,amssymb}
\usepackage{booktabs,longtable,graphicx}
\allowdisplaybreaks
\setlength{\parindent}{0pt}
\setlength{\parskip}{4pt}
% the math bullet: \textbullet comes from TS1, a Type 3 bitmap font without cm-super
\renewcommand{\labelitemi}{$\bullet$}
"""

VERDICT_TEX = {"confirmed-symbolic": "confirmed (symbolic)", "confirmed-numeric":
               "confirmed (numeric)", "erratum": r"\textbf{erratum}",
               "not-checkable": "not checkable"}


def _study(point) -> str:
    return "[" + ":".join(latex(c) for c in point) + "]"


def _section_overview(record) -> list[str]:
    """The first page: what the mechanism is, where it comes from, its mobility and modes,
    where the printed equations stand, and what the report contains."""
    from collections import Counter

    d, gm = record.derivation, record.generated
    m = d.mechanism
    counts = mobility_counts(m.closures)
    fk_modes = getattr(gm.module, "FK_MODES", 0) if gm.module is not None else 0
    verdicts = Counter(v.verdict for v in record.verification)
    errata = [v.ref for v in record.verification if v.verdict == "erratum"]
    legs = sum(len(c.legs) for c in m.closures)
    rows = [
        ("mechanism", tex_escape(m.title)),
        ("source", tex_escape(m.source)),
        ("closures, legs", f"{len(m.closures)} closure{'s' if len(m.closures) > 1 else ''} ("
         + ", ".join(tex_escape(c.name) for c in m.closures) + f"), {legs} legs"),
        ("actuated joints", ", ".join(
            f"${latex(q)}$" if q not in m.angle_joints else
            f"${latex(sp.Symbol(m.angle_joints[q]))} = 2\\arctan {latex(q)}$ [rad]"
            for q in m.joints)),
        ("pose", ", ".join(f"${latex(c)}$ [{tex_escape(u)}]"
                           for c, u in zip(m.pose.coordinates, m.pose.units))),
        ("mobility", f"$M = {sum(c.mobility for c in counts)}$ (the classical "
         "Kutzbach--Gr\\\"ubler count, per closure in Sect.~1; the screw-theory count and "
         "the ideal's dimension are in the section on mobility)"),
        ("working modes (IK)", f"{d.modes}"),
        ("assembly modes (FK)", str(fk_modes) if fk_modes else
         "not generated: " + tex_escape(d.fk_note)),
        ("singularity polynomials", ", ".join(
            f"{tex_escape(s.name)} ({singularity_class(s.name)[0]})"
            for s in d.singularities) or "none"),
        ("printed results", ", ".join(f"{n} {VERDICT_TEX[k]}" for k, n in sorted(
            verdicts.items())) + (("; errata: " + tex_escape(", ".join(errata))) if errata
                                  else "")),
    ]
    out = [r"\section*{Overview}", r"\begin{longtable}{p{0.22\textwidth}p{0.72\textwidth}}"
           r"\toprule"]
    out += [f"{k} & {v}\\\\" for k, v in rows]
    out.append(r"\bottomrule\end{longtable}")
    drawing = record.studies.get("configurations")
    if drawing is not None:
        png = next(f for f in drawing.files if f.endswith(".png"))
        out.append(r"\begin{center}\includegraphics[width=0.95\textwidth]{" + png
                   + r"}\end{center}")
        out.append(r"{\small The mechanism at home and on a singularity locus, drawn from the "
                   r"generated functions (Sect.~\ref{sec:configurations}).}")
    return out


def _section_mechanism(d) -> list[str]:
    m = d.mechanism
    out = [r"\section{Mechanism}", tex_escape(" ".join(m.summary.split())), "",
           f"Source: {tex_escape(m.source)}.", "",
           r"\subsection{Geometric parameters}",
           r"\begin{longtable}{llp{0.45\textwidth}p{0.22\textwidth}}\toprule",
           r"name & value & meaning & value source\\\midrule"]
    for p in m.parameters:
        val = f"{p.value:g} {tex_escape(p.unit)}"
        out.append(f"${latex(p.symbol)}$ & {val} & {tex_escape(p.description)} & "
                   f"{tex_escape(p.source)}\\\\")
    graph = topology(m.closures)
    out += [r"\bottomrule\end{longtable}", r"\subsection{Topology}",
            "Bodies and joints, derived from the legs (a networkx multigraph):",
            r"\begin{itemize}"]
    for a, b, data in sorted(graph.edges(data=True), key=lambda e: (e[2]["label"], e[0])):
        label = tex_escape(data['label'])
        out.append(rf"\item {tex_escape(data['joint'])} joint \texttt{{{label}}}"
                   f" between {tex_escape(a)} and {tex_escape(b)}")
    out.append(r"\end{itemize}")
    cycles = "; ".join("(" + ", ".join(loop) + ")" for loop in loops(graph))
    out.append(f"Independent loops (cycle basis): {tex_escape(cycles)}.")
    counts = mobility_counts(m.closures)
    rows = []
    for c in counts:
        rows.append(f"{tex_escape(c.closure)}: $M = {c.formula()}$"
                    + (f" ($c = {c.extra_constraints}$: {tex_escape(c.note)})"
                       if c.extra_constraints else ""))
    out.append(r"Kutzbach--Gr\"ubler mobility $M = \lambda(n-1-j) + \sum f_i - c$, per closure "
               r"($\lambda = 3$ for planar, 6 for spatial loops): " + "; ".join(rows)
               + f"; in all $M = {sum(c.mobility for c in counts)}$. The active joints are "
               + ", ".join(f"${latex(q)}$" for q in m.active) + ".")
    driven = [c for c in m.closures if c.driven]
    for c in driven:
        out.append(f"The {tex_escape(c.name)} is driven by "
                   + ", ".join(f"${latex(s)}$" for s in c.inputs)
                   + " (outputs of the other closures): its ideal is derived and generated, "
                   "not counted here.")
    helical = [j for c in m.closures for leg in c.legs for j in leg.joints if j.coupling]
    for j in helical:
        out.append(f"Helical joint {tex_escape(j.label)}: the ideal carries its turn "
                   f"${latex(j.coupling.rotation)}$ and slide ${latex(j.coupling.translation)}$"
                   " as a cylindrical joint (one more freedom than the joint has); the relation "
                   f"${latex(j.coupling.translation)} = {latex(j.coupling.pitch)}\\,\\theta$ "
                   "is applied to the recovered joint values.")
    return out


def _section_chains(d) -> list[str]:
    out = [r"\section{Chains of Study-parameter factors}",
           r"Convention (bonered\_alg.algebra.convention): $[x_0:x_1:x_2:x_3:y_0:y_1:y_2:y_3]$, "
           r"$y = -\tfrac12 t\,x$; a rotation by $\varphi$ about an axis is "
           r"$[1:u\,e:0:0:0:0]$ with $u = \tan(\varphi/2)$, a translation by $s$ along an axis "
           r"is $[1:0:0:0:0:-\tfrac{s}{2}e]$. The product of study points is the dual "
           "quaternion product and is a homomorphism of the matrix product, so each chain is "
           "read base to platform."]
    for r in d.legs:
        out += [rf"\subsection{{Leg {tex_escape(r.leg.name)} ({tex_escape(r.closure.name)}, "
                rf"point {tex_escape(r.closure.point)})}}",
                r"\begin{longtable}{lp{0.36\textwidth}lp{0.33\textwidth}}\toprule",
                r"symbol & factor & role & description\\\midrule"]
        for f in r.leg.factors:
            out.append(f"{tex_escape(f.label)} & ${_study(f.study())}$ & {f.role.value} & "
                       f"{tex_escape(f.motion())}; {tex_escape(f.description)}\\\\")
        out.append(r"\bottomrule\end{longtable}")
        out.append("Chain product (expanded):")
        names = ["x_0", "x_1", "x_2", "x_3", "y_0", "y_1", "y_2", "y_3"]
        for nm, c in zip(names, r.product):
            if c != 0:
                out.append(broken_math(nm, pr.expanded(c)))  # sp.expand's result
        zeros = [nm for nm, c in zip(names, r.product) if c == 0]
        if zeros:
            out.append("and $" + " = ".join(zeros) + " = 0$.")
    return out


def _section_elimination(d) -> list[str]:
    out = [r"\section{Closure equations and elimination}",
           "A leg closes on the platform when its chain product $C$ and the platform's Study "
           r"point $X$ are the same projective point. With the normalization $X_p = 1$ "
           r"the closure equations are $C_k - C_p X_k = 0$ ($k \neq p$) together with "
           r"$1 - \mu\, C_p = 0$, which excludes $C_p = 0$ (saturation). The passive joint "
           r"variables and $\mu$ are eliminated by a Groebner basis for an elimination order; "
           "the result is the reduced Groebner basis of the elimination ideal in the "
           "degree-reverse-lexicographic order on the kept variables, made primitive over the "
           "integers with a positive leading coefficient, so it is unique and both engines "
           "return it identically."]
    for r in d.legs:
        p = r.problem
        out += [rf"\subsection{{Leg {tex_escape(r.leg.name)}}}",
                f"Platform point ${tex_escape(r.closure.point)} = {_study(r.closure.platform)}$. "
                + tex_escape(r.closure.note)]
        if r.certificate:
            out += _distance_leg(r)
            continue
        if r.leg.mount is not None:
            out.append("The leg is mounted on a moving frame, $"
                       + _study(r.leg.mount) + "$; it is eliminated in that frame (platform "
                       r"coordinates $X' = \overline{T}X$, a linear change of coordinates) "
                       "and its generators carried back.")
        out.append(f"Closure equations ({len(p.equations)}):")
        for k, e in enumerate(p.equations, 1):
            out.append(broken_math(f"e_{{{k}}}", e))
        out += [
            "Eliminated: " + ", ".join(f"${latex(s)}$" for s in p.eliminate)
            + "; kept (in this order): " + ", ".join(f"${latex(s)}$" for s in p.keep) + ".",
            f"Result: {len(r.result.generators)} generator(s); Hilbert (Krull) dimension "
            f"{r.result.dimension} in {len(p.keep)} variables."]
        out += _generator_table(d, r, r.result.generators)
        if r.leg.mount is not None:
            out.append("In the platform's coordinates and the inputs:")
            out += _generator_table(d, r, r.generators)
    return out


def _summary(expr) -> str:
    """Degree in each variable, as a monomial of the variables: x^2 q^1 -> $x^{2} q$."""
    return "$" + r"\,".join(latex(v) + (f"^{{{k}}}" if k > 1 else "")
                             for v, k in degrees(expr) if k) + "$"


def _generator_table(d, r, generators) -> list[str]:
    """One row per generator (degrees, terms, use), then the short ones in full; every one
    is in full in ``<name>.algebra.json``."""
    used = {pr.expanded(sp.sympify(s.generator)): s for s in d.steps}
    out = [r"\begin{longtable}{lp{0.55\textwidth}rl}\toprule",
           r"generator & degree in each variable & terms & used for\\\midrule"]
    for k, g in enumerate(generators, 1):
        step = used.get(pr.expanded(sp.sympify(g)))
        use = f"IK of ${latex(step.joint)}$" if step is not None else ""
        out.append(f"$g_{{{k}}}$ & {_summary(g)} & {terms(g)} & {use}\\\\")
    out.append(r"\bottomrule\end{longtable}")
    short = [(k, g) for k, g in enumerate(generators, 1) if not is_long(g)]
    if short:
        out.append(f"The generators of at most {FULL_TERMS} terms"
                   + ("" if len(short) == len(generators) else
                      f" (the others, in full, in \\texttt{{{_algebra_file(d)}}})") + ":")
        for k, g in short:
            out.append(broken_math(f"g_{{{k}}}", g))
    else:
        out.append(f"Each has more than {FULL_TERMS} terms; in full in "
                   f"\\texttt{{{_algebra_file(d)}}}.")
    return out


def _algebra_file(d) -> str:
    return tex_escape(f"{d.mechanism.name}.algebra.json")


def _polynomial(lhs: str, expr, d) -> str:
    """``lhs = expr`` in full, or its summary where it is long."""
    if not is_long(expr):
        return broken_math(lhs, expr)
    return (f"${lhs}$: {terms(expr)} terms, degree in each variable {_summary(expr)} "
            f"(in full in \\texttt{{{_algebra_file(d)}}}).\n")


DISTANCE_LEG_MAX_TERMS = 120


def _constant_symbols(r) -> list:
    """Symbols of the leg problem bound by a univariate equation (algebraic constants)."""
    return [next(iter(e.free_symbols)) for e in r.problem.equations
            if len(e.free_symbols) == 1]


def _distance_leg(r) -> list[str]:
    """A leg whose ideal is the pulled-back sphere condition (no elimination run)."""
    p = r.problem
    out = ["This leg only fixes the distance between a base point and a platform point. Its "
           "ideal is not eliminated but written down, the Study quadric and the sphere "
           r"condition $q^2 |x|^2 - 4 |y'|^2$ with $[x:y'] = T(-A)\,X\,T(B)$, and certified "
           "(the steps are in \\texttt{bonered\\_alg/elimination/sphere\\_leg.py}): "
           + tex_escape(r.certificate) + ".",
           f"Defining equations ({len(p.equations)}):"]
    for k, e in enumerate(p.equations, 1):
        out.append(broken_math(f"e_{{{k}}}", e))
    gens = r.result.generators
    # the generators are sums of monomials already (as_expressions): their terms are
    # counted as they are (expanding them again took a tenth of Stewart's derivation)
    short = [g for g in gens if len(sp.Add.make_args(g)) <= DISTANCE_LEG_MAX_TERMS]
    consts = [c for c in _constant_symbols(r) if c in p.keep]
    bound = (", with " + ", ".join(f"${latex(c)}$" for c in consts) + " as variables bound by "
             "their minimal polynomials" if consts else "")
    out.append(f"Reduced Groebner basis (Hilbert dimension {r.result.dimension} in "
               f"{len(p.keep)} variables{bound}): {len(gens)} generators; the "
               f"{len(gens) - len(short)} with more than {DISTANCE_LEG_MAX_TERMS} terms are "
               "omitted here.")
    for k, g in enumerate(short, 1):
        out.append(broken_math(f"g_{{{k}}}", g))
    return out


POSE_MAP_MAX_CHARS = 1500


def _pose_map(d) -> list[str]:
    """The Study coordinates of the platform as functions of the pose, one display each, or
    a pointer to the generated kernel where one is too long to read."""
    out = []
    for k, v in d.pose_to_study.items():
        if len(latex(v)) <= POSE_MAP_MAX_CHARS:
            out.append(broken_math(latex(k), v))
        else:
            out.append(f"${latex(k)}$: a rational function of the pose with "
                       f"{pr.count_ops(v)} operations before common-subexpression "
                       "elimination; its construction is given in the mechanism's own "
                       r"section, its code in \texttt{\_study}.")
    return out


def _section_ik(d) -> list[str]:
    out = [r"\section{Inverse kinematics}",
           "Each active joint is solved from a generator of the ideals above whose only "
           "unknown joint is that one (back-substitution). A quadratic "
           r"$A q^2 + B q + C = 0$ has the roots $q = (-B \pm \sqrt{B^2-4AC})/(2A)$; "
           r"the sign is the working mode of that step ($+$: mode bit 0). "
           f"Number of working modes: {d.modes}. The platform's Study coordinates in the "
           "pose coordinates (" + tex_escape(d.mechanism.pose.description) + "):"]
    out += _pose_map(d)
    out += _mode_table(d)
    for s in d.steps:
        out.append(rf"\paragraph{{Joint ${latex(s.joint)}$}} from {tex_escape(s.source)}, "
                   f"degree {s.degree}:")
        if s.degree == 2:
            out.append(_polynomial("A", s.A, d))
        out.append(_polynomial("B", s.B, d))
        out.append(_polynomial("C", s.C, d))
    return out


def _mode_table(d) -> list[str]:
    """The working-mode bits: which root of which joint's step each bit selects, and which
    root mode 0 is at the home pose (the declared physical branch)."""
    m = d.mechanism
    branch = {b.joint: b for b in d.branches}
    rows, bit = [], 0
    for st in d.steps:
        if st.degree != 2:
            rows.append(f"${latex(st.joint)}$ & linear & -- & one root\\\\")
            continue
        b = branch.get(st.joint)
        if b is None:
            home = "not declared: the $+$ root of the generator as eliminated"
        else:
            home = (f"${b.mode0:.6g}$ (declared ${b.declared:g}$; the other root "
                    f"${b.roots[0] if b.negated else b.roots[1]:.6g}$"
                    + ("; generator negated" if b.negated else "") + ")")
        rows.append(f"${latex(st.joint)}$ & quadratic & {bit} & {home}\\\\")
        bit += 1
    where = ("at the home pose $(" + ", ".join(f"{v:g}" for v in m.home) + ")$ in ("
             + ", ".join(f"${latex(c)}$" for c in m.pose.coordinates) + ")"
             if m.home else "(no home pose declared)")
    return [f"Working modes: mode $m$ takes the $-$ root of a step when its bit is set in "
            f"$m$; mode 0 is the physical branch the mechanism declares {where}.",
            r"\begin{longtable}{llcp{0.55\textwidth}}\toprule",
            r"joint & step & mode bit & mode 0 at home\\\midrule", *rows,
            r"\bottomrule\end{longtable}"]


def _section_fk(d) -> list[str]:
    if not d.fk:
        return [r"\section{Forward kinematics}", "Not generated: " + tex_escape(d.fk_note)
                + "."]
    out = [r"\section{Forward kinematics}",
           "For each closure, the union of its leg ideals is a system in the platform's Study "
           "coordinates with the active joints and the geometry as parameters. Its "
           r"lexicographic Groebner basis over $\mathbb{Q}(\text{joints}, \text{geometry})$ "
           "is triangular (zero-dimensional ideal), so all assembly modes follow by "
           "back-substitution; denominators are cleared and each generator is made primitive. "
           "Where a leading coefficient of the basis vanishes for particular joint values, the "
           "specialization of the basis is not valid there (the analogue of the divisions "
           "noted in 004 Sect. 3.3); the generated \\texttt{fk} reports such points as "
           "failures rather than returning values."]
    total = 1
    for f in d.fk:
        total *= f.solutions or 0
        out.append(rf"\subsection{{{tex_escape(f.closure)}}}")
        if f.system is not None:
            out += _rps_fk(f)
            continue
        out.append("Unknowns " + ", ".join(f"${latex(u)}$" for u in f.problem.unknowns)
                   + "; parameters " + ", ".join(f"${latex(p)}$" for p in f.problem.parameters)
                   + f". Hilbert dimension {f.dimension} over the parameter field; "
                   f"{f.solutions} solutions counted with multiplicity (standard monomials).")
        for k, g in enumerate(f.result.generators, 1):
            out.append(broken_math(f"b_{{{k}}}", g))
        out.append("Back-substitution order: " + ", ".join(
            f"${latex(s.joint)}$ (degree {s.degree})" for s in f.steps) + ".")
        out += _alternate_plans(f)
    out.append(f"Assembly modes of the whole: {total} (the product over the closures); "
               r"the generated \texttt{fk} returns every one of them, NaN where a mode is not "
               "real, real modes of a 3-RPS closure first.")
    return out


def _alternate_plans(f) -> list[str]:
    """The plans from other elimination orders and why they are there."""
    if not f.alternates:
        return []

    def pivot(b):  # in full where it is short, else its size (long ones run off the page)
        text = latex(sp.factor(b))
        if len(text) <= 80:
            return f"${text}$"
        free = sorted(b.free_symbols, key=str)
        return (f"a polynomial of total degree {sp.Poly(b, *free).total_degree()} with "
                f"{len(sp.Add.make_args(sp.expand(b)))} terms in "
                + ", ".join(f"${latex(x)}$" for x in free))

    def pivots(steps):
        return ", ".join(f"${latex(s.joint)}$: {pivot(s.B)}" for s in steps
                         if s.degree == 1 and s.B.free_symbols) or "none"

    out = ["Pivots of the linear steps that can vanish: " + pivots(f.steps) + ". Where one "
           "vanishes the basis divides by zero although the closure need not be singular "
           "there. The lex bases in the other orders of the unknowns "
           "give these plans, whose pivots share no factor with the first plan's (gcd 1, "
           "checked symbolically), so both divide by zero only where their pivots vanish "
           "together, a set of codimension two:"]
    for k, alt in enumerate(f.alternates, 1):
        out.append(f"plan {k + 1}: order " + ", ".join(
            f"${latex(s.joint)}$ (degree {s.degree})" for s in alt) + "; pivots "
            + pivots(alt) + ".")
    out.append(r"The generated \texttt{fk} checks every mode of the first plan by a "
               "Gauss-Newton step on the leg generators; a mode that fails is taken from "
               "the other plans (status OK or FORWARD\\_SINGULAR after the same check), and "
               "where none gives it the mode is UNVERIFIED (NaN), never a wrong pose. A locus "
               "where only the first plan's pivot vanishes is therefore an artefact of the "
               "basis, not a singularity: there the other plan solves, and the closure's "
               "Jacobian, checked at each returned mode, is regular.")
    return out


def _rps_fk(f) -> list[str]:
    """The 3-RPS closure's forward kinematics (kinematics/rps_forward.py)."""
    r = f.system
    u = ", ".join(f"${latex(a)}$" for a in r.angles)
    out = [
        "A 3-RPS closure: each leg's revolute joint (" + u + ", tangents of the half "
        "angles) turns the leg of length " + ", ".join(f"${latex(q)}$" for q in r.joints)
        + " in a plane, so its spherical joint centre $B_k$ runs on a circle. The centres, "
        "from the product of the leg's factors before the spherical joint:"]
    for k, c in enumerate(r.centres, 1):
        out.append(broken_math(f"B_{{{k}}}", sp.Matrix(c).T))
    out.append("The platform is rigid: $|B_i - B_j|^2 = |P_i - P_j|^2$ with the platform "
               "points $P_k$ (the trailing offsets inverted), "
               + ", ".join(f"$P_{{{k}}} = {latex(sp.Matrix(p).T)}$"
                           for k, p in enumerate(r.platform, 1))
               + ". Cleared of the denominators $1 + u_k^2$ (no real zeros) and of content, "
               "each condition is biquadratic:")
    for (i, j), e in zip(PAIRS, r.equations):
        out.append(broken_math(f"e_{{{i + 1}{j + 1}}}", e))
    at = ", ".join(f"${latex(k)} = {latex(v)}$" for k, v in f.count_at.items())
    out.append(
        r"The lex basis of $\langle e_{12}, e_{23}, e_{31}\rangle$ over $\mathbb{Q}$(joints, "
        "geometry) did not finish in 600 s in Singular (measured once, for the layout of "
        "001), so the generated code forms the "
        "eliminant per configuration as the iterated resultant "
        r"$\mathrm{Res}_{u_3}(\mathrm{Res}_{u_2}(e_{12}, e_{23}), e_{31})$, a polynomial of "
        rf"degree at most $2\cdot 4 + 4\cdot 2 = {DEGREE_BOUND}$ in the first angle that lies "
        "in the ideal. A Groebner basis certifies that degree: at the generic rational "
        f"configuration {at} the ideal has {f.solutions} solutions (standard monomials of its "
        "lex basis), so the eliminant neither misses nor adds an assembly mode. "
        r"Every solution has a mirror image through the base plane ($u_k \to 1/u_k$, "
        r"$\theta_k \to \pi - \theta_k$), so the real modes come in pairs, half of them "
        "with the platform below the base.")
    out.append(
        r"Numerically (\texttt{\_rps\_solve}): the eliminant is sampled at 17 roots of unity "
        "of a shifted variable $w$ ($u_1 = (w + T)/(1 - T w)$, so a vertical leg costs no "
        "degree), its coefficients follow by a discrete Fourier transform, its roots from the "
        "companion matrix; $u_2$, $u_3$ are the roots of $e_{12}$ and $e_{31}$ that satisfy "
        "$e_{23}$ (every pair that does, where two modes share $u_1$, as at symmetric "
        "configurations); five Newton steps in the joint angles polish each real mode, a "
        "residual test rejects what does not converge, and duplicates are removed. A mode "
        r"where the Jacobian of $(e_{12}, e_{23}, e_{31})$ is nearly singular (two modes "
        r"merge: a forward singularity) is returned with the status FORWARD\_SINGULAR. "
        "The platform frame follows from the three centres, its Study coordinates from "
        "004 eq. (4)-(5) in the chart $x_0 = 1$.")
    return out


def _section_velocity(d) -> list[str]:
    out = [r"\section{Velocity model and singularities}",
           r"With the IK generators $G$ (one per active joint), $J_i \dot q + J_o \dot X = 0$ "
           r"with $J_i = \partial G/\partial q$ and $J_o = \partial G/\partial X$ (004 eq. "
           r"19--21), so $\partial q/\partial X = -J_i^{-1} J_o$. The generated module "
           "evaluates both matrices and the solve, and returns NaN with a status where "
           r"$\det J_i$ vanishes."]
    for v in d.velocity:
        out.append(rf"\subsection{{{tex_escape(v.closure)}}}")
        out.append("Rows: the IK generators of " + ", ".join(f"${latex(q)}$" for q in v.joints)
                   + "; $J_i$ columns " + ", ".join(f"${latex(q)}$" for q in v.joints)
                   + ", $J_o$ columns " + ", ".join(f"${latex(y)}$" for y in v.pose) + ".")
        for name, mat in (("J_i", v.ji), ("J_o", v.jo)):
            out += _jacobian(name, mat, d)
    out.append(r"\subsection{Singularity polynomials}")
    out += _singularity_table(d)
    for s in d.singularities:
        if s.is_determinant:
            out.append(rf"\paragraph{{{tex_escape(s.name)}}} {tex_escape(s.meaning)}. "
                       f"A polynomial of high degree, not expanded: the generated code "
                       f"evaluates the {s.expression.rows}$\\times${s.expression.cols} "
                       r"matrix $J_o$ of this closure (above) with the gradient of the Study "
                       r"quadric $S$ appended as its last row, and its determinant "
                       "numerically:")
            last = s.expression[s.expression.rows - 1, :]
            out.append(matrix_math(r"\partial S/\partial y", last))
            continue
        loci, never = _classified_factors(d, s)
        out.append(rf"\paragraph{{{tex_escape(s.name)}}} {tex_escape(s.meaning)}. ")
        if never:
            out.append("Factors that vanish nowhere (left out below): the constant "
                       f"${latex(s.constant)}$, "
                       + ", ".join(f"${latex(f)}$ (" + (f"power {m}; " if m > 1 else "")
                                   + f"{why})" for f, m, why in never) + ".")
        else:
            out.append(f"Constant factor ${latex(s.constant)}$.")
        out.append("The irreducible factors whose zero sets are the locus:" if loci else
                   "No factor vanishes anywhere: never singular.")
        for k, (f, mult) in enumerate(loci, 1):
            name = f"f_{{{k}}}" + (f"^{{{mult}}}" if mult > 1 else "")
            out.append(_polynomial(name, f, d))
        notes = d.mechanism.singularity_notes
        if s.name in notes:
            out.append(tex_escape(notes[s.name]))
    return out


SINGULARITY_CLASSES = (  # name prefix -> (class, what a reviewer should read it as)
    ("det_Ji", "input (type I)", "a joint rate does not move the platform: an actuator "
                                 "direction is lost"),
    ("boundary", "boundary", "two working modes of a leg merge: the edge of its reach, "
                             "also an input singularity"),
    ("det_Jo", "output (type II)", "the platform moves with the actuators locked"),
    ("det_forward", "forward (type II)", "two assembly modes merge: the platform moves with "
                                         "the actuators locked"),
)


def singularity_class(name: str) -> tuple[str, str]:
    """The class of a singularity polynomial by the name the pipeline gives it."""
    for prefix, cls, meaning in SINGULARITY_CLASSES:
        if name.startswith(prefix):
            return cls, meaning
    return "other", ""


def _singularity_table(d) -> list[str]:
    """One row per singularity polynomial: its class, the factors that define its locus."""
    out = [r"\begin{longtable}{lllp{0.42\textwidth}}\toprule",
           r"polynomial & class & locus factors & meaning\\\midrule"]
    for s in d.singularities:
        cls, meaning = singularity_class(s.name)
        if s.is_determinant:
            count = f"det of {s.expression.rows}$\\times${s.expression.cols}"
        else:
            loci, _ = _classified_factors(d, s)
            count = str(len(loci)) if loci else "none (never singular)"
        out.append(f"{tex_escape(s.name)} & {cls} & {count} & {tex_escape(meaning)}\\\\")
    out.append(r"\bottomrule\end{longtable}")
    return out


def _classified_factors(d, s):
    """The factors of a singularity polynomial that define a locus, and those that do not
    (free of the configuration, or positive for every real configuration) with the reason."""
    from ..kinematics.ik_plan import _definite

    m = d.mechanism
    values = {c.symbol: c.value for c in m.constants}
    fixed = set(m.geometric) | set(values)
    loci, never = [], []
    for f, mult in s.factors:
        # a factor without the constants is expanded as it is (subs would copy it)
        g = sp.expand(f.subs(values)) if f.free_symbols & set(values) else pr.expanded(f)
        if g.is_number and g != 0:
            never.append((f, mult, "a non-zero constant"))
        elif _definite(g):
            never.append((f, mult, "positive for all real values"))
        elif not (f.free_symbols - fixed):
            never.append((f, mult, "free of the configuration: a condition on the geometry"))
        else:
            loci.append((f, mult))
    return loci, never


def _jacobian(name: str, mat, d) -> list[str]:
    """The matrix itself where it fits the page; else its pattern (entries named by row and
    column, zeros shown) and the entries, in full where they are short."""
    mat = mat.applyfunc(lambda e: pr.expanded(sp.sympify(e)))
    if all(not is_long(e) for e in mat):
        return [matrix_math(name, mat.applyfunc(sp.factor))]

    def entry(i, j):
        return f"({name})_{{{i + 1}{j + 1}}}" if mat.cols < 10 else f"({name})_{{{i + 1},{j + 1}}}"

    rows = [" & ".join("0" if mat[i, j] == 0 else entry(i, j) for j in range(mat.cols))
            for i in range(mat.rows)]
    out = ["\\begin{align*}\n" + f"{name} &= \\begin{{bmatrix}}" + r"\\".join(rows)
           + "\\end{bmatrix}\n\\end{align*}", "with"]
    for i in range(mat.rows):
        for j in range(mat.cols):
            if mat[i, j] != 0:
                e = mat[i, j]
                out.append(_polynomial(entry(i, j), e if is_long(e) else sp.factor(e), d))
    return out


def _section_passive(d) -> list[str]:
    """How each leg's passive joints follow from the pose (kinematics/passive.py)."""
    from ..kinematics.passive import LinearStep, QuadraticStep

    if not d.passive:
        return []
    out = [r"\section{Passive joints}",
           "Each passive joint variable is recovered from the pose and the actuated joints "
           "(the generated \\texttt{passive\\_joints}): from generators of the leg's closure "
           "ideal linear in it (several candidates; per configuration the one with the "
           "largest relative pivot), from a quadratic (the root of smaller magnitude, the "
           "joint within 90 degrees of its zero), or, for a spherical joint, as the rotation "
           r"that remains, $\overline{B} X \overline{A}$ for the factors $B$ before and $A$ "
           "after it.",
           r"\begin{longtable}{lp{0.75\textwidth}}\toprule leg & recovery\\\midrule"]
    for r in d.passive:
        if r.note:
            out.append(f"{tex_escape(r.leg)} & not recovered: {tex_escape(r.note)}\\\\")
            continue
        parts = []
        for st in r.steps:
            if isinstance(st, LinearStep):
                parts.append(f"${latex(st.variable)}$ (linear, {len(st.candidates)} "
                             "candidate" + ("s" if len(st.candidates) > 1 else "") + ")")
            elif isinstance(st, QuadraticStep):
                parts.append(f"${latex(st.variable)}$ (quadratic)")
            else:
                parts.append("$" + ", ".join(latex(v) for v in st.variables)
                             + "$ (spherical)")
        out.append(f"{tex_escape(r.leg)} & " + "; ".join(parts) + r"\\")
    out.append(r"\bottomrule\end{longtable}")
    if d.mechanism.pose.end_effector is not None:
        out.append("The end effector's spatial twist $(\\omega; v) = (\\dot g g^{-1})^\\vee$ "
                   "follows from the derivative of its Study point (\\texttt{pose\\_twist}); "
                   "with the inverse of $\\partial q/\\partial X$ it maps joint rates to the "
                   "twist (\\texttt{twist\\_jacobian}).")
    return out


def section_verification(verdicts) -> list[str]:
    out = [r"\section{Verification against the paper}",
           "One row per printed equation or table row. Verdicts: confirmed symbolically "
           "(identity proven by computer algebra), confirmed numerically (max error given), "
           "erratum (the printed form disagrees with the derivation; the corrected form and "
           "the evidence follow), not checkable (an input or a definition).",
           r"\begin{longtable}{p{0.17\textwidth}p{0.2\textwidth}p{0.13\textwidth}"
           r"p{0.4\textwidth}}\toprule",
           r"reference & quantity & verdict & detail\\\midrule\endhead"]
    for v in verdicts:
        err = "" if v.max_error is None else (
            f" (max error at most {v.max_error:.0e}: floating-point noise)"
            if v.max_error == NOISE_FLOOR else f" (max error {v.max_error:.2e})")
        out.append(f"{tex_escape(v.ref)} & {prose(v.quantity)} & "
                   f"{VERDICT_TEX[v.verdict]}{err} & {prose(v.detail)}\\\\")
    out.append(r"\bottomrule\end{longtable}")
    errata = [v for v in verdicts if v.verdict == "erratum" and v.evidence]
    if errata:
        out.append(r"\subsection{Evidence for the errata}")
        for v in errata:
            out.append(rf"\paragraph{{{tex_escape(v.ref)}}} printed minus derived "
                       "(or the stated residual):")
            out.append(r"\begin{align*}&" + v.evidence.replace("&", r"\&") + r"\end{align*}")
    return out


def _section_interpretation(d) -> list[str]:
    notes = d.mechanism.reading_notes
    if not notes:
        return []
    out = [r"\section{Reading of the source text}", r"\begin{itemize}"]
    out += [rf"\item {tex_escape(' '.join(b.split()))}" for b in notes]
    out.append(r"\end{itemize}")
    return out


def render_report(record) -> str:
    """The complete ``.tex`` source of a derivation record."""
    from ..pipeline.stages import report_sections

    d, gm = record.derivation, record.generated
    m = d.mechanism
    ik_ops = sum(v for k, v in gm.operations.items() if k.startswith("_step"))
    body = [PREAMBLE, r"\title{" + tex_escape(m.title) + r": derivation report}",
            r"\author{bonered\_alg (generated by \texttt{make derive})}", r"\date{}",
            r"\begin{document}", r"\maketitle",
            f"Derivation hash: \\texttt{{{d.derivation_hash}}}. Generated module: "
            f"\\texttt{{generated/{tex_escape(m.name)}.py}} ({gm.total_operations} operations "
            f"after common-subexpression elimination, {ik_ops} of them in the IK steps).", ""]
    body += _section_overview(record)
    for part in (_section_mechanism, _section_chains, _section_elimination, _section_ik,
                 _section_fk, _section_velocity, _section_passive):
        body += part(d)
    body += report_sections(d, record.studies)
    body += section_verification(record.verification)
    body += _section_interpretation(d)
    body.append(r"\end{document}")
    return "\n".join(body) + "\n"
