"""Code-generation printer and IK-planner details that every mechanism relies on."""

import numpy as np
import sympy as sp

from bonered_alg.codegen.kernels import kernel
from bonered_alg.kinematics.ik_plan import _definite, plan


def _run(k, *args):
    ns = {"numpy": np}
    exec(k.source, ns)  # noqa: S102 - our own generated source
    return ns[k.name](*args)


def test_integer_powers_keep_their_precedence():
    """x**2 is printed as (x*x): a/x**2 must not become a/x*x (it did, and broke the
    Jacobian of tripod_planar before this was fixed)."""
    x, a = sp.symbols("x a")
    exprs = [a / x**2, a / x**3, a * x**3, (x + 1) ** -2, 1 / (a * x**2), x**1,
             (x + a) ** -1, (x + a) ** -3 + x, (x - a) ** -5]
    k = kernel("f", [x, a], exprs, "test")
    got = _run(k, 1.7, -0.3)
    ref = [float(e.subs({x: 1.7, a: -0.3})) for e in exprs]
    assert np.allclose(got, ref, rtol=1e-15, atol=0)


class _Counted(np.ndarray):
    """An array that counts the numpy ufunc calls with it as an operand."""

    calls = 0

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        _Counted.calls += 1
        inputs = [np.asarray(v) if isinstance(v, _Counted) else v for v in inputs]
        return getattr(ufunc, method)(*inputs, **kwargs).view(_Counted)


def _array_calls(f, *args):
    _Counted.calls = 0
    f(*[a.view(_Counted) if isinstance(a, np.ndarray) else a for a in args])
    return _Counted.calls


def test_sums_are_grouped_by_their_array_factors():
    """kernels.scalar_coefficients: terms that differ only in scalar (parameter) factors
    share one array multiplication; the value is unchanged and Abs stays unevaluated."""
    from bonered_alg.codegen.kernels import scalar_coefficients

    x, y, ra, rb = sp.symbols("x y ra rb", real=True)
    e = ra * x + rb * x + ra * rb * x * y - 2 * y + ra + 1 + sp.Abs(ra * x - rb * x,
                                                                   evaluate=False)
    g = scalar_coefficients(e, {ra, rb})
    point = {x: 0.3, y: -1.7, ra: 2.5, rb: 0.25}
    assert abs(float((g - e).subs(point))) < 1e-15
    assert x * (ra + rb) in g.args  # one x-term, its coefficient the sum of the two
    assert any(isinstance(a, sp.Abs) and a.args[0] == (ra - rb) * x for a in g.atoms(sp.Abs))
    args = [x, y, ra, rb]
    plain = kernel("_p", args, [e], "")
    grouped = kernel("_g", args, [e], "", scalars=[ra, rb])
    f_plain, f_grouped = ({}, {})
    exec(plain.source, {"numpy": np}, f_plain)
    exec(grouped.source, {"numpy": np}, f_grouped)
    xs, ys = np.linspace(-2, 2, 7), np.linspace(1, 3, 7)
    assert np.allclose(f_plain["_p"](xs, ys, 2.5, 0.25), f_grouped["_g"](xs, ys, 2.5, 0.25),
                       rtol=1e-14, atol=0)
    # the scalar coefficients are computed once, as numbers (placeholders _s<k>), and the
    # array operations are fewer: counted as numpy ufunc calls on array operands
    assert "_s0 = " in grouped.source

    counts = [_array_calls(f, xs, ys, 2.5, 0.25) for f in (f_plain["_p"], f_grouped["_g"])]
    assert counts[1] < counts[0], counts


def test_scalar_factors_are_multiplied_first():
    """kernels._print_mul_scalars_first: ``2 rb t u`` with ``t``, ``u`` array temporaries is
    printed with the parameter first, so the scalar product is formed once and the arrays
    take two multiplications (sympy's order, ``2.0*_c0*_c1*rb``, takes three); the values
    are those of sympy's order, and the C source orders its product alike."""
    x, y, rb = sp.symbols("x y rb", real=True)
    t, u = sp.tan(x), sp.tan(y)
    outs = [2 * rb * t * u + t, t * u - rb * t / sp.cos(x) ** 2]
    k = kernel("_k", [x, y, rb], outs, "", c=True, scalars=[rb])
    plain = kernel("_p", [x, y, rb], outs, "")
    assert "2.0*rb*_c" in k.source and "2.0*v_rb*v__c" in k.c_source
    assert "rb*_c0/" in k.source
    f = {}
    exec(k.source + plain.source, {"numpy": np}, f)
    xs, ys = np.linspace(-1, 1, 9), np.linspace(0.2, 1.1, 9)
    for a, b in zip(f["_k"](xs, ys, 1.5), f["_p"](xs, ys, 1.5)):
        np.testing.assert_allclose(a, b, rtol=1e-15, atol=0)
    assert _array_calls(f["_k"], xs, ys, 1.5) < _array_calls(f["_p"], xs, ys, 1.5)


