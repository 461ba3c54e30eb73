"""Checks shared by papers 000 and 001, whose 3-PRP double-triangular stage is the same."""

from __future__ import annotations

import sympy as sp


def output_determinant_with_ik(deriv, name: str, joints, g: sp.Symbol
                               ) -> tuple[sp.Expr, list[str]]:
    """The derived output-Jacobian determinant ``name`` of the planar closure with the
    derived IK of ``joints`` inserted, factored over Q(sqrt 3), and the angles 2 atan(g) at
    which its numerator vanishes (000 eq. 41, 001 eq. 52)."""
    cs = deriv.constants
    det_o = next(s for s in deriv.singularities if s.name == name).expression.subs(cs)
    steps = {st.joint: (-st.C / st.B).subs(cs) for st in deriv.steps if st.joint in joints}
    fwd = sp.factor(sp.cancel(det_o.subs(steps)), extension=sp.sqrt(3))
    roots = sorted({str(sp.nsimplify(2 * sp.atan(r))) for r in sp.solve(sp.numer(fwd), g)})
    return fwd, roots
