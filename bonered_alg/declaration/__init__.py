"""The mechanism contract: everything a mechanism declaration uses, in one import.

``from bonered_alg.declaration import *`` gives the declaration types (:class:`Mechanism`,
:func:`declare`, :class:`Parameter`, :class:`Constant`, :class:`Closure`, the charts, the
pose map, limits and generated functions) and the chain builders (``joint``, ``leg``,
:class:`Role`).
"""

from ..chains.joints import HelicalCoupling, Joint, Leg, Role, joint, leg
from .closures import Closure, Coupling, UnitCoordinate, UnitRotation
from .mechanism import (
    ExtraGenerator,
    InputFunction,
    Limit,
    Mechanism,
    PoseFunction,
    PoseMap,
    declare,
    load_declaration,
    validate,
)
from .parameters import Constant, Parameter
from .weights import LinkWeight, WeightPoint

__all__ = ["Closure", "Constant", "Coupling", "ExtraGenerator", "HelicalCoupling",
           "InputFunction", "Joint", "Leg", "Limit", "LinkWeight", "Mechanism", "Parameter",
           "PoseFunction", "PoseMap", "Role", "UnitCoordinate", "UnitRotation", "WeightPoint",
           "declare", "joint", "leg", "load_declaration", "validate"]
