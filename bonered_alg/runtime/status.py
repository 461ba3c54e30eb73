"""Status codes of every generated module (DESIGN.md section 4), documented once.

A generated function returns NaN where it has no valid answer; the matching ``*_status``
function returns one of these codes per input, and ``STATUS`` says what each means.
"""

from __future__ import annotations

OK = 0
NO_REAL_SOLUTION = 1
JOINT_AT_INFINITY = 2
ON_BOUNDARY = 3
INPUT_SINGULAR = 4
INVALID_INPUT = 5
STROKE_LIMIT = 6
PASSIVE_JOINT_LIMIT = 7
FORWARD_SINGULAR = 8
OUTSIDE_CHART = 9
UNVERIFIED = 10
NOT_SOLVED = 11

STATUS = {
    OK: "ok",
    NO_REAL_SOLUTION: "no real solution: the pose is outside the reach of the leg that "
                      "drives this joint (negative discriminant)",
    JOINT_AT_INFINITY: "joint parameter at infinity (a tan-half-angle at joint angle pi, or "
                       "an overflow)",
    ON_BOUNDARY: "on the workspace boundary of a leg (double root, input singularity): the "
                 "joint values are valid, the Jacobian is not",
    INPUT_SINGULAR: "input singularity: a pivot of Ji vanishes (det Ji = 0); the joint "
                    "value is undetermined or unbounded and dq/dX is not defined",
    INVALID_INPUT: "non-finite input: a pose coordinate (inverse kinematics) or a joint "
                   "(forward kinematics)",
    STROKE_LIMIT: "an actuator stroke is outside its range (LIMITS, kind 'stroke')",
    PASSIVE_JOINT_LIMIT: "a passive joint (an angle, or a collar's slide) is outside its "
                         "range (LIMITS, kind 'passive')",
    FORWARD_SINGULAR: "forward (output) singularity: two assembly modes (nearly) merge; the "
                      "pose of this mode is returned but not determined to working precision",
    OUTSIDE_CHART: "the platform is turned by a half-turn (x0 = 0), outside the chart x0 = 1 "
                   "in which the closure is written",
    UNVERIFIED: "the forward-kinematics solution failed its check (a Gauss-Newton step on "
                "the closure equations did not vanish, or an equation was not satisfied): a "
                "step of the solver divided by a pivot near zero, which is not a singularity "
                "of the mechanism; no pose is returned",
    NOT_SOLVED: "not solved: the step that solves this joint uses another joint that has "
                "no valid value (its own status says why); per-joint status only",
}

# relative tolerances of the tests above (discriminant against B^2, pivot against its row)
DISC_RTOL = 1e-10
DET_RTOL = 1e-12
# forward kinematics: a solution is accepted where one more Gauss-Newton step changes
# no unknown by more than VERIFY_RTOL (1 + |x|) and each closure equation's residual is at
# most RESIDUAL_RTOL of its row of the Jacobian (columns scaled by 1 + |x|: a first-order
# distance to the equation's zero set, relative to the unknowns), and is FORWARD_SINGULAR
# where that Jacobian has sigma_min / sigma_max below COND_RTOL
VERIFY_RTOL = 1e-9
RESIDUAL_RTOL = 1e-10
COND_RTOL = 1e-8
