"""The mechanism contract: bad declarations give specific errors before any algebra, and
nothing is written."""

import types

import pytest
import sympy as sp

from bonered_alg.chains.topology import loops, mobility_counts, topology
from bonered_alg.declaration import (
    Closure,
    Coupling,
    Parameter,
    PoseMap,
    Role,
    declare,
    joint,
    leg,
    load_declaration,
)
from bonered_alg.errors import (
    MechanismDefinitionError,
    NonClosingMechanismError,
    UndefinedParameterError,
    UnknownJointTypeError,
)
from bonered_alg.mechanisms import pro_hep_lct
from bonered_alg.pipeline import runner

u, s, a, X, Y, px, py = sp.symbols("u s a X Y px py", real=True)


def toy_fields(name="toy", platform=None, extra=(), couplings=(), **overrides):
    joints = [joint(name, "prismatic", "F1", "x", u, Role.ACTIVE),
              joint(name, "offset", "F2", axis="x", value=a),
              joint(name, "prismatic", "F3", "y", s, Role.PASSIVE), *extra]
    fields = dict(
        name=name, title="toy", source="test", summary="one P-P leg",
        parameters=(Parameter("a", 1.0, "mm", "offset"),), joints=(u,), joint_units=("1",),
        closures=(Closure("c", "P", (leg("L", *joints),), platform or (1, 0, 0, 0, 0, X, Y, 0),
                          (X, Y), couplings=couplings, motion="planar"),),
        pose=PoseMap((px, py), ("mm", "mm"), {X: -px / 2, Y: -py / 2}),
        forward_kinematics="not needed for the test")
    fields.update(overrides)
    return fields


def toy_module(**kw) -> types.ModuleType:
    mod = types.ModuleType("toy")
    mod.MECHANISM = declare(**toy_fields(**kw))
    mod.__file__ = __file__
    return mod


def test_unknown_joint_type_in_chain():
    with pytest.raises(UnknownJointTypeError, match=r"mechanism 'toy'.*unknown joint type "
                                                    r"'screwdriver'"):
        joint("toy", "screwdriver", "F9", "z", u)


def test_unknown_joint_type_in_a_coupling_linkage():
    cp = Coupling(s - a, "a slider", linkage=(("base", "slider", "hinge", "h"),))
    with pytest.raises(UnknownJointTypeError, match="joint h between 'base' and 'slider' has "
                                                    "unknown type 'hinge'"):
        load_declaration(toy_module(couplings=(cp,)))


def test_undefined_parameter():
    b = sp.Symbol("b", real=True)
    mod = toy_module(extra=[joint("toy", "offset", "F4", axis="y", value=b)])
    with pytest.raises(UndefinedParameterError, match=r"leg 'L', factor F4: parameter\(s\) "
                                                      r"\['b'\] are not declared"):
        load_declaration(mod)


def test_wrong_role():
    mod = toy_module(extra=[joint("toy", "revolute", "F5", "z", s, Role.ACTIVE)])
    with pytest.raises(MechanismDefinitionError, match="F5: marked active but uses"):
        load_declaration(mod)


def test_a_symbol_has_one_role():
    # a passive joint named like a Study coordinate of the platform is the same symbol
    mod = toy_module(extra=[joint("toy", "revolute", "F6", "z", X, Role.PASSIVE)])
    with pytest.raises(MechanismDefinitionError, match=r"\['X'\] are both closure Study "
                                                       "coordinate and passive joint"):
        load_declaration(mod)


def test_unknown_and_missing_fields_are_named():
    with pytest.raises(MechanismDefinitionError, match=r"mechanism 'toy': unknown declaration "
                                                       r"field 'limts' \(did you mean 'limits'"):
        declare(**toy_fields(limts=()))
    fields = toy_fields()
    del fields["pose"]
    with pytest.raises(MechanismDefinitionError, match="lacks the required field.*pose"):
        declare(**fields)


@pytest.mark.parametrize("value", [None, float("nan"), "1.0", True])
def test_a_parameter_needs_a_finite_value(value):
    mod = toy_module(parameters=(Parameter("a", value, "mm", "offset"),))
    with pytest.raises(MechanismDefinitionError, match="parameter 'a' has value .*expected a "
                                                       "finite number in mm"):
        load_declaration(mod)


@pytest.mark.parametrize("fields, message", [
    (dict(parameters=(Parameter("a", 1.0, "mm", "offset", domain="length"),)),
     r"parameter 'a' has domain 'length'; expected one of \('real', 'positive'"),
    (dict(parameters=(Parameter("a", -1.0, "mm", "offset", domain="positive"),)),
     "parameter 'a' is declared positive but its value is -1.0"),
    (dict(home=(0.0,)), r"home must be 2 finite numbers, one per pose coordinate \('px', "
                        r"'py'\)"),
    (dict(home_joints={u: 1.0}), "home_joints .* needs the home pose"),
    (dict(home=(0.0, 0.0), home_joints={s: 1.0}), "home_joints names s, which is not an "
                                                   "actuated joint"),
    (dict(angle_joints={s: "sigma"}), "angle_joints names s, which is not an actuated "
                                      "joint"),
    (dict(angle_joints={u: "theta"}), r"angle joint theta \(2 atan\(u\)\) must have the "
                                      "unit 'rad', got '1'"),
    (dict(angle_joints={u: "not a name"}, joint_units=("rad",)),
     "angle_joints.u. must be an identifier"),
])
def test_domains_and_the_physical_branch_are_checked(fields, message):
    with pytest.raises(MechanismDefinitionError, match=message):
        load_declaration(toy_module(**fields))


