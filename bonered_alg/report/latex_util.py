"""Small LaTeX helpers: escaping plain text and breaking long formulas across lines.

:func:`broken_math` breaks by the *printed* width of a formula (:func:`visible_width`), not
by its source length, and goes inside products and powers: a long sum is packed term by
term, a long product factor by factor, and a factor that is itself a long sum is opened
with ``\\bigl(`` on one line and closed with ``\\bigr)`` on a later one.
"""

from __future__ import annotations

import re

import sympy as sp

# ^ and ~ as accents, |, <, > and \ as math symbols: the text commands take them from the
# TS1 encoding, which pdflatex without cm-super embeds as a Type 3 bitmap font
_ESC = {"\\": r"$\backslash$", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#",
        "_": r"\_\allowbreak{}", "{": r"\{", "}": r"\}", "~": r"\~{}",
        "^": r"\^{}", "|": r"$|$", "<": r"$<$", ">": r"$>$",
        "/": r"/\allowbreak{}"}

# math on an A4 page with 2 cm margins (483 pt) at 10 pt: about 90 glyphs of 5.3 pt; lines
# of an align* block start after "lhs &=" or "&\quad"
LINE_WIDTH = 84


def tex_escape(text: str) -> str:
    """Plain text -> LaTeX text mode (underscores and slashes may break a line)."""
    return "".join(_ESC.get(ch, ch) for ch in str(text))


def texttt(text: str) -> str:
    """Monospace with line-break opportunities after operators (for long formulas as text)."""
    out = tex_escape(text)
    for op in ("+", "-", "*", ",", ";", ":", "=", "("):
        out = out.replace(op, op + r"\allowbreak{}")
    return r"\texttt{" + out + "}"


GREEK = ("alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota",
         "kappa", "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "phi", "chi",
         "psi", "omega", "Gamma", "Delta", "Theta", "Lambda", "Phi", "Psi", "Omega")
# a symbol of plain-text mathematics: a base, a subscript, a superscript, primes
_SYMBOL = re.compile(r"([A-Za-z]+)(\d*)(?:_([A-Za-z0-9]+))?(?:\^(-?[A-Za-z0-9]+))?('*)")
_EDGE = re.compile(r"^([(\[|]*)(.*?)([)\],;:.|]*)$")
_ENGLISH = {"a", "A", "I"}  # one-letter English words: not symbols


def _math_part(part: str) -> str:
    return rf"\{part}" if part in GREEK else (part if len(part) == 1 else
                                             rf"\mathrm{{{part}}}")


def _symbol(token: str) -> str | None:
    """``token`` as inline math when it is visibly a symbol (``q_k``, ``J_A^-1``, ``a11``,
    ``rho_k^T``, ``gamma``, ``q4'``), else None (a word stays a word)."""
    m = _SYMBOL.fullmatch(token)
    if not m:
        return None
    base, digits, sub, sup, primes = m.groups()
    greek = base in GREEK
    if not (greek or sub or sup or primes or (digits and len(base) == 1)
            or (len(base) == 1 and base not in _ENGLISH)):
        return None  # a word, or a word with digits ("MP1", "B1B2") stays text
    out = _math_part(base)
    lower = [x for x in (digits, sub) if x]
    if lower:
        out += "_{" + ",".join(_math_part(x) if not x.isdigit() else x for x in lower) + "}"
    if sup:
        out += "^{" + (sup if not sup.lstrip("-").isalpha() or len(sup.lstrip("-")) == 1
                       else "-" * sup.startswith("-") + _math_part(sup.lstrip("-"))) + "}"
    return "$" + out + "'" * len(primes) + "$"


def prose(text: str) -> str:
    """Plain text with its symbols typeset as mathematics (the verification details):
    each space-separated token that is visibly a symbol becomes inline math, everything
    else is escaped text; an ``=`` between symbols becomes the math relation."""
    words = []
    tokens = str(text).split(" ")
    for i, token in enumerate(tokens):
        if token == "x" and 0 < i < len(tokens) - 1 and tokens[i - 1].isdigit() \
                and tokens[i + 1].rstrip(",;:.)").isdigit():
            words.append(r"$\times$")  # 6 x 6
            continue
        lead, core, trail = _EDGE.match(token).groups()
        sym = _symbol(core) if core else None
        if sym is None and core in ("=", "<", ">", "<=", ">="):
            sym = "$" + {"<=": r"\le", ">=": r"\ge"}.get(core, core) + "$"
        if sym is not None and lead.endswith("|") and trail.startswith("|"):
            sym, lead, trail = "$|" + sym[1:-1] + "|$", lead[:-1], trail[1:]  # |x|
        words.append(tex_escape(lead) + sym + tex_escape(trail) if sym is not None
                     else tex_escape(token))
    return " ".join(words)


