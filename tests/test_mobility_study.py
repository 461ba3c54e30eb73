"""Mobility two ways for every mechanism (issue 17): the screw-theory count of the
committed ``derivations/<name>.mobility.csv`` against the dimension of the closure's ideal
(its tangent space at home, and its Krull dimension where computed), and against the
papers' and the textbook's mobilities."""

import csv

import pytest
from conftest import ROOT

from bonered_alg.registry import REGISTRY


def _rows(name):
    with open(ROOT / "derivations" / f"{name}.mobility.csv", newline="") as f:
        return {r["closure"]: r for r in csv.DictReader(f)}


@pytest.mark.parametrize("name", sorted(REGISTRY))
def test_screw_count_equals_the_ideal_dimension(name):
    """M plus the local freedoms (joint motions that move no other body) is the dimension
    of the closure variety at home; the Krull dimension, where computed, too."""
    rows = _rows(name)
    assert rows
    for closure, r in rows.items():
        assert int(r["M"]) + int(r["local"]) == int(r["tangent"]), (name, closure)
        if r["krull"]:
            assert int(r["krull"]) == int(r["tangent"]), (name, closure)


def _motion(r):
    return int(r["M"]), int(r["rotations"]), int(r["platform"]) - int(r["rotations"])


def test_mobilities_printed_or_known():
    # 6-UPS: six freedoms, three rotations and three translations (no common constraint)
    st = _rows("stewart")
    assert [_motion(r) for r in st.values()] == [(6, 3, 3)]
    assert int(next(iter(st.values()))["order"]) == 6
    # 000 Sect. 2 / 001 Sect. 2: the 3-RPS tripod has 3 DOF (two rotations, one
    # translation); the planar 3-PRP stage 3 (a rotation and two translations), order 3
    for name in ("planar_tripod", "tripod_planar"):
        rows = _rows(name)
        assert _motion(rows["3-RPS tripod"]) == (3, 2, 1)
        prp = rows["planar 3-PRP mechanism"]
        assert _motion(prp) == (3, 1, 2) and int(prp["order"]) == 3
    # 004 Sect. 3.2: the upper and lower planar mechanisms move their points in a plane,
    # 2 DOF each (the lower one's parallelograms keep link d's orientation)
    ph = _rows("pro_hep_lct")
    assert _motion(ph["upper planar mechanism"]) == (2, 0, 2)
    assert _motion(ph["lower planar mechanism (with its coordinates)"]) == (2, 0, 2)
    # 002 eq. (3): 4 DOF; collar 1's frame (the algebra's platform) 2R1T, collar 2's slide
    # along the shaft (the spin, through the virtual screw) a local freedom of limb 2
    (ur,) = _rows("urrh_rcm").values()
    assert _motion(ur) == (3, 2, 1) and int(ur["local"]) == 1 and int(ur["krull"]) == 4
    # 003 eq. (6): M = 5 (9 - 10 - 1) + 12 + 1 = 3, order 5 (the common couple about Y0),
    # one redundant constraint, pure translation (Sect. 2.1)
    (lm,) = _rows("lamina_milling").values()
    assert _motion(lm) == (3, 0, 3) and int(lm["krull"]) == 3
    assert (int(lm["order"]), int(lm["redundant"]), int(lm["local"])) == (5, 1, 0)
