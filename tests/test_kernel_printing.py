"""The kernel generator's array-operation savings (issue 15): a leading negation written as
a subtraction, products by powers of two kept out of CSE temporaries, and quadratic steps
of a revolute joint in their half-angle form; each checked against the kernel without it.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from bonered_alg.codegen.kernels import Program, _Printer, kernel
from bonered_alg.codegen.module import _half_angle_split

x, y, z, a, b = sp.symbols("x y z a b", real=True)


def _run(k, args):
    space: dict = {"numpy": np}
    exec(k.source, space)
    return space[k.name](*args)


def test_a_leading_negative_term_is_subtracted_with_the_same_bits():
    """``-x*y + z`` is printed ``z - x*y`` (numpy negates no array), and evaluates to the
    same bits as sympy's own printing, ``-x*y + z``, signed zeros and infinities included;
    a sum that starts with two negative terms is printed as sympy prints it."""
    from sympy.printing.numpy import NumPyPrinter

    p = _Printer({"fully_qualified_modules": True}, scalars=frozenset({"a"}))
    assert p.doprint(-x + z - y) == "-x - y + z"
    assert p.doprint(-x - y) == "-x - y"
    rng = np.random.default_rng(1)
    special = np.array([0.0, -0.0, np.inf, -np.inf, 1e-310, -1e-310])
    vals = [np.concatenate([rng.standard_normal(2000) * 10.0 ** rng.integers(-200, 200, 2000),
                            np.repeat(special, 6), np.tile(special, 6)]) for _ in range(3)]
    for expr, printed in ((-x * y + z, "z - x*y"), (-x + y * z, "y*z - x"),
                          (-2 * x + y + z, "y - 2.0*x + z")):
        assert p.doprint(expr) == printed
        sympys = NumPyPrinter().doprint(expr)
        assert sympys.startswith("-")
        space = {"x": vals[0], "y": vals[1], "z": vals[2]}
        with np.errstate(all="ignore"):
            ours, theirs = eval(printed, space), eval(sympys, space)  # noqa: S307 - test
        assert np.array_equal(ours, theirs, equal_nan=True)
        finite = ~np.isnan(ours)
        assert np.array_equal(np.signbit(ours[finite]), np.signbit(theirs[finite]))


def test_products_by_a_power_of_two_are_not_shared_where_each_reader_scales_them():
    """CSE shares ``2*x`` between ``2*a*x`` and ``2*b*x``; printed scalars first each is one
    array operation, so the temporary goes and the products are the same numbers.  A
    temporary read by a product with another array, or by a sum, stays."""
    k = kernel("_k", [x, y, a, b], [2 * a * x, 2 * b * x], "t", scalars=[a, b])
    assert "2.0*x" not in k.source.replace("2.0*a*x", "").replace("2.0*b*x", "")
    kept = kernel("_k", [x, y, a, b], [2 * a * x * y, 2 * b * x * y + 2 * x], "t",
                  scalars=[a, b])
    assert "= 2.0*x" in kept.source
    rng = np.random.default_rng(2)
    xs = rng.standard_normal(1000)
    got = _run(k, [xs, xs, 0.3, -1.7])
    assert np.array_equal(got[0], 0.3 * (2.0 * xs)) and np.array_equal(got[1],
                                                                       -1.7 * (2.0 * xs))


def test_a_half_angle_step_is_split_into_its_shared_and_cosine_parts():
    """003's theta1 step (lamina_milling: ``A, C = lAF^2 - lOA^2 - x^2 - y^2 -+ 2 lOA x``)
    becomes ``P - Q, P + Q`` with ``P = lAF^2 - lOA^2 - x^2 - y^2`` and ``Q = 2 lOA x``;
    the kernel has fewer operations and gives the coefficients to rounding.  A step whose
    A and C share nothing is left as it is."""
    lOA, lAF = sp.symbols("lOA lAF", real=True)
    shared = lAF**2 - lOA**2 - x**2 - y**2
    coeffs = [shared - 2 * lOA * x, 4 * lOA * y, shared + 2 * lOA * x]
    prog = Program("_h")
    split = _half_angle_split(coeffs, prog)
    assert split is not None
    out, entries = split
    assert [sp.expand(e) for _, e in entries] == [sp.expand(shared), 2 * lOA * x]
    args, par = [x, y], [lOA, lAF]
    plain = kernel("_p", [*args, *par], coeffs, "t", scalars=par)
    halved = kernel("_h", [*args, *par], out, "t", scalars=par, program=entries)
    assert halved.operations < plain.operations
    rng = np.random.default_rng(3)
    vals = [rng.uniform(-200, 200, 500), rng.uniform(-200, 200, 500), 90.0, 160.0]
    for got, want in zip(_run(halved, vals), _run(plain, vals)):
        np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-9)
    assert _half_angle_split([x**2 + 1, y, z**3 - z], Program("_h")) is None
