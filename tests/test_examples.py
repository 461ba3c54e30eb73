"""The scripts in examples/ run as a user runs them, and give what they say (issue 14)."""

import runpy
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


def test_there_are_examples():
    assert {p.stem for p in EXAMPLES} >= {"workspace_study", "trajectory_continuous_mode",
                                          "rcm_manipulation"}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs_as_a_script(path):
    out = subprocess.run([sys.executable, str(path)], capture_output=True, text=True,
                         cwd=ROOT, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip()


def _main(name):
    return runpy.run_path(str(ROOT / "examples" / f"{name}.py"))["main"]()


def test_workspace_example_explains_the_edge():
    r = _main("workspace_study")
    assert r["result"].count > 0
    assert "above its upper limit" in __import__(
        "bonered_alg.generated.tripod_planar", fromlist=["x"]).ik_explain(r["beyond"])


def test_trajectory_example_stays_continuous():
    r = _main("trajectory_continuous_mode")
    assert np.isfinite(r["joints"]).all()
    assert np.abs(np.diff(r["joints"], axis=0)).max() < 0.01  # no jump between branches


def test_rcm_example_returns_through_the_entry_point():
    r = _main("rcm_manipulation")
    assert (r["status"] == 0).all() and r["fk_error"].max() < 1e-9
