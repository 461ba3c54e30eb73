"""The exceptions bonered_alg raises; each names the mechanism and what was expected."""

from __future__ import annotations


class BoneredError(Exception):
    """Base class of every error raised by bonered_alg."""


class MechanismDefinitionError(BoneredError):
    """A mechanism module is malformed (unknown joint, undefined parameter, bad topology)."""

    def __init__(self, mechanism: str, detail: str):
        self.mechanism = mechanism
        super().__init__(f"mechanism {mechanism!r}: {detail}")


class UnknownJointTypeError(MechanismDefinitionError):
    """A joint type that bonered_alg does not know."""


class UndefinedParameterError(MechanismDefinitionError):
    """A chain uses a symbol that the mechanism does not declare."""


class NonClosingMechanismError(MechanismDefinitionError):
    """The legs of a closure cannot meet on a common platform pose."""


class EngineError(BoneredError):
    """A Groebner engine failed."""


class EngineUnavailableError(EngineError):
    """The requested Groebner engine is not installed."""


class EngineTimeoutError(EngineError):
    """A Groebner engine ran out of its time budget."""

    def __init__(self, engine: str, context: str, budget_s: float):
        self.engine, self.context, self.budget_s = engine, context, budget_s
        super().__init__(
            f"{context}: the {engine} engine exceeded its time budget of {budget_s:g} s"
        )
