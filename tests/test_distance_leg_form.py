"""The geometric form of a distance leg's IK generator (elimination/sphere_leg.py,
compact_sphere; issue 15, item 1): accepted only where it is proved equal to the generator
the ideal holds, and what the generated Stewart kernels evaluate."""

import re

import sympy as sp

from bonered_alg.elimination import sphere_leg

X = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", real=True)
PLATFORM = (sp.Integer(1), *X)
A = sp.symbols("a1 a2", real=True)
B = sp.symbols("b1 b2", real=True)
Q = sp.Symbol("q", real=True)
LEG = sphere_leg.DistanceLeg("L", (A[0], A[1], sp.Integer(0)), (B[0], B[1], sp.Integer(0)), Q)


def test_a_multiple_of_the_sphere_condition_is_recognized_with_its_scale():
    gen = sphere_leg.sphere_condition(LEG, PLATFORM)
    for factor in (1, -3, sp.Rational(2, 5)):
        form = sphere_leg.compact_sphere(LEG, PLATFORM, sp.expand(factor * gen))
        assert form is not None
        assert sp.expand(form.generator() - factor * gen) == 0
        # the geometric form is far shorter than the expansion
        assert sp.count_ops(form.rotation) + sp.count_ops(form.dual) < sp.count_ops(gen) / 2


def test_anything_else_is_refused():
    gen = sphere_leg.sphere_condition(LEG, PLATFORM)
    assert sphere_leg.compact_sphere(LEG, PLATFORM, sp.expand(gen + X[0])) is None
    assert sphere_leg.compact_sphere(LEG, PLATFORM, sp.expand(gen * (1 + X[0]))) is None
    other = sphere_leg.DistanceLeg("M", (A[0], A[1] + 1, sp.Integer(0)), LEG.platform, Q)
    assert sphere_leg.compact_sphere(other, PLATFORM, gen) is None


def test_the_sphere_condition_is_the_leg_length_in_the_pose():
    """q^2 = |t + R b - a|^2 on the Study point of a pose: R, t from the quaternion of a
    rotation about a random axis and a translation (independent of the module)."""
    import random

    rng = random.Random(4)
    vals = {A[0]: 3, A[1]: -2, B[0]: 1, B[1]: 5}
    x = [sp.Rational(rng.randint(1, 9), 7) for _ in range(4)]
    x[0] = sp.Integer(1)
    t = [sp.Rational(rng.randint(-9, 9), 3) for _ in range(3)]
    n2 = sum(c**2 for c in x)
    # y = -1/2 t x (004 eq. 13): the dual part of the displacement
    tq = (0, *t)
    y = [-sp.Rational(1, 2) * c for c in _qmul(tq, x)]
    point = dict(zip(X, [c / x[0] for c in (*x[1:], *y)]))
    form = sphere_leg.compact_sphere(LEG, PLATFORM, sphere_leg.sphere_condition(LEG, PLATFORM))
    rot = _rotate(x, (vals[B[0]], vals[B[1]], 0), n2)
    length2 = sum((t[i] + rot[i] - (vals[A[0]], vals[A[1]], 0)[i]) ** 2 for i in range(3))
    r_val = form.rotation.subs(vals).subs(point)
    d_val = form.dual.subs(vals).subs(point)
    assert sp.simplify(4 * d_val / r_val - length2) == 0


def _qmul(a, b):
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return (a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
            a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0)


def _rotate(x, v, n2):
    conj = (x[0], -x[1], -x[2], -x[3])
    r = _qmul(_qmul(x, (0, *v)), conj)
    return [c / n2 for c in r[1:]]


def test_the_stewart_module_evaluates_its_legs_in_the_geometric_form():
    """Each leg's IK step: about 125 operations after CSE, where the expanded sphere
    polynomial took 620 (generated/stewart.py OPERATIONS, main 2dd1098); the six legs'
    coefficients from one program (``_step_coefficients``, what the numpy runtime
    evaluates) share the rotation's products: fewer operations than the six kernels."""
    from bonered_alg.generated import stewart

    steps = {k: v for k, v in stewart.OPERATIONS.items() if re.fullmatch(r"_step\d+_.*", k)}
    assert len(steps) == 6 and max(steps.values()) < 200, steps
    assert stewart.OPERATIONS["_step_coefficients"] < 0.6 * sum(steps.values())


