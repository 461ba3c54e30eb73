"""The numpy-only runtime every generated module imports (``bonered_alg.generated.<name>``).

Generated modules hold tables, kernels and thin wrappers; the algorithms are here, once:
argument checks (:mod:`.inputs`), the compiled fast path (:mod:`.compiled`), back-
substitution (:mod:`.backsubstitution`), the model with IK, Jacobians, limits and
singularities (:mod:`.model`), forward kinematics (:mod:`.fk`, :mod:`.rps`, with the Newton
step of :mod:`.newton`) and the status codes (:mod:`.status`). Importing it never imports sympy.
"""

from __future__ import annotations

from .compiled import FastPath
from .model import ForwardKinematics, Model, RPSKernels
from .statics import Statics
from .status import (
    FORWARD_SINGULAR,
    INPUT_SINGULAR,
    INVALID_INPUT,
    JOINT_AT_INFINITY,
    NO_REAL_SOLUTION,
    NOT_SOLVED,
    OK,
    ON_BOUNDARY,
    OUTSIDE_CHART,
    PASSIVE_JOINT_LIMIT,
    STATUS,
    STROKE_LIMIT,
    UNVERIFIED,
)

# the contract between the code generator and this runtime; a generated module states the
# version it was written for, and importing it with another runtime fails clearly
API_VERSION = 3


def require(version: int, mechanism: str) -> None:
    """Raise ImportError when a generated module was written for another runtime API."""
    if version != API_VERSION:
        raise ImportError(f"generated module {mechanism!r} was written for runtime API "
                          f"{version}, this bonered_alg has {API_VERSION}: run `make derive`")


__all__ = ["API_VERSION", "FORWARD_SINGULAR", "INPUT_SINGULAR", "INVALID_INPUT",
           "FastPath", "JOINT_AT_INFINITY", "NO_REAL_SOLUTION", "NOT_SOLVED", "OK", "ON_BOUNDARY",
           "OUTSIDE_CHART",
           "PASSIVE_JOINT_LIMIT", "STATUS", "STROKE_LIMIT", "ForwardKinematics", "Model",
           "RPSKernels", "Statics", "UNVERIFIED", "require"]
