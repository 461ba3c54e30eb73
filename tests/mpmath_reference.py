"""Layer 3 of DESIGN.md section 6: the derived symbolic IK at 50 digits vs. generated floats."""

import sympy as sp


def assert_ik_matches_mpmath(m, d, poses, rtol=1e-12):
    """Each joint of ``m.ik`` (mode 0, no limits) equals the derivation's root, evaluated
    with 50-digit floats through the same solve order, to ``rtol``."""
    par = {sp.Symbol(k, real=True): sp.Float(v, 50) for k, v in m.PARAMETERS.items()}
    for pose in poses:
        q = m.ik(pose, limits=False)
        vals = dict(par)
        vals.update({s: sp.Float(v, 50) for s, v in zip(d.mechanism.pose.coordinates, pose)})
        vals.update({k: sp.N(sp.sympify(v).subs(d.constants).subs(vals), 50)
                     for k, v in d.pose_to_study.items()})
        for step in d.steps:
            exact = sp.N(step.roots()[0].subs(d.constants).subs(vals), 50)
            vals[step.joint] = exact
            got = q[m.JOINTS.index(str(step.joint))]
            assert abs(float(exact) - got) <= rtol * max(1.0, abs(float(exact))), step.joint
