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


_SYMBOLIC: dict = {}


def symbolic_of(name: str):
    """The symbolic derivation of a registered mechanism: elimination, IK plan, Jacobians,
    singularities, forward kinematics, passive joints, analyses, pose map and limits, but no
    code generation, studies or verification (the committed outputs hold those).  That is
    what a test of the derived algebra needs, in a fraction of the time (tripod_planar: 50 s
    of 210 s)."""
    if name not in _SYMBOLIC:
        from bonered_alg.pipeline import stages
        from bonered_alg.pipeline.algebra import Algebra
        from bonered_alg.pipeline.results import Derivation
        from bonered_alg.pipeline.runner import current_hash
        from bonered_alg.registry import load

        algebra = Algebra.default(None)
        d = Derivation(stages.build(load(name)), current_hash(name))
        for stage in (stages.eliminate, stages.plan, stages.analyse):
            d = stage(d, algebra)
        _SYMBOLIC[name] = stages.specify(d)
    return _SYMBOLIC[name]


def verdicts_of(name: str) -> dict[str, str]:
    """Verdict per printed reference from the committed ``derivations/<name>.verification.json``
    (CI re-derives it with ``derive --force`` and fails on any difference)."""
    import json

    rows = json.loads((ROOT / "derivations" / f"{name}.verification.json").read_text())
    return {row["ref"]: row["verdict"] for row in rows}


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
