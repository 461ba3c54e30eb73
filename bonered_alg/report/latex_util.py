"""Small LaTeX helpers: escaping plain text and breaking long polynomials across lines."""

from __future__ import annotations

import sympy as sp

_ESC = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
        "|": r"\textbar{}", "<": r"\textless{}", ">": r"\textgreater{}"}


def tex_escape(text: str) -> str:
    """Plain text -> LaTeX text mode."""
    return "".join(_ESC.get(ch, ch) for ch in str(text))


def texttt(text: str) -> str:
    """Monospace with line-break opportunities after operators (for long formulas as text)."""
    out = tex_escape(text)
    for op in ("+", "-", "*", ",", ";"):
        out = out.replace(op, op + r"\allowbreak{}")
    return r"\texttt{" + out + "}"


def latex(expr) -> str:
    return sp.latex(sp.sympify(expr))


def broken_math(lhs: str, expr, width: int = 95) -> str:
    """``lhs = expr`` as an ``align*`` block with the sum split into lines of ~width chars."""
    expr = sp.sympify(expr)
    terms = sp.Add.make_args(sp.expand(expr)) if isinstance(expr, sp.Add) else (expr,)
    if isinstance(expr, sp.Add):
        terms = expr.as_ordered_terms()
    lines, current = [], ""
    for k, term in enumerate(terms):
        t = sp.latex(term)
        piece = t if k == 0 else (t if t.startswith("-") else "+ " + t)
        if current and len(current) + len(piece) > width:
            lines.append(current)
            current = piece
        else:
            current = f"{current} {piece}".strip()
    lines.append(current)
    body = f"{lhs} &= {lines[0]}"
    for line in lines[1:]:
        body += r"\\" + "\n" + r"&\quad " + line
    return "\\begin{align*}\n" + body + "\n\\end{align*}\n"
