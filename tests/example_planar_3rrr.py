"""A planar 3-RRR parallel mechanism: the worked example of "Adding a mechanism" (README).

Three legs from base joints A_k to platform joints B_k, each an actuated revolute joint
(theta_k, tan-half u_k), a link l1, a passive revolute (e_k), a link l2 and a passive
revolute (f_k) at B_k.  Right-isosceles layouts keep every coordinate rational: A = (0, 0),
(L, 0), (0, L) on the base, B = (0, 0), (b, 0), (0, b) on the platform.  The platform pose
is (x, y, phi): its origin B_1 and its rotation about z.
"""

import sympy as sp

from bonered_alg.algebra import study_symbolic as ss
from bonered_alg.declaration import Closure, Parameter, PoseMap, Role, declare, joint, leg

NAME = "planar_3rrr"
R = {"real": True}
L, b, l1, l2 = sp.symbols("L b l1 l2", **R)
U = sp.symbols("u1:4", **R)  # actuated: tan(theta_k / 2)
V = sp.symbols("e1:4", **R)  # passive elbows
W = sp.symbols("f1:4", **R)  # passive platform joints
g, v1, v2 = sp.symbols("g v1 v2", **R)  # the platform's Study coordinates (chart x0 = 1)
x, y, phi = sp.symbols("x y phi", **R)
BASE = ((0, 0, 0), (L, 0, 0), (0, L, 0))
PLATFORM = ((0, 0, 0), (b, 0, 0), (0, b, 0))


def _leg(k):
    return leg(f"L{k + 1}",
               joint(NAME, "offset", f"A{k + 1}", vector=BASE[k], description="base joint"),
               joint(NAME, "revolute", f"R{k + 1}", "z", U[k], Role.ACTIVE, "actuated"),
               joint(NAME, "offset", f"l1_{k + 1}", axis="x", value=l1, description="link l1"),
               joint(NAME, "revolute", f"E{k + 1}", "z", V[k], Role.PASSIVE, "elbow"),
               joint(NAME, "offset", f"l2_{k + 1}", axis="x", value=l2, description="link l2"),
               joint(NAME, "revolute", f"B{k + 1}", "z", W[k], Role.PASSIVE, "platform joint"),
               joint(NAME, "offset", f"P{k + 1}", vector=tuple(-c for c in PLATFORM[k]),
                     description="from B_k to the platform origin"))


t = sp.tan(phi / 2)
MECHANISM = declare(
    name=NAME,
    title="Planar 3-RRR parallel mechanism (worked example)",
    source="README, Adding a mechanism",
    summary="Three RRR legs, actuated at the base, carry a triangular platform in the plane.",
    parameters=(Parameter("L", 300.0, "mm", "side of the base triangle", "chosen"),
                Parameter("b", 100.0, "mm", "side of the platform triangle", "chosen"),
                Parameter("l1", 160.0, "mm", "proximal links", "chosen"),
                Parameter("l2", 160.0, "mm", "distal links", "chosen")),
    joints=U,
    joint_units=("1 (tan(theta/2))",) * 3,
    closures=(Closure("3-RRR", "platform", tuple(_leg(k) for k in range(3)),
                      (1, 0, 0, g, 0, v1, v2, 0), (g, v1, v2), motion="planar",
                      note="the platform turns by phi about z and moves in the plane"),),
    pose=PoseMap((x, y, phi), ("mm", "mm", "rad"),
                 {g: t, v1: -(x + t * y) / 2, v2: -(y - t * x) / 2},
                 end_effector=ss.product(ss.translation_vector((x, y, 0)),
                                         ss.rotation("z", t))),
    forward_kinematics="the forward kinematics of a 3-RRR is a univariate sextic (six "
                       "assembly modes); back-substitution steps of degree > 2 are not "
                       "generated yet",
    # mode 0 is the assembly as built: at this home pose the actuators stand at theta =
    # 114, 81 and 4 deg (tan-halves 1.55, 0.86, 0.04); the other roots are the other modes
    home=(80.0, 80.0, 0.1),
    home_joints={U[0]: 1.55, U[1]: 0.86, U[2]: 0.04},
)
