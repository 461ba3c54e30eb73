"""The long polynomials of a derivation, machine-readable: ``derivations/<name>.algebra.json``.

The report prints a polynomial in full only where a reader can follow it (:data:`FULL_TERMS`
terms or fewer) and summarizes the others (degrees, number of terms); every one of them, in
full, is in this file beside the report: the generators of each leg's ideal, the IK
coefficients, the Jacobian entries and the singularity factors, as sympy ``str`` text (read
them back with ``sympy.parse_expr``, which is safe on this file as it is our own output).
"""

from __future__ import annotations

import json

import sympy as sp

from ..algebra import polyring as pr

# a polynomial with more terms than this is summarized in the report (about six lines)
FULL_TERMS = 24


def terms(expr) -> int:
    return len(sp.Add.make_args(pr.expanded(sp.sympify(expr))))


def is_long(expr) -> bool:
    return terms(expr) > FULL_TERMS


def degrees(expr) -> list[tuple[sp.Symbol, int]]:
    """(variable, degree) for every variable of the polynomial ``expr``, sorted by name."""
    free = sorted(sp.sympify(expr).free_symbols, key=str)
    if not free:
        return []
    expanded = pr.expanded(sp.sympify(expr))
    monomials = pr.terms_of(expanded, free)  # read off the terms: Poly takes seconds
    if not monomials:  # not a sum of monomials, or zero once expanded
        return list(zip(free, sp.Poly(expanded, *free).degree_list()))
    return [(v, max(m[i] for m in monomials)) for i, v in enumerate(free)]


def _text(expr, expanded: bool = False) -> str:
    """``expr`` expanded, as text (``str``'s characters, :func:`..algebra.polyring.text`);
    ``expanded``: it is a sum of monomials already (a leg's generators, built so from the
    engine's terms), printed as it is."""
    return pr.text(expr if expanded else pr.expanded(sp.sympify(expr)))


def algebra_json(d) -> str:
    """Every generator, IK coefficient, Jacobian entry and singularity factor of ``d``."""
    record = {
        "mechanism": d.mechanism.name,
        "derivation_hash": d.derivation_hash,
        "legs": [{"leg": r.leg.name, "closure": r.closure.name,
                  "variables": [str(v) for v in r.problem.keep],
                  "generators": [_text(g, expanded=True) for g in r.generators]}
                 for r in d.legs],
        "ik": [{"joint": str(s.joint), "source": s.source, "degree": s.degree,
                "A": _text(s.A), "B": _text(s.B), "C": _text(s.C)} for s in d.steps],
        "jacobians": [{"closure": v.closure,
                       "rows": [str(q) for q in v.joints],
                       "Ji_columns": [str(q) for q in v.joints],
                       "Jo_columns": [str(y) for y in v.pose],
                       "Ji": [[_text(e) for e in v.ji.row(i)] for i in range(v.ji.rows)],
                       "Jo": [[_text(e) for e in v.jo.row(i)] for i in range(v.jo.rows)]}
                      for v in d.velocity],
        "singularities": [{"name": s.name, "constant": str(s.constant),
                           "factors": [[_text(f), int(k)] for f, k in s.factors]}
                          if not s.is_determinant else
                          {"name": s.name, "determinant_of": [
                              [_text(e) for e in s.expression.row(i)]
                              for i in range(s.expression.rows)]}
                          for s in d.singularities],
    }
    return json.dumps(record, indent=1, sort_keys=True) + "\n"
