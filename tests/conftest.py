import importlib
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

_RECORDS: dict = {}
_DERIVE = None


def record_of(target):
    """The in-memory derivation record of a registered mechanism (or a declaration module),
    derived once per test session (through the elimination cache) and shared by every test
    that needs it."""
    global _DERIVE
    key = target if isinstance(target, str) else target.__name__
    if key not in _RECORDS:
        if _DERIVE is None:  # the runner's own, even where a test has patched it
            from bonered_alg.pipeline.runner import derive

            _DERIVE = derive
        _RECORDS[key] = _DERIVE(target)
    return _RECORDS[key]


@pytest.fixture(scope="session")
def gen():
    """The committed generated module ``bonered_alg.generated.pro_hep_lct``."""
    return importlib.import_module("bonered_alg.generated.pro_hep_lct")


@pytest.fixture(scope="session")
def record():
    """The derivation record of pro_hep_lct (derivation, generated module, studies,
    verdicts)."""
    return record_of("pro_hep_lct")


@pytest.fixture(scope="session")
def derivation(record):
    """The symbolic derivation of pro_hep_lct."""
    return record.derivation