def test_the_declared_branch_chooses_the_root_of_mode_0():
    """kinematics.branches.orient: q^2 - (x^2 + 4) at x = 0 has the roots +-2; declaring
    -2 negates the generator (mode 0 then takes -2), declaring 2 keeps it; a value as near
    one root as the other, a linear step, or a home pose without real roots are errors."""
    from bonered_alg.kinematics.branches import orient
    from bonered_alg.kinematics.ik_plan import IKStep

    q, x, p = sp.symbols("q x p", real=True)
    quad = IKStep(q, q**2 - x**2 - 4, 2, sp.Integer(1), sp.Integer(0), -x**2 - 4, "t")
    lin = IKStep(p, p - q, 1, sp.Integer(0), sp.Integer(1), -q, "t")
    steps, rec = orient("toy", [quad, lin], {}, (x,), (0.0,), {q: -1.9}, {})
    assert rec[0].negated and rec[0].mode0 == -2.0
    assert steps[0].generator == -(q**2 - x**2 - 4) and steps[1] is lin
    root0 = (-steps[0].B + sp.sqrt(steps[0].B**2 - 4 * steps[0].A * steps[0].C)) / (
        2 * steps[0].A)
    assert root0.subs(x, 0) == -2  # the '+sqrt' root of the negated generator
    steps, rec = orient("toy", [quad, lin], {}, (x,), (0.0,), {q: 2.5}, {})
    assert not rec[0].negated and steps[0] is quad
    with pytest.raises(MechanismDefinitionError, match="as near the one root"):
        orient("toy", [quad], {}, (x,), (0.0,), {q: 0.0}, {})
    with pytest.raises(MechanismDefinitionError, match="linear"):
        orient("toy", [quad, lin], {}, (x,), (0.0,), {p: 1.0}, {})
    bad = IKStep(q, q**2 + x**2 + 4, 2, sp.Integer(1), sp.Integer(0), x**2 + 4, "t")
    with pytest.raises(MechanismDefinitionError, match="no real roots"):
        orient("toy", [bad], {}, (x,), (0.0,), {q: 1.0}, {})


def test_former_hooks_are_rejected():
    mod = toy_module()
    mod.verify = lambda d: []
    with pytest.raises(MechanismDefinitionError, match=r"defines \['verify'\], names of the "
                                                       "former hook contract"):
        load_declaration(mod)
    bare = types.ModuleType("old_style")
    bare.build = lambda: None
    with pytest.raises(MechanismDefinitionError, match="defines no MECHANISM"):
        load_declaration(bare)


def test_missing_checks_module_is_found_before_any_algebra():
    mod = toy_module(checks="bonered_alg.papers.no_such_paper")
    with pytest.raises(MechanismDefinitionError, match="no_such_paper.*cannot be imported"):
        load_declaration(mod)
    mod = toy_module(checks="bonered_alg.papers.study_algebra")
    with pytest.raises(MechanismDefinitionError, match="defines no function verify"):
        load_declaration(mod)


def test_pose_map_must_cover_the_study_coordinates_the_ik_uses(tmp_path):
    mod = toy_module(pose=PoseMap((px, py), ("mm", "mm"), {Y: -py / 2}))
    with pytest.raises(MechanismDefinitionError, match=r"no expression for the Study "
                                                       r"coordinate\(s\) \['X'\]"):
        runner.derive(mod, use_cache=False)


def test_non_closing_mechanism_leaves_outputs_untouched(tmp_path):
    # the leg only translates; the platform is turned by 90 degrees about X: no closure
    mod = toy_module(platform=(1, 1, 0, 0, 0, X, Y, 0))
    (tmp_path / "generated").mkdir()
    (tmp_path / "derivations").mkdir()
    with pytest.raises(NonClosingMechanismError, match=r"mechanism 'toy': leg 'L' cannot close "
                                                       r"on the platform point P"):
        runner.write(runner.derive(mod, use_cache=False), tmp_path)
    assert not any(tmp_path.rglob("*.*"))


def test_topology_loops_and_mobility():
    """004 Sect. 3.1: the planar part is driven by q2, q3 (t1, w1), q4 and q5; the
    topology comes from the legs (and the rod linkage of the coupling)."""
    mech = pro_hep_lct.MECHANISM
    actuated = mech.actuated_closures
    assert len(loops(topology(actuated))) == 2
    counts = {c.closure: c.mobility for c in mobility_counts(mech.closures)}
    assert counts == {"upper planar mechanism": 2, "lower planar mechanism": 2}
    assert sum(counts.values()) == 4 == len(mech.joints)
    # the driven platform adds the loop through Pd, the platform and Pu
    assert len(loops(topology(mech.closures))) == 3