def test_generated_modules_compute_the_pose_functions_once():
    """codegen.module._pose_sharing: the Study map, the Jacobian and the limits of a
    generated module take tan(alpha/2), ... from ``_shared`` instead of each computing them;
    the kernels under their old names (wrappers) give the same numbers."""
    import inspect

    from bonered_alg.generated import planar_tripod as m

    assert m._MODEL.shared is m._shared and m._MODEL.study is m._study_of
    assert m._MODEL.jac is m._jac_of and m._MODEL.limit_kernel is m._limit_values_of
    for name in ("_study_of", "_jac_of", "_limit_values_of"):
        assert "numpy.tan" not in inspect.getsource(getattr(m, name)), name
    rng = np.random.default_rng(3)
    pose = [rng.uniform(-0.5, 0.5, 5) for _ in m.POSE]
    q = [rng.uniform(100, 200, 5) for _ in m.JOINTS]
    par = list(m.PARAMETERS.values())
    f = m._shared(*pose, *par)
    for a, b in zip(m._jac(*pose, *q, *par), m._jac_of(*f, *pose, *q, *par)):
        np.testing.assert_array_equal(a, b)
    # the shared values are the tangents of the half angles (alpha, beta, gamma), as numpy
    # computes them
    for v, angle in zip(f, pose[3:]):
        np.testing.assert_array_equal(v, np.tan(0.5 * angle))


def test_definite_leading_coefficients():
    x, y = sp.symbols("x y", real=True)
    assert _definite(1 + x**2)
    assert _definite(4 + (x + sp.sqrt(3) * y) ** 2)  # a square of a linear form plus 4
    assert _definite(sp.Integer(3))
    assert not _definite((1 + x) ** 2)  # vanishes at x = -1
    assert not _definite(x**2 + y**2)  # vanishes at 0
    assert not _definite(1 - x**2)
    assert not _definite(1 + x * y)
    # beyond degree 2 (decided on the terms): even monomials with positive coefficients
    assert _definite(1 + x**4 + 3 * x**2 * y**2)
    assert not _definite(1 + x**4 - x**2)  # positive, but not visibly so
    assert not _definite(x**4 + y**4)  # no constant: vanishes at 0
    assert not _definite(2 + x**4 * y**2 + x**3)  # an odd power


def test_definite_on_terms_agrees_with_poly():
    """The terms route of _definite against the Poly reading it replaced, on random
    polynomials of degree up to 6 with a constant term and mostly even powers."""
    import random

    x, y, z = sp.symbols("x y z", real=True)
    rng = random.Random(7)

    def reference(a):
        poly = sp.Poly(sp.expand(a), *sorted(a.free_symbols, key=str))
        terms = poly.terms()
        has_const = any(all(e == 0 for e in m) for m, _ in terms)
        return has_const and all(c > 0 and all(e % 2 == 0 for e in m) for m, c in terms)

    seen = set()
    for _ in range(200):
        a = sp.Integer(rng.choice([0, 1, 5]))
        for _ in range(rng.randint(1, 4)):
            ex = [rng.choice([0, 2, 2, 4, 1, 3]) for _ in range(3)]
            a += rng.choice([1, 2, -1, sp.Rational(1, 3)]) * x**ex[0] * y**ex[1] * z**ex[2]
        if a.free_symbols and sp.Poly(a, *sorted(a.free_symbols, key=str)).total_degree() > 2:
            assert _definite(a) == reference(a), a
            seen.add(_definite(a))
    assert seen == {True, False}


def test_the_planner_demotes_a_generator_that_vanishes_at_home():
    """x q + x y is the cheaper generator for q, but every coefficient vanishes at the home
    point x = 0 (q undetermined there); with the probe the planner takes q - y + x^2."""
    x, y, q = sp.symbols("x y q", real=True)
    gens = [("L", x * q + x * y), ("L", q - y + x**2 + y**3 * x**2)]
    plain = plan(gens, [q], "test")
    assert sp.expand(plain[0].generator - gens[0][1]) == 0
    probed = plan(gens, [q], "test", probe={x: sp.Integer(0), y: sp.Integer(2)})
    assert sp.expand(probed[0].generator - gens[1][1]) == 0


def test_generated_functions_name_only_what_their_module_defines():
    """Every global a generated function reads is defined in its module or a builtin: the
    kernels of planar_tripod's and tripod_planar's other forward-kinematics charts read the
    symbol s3 (sqrt 3), left in them when the algebraic constants were put in the other
    plans and not in these, a NameError whenever the forward kinematics needed them."""
    import builtins
    import dis
    import importlib
    import inspect

    from bonered_alg.registry import MECHANISMS

    for name in MECHANISMS:
        m = importlib.import_module(f"bonered_alg.generated.{name}")
        for fname, fn in vars(m).items():
            if not inspect.isfunction(fn) or fn.__module__ != m.__name__:
                continue
            read = {ins.argval for ins in dis.get_instructions(fn)
                    if ins.opname in ("LOAD_GLOBAL", "LOAD_NAME")}
            undefined = {g for g in read if g not in vars(m) and not hasattr(builtins, g)}
            assert not undefined, (name, fname, sorted(undefined))
