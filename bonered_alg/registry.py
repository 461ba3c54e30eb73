"""The mechanisms ``make derive`` derives: name -> declaration module.

Registering a mechanism here changes no other mechanism's derivation hash (this module is
read by the command line and the runner, never by a derivation).
"""

from __future__ import annotations

import importlib
from types import ModuleType

MECHANISMS = {
    "pro_hep_lct": "bonered_alg.mechanisms.pro_hep_lct",
    "planar_tripod": "bonered_alg.mechanisms.planar_tripod",
    "tripod_planar": "bonered_alg.mechanisms.tripod_planar",
    "stewart": "bonered_alg.mechanisms.stewart",
    "urrh_rcm": "bonered_alg.mechanisms.urrh_rcm",
    "lamina_milling": "bonered_alg.mechanisms.lamina_milling",
}
REGISTRY = tuple(MECHANISMS)


def module_path(name: str) -> str:
    """The declaration module of mechanism ``name``; a clear error for unknown names."""
    try:
        return MECHANISMS[name]
    except KeyError:
        raise KeyError(f"unknown mechanism {name!r}; known: {', '.join(MECHANISMS)}") from None


def load(name: str) -> ModuleType:
    """The declaration module of mechanism ``name``."""
    return importlib.import_module(module_path(name))
