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

# seconds a cold derivation of each took on a 2-core machine (bench derive, 2026-12-06
# 22:34 UTC, one process):
# only the order in which ``derive_all`` hands mechanisms to its worker processes reads
# them (the longest first, so that two workers finish together); a local record of the
# last run's times (``pipeline.runner``) takes their place once there is one
EXPECTED_SECONDS = {
    "tripod_planar": 25, "urrh_rcm": 21, "stewart": 19, "planar_tripod": 14,
    "pro_hep_lct": 9, "lamina_milling": 4,
}


def module_path(name: str) -> str:
    """The declaration module of mechanism ``name``; a clear error for unknown names."""
    try:
        return MECHANISMS[name]
    except KeyError:
        raise KeyError(f"unknown mechanism {name!r}; known: {', '.join(MECHANISMS)}") from None


def load(name: str) -> ModuleType:
    """The declaration module of mechanism ``name``."""
    return importlib.import_module(module_path(name))
