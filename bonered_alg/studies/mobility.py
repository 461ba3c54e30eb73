"""Mobility of every mechanism two independent ways (issue 17; 003 Sect. 2.1): screw theory
at the home configuration, and the dimension of the constraint variety.

Run for every mechanism that declares a home pose.  At home (the generated module's IK in
mode 0 and its passive joints), each leg's joint screws (:mod:`bonered_alg.mobility.chains`)
give, per closure, the order d, the redundant constraints v, the local freedoms and the
modified Kutzbach-Grubler count M (003 eq. 2), and the platform's twist space (its
dimension and how many rotations it has).  Independently, the tangent space of the
closure's ideal at the same point: the number of its coordinates and joints minus the
rank of the generators' Jacobian there; and its Krull dimension where the declaration asks
for it (:mod:`bonered_alg.analyses.closure_dimension`).  The counts agree when M plus the
local freedoms (the joint motions of a chain that move no other body) equals the tangent
dimension.  One configuration: a generic one gives the generic counts.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp

from ..algebra import polyring as pr
from ..analyses.closure_dimension import ClosureDimension
from ..mobility.chains import leg_chain, spatial_twist
from ..mobility.screws import ChainScrews, mobility, rank
from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from .files import csv_text


def home_values(d, gen, pose=None) -> dict[sp.Symbol, float]:
    """Every symbol of the legs at home (or at ``pose``): the geometry, the constants, the
    closures' coordinates (pose map), the actuated joints (the algebra's, IK mode 0) and
    the passive joints."""
    home = np.asarray(gen.HOME if pose is None else pose, dtype=float)
    mech = d.mechanism
    vals: dict[sp.Symbol, float] = {s.symbol: float(s.value) for s in mech.parameters}
    vals.update({k: float(sp.sympify(v).evalf()) for k, v in d.constants.items()})
    pose = dict(zip(mech.pose.coordinates, home))
    vals.update({k: float(v) for k, v in pose.items()})
    for k, v in d.pose_to_study.items():
        vals[k] = float(sp.sympify(v).subs(d.constants).subs(pose).subs(vals).evalf())
    q = gen._MODEL.algebraic(gen.ik(home, limits=False))  # noqa: SLF001
    vals.update({s: float(x) for s, x in zip(mech.joints, q)})
    passive = gen.passive_joints(home)
    names = {str(s): s for s in mech.passive}
    vals.update({names[n]: float(x) for n, x in zip(gen.PASSIVE, passive)})
    return vals


def _fill_coordinates(d, closure, vals) -> None:
    """Closure coordinates the pose map does not give (e.g. 004's yu3, fixed by the
    height): from a generator linear in one of them whose other symbols have values."""
    gens = d.closure_generators(closure.point)
    for c in closure.pose:
        if c in vals:
            continue
        for g in gens:
            if g.has(c) and sp.degree(g, c) == 1 and g.free_symbols - {c} <= set(vals):
                a, b = sp.Poly(g, c).all_coeffs()
                vals[c] = float(-b.subs(vals) / a.subs(vals))
                break


def platform_chain(closure, vals) -> ChainScrews | None:
    """The closure's platform coordinates as one more chain where they restrict its motion
    (rank of their twists below 6: a declared constraint such as 004's parallelograms, or a
    planar closure, where it changes nothing): one joint per freedom."""
    point = tuple(sp.sympify(c) for c in closure.platform)
    g = np.array([float(c.subs(vals)) for c in point])
    screws = np.array([spatial_twist(g, np.array([float(sp.diff(c, v).subs(vals))
                                                  for c in point]))
                       for v in closure.pose])
    r = rank(screws)
    return None if r == 6 else ChainScrews("platform coordinates", screws, r, r)


def _gradient(expr, unknowns, vals) -> tuple[np.ndarray, float]:
    """d(expr)/d(unknowns) at ``vals``, from its polynomial terms in exact rational
    arithmetic at the (binary) point, and the largest sum of the terms' magnitudes (the
    scale the gradient is computed against: the long generators' terms cancel by many
    orders of magnitude).  Both exact (FLINT's rational polynomials): the partial of the
    polynomial at ``x``, and the partial of the polynomial with the coefficients' absolute
    values at ``|x|`` (the sum of the partial's terms' magnitudes)."""
    import flint

    syms = sorted(expr.free_symbols, key=str)
    if not syms:
        return np.zeros(len(unknowns)), 0.0
    terms = pr.terms_of(expr, syms)
    if terms is None:  # not an expanded polynomial with rational coefficients
        poly = sp.Poly(expr, *syms)
        terms = {e: Fraction(int(c.p), int(c.q)) if c.is_Rational else Fraction(float(c))
                 for e, c in zip(poly.monoms(), poly.coeffs())}
    ctx = flint.fmpq_mpoly_ctx.get(tuple(f"v{i}" for i in range(len(syms))), "lex")

    def rational(c: Fraction):
        return flint.fmpq(c.numerator, c.denominator)

    signed = ctx.from_dict({e: rational(c) for e, c in terms.items()})
    size = ctx.from_dict({e: rational(abs(c)) for e, c in terms.items()})
    x = [Fraction(float(vals[s])) for s in syms]
    at, at_abs = [rational(v) for v in x], [rational(abs(v)) for v in x]

    def exact(value) -> float:
        return float(Fraction(int(value.p), int(value.q)))

    out = np.zeros(len(unknowns))
    scale = 0.0
    for k, u in enumerate(unknowns):
        if u not in syms:
            continue
        i = syms.index(u)
        out[k] = exact(signed.derivative(i)(*at))
        scale = max(scale, exact(size.derivative(i)(*at_abs)))
    return out, scale


def tangent_dimension(d, closure, vals) -> int:
    """Coordinates and joints of the closure's ideal minus the rank of its Jacobian at
    ``vals`` (a smooth point's tangent space)."""
    gens = d.closure_generators(closure.point)
    unknowns = list(closure.pose) + [j for j in d.mechanism.joints
                                     if any(g.has(j) for g in gens)]
    grads = [_gradient(sp.sympify(g), unknowns, vals) for g in gens]
    jac = np.array([g for g, _ in grads])
    scales = np.array([s for _, s in grads])
    norms = np.linalg.norm(jac, axis=1)
    # a gradient that cancels to below 1e-9 of its terms vanishes at the point (the point is
    # on the variety to rounding only): it is no direction; the others to unit size
    keep = norms > 1e-9 * scales
    rows = jac[keep] / norms[keep, None]
    sv = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(1)
    return len(unknowns) - (int((sv > 1e-9 * sv[0]).sum()) if sv[0] > 0 else 0)


def run(d, gen) -> Study:
    vals = home_values(d, gen)
    krull = {a.closure: a for a in d.mechanism.analyses if isinstance(a, ClosureDimension)}
    rows = []
    skipped = []
    for closure in d.mechanism.closures:
        _fill_coordinates(d, closure, vals)
        needed = set().union(*(leg.free_symbols for leg in closure.legs))
        missing = sorted(str(s) for s in needed - set(vals) - set(closure.pose))
        if missing:  # e.g. joints the generated module does not recover
            skipped.append((closure.name, missing))
            continue
        chains = [leg_chain(leg, closure.pose, vals) for leg in closure.legs]
        m = mobility(chains)
        chart = platform_chain(closure, vals)
        with_chart = mobility([*chains, chart]) if chart is not None else m
        counted = with_chart.kutzbach_grubler != m.kutzbach_grubler
        if counted:  # the coordinates constrain the platform beyond what the legs do
            m, chains = with_chart, [*chains, chart]
        k = krull.get(closure.point)
        rows.append({
            "closure": closure.name + (" (with its coordinates)" if counted else ""),
            "chains": len(chains), "order": m.order,
            "redundant": m.redundant, "local": m.local, "links": m.links,
            "joints": m.joints, "freedoms": m.freedoms, "M": m.kutzbach_grubler,
            "platform": m.platform_dimension, "rotations": m.rotational_dimension,
            "tangent": tangent_dimension(d, closure, vals),
            "krull": d.analyses[k.name].dimension if k else None})
    cols = ("closure", "order", "redundant", "local", "links", "joints", "freedoms", "M",
            "platform", "rotations", "tangent", "krull")
    table = csv_text(cols, [tuple(str(r[c]).replace(",", ";") if isinstance(r[c], str) else
                                  r[c] if r[c] is not None else "" for c in cols)
                            for r in rows], ".0f")
    return Study("mobility", {"closures": rows, "skipped": skipped},
                 {f"{d.mechanism.name}.mobility.csv": table}, tuple(_report(rows, skipped)))


def _motion(r) -> str:
    t = r["platform"] - r["rotations"]
    return f"{r['rotations']}R{t}T"


def _report(rows, skipped) -> list[str]:
    out = [r"\section{Mobility two ways (003 Sect.~2.1, eq.~2)}",
           "At home, each chain's joint screws give the constraint wrenches reciprocal to "
           "them; the common ones fix the order $d$ (6 minus their number), the others' "
           "dependence the redundant constraints $v$, and joint motions of a chain that "
           "move no other body the local freedoms $\\varsigma$: "
           "$M = d(n - g - 1) + \\sum f + v - \\varsigma$ (003 eq.~2), with $n$ the links "
           "(base and platform included) and $g$ the joints. The platform's twists are "
           "the screws reciprocal to every constraint. Independently, the closure's ideal "
           "at the same point: its coordinates and joints minus the rank of its Jacobian "
           "(the tangent space), and its Krull dimension where computed. Where the "
           "closure's platform coordinates restrict its motion beyond what its legs do (a "
           "declared constraint such as 004's parallelograms), they count as one more "
           "chain, one joint per coordinate (``with its coordinates'').",
           r"\begin{center}\begin{tabular}{lrrrrrrrlrr}\hline closure & $d$ & $v$ & "
           r"$\varsigma$ & $n$ & $g$ & $\sum f$ & $M$ & platform & tangent & Krull\\\hline"]
    for r in rows:
        out.append(f"{tex_escape(r['closure'])} & {r['order']} & {r['redundant']} & "
                   f"{r['local']} & {r['links']} & {r['joints']} & {r['freedoms']} & "
                   f"{r['M']} & {_motion(r)} & {r['tangent']} & "
                   f"{r['krull'] if r['krull'] is not None else '--'}\\\\")
    out.append(r"\hline\end{tabular}\end{center}")
    for name, missing in skipped:
        out.append(tex_escape(f"Not counted: the {name} (no value at home for "
                              f"{', '.join(missing)}: the generated module does not "
                              "recover them)."))
    agree = all(r["M"] + r["local"] == r["tangent"] for r in rows)
    out.append("Screw theory and the ideal agree: $M + \\varsigma$ equals the tangent "
               "dimension in every closure." if agree else
               "Screw theory and the ideal DISAGREE in some closure: $M + \\varsigma$ is not "
               "the tangent dimension (see the table).")
    return out
