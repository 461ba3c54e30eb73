"""One module per mechanism: ``build() -> Mechanism``, ``POSE``, ``JOINTS``, ``verify()``."""

from __future__ import annotations

import importlib
from types import ModuleType

REGISTRY = ("pro_hep_lct", "planar_tripod", "tripod_planar", "stewart")


def load(name: str) -> ModuleType:
    """The mechanism module ``bonered_alg.mechanisms.<name>``; clear error for unknown names."""
    if name not in REGISTRY:
        raise KeyError(f"unknown mechanism {name!r}; known: {', '.join(REGISTRY)}")
    return importlib.import_module(f"{__name__}.{name}")
