"""The double-triangular 3-PRP planar mechanism as Study-parameter legs (000 eq. 1-3,
001 eq. 17-20).

Both bone-reduction papers use the same planar stage: the active prismatic joints R_k slide
along the edges of a lower equilateral triangle of circumradius ``r`` with corners at
-30, 90 and 210 degrees, a revolute joint about the normal connects each slider to a
passive prismatic joint R'_k on an edge of the upper triangle (corners at 30, 150 and
270 degrees, same circumradius).  The 120-degree layout needs ``sqrt(3)``, which the legs
use as the algebraic constant ``s3`` (``s3**2 = 3``).

Leg k, from the lower frame to the upper frame O:
``T(A_k) Rz(e_k) Tx(q_k) Rz(-e_k)`` (active stroke along the lower edge),
``Tz(h)`` (height of the upper triangle, 001 eq. 7 and 20; 0 in 000),
``Rz(u_k)`` (passive revolute), ``Rz(f_k) Tx(-l_k) Rz(-f_k)`` (back along the upper edge by
the passive stroke ``l_k``, 000 eq. 2, 001 eq. 18) and ``T(-C_k)`` from the corner to O.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from .joints import Leg, Role, joint, leg


def prp_legs(mechanism: str, r: sp.Expr, s3: sp.Symbol, strokes: Sequence[sp.Symbol],
             revolutes: Sequence[sp.Symbol], passive_strokes: Sequence[sp.Symbol],
             names: Sequence[str] = ("P1", "P2", "P3"), height: sp.Expr = 0,
             upper: str = "MP1", corner: str = "B") -> tuple[Leg, ...]:
    """The three PRP legs of the double-triangular mechanism of circumradius ``r``."""
    active, passive = Role.ACTIVE, Role.PASSIVE
    half = s3 / 2
    lower = [(half * r, -r / 2, 0), (0, r, 0), (-half * r, -r / 2, 0)]
    corners = [(half * r, r / 2, 0), (-half * r, r / 2, 0), (0, -r, 0)]
    # tan(angle/2) of the lower edge directions (120, 240, 0 deg) and of the upper edges
    lower_u = [s3, -s3, None]
    upper_u = [None, -s3 / 3, s3 / 3]  # edge C1C2 runs along -x: a +x translation of -l
    legs = []
    for k, (qk, uk, lk, lab) in enumerate(zip(strokes, revolutes, passive_strokes, names)):
        n = k + 1
        f = [joint(mechanism, "offset", f"{lab}.A", vector=lower[k],
                   description=f"lower corner {n}, start of its edge")]
        if lower_u[k] is not None:
            f.append(joint(mechanism, "offset", f"{lab}.e", axis="z", rotation_u=lower_u[k],
                           description="turn to the lower edge direction"))
        f.append(joint(mechanism, "prismatic", f"{lab}.q", "x", qk, active,
                       f"active {qk} along the lower edge"))
        if lower_u[k] is not None:
            f.append(joint(mechanism, "offset", f"{lab}.e'", axis="z", rotation_u=-lower_u[k],
                           description="turn back"))
        if sp.sympify(height) != 0:
            f.append(joint(mechanism, "offset", f"{lab}.h", axis="z", value=height,
                           description="up to the plane of the upper triangle"))
        f.append(joint(mechanism, "revolute", f"{lab}.R", "z", uk, passive,
                       "passive revolute about the normal"))
        if upper_u[k] is None:
            f.append(joint(mechanism, "prismatic", f"{lab}.l", "x", lk, passive,
                           f"passive prismatic back along the {upper} edge"))
        else:
            f.append(joint(mechanism, "offset", f"{lab}.m", axis="z", rotation_u=upper_u[k],
                           description=f"turn to the {upper} edge direction"))
            f.append(joint(mechanism, "prismatic", f"{lab}.l", "x", -lk, passive,
                           f"passive prismatic back along the {upper} edge"))
            f.append(joint(mechanism, "offset", f"{lab}.m'", axis="z", rotation_u=-upper_u[k],
                           description="turn back"))
        f.append(joint(mechanism, "offset", f"{lab}.{corner}",
                       vector=tuple(-c for c in corners[k]),
                       description=f"from the {upper} corner {corner}{n} to its centre"))
        legs.append(leg(lab, *f))
    return tuple(legs)