def _plain_symbol(name: str) -> str | None:
    """The LaTeX of a symbol whose base name ends in one of sympy's modifiers (``lBM``
    would print as a bold l, ``xbar`` as x with a bar): the name as written, with its
    sub- and superscripts; None for the others (sympy's own printing)."""
    from sympy.printing.conventions import split_super_sub
    from sympy.printing.latex import modifier_dict

    base, sups, subs = split_super_sub(name)
    low = base.lower()
    if not any(low.endswith(k) and len(base) > len(k) for k in modifier_dict):
        return None
    out = base
    if subs:
        out += "_{" + " ".join(subs) + "}"
    if sups:
        out += "^{" + " ".join(sups) + "}"
    return out


def latex(expr) -> str:
    e = sp.sympify(expr)
    names = {}
    for sym in getattr(e, "free_symbols", ()):
        if isinstance(sym, sp.Symbol):
            plain = _plain_symbol(sym.name)
            if plain is not None:
                names[sym] = plain
    return sp.latex(e, symbol_names=names) if names else sp.latex(e)


_COMMAND = re.compile(r"\\([a-zA-Z]+|.)")
# a binary operator or relation prints with its spaces, about two glyphs wide
_GLYPH = {"+": 2.2, "-": 2.2, "=": 2.4, "(": 0.8, ")": 0.8, ",": 0.6, ".": 0.5, "&": 0.0}
_SILENT = {"left", "right", "bigl", "bigr", "Bigl", "Bigr", "allowbreak", "limits",
           "operatorname", "mathrm", "text", "mathbf", "mathit", "displaystyle",
           ",", ";", "!", " ", "\\"}
_WORDS = {"sin", "cos", "tan", "cot", "sec", "csc", "log", "exp", "det", "arctan", "atan",
          "operatorname", "min", "max", "ln"}
_WIDE = {"quad": 2.0, "qquad": 4.0, "cdot": 1.6, "pm": 2.2, "mp": 2.2, "times": 2.2,
         "cdots": 3.0, "ldots": 3.0, "dots": 3.0}


def _group(tex: str, i: int) -> tuple[str, int]:
    """The argument starting at ``tex[i]``: a braced group (without braces) or one token."""
    while i < len(tex) and tex[i] == " ":
        i += 1
    if i >= len(tex):
        return "", i
    if tex[i] == "{":
        depth, j = 0, i
        while j < len(tex):
            if tex[j] == "\\":
                j += 2
                continue
            depth += tex[j] == "{"
            depth -= tex[j] == "}"
            if depth == 0:
                return tex[i + 1:j], j + 1
            j += 1
        return tex[i + 1:], len(tex)
    if tex[i] == "\\":
        m = _COMMAND.match(tex, i)
        return m.group(0), m.end()
    return tex[i], i + 1


def visible_width(tex: str) -> float:
    """Estimated printed width of math ``tex`` in glyphs of about 5 pt (10 pt type): a
    fraction is as wide as the wider of its parts, scripts count 0.7, ``\\tan`` three
    glyphs, ``\\alpha`` one, ``\\left`` none, an operator with its spaces about two."""
    width, i, n = 0.0, 0, len(tex)
    while i < n:
        ch = tex[i]
        if ch == "\\":
            m = _COMMAND.match(tex, i)
            name, i = m.group(1), m.end()
            if name == "frac":
                num, i = _group(tex, i)
                den, i = _group(tex, i)
                width += max(visible_width(num), visible_width(den)) + 0.4
            elif name == "sqrt":
                arg, i = _group(tex, i)
                width += visible_width(arg) + 1.2
            elif name in ("operatorname", "mathrm", "text"):
                arg, i = _group(tex, i)
                width += len(arg)
            elif name in _WORDS:
                width += len(name)
            elif name in _WIDE:
                width += _WIDE[name]
            elif name in ("left", "right"):  # a delimiter grown to its contents
                delim, i = _group(tex, i)
                width += 0.0 if delim == "." else 1.4
            elif name not in _SILENT:
                width += 1.0
            continue
        if ch in "^_":
            arg, i = _group(tex, i + 1)
            width += 0.7 * visible_width(arg)
            continue
        if ch not in "{} ":
            width += _GLYPH.get(ch, 1.4 if ch.isupper() else 1.0)  # capitals are wider
        i += 1
    return width


def _signed(tex: str) -> tuple[str, str]:
    """('-', rest) or ('+', tex)."""
    return ("-", tex[1:].lstrip()) if tex.startswith("-") else ("+", tex)


def _sum_lines(terms: list, width: float) -> list[str]:
    """The terms of a sum packed into lines, each line after the first starting with its
    sign; a term too long for a line is broken itself."""
    lines: list[str] = []
    current = ""
    for k, term in enumerate(terms):
        sign, body = _signed(latex(term))
        lead = ("-" if sign == "-" else "") if k == 0 else sign + " "
        piece = lead + body
        if visible_width(piece) > width:  # a long product or power: break it
            if current:
                lines.append(current)
                current = ""
            parts = _lines(-term if sign == "-" else term, width - 2)  # the sign is in lead
            parts[0] = lead + parts[0]
            lines += parts[:-1]
            current = parts[-1]
            continue
        if current and visible_width(current) + visible_width(piece) + 1 > width:
            lines.append(current)
            current = piece
        else:
            current = f"{current} {piece}".strip()
    lines.append(current)
    return lines