def test_the_sphere_condition_between_the_points_is_that_of_the_whole_chain():
    """certify takes the sphere condition on the chain between the two points (T(-A) X T(B)
    = Mid for X = T(A) Mid T(-B)); that shortcut is exact: the same polynomial as on the
    whole chain product, for a U-P-S leg with symbolic points (zero) and for a chain whose
    middle is not a distance leg (a slide across the stroke: not zero, and equal too)."""
    from bonered_alg.chains.joints import Role, joint, leg

    u = sp.symbols("u1 u2", real=True)
    e = sp.symbols("e0:4", real=True)
    a, b = (A[0], A[1], sp.Integer(3)), (B[0], sp.Integer(2), B[1])
    ups = leg("L", joint("t", "offset", "A", vector=a),
              joint("t", "universal", "U", ("x", "y"), u, Role.PASSIVE),
              joint("t", "prismatic", "P", "z", Q, Role.ACTIVE),
              joint("t", "spherical", "S", e, Role.PASSIVE),
              joint("t", "offset", "B", vector=tuple(-c for c in b)))
    d = sphere_leg.recognize(ups)
    assert d is not None and d.base == a and d.platform == b
    d0, mid = sphere_leg._between_the_points(ups, d)
    assert d0.base == d0.platform == (0, 0, 0)
    short = sphere_leg.sphere_condition(d0, mid)
    assert short == 0 == sphere_leg.sphere_condition(d, ups.product())
    # a passive slide across the stroke: the distance is not |q| (not a distance leg)
    v = sp.Symbol("v", real=True)
    wrong = leg("W", joint("t", "offset", "A", vector=a),
                joint("t", "universal", "U", ("x", "y"), u, Role.PASSIVE),
                joint("t", "prismatic", "P", "z", Q, Role.ACTIVE),
                joint("t", "offset", "V", vector=(v, 0, 0)),
                joint("t", "spherical", "S", e, Role.PASSIVE),
                joint("t", "offset", "B", vector=tuple(-c for c in b)))
    dw = sphere_leg.DistanceLeg("W", a, b, Q)
    d0, mid = sphere_leg._between_the_points(wrong, dw)
    short = sphere_leg.sphere_condition(d0, mid)
    assert short != 0
    assert sp.expand(short - sphere_leg.sphere_condition(dw, wrong.product())) == 0 or \
        sp.expand(short + sphere_leg.sphere_condition(dw, wrong.product())) == 0


def test_an_r_p_s_stroke_is_a_distance_on_the_chain_though_not_a_distance_leg():
    """planar_tripod's tripod legs T(C_k) R(u_k) T(-+q_k) S T(D_k) (000 eq. 13, 18): the
    stroke is |D_k - C_k| on every configuration (distance_on_chain, which the Jacobian's
    leg-line rows rely on), but the leg's image has dimension 5, so the elimination does not
    take the sphere condition as its ideal (certify refuses it); the planar P-R-P legs are
    no distance legs at all."""
    from bonered_alg.mechanisms import planar_tripod as pt

    planar, tripod = pt.MECHANISM.closures
    ra, rb = sp.Symbol("ra", real=True), sp.Symbol("rb", real=True)
    expected = {"T1": ((ra, 0, 0), (rb, 0, 0)), "T2": ((0, ra, 0), (0, rb, 0)),
                "T3": ((-ra, 0, 0), (-rb, 0, 0))}
    for leg, q in zip(tripod.legs, sp.symbols("q4 q5 q6", real=True)):
        dl = sphere_leg.distance_on_chain(leg)
        assert dl is not None and dl.stroke == q
        assert (dl.base, dl.platform) == tuple(tuple(map(sp.sympify, p))
                                               for p in expected[leg.name])
        assert sphere_leg.recognize(leg) is None or leg.name == "T3"  # T(-q): signed only
    for leg in planar.legs:
        assert sphere_leg.distance_on_chain(leg, {sp.Symbol("s3", real=True): sp.sqrt(3)}) \
            is None
