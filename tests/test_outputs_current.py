"""generated/ and derivations/ are up to date with the code, deterministic, and incremental.

That a re-derivation reproduces every committed output byte for byte is checked where it
costs minutes, not in this suite: CI runs ``derive --force`` and ``git diff --exit-code``
(``.ci/run``).  Here: the committed outputs carry the hash of the current sources."""

import shutil
import subprocess
import sys

import pytest
from conftest import ROOT

from bonered_alg.pipeline import outputs
from bonered_alg.pipeline.provenance import derivation_hash
from bonered_alg.pipeline.runner import current_hash
from bonered_alg.pipeline.stages import GENERATOR
from bonered_alg.registry import MECHANISMS, REGISTRY


@pytest.mark.parametrize("name", REGISTRY)
def test_committed_outputs_carry_current_hash(name):
    assert outputs.recorded_hash(ROOT, name) == current_hash(name)


def test_committed_outputs_were_derived_with_this_toolchain():
    """derivations/toolchain.json names the Groebner engine release and the pinned packages
    the outputs were derived with; another Singular, or other package versions, must be
    seen, not silently trusted (re-derive with `make derive-force` and compare)."""
    from bonered_alg.elimination.engines import get_engine
    from bonered_alg.pipeline import toolchain

    recorded = toolchain.recorded(ROOT)
    assert recorded is not None, "derivations/toolchain.json is missing: run `make derive`"
    assert recorded == toolchain.current(ROOT, get_engine()), (
        f"derived with {recorded}, this machine has {toolchain.current(ROOT, get_engine())}")


def test_study_algebra_record_is_current():
    from bonered_alg.papers import study_algebra

    text = (ROOT / "derivations" / "study_algebra.tex").read_text()
    assert study_algebra.record_hash() in text
    verdicts = study_algebra.algebra_verdicts()
    assert outputs.verification_json(verdicts) == (
        ROOT / "derivations" / "study_algebra.verification.json").read_text()


