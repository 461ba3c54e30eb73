"""A helical joint is carried in the ideal as a cylindrical one, and its relation
``s = pitch * theta`` is a generated step applied to the recovered joint values: a toy
slider with a nut on a vertical screw, derived end to end in memory."""

import types

import numpy as np
import sympy as sp

from bonered_alg.algebra import study_symbolic as ss
from bonered_alg.chains.topology import mobility_counts
from bonered_alg.declaration import Closure, Parameter, PoseMap, Role, declare, joint, leg
from bonered_alg.pipeline import runner

q, v, s, p = sp.symbols("q v s p", real=True)
g, *Y = sp.symbols("g y0:4", real=True)
x, theta, zeta = sp.symbols("x theta zeta", real=True)


# the nut: turned by theta about z and moved by (x, 0, zeta)
platform = ss.product(ss.translation_vector((x, 0, zeta)), ss.rotation("z", sp.tan(theta / 2)))


def _module():
    screw = leg("S",
                joint("screw", "prismatic", "q", "x", q, Role.ACTIVE, "carriage along x"),
                joint("screw", "helical", "H", "z", v, s, p, Role.PASSIVE, "nut on the screw"))
    mech = declare(
        name="screw", title="screw toy", source="test", summary="a nut on a screw on a slider",
        parameters=(Parameter("p", 2.0, "mm/rad", "pitch of the screw per radian"),),
        joints=(q,), joint_units=("mm",),
        # the platform: turned by g = tan(theta/2) about z, moved by (x, 0, zeta)
        closures=(Closure("screw", "nut", (screw,), (1, 0, 0, g, *Y), (g, *Y)),),
        pose=PoseMap((x, theta, zeta), ("mm", "rad", "mm"), dict(zip((g, *Y), platform[3:]))),
        forward_kinematics="the toy's forward kinematics is not needed")
    mod = types.ModuleType("screw_toy")
    mod.MECHANISM, mod.__file__ = mech, __file__
    return mod


def test_helical_relation_is_generated_and_counted():
    record = runner.derive(_module())
    gen = record.generated.module
    assert gen.HELICAL == (("v", "s", "p"),)
    assert set(gen.PASSIVE) == {"v", "s"}
    pose = np.array([[12.0, 0.4, 0.8], [12.0, 0.4, 3.0]])  # on the helix, and off it
    assert np.allclose(gen.ik(pose)[:, 0], 12.0)
    res = gen.helical_residuals(pose)
    assert np.allclose(res[:, 0], [0.8 - 2.0 * 0.4, 3.0 - 2.0 * 0.4])
    assert np.allclose(gen.helical_residuals(pose, p=1.5)[:, 0], [0.8 - 0.6, 3.0 - 0.6])
    # the Kutzbach-Gruebler count takes the helical joint's one freedom
    (count,) = mobility_counts(record.derivation.mechanism.closures)
    assert count.freedoms == 2
    from bonered_alg.pipeline import outputs

    assert "Helical joint H" in outputs.files(record)["derivations/screw.tex"]
