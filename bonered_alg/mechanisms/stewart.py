"""Stewart platform (6-UPS), the reference the bone-reduction papers compare against.

000 Sect. 5 and 001 Sect. 3 compare the hybrid mechanisms with "a Stewart platform of the
same general dimensions" without giving its joint layout.  Dimensions here follow 001
Sect. 3: rings of 400 mm diameter (``ra = rb = 200`` mm), prismatic strokes 160-320 mm,
joint angles within +-20 deg.  The layout, which neither paper gives, is the standard
semi-regular hexagon: the base joints in pairs at ``theta_j +- phi_a`` with
``theta_j = -30, 90, 210`` deg, the platform joints in pairs at ``theta_j + 60 +- phi_b``,
each base joint joined to the nearer platform joint of the neighbouring pair.  The spacing
is a geometric parameter, ``ta = tan(phi_a/2)`` and ``tb = tan(phi_b/2)`` (default 1/8 for
both: phi = 14.25 deg, joints 28.5 deg apart within a pair), so that every coordinate is
rational in the parameters and ``sqrt(3)``; the workspace study shows how much the
comparison depends on it.

Each leg is ``T(A_k) Rx(u_k1) Ry(u_k2) Tz(q_k) S T(-B_k)``: a universal joint at the base
corner ``A_k``, the active stroke ``q_k``, a spherical joint at the platform corner
``B_k``.  Its elimination ideal in the platform's Study coordinates is the leg-length
sphere; the IK takes the positive root (mode 0).

The papers print no equation for the Stewart platform (``papers/stewart_reference.py``
records that); the generated functions are checked against an independent numeric model
(``tests/test_stewart.py``).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import study_symbolic as ss
from ..declaration import Closure, Constant, Limit, Parameter, PoseMap, Role, declare, joint, leg

NAME = "stewart"

R = {"real": True}
ra, rb, ta, tb = sp.symbols("ra rb ta tb", **R)
s3 = sp.Symbol("s3", positive=True)
Q = sp.symbols("q1:7", **R)
U = [sp.symbols(f"u{k}1 u{k}2", **R) for k in range(1, 7)]
E = [sp.symbols(f"e{k}_0:4", **R) for k in range(1, 7)]
PX = sp.symbols("x_1 x_2 x_3 y_0 y_1 y_2 y_3", **R)

LIMITS = {  # 001 Sect. 3
    "q": (160.0, 320.0),
    "joint_deg": (-20.0, 20.0),
}
HOME = (0.0, 0.0, 210.0, 0.0, 0.0, 0.0)  # 001 Table 1, homing position

x, y, z, alpha, beta, gamma = sp.symbols("x y z alpha beta gamma", **R)
POSE = (x, y, z, alpha, beta, gamma)
JOINTS = Q

# cos and sin of theta_j = -30, 90, 210 deg
_THETA = [(s3 / 2, -sp.Rational(1, 2)), (sp.Integer(0), sp.Integer(1)),
          (-s3 / 2, -sp.Rational(1, 2))]


def _turn(cs, sign, t):
    """(cos, sin) of theta + sign * phi with ``t = tan(phi/2)`` (rational in ``t``)."""
    (c, s), cp, sp_ = cs, (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    return (c * cp - sign * s * sp_, s * cp + sign * c * sp_)


def _sixty(cs):
    """(cos, sin) of theta + 60 deg."""
    c, s = cs
    return (c / 2 - s3 / 2 * s, s / 2 + s3 / 2 * c)


def _reduced(expr: sp.Expr) -> sp.Expr:
    """``expr`` over a common denominator with ``s3^2 = 3`` applied (degree <= 1 in
    ``s3``)."""
    num, den = sp.fraction(sp.together(expr))
    return sp.expand(sp.rem(sp.expand(num), s3**2 - 3, s3)) / sp.factor(den)


def corners() -> tuple[list, list]:
    """Base corners A_k and platform corners B_k (platform frame), legs k = 1..6."""
    base, plat = [], []
    for j in range(3):
        nxt = _THETA[(j + 1) % 3]
        mid = _sixty(_THETA[j])  # the platform pair between base pairs j and j + 1
        for a_cs, b_cs in ((_turn(_THETA[j], 1, ta), _turn(mid, -1, tb)),
                           (_turn(nxt, -1, ta), _turn(mid, 1, tb))):
            base.append(tuple(_reduced(ra * c) for c in a_cs) + (sp.Integer(0),))
            plat.append(tuple(_reduced(rb * c) for c in b_cs) + (sp.Integer(0),))
    return base, plat


def _legs():
    base, plat = corners()
    out = []
    for k in range(6):
        lab = f"L{k + 1}"
        out.append(leg(
            lab,
            joint(NAME, "offset", f"{lab}.A", vector=base[k],
                  description=f"base corner A{k + 1}"),
            joint(NAME, "universal", f"{lab}.U", ("x", "y"), U[k], Role.PASSIVE,
                  "passive universal joint at the base"),
            joint(NAME, "prismatic", f"{lab}.q", "z", Q[k], Role.ACTIVE,
                  f"active stroke {Q[k]}"),
            joint(NAME, "spherical", f"{lab}.S", E[k], Role.PASSIVE,
                  f"passive spherical joint B{k + 1}"),
            joint(NAME, "offset", f"{lab}.B", vector=tuple(-c for c in plat[k]),
                  description=f"from B{k + 1} to the platform origin"),
        ))
    return tuple(out)


_HALVES = dict(zip(sp.symbols("t_alpha t_beta t_gamma", **R),
                   (sp.tan(alpha / 2), sp.tan(beta / 2), sp.tan(gamma / 2))))


def _pose_study() -> tuple:
    ta, tb, tg = _HALVES
    return ss.product(ss.translation_vector((x, y, z)), ss.rotation("z", tg),
                      ss.rotation("y", tb), ss.rotation("x", ta))


def pose_to_study(_derivation) -> dict:
    """Study coordinates PX (chart x0 = 1) of the pose, rational in the tan-half-angles."""
    st = _pose_study()
    return {s: (st[i + 1] / st[0]).subs(_HALVES) for i, s in enumerate(PX)}


def _leg_vectors(pose_subs: dict | None = None) -> tuple[list[sp.Matrix], sp.Matrix]:
    """A_k -> B_k in the base frame at the pose (symbols) or at ``pose_subs``."""
    base, plat = corners()
    # active rotations: sympy's rot_axis matrices are the passive ones
    rot = sp.rot_axis3(-gamma) * sp.rot_axis2(-beta) * sp.rot_axis1(-alpha)
    t = sp.Matrix([x, y, z])
    out = []
    for a, b in zip(base, plat):
        v = t + rot * sp.Matrix(b) - sp.Matrix(a)
        out.append(v.subs(pose_subs) if pose_subs else v)
    return out, rot


def limits(_derivation) -> list[Limit]:
    """Strokes 160-320 mm and joint angles +-20 deg at both ends (001 Sect. 3), read as the
    angle between the leg and its direction at the homing pose (x = y = 0, z = 210 mm,
    001 Table 1)."""
    home = dict(zip(POSE, HOME))
    vecs, rot = _leg_vectors()
    home_vecs, _ = _leg_vectors(home)
    lo, hi = LIMITS["q"]
    out = [Limit(str(q), q, lo, hi, "stroke", "mm", "001 Sect. 3") for q in JOINTS]
    a_hi = sp.rad(LIMITS["joint_deg"][1])  # |angle| <= 20 deg: the angle is >= 0
    for k, (v, h) in enumerate(zip(vecs, home_vecs), 1):
        h = h.subs(s3, sp.sqrt(3))
        v = v.subs(s3, sp.sqrt(3))
        n, hn = sp.sqrt(v.dot(v)), sp.sqrt(h.dot(h))
        # base end: the leg against its homing direction; platform end: the same, seen from
        # the platform (R^T v against the homing direction, R = I at home)
        out.append(Limit(f"phi_u{k}", sp.acos(v.dot(h) / (n * hn)), 0, a_hi, "passive", "rad",
                         "001 Sect. 3: joint A_k, angle to the homing direction"))
        out.append(Limit(f"phi_s{k}", sp.acos((rot.T * v).dot(h) / (n * hn)), 0, a_hi,
                         "passive", "rad", "001 Sect. 3: joint B_k, angle to the homing "
                         "direction"))
    return out


MECHANISM = declare(
    name=NAME,
    title="Stewart platform (6-UPS), comparison mechanism",
    source="000_c0528de5aff00fc3.txt Sect. 5 (Table 1) and 001_5ecc975eb69feb79.txt Sect. 3 "
           "(comparison Stewart platform; layout chosen here, see the module docstring)",
    summary="The 6-UPS Stewart platform that 000 Sect. 5 and 001 Sect. 3 compare the hybrid "
            "mechanisms with: rings of 400 mm diameter, strokes 160-320 mm, joints within "
            "+-20 deg (001 Sect. 3); the semi-regular hexagonal layout, which neither paper "
            "gives, has the joint spacing as parameters ta = tb = tan(phi/2).",
    parameters=(
        Parameter("ra", 200.0, "mm", "circumradius of the base joints",
                  "001 Sect. 3: rings of 400 mm diameter", domain="positive"),
        Parameter("rb", 200.0, "mm", "circumradius of the platform joints",
                  "001 Sect. 3: rings of 400 mm diameter", domain="positive"),
        Parameter("ta", 0.125, "1", "tan(phi_a/2): the base joints of a pair sit at "
                  "theta_j +- phi_a on the ring", "layout chosen here (not in 000 or 001)",
                  domain="positive"),
        Parameter("tb", 0.125, "1", "tan(phi_b/2): the platform joints of a pair sit at "
                  "theta_j + 60 deg +- phi_b", "layout chosen here (not in 000 or 001)",
                  domain="positive")),
    constants=(Constant(s3, s3**2 - 3, sp.sqrt(3), "sqrt(3) of the three-fold layout"),),
    joints=JOINTS,
    joint_units=("mm",) * 6,
    closures=(Closure("6-UPS Stewart platform", "P", _legs(), (1, *PX), PX,
                      note="the platform in the base frame, chart x0 = 1 (no half-turns)"),),
    pose=PoseMap(POSE, ("mm", "mm", "mm", "rad", "rad", "rad"), pose_to_study,
                 end_effector=ss.study_from_pose(*POSE),
                 description="R = Rz(gamma) Ry(beta) Rx(alpha), translation (x, y, z); chart "
                             "x0 = 1"),
    forward_kinematics="the forward kinematics of the general 6-6 Stewart platform has 40 "
                       "complex solutions; it is not needed for the workspace comparison "
                       "(issue 4) and not generated",
    limits=limits,
    checks="bonered_alg.papers.stewart_reference",
    # the homing pose of 001 Table 1; each leg is then 236.4 mm long (positive strokes)
    home=HOME,
    home_joints={q: 236.4 for q in JOINTS},
)
