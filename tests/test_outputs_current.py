"""generated/ and derivations/ are up to date with the code, deterministic, and incremental."""

import shutil
import subprocess
import sys

import pytest

from bonered_alg.mechanisms import REGISTRY
from bonered_alg.pipeline import (
    derivation_hash,
    derive,
    ik_module_source,
    recorded_hash,
    verification_json,
)
from bonered_alg.report.latex_report import render_report
from tests.conftest import ROOT


@pytest.mark.parametrize("name", REGISTRY)
def test_committed_outputs_carry_current_hash(name):
    assert recorded_hash(ROOT, name) == derivation_hash(name)


@pytest.mark.parametrize("name", REGISTRY)
def test_rederivation_is_byte_identical(name):
    d = derive(name)
    assert ik_module_source(d) == (ROOT / f"generated/{name}.py").read_text()
    assert render_report(d) == (ROOT / f"derivations/{name}.tex").read_text()
    assert verification_json(d) == (ROOT / f"derivations/{name}.verification.json").read_text()


def test_second_derive_changes_nothing(tmp_path):
    for folder in ("generated", "derivations"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    out = subprocess.run([sys.executable, "-m", "bonered_alg.cli", "derive", "--root",
                          str(tmp_path)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    for name in REGISTRY:
        assert f"{name}: up to date" in out.stdout
    after = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert after == before


def test_hash_covers_only_the_mechanism_and_the_core(tmp_path):
    pkg = tmp_path / "bonered_alg"
    shutil.copytree(ROOT / "bonered_alg", pkg, ignore=shutil.ignore_patterns("__pycache__"))
    (pkg / "mechanisms" / "other.py").write_text("X = 1\n")
    h_pro, h_other = derivation_hash("pro_hep_lct", pkg), derivation_hash("other", pkg)
    (pkg / "mechanisms" / "other.py").write_text("X = 2\n")
    assert derivation_hash("pro_hep_lct", pkg) == h_pro
    assert derivation_hash("other", pkg) != h_other
    # an optional package shapes only the mechanisms that declare it (USES_PACKAGES)
    h_other = derivation_hash("other", pkg)
    (pkg / "surgical" / "manipulation.py").write_text(
        (pkg / "surgical" / "manipulation.py").read_text() + "\n# changed\n")
    assert derivation_hash("other", pkg) == h_other
    assert derivation_hash("pro_hep_lct", pkg) != h_pro
    h_pro = derivation_hash("pro_hep_lct", pkg)
    (pkg / "algebra" / "convention.py").write_text(
        (pkg / "algebra" / "convention.py").read_text() + "\n# changed\n")
    assert derivation_hash("pro_hep_lct", pkg) != h_pro
    assert derivation_hash("other", pkg) != h_other


def test_missing_engine_leaves_outputs_untouched(tmp_path, monkeypatch):
    """An engine that is not installed (and no cached result) stops before any write."""
    from bonered_alg.elimination.engines import SingularEngine
    from bonered_alg.errors import EngineUnavailableError
    from bonered_alg.pipeline import derive_all

    monkeypatch.setenv("BONERED_CACHE_DIR", str(tmp_path / "empty-cache"))
    for folder in ("generated", "derivations"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(EngineUnavailableError, match="mechanism 'pro_hep_lct'.*singular"):
        derive_all(tmp_path, ["pro_hep_lct"], force=True,
                   engine=SingularEngine("no-such-singular"), log=lambda _: None)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


@pytest.mark.parametrize("name", REGISTRY)
def test_artifacts_are_reproduced_byte_for_byte(name):
    """Trajectory tables and plots written by make derive are deterministic and current."""
    from bonered_alg.mechanisms import load
    from bonered_alg.pipeline import load_generated

    if not hasattr(load(name), "artifacts"):
        pytest.skip("no artifacts")
    d = derive(name)
    gen = load_generated(ik_module_source(d), name)
    for rel, content in d.module.artifacts(d, gen).items():
        committed = (ROOT / "derivations" / rel)
        data = content if isinstance(content, bytes) else content.encode()
        assert committed.read_bytes() == data, rel
