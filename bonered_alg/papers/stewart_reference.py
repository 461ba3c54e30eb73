"""The Stewart platform of the comparisons in 000 Sect. 5 and 001 Sect. 3: the papers print
no equation for it, only its dimensions, which are inputs of the derivation."""

from __future__ import annotations

from ..verification import Verdict


def verify(deriv, gen, studies) -> list[Verdict]:
    """No printed equation: the dimensions are inputs (000 Table 1, 001 Sect. 3)."""
    return [Verdict("001 Sect. 3", "Stewart platform dimensions: rings of 400 mm, strokes "
                    "160-320 mm, joints +-20 deg", "not-checkable", None,
                    "inputs of the comparison; the joint layout is not given in 000 or 001 "
                    "and is chosen here (module docstring)"),
            Verdict("000 Table 1", "Stewart platform dimensions: ra = rb = 190 mm, strokes "
                    "175-250 mm", "not-checkable", None,
                    "the alternative dimensioning of 000; pass ra=190, rb=190 to the generated "
                    "functions (the stroke limits in LIMITS are 001's)")]