def test_second_derive_changes_nothing(tmp_path):
    for folder in ("generated", "derivations"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    out = subprocess.run([sys.executable, "-m", "bonered_alg.cli", "derive", "--root",
                          str(tmp_path)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    for name in (*REGISTRY, "study_algebra"):
        assert f"{name}: up to date" in out.stdout
    after = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert after == before


def _edit(path):
    path.write_text(path.read_text() + "\n# changed\n")


def test_hash_covers_what_produces_the_mechanism_and_nothing_else(tmp_path):
    pkg = tmp_path / "bonered_alg"
    shutil.copytree(ROOT / "bonered_alg", pkg, ignore=shutil.ignore_patterns("__pycache__"))

    def hashes():
        return {n: derivation_hash(MECHANISMS[n], GENERATOR, pkg) for n in REGISTRY}

    h0 = hashes()
    assert len(set(h0.values())) == len(h0)
    # registering a mechanism (and adding its module) re-derives no other one
    (pkg / "mechanisms" / "other.py").write_text("X = 1\n")
    _edit(pkg / "registry.py")
    assert hashes() == h0
    # a mechanism's own declaration, paper checks and studies shape only that mechanism
    for rel, name in (("mechanisms/stewart.py", "stewart"),
                      ("papers/p000_planar_tripod.py", "planar_tripod"),
                      ("studies/rcm_paths_004.py", "pro_hep_lct"),
                      ("surgical/pro_hep_lct_tool.py", "pro_hep_lct"),
                      ("analyses/parasitic.py", None)):
        before = hashes()
        _edit(pkg / rel)
        after = hashes()
        changed = {n for n in REGISTRY if after[n] != before[n]}
        if name is None:  # the parasitic analysis: both tripod mechanisms use it
            assert changed == {"planar_tripod", "tripod_planar"}, rel
        else:
            assert changed == {name}, rel
    # the shared engine shapes everything; the workspace tool only the mechanisms whose
    # studies use it (002's workspace study); the command line nothing
    before = hashes()
    _edit(pkg / "workspace" / "scan.py")
    after = hashes()
    assert {n for n in REGISTRY if after[n] != before[n]} == {"urrh_rcm"}
    before = after
    _edit(pkg / "cli.py")
    assert hashes() == before
    _edit(pkg / "algebra" / "convention.py")
    after = hashes()
    assert all(after[n] != before[n] for n in REGISTRY)


def test_missing_engine_leaves_outputs_untouched(tmp_path, monkeypatch):
    """An engine that is not installed (and no cached result) stops before any write."""
    from bonered_alg.elimination.engines import SingularEngine
    from bonered_alg.errors import EngineUnavailableError
    from bonered_alg.pipeline.runner import derive_all

    monkeypatch.setenv("BONERED_CACHE_DIR", str(tmp_path / "empty-cache"))
    for folder in ("generated", "derivations"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(EngineUnavailableError, match="mechanism 'pro_hep_lct'.*singular"):
        derive_all(tmp_path, ["pro_hep_lct"], force=True,
                   engine=SingularEngine("no-such-singular"), log=lambda _: None)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


def test_parallel_derive_writes_the_committed_bytes(tmp_path):
    """derive_all in two worker processes (one mechanism each) writes what a serial run
    wrote: the committed outputs, byte for byte, and logs in registry order.  A study
    handed to it (``then``, as ``derive --comparison``) runs once, after the mechanism it
    needs; its error is raised after every derivation is written and logged."""
    from bonered_alg.pipeline.runner import derive_all

    names = ["pro_hep_lct", "lamina_milling"]
    for folder in ("generated", "derivations"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    shutil.copy(ROOT / "constraints.txt", tmp_path)  # derivations/toolchain.json hashes it
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    lines, calls = [], []

    def study():
        calls.append(sorted(line.split(":")[0] for line in lines))
        raise RuntimeError("the study failed")

    with pytest.raises(RuntimeError, match="the study failed"):
        derive_all(tmp_path, names, force=True, log=lines.append, jobs=2,
                   then=(["lamina_milling"], study))
    assert calls == [[]]  # once, before the derivations were logged (registry order)
    assert [line.split(":")[0] for line in lines] == names
    assert all(line.endswith("wrote nothing new") for line in lines), lines
    lines = []
    status = derive_all(tmp_path, names, force=True, log=lines.append, jobs=2)
    assert status == {n: "derived" for n in names}
    assert [line.split(":")[0] for line in lines] == names
    assert all(line.endswith("wrote nothing new") for line in lines), lines
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


def test_workers_get_the_longest_derivation_first(tmp_path, monkeypatch):
    """derive_all hands mechanisms to its workers longest first: the registry's estimates
    on a machine without a record, this machine's last times once recorded; a damaged
    record falls back to the estimates."""
    from bonered_alg.pipeline import runner
    from bonered_alg.registry import EXPECTED_SECONDS, REGISTRY

    monkeypatch.setenv("BONERED_CACHE_DIR", str(tmp_path / "cache" / "elimination"))
    by_estimate = sorted(REGISTRY, key=lambda n: -EXPECTED_SECONDS[n])
    assert runner.longest_first(list(REGISTRY)) == by_estimate
    assert runner.longest_first(["lamina_milling", "new_one", "urrh_rcm"]) == [
        "new_one", "urrh_rcm", "lamina_milling"]  # no estimate: first
    runner._record_seconds({"lamina_milling": 500.0})  # noqa: SLF001
    runner._record_seconds({"stewart": 1.0})  # noqa: SLF001
    order = runner.longest_first(list(REGISTRY))
    assert order[0] == "lamina_milling" and order[-1] == "stewart"
    (tmp_path / "cache" / "derive_seconds.json").write_text("{not json")
    assert runner.longest_first(list(REGISTRY)) == by_estimate
