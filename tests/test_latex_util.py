"""The report's line breaking (issue 14): every line fits, and the lines put back together
are the formula sympy prints, term for term and factor for factor."""

import re

import pytest
import sympy as sp

from bonered_alg.report.latex_util import LINE_WIDTH, _lines, broken_math, visible_width

x, y, z, ra, q1 = sp.symbols("x y z ra q_1")


def _joined(lines: list[str]) -> str:
    text = "".join(lines).replace(r"\bigl(", r"\left(").replace(r"\bigr)", r"\right)")
    return re.sub(r"\s+", "", text)


EXPRESSIONS = [
    sp.expand((x + y + z + ra + 1) ** 6),                                 # a long sum
    sp.Mul(3, sp.expand((x + 2 * y - z + ra) ** 4), sp.expand((q1 - ra * x + 7) ** 3),
           x * y + 1, evaluate=False),                                  # a product of sums
    -5 * (sp.expand((x - y + 3 * z + q1) ** 5)) ** 2 * (x + 1),          # a power of a long sum
    sp.expand((x + y) ** 3) - 2 * sp.Mul(ra, sp.expand((x + y + z + q1) ** 5),
                                         evaluate=False),               # a long term in a sum
]


@pytest.mark.parametrize("expr", EXPRESSIONS)
def test_lines_fit_and_reassemble_to_the_printed_formula(expr):
    lines = _lines(expr, LINE_WIDTH)
    assert len(lines) > 1
    assert max(visible_width(line) for line in lines) <= LINE_WIDTH
    assert _joined(lines) == re.sub(r"\s+", "", sp.latex(expr))


def test_visible_width_counts_what_prints():
    # x, then the script 2 at 0.7; the fraction as wide as its wider part
    assert visible_width(r"\frac{x^{2}}{y}") == pytest.approx(max(1 + 0.7, 1) + 0.4)
    assert visible_width(r"\tan{\left(\frac{\alpha}{2} \right)}") > visible_width("x + y")
    assert visible_width(r"\left(x\right)") == pytest.approx(1 + 2 * 1.4)


def test_broken_math_is_an_align_block_with_one_lhs():
    tex = broken_math("g_{1}", EXPRESSIONS[0])
    assert tex.startswith("\\begin{align*}\ng_{1} &= ") and tex.count("&=") == 1
    assert tex.count(r"&\quad") == tex.count("\\\\")


def test_prose_typesets_symbols_and_leaves_words():
    from bonered_alg.report.latex_util import prose

    assert prose("J_A^-1 J_B vs the derivative") == r"$J_{A}^{-1}$ $J_{B}$ vs the derivative"
    assert prose("rho_k^T omega = 0,") == r"$\rho_{k}^{T}$ $\omega$ $=$ 0,"
    assert prose("(a11 = rb ca") == r"($a_{11}$ $=$ rb ca"
    assert prose("q4' of MP1 and x_par") == r"$q_{4}'$ of MP1 and $x_{\mathrm{par}}$"
    assert prose("mm^2; eq. (17)") == r"$\mathrm{mm}^{2}$; eq. (17)"
    assert prose("50% & $5") == r"50\% \& \$5"  # text is escaped
    assert prose("|alpha| < 0.3 in a plane, x") == r"$|\alpha|$ $<$ 0.3 in a plane, $x$"
    assert prose("the 6 x 6 dq/dX") == r"the 6 $\times$ 6 dq/\allowbreak{}dX"
