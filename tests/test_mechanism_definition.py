"""Bad mechanism definitions give specific errors and leave outputs untouched."""

import types

import networkx as nx
import pytest
import sympy as sp

from bonered_alg.chains.joints import Role
from bonered_alg.chains.mechanism import Closure, Mechanism, Parameter, joint, leg
from bonered_alg.errors import (
    MechanismDefinitionError,
    NonClosingMechanismError,
    UndefinedParameterError,
    UnknownJointTypeError,
)
from bonered_alg.mechanisms import load
from bonered_alg.pipeline import derive, write

u, s, a, X, Y = sp.symbols("u s a X Y", real=True)


def toy_module(name="toy", platform=None, chain_extra=(), joint_kind="revolute", geometry=("a",)):
    def build():
        g = nx.MultiGraph()
        g.add_edge("base", "link", joint=joint_kind, label="u")
        g.add_edge("link", "slider", joint="prismatic", label="s")
        factors = [joint(name, "revolute", "F1", "z", u, Role.ACTIVE),
                   joint(name, "offset", "F2", axis="x", value=a),
                   joint(name, "prismatic", "F3", "x", s, Role.PASSIVE), *chain_extra]
        cl = Closure("c", "P", (leg("L", *factors),),
                     platform or (1, 0, 0, 0, 0, X, Y, 0), (X, Y))
        return Mechanism(name, "toy", "test", {k: Parameter(k, 1.0, "mm", "") for k in geometry},
                         (u,), (s,), (cl,), g, planar=True)

    mod = types.ModuleType(name)
    mod.NAME, mod.build, mod.__file__ = name, build, __file__
    mod.POSE, mod.JOINTS, mod.POSE_UNITS, mod.JOINT_UNITS = (X, Y), (u,), ("mm",) * 2, ("1",)
    mod.POSE_TO_STUDY = {}
    mod.verify = lambda d: []
    return mod


def test_unknown_joint_type_in_chain():
    with pytest.raises(UnknownJointTypeError, match=r"mechanism 'toy'.*unknown joint type "
                                                    r"'screwdriver'"):
        joint("toy", "screwdriver", "F9", "z", u)


def test_unknown_joint_type_in_topology():
    with pytest.raises(UnknownJointTypeError, match="joint u between 'base' and 'link' has "
                                                    "unknown type 'hinge'"):
        toy_module(joint_kind="hinge").build().validate()


def test_undefined_parameter():
    b = sp.Symbol("b", real=True)
    mod = toy_module(chain_extra=[joint("toy", "offset", "F4", axis="y", value=b)])
    with pytest.raises(UndefinedParameterError, match=r"leg 'L', factor F4: parameter\(s\) "
                                                      r"\['b'\] are not declared"):
        mod.build().validate()


def test_wrong_role():
    mod = toy_module(chain_extra=[joint("toy", "revolute", "F5", "z", s, Role.ACTIVE)])
    with pytest.raises(MechanismDefinitionError, match="F5: marked active but uses"):
        mod.build().validate()


def test_non_closing_mechanism_leaves_outputs_untouched(tmp_path):
    # the leg only rotates about Z; the platform is turned by 90 degrees about X: no closure
    mod = toy_module(platform=(1, 1, 0, 0, 0, X, Y, 0))
    (tmp_path / "generated").mkdir()
    (tmp_path / "derivations").mkdir()
    with pytest.raises(NonClosingMechanismError, match=r"mechanism 'toy': leg 'L' cannot close "
                                                       r"on the platform point P"):
        write(derive(mod, use_cache=False), tmp_path)
    assert not any(tmp_path.rglob("*.*"))


def test_topology_loops_and_mobility():
    mech = load("pro_hep_lct").build()
    assert len(mech.loops()) == 2
    # 004 Sect. 3.1: the planar part is driven by q2, q3 (t1, w1), q4 and q5
    assert mech.mobility() == 4 == len(mech.active)