def _factor_tex(f) -> str:
    tex = latex(f)
    if isinstance(f, sp.Add):
        return rf"\left({tex}\right)"
    return tex


def _product_lines(expr: sp.Mul, width: float) -> list[str]:
    """A product packed factor by factor; a factor that is a long sum (or a power of one) is
    opened with \\bigl( and closed with \\bigr) on the line where its last term falls."""
    coeff, rest = expr.as_coeff_Mul()
    factors = rest.as_ordered_factors() if rest.is_Mul else [rest]  # sympy's print order
    numer = [f for f in factors if not (f.is_Pow and f.exp.is_negative)]
    denom = [1 / f for f in factors if f.is_Pow and f.exp.is_negative]
    lines: list[str] = []
    current = ""
    if coeff == -1:
        current = "-"
    elif coeff != 1:
        current = latex(coeff)
    if denom:
        den = sp.Mul(*denom)
        current += rf"\frac{{1}}{{{latex(den)}}}"

    def flush():
        nonlocal current
        if current.strip() and current.strip() != "-":
            lines.append(current)
            current = ""

    for f in numer:
        tex = _factor_tex(f)
        if visible_width(current) + visible_width(tex) <= width:
            current += " " + tex if current and current != "-" else tex
            continue
        base, exp = (f.base, f.exp) if f.is_Pow else (f, None)
        if visible_width(tex) > width and isinstance(base, sp.Add):
            flush()
            inner = _sum_lines(list(base.as_ordered_terms()), width - 3)
            inner[0] = (current if current == "-" else "") + r"\bigl(" + inner[0]
            current = ""
            tail = r"\bigr)" + (f"^{{{latex(exp)}}}" if exp is not None else "")
            lines += inner[:-1]
            current = inner[-1] + tail
            continue
        flush()
        current = tex
    if current:
        lines.append(current)
    return lines


def _lines(expr, width: float = LINE_WIDTH) -> list[str]:
    """The LaTeX of ``expr`` in lines of at most about ``width`` glyphs."""
    tex = latex(expr)
    if visible_width(tex) <= width:
        return [tex]
    if isinstance(expr, sp.Add):
        return _sum_lines(list(expr.as_ordered_terms()), width)
    if isinstance(expr, sp.Mul):
        return _product_lines(expr, width)
    if isinstance(expr, sp.Pow) and isinstance(expr.base, sp.Add):
        inner = _sum_lines(list(expr.base.as_ordered_terms()), width - 3)
        inner[0] = r"\bigl(" + inner[0]
        inner[-1] += r"\bigr)^{" + latex(expr.exp) + "}"
        return inner
    return [tex]  # an atom, a function call: nothing to break at


def broken_math(lhs: str, expr, width: float = LINE_WIDTH) -> str:
    """``lhs = expr`` as an ``align*`` block, broken into lines of about ``width`` glyphs
    (:func:`visible_width`) at the terms of sums and the factors of products."""
    expr = sp.sympify(expr)
    if isinstance(expr, sp.MatrixBase):
        return matrix_math(lhs, expr, width)
    lines = _lines(expr, width - visible_width(lhs) / 2)
    body = f"{lhs} &= {lines[0]}"
    for line in lines[1:]:
        body += r"\\" + "\n" + r"&\quad " + line
    return "\\begin{align*}\n" + body + "\n\\end{align*}\n"


def matrix_math(lhs: str, matrix, width: float = LINE_WIDTH) -> str:
    """A matrix as ``bmatrix`` where it fits the line (the widest entry of each column, plus
    the column gaps), else entry by entry as ``(lhs)_{ij}``."""
    cells = [[latex(matrix[i, j]) for j in range(matrix.cols)] for i in range(matrix.rows)]
    wide = sum(max(visible_width(cells[i][j]) for i in range(matrix.rows)) + 2.0
               for j in range(matrix.cols))
    if wide + visible_width(lhs) + 4 <= width and matrix.rows <= 12:
        body = r"\\".join(" & ".join(row) for row in cells)
        return ("\\begin{align*}\n" + f"{lhs} &= \\begin{{bmatrix}}{body}\\end{{bmatrix}}"
                + "\n\\end{align*}\n")
    out = []
    for i in range(matrix.rows):
        for j in range(matrix.cols):
            if matrix[i, j] != 0:
                sub = (f"{j + 1}" if matrix.rows == 1 else f"{i + 1}" if matrix.cols == 1
                       else f"{i + 1}{j + 1}")
                out.append(broken_math(f"({lhs})_{{{sub}}}", matrix[i, j], width))
    return "".join(out)
