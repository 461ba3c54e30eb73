import importlib
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))


@pytest.fixture(scope="session")
def gen():
    """The committed generated module ``bonered_alg.generated.pro_hep_lct``."""
    return importlib.import_module("bonered_alg.generated.pro_hep_lct")


@pytest.fixture(scope="session")
def derivation():
    """The in-memory derivation of pro_hep_lct (through the elimination cache)."""
    from bonered_alg.pipeline import derive

    return derive("pro_hep_lct")
