"""The derivation reports compile with a real LaTeX toolchain (pdflatex via latexmk)."""

import shutil
import subprocess

import pytest
from conftest import ROOT

from bonered_alg.registry import REGISTRY
from bonered_alg.report.layout_check import layout_problems


@pytest.mark.skipif(shutil.which("latexmk") is None, reason="no LaTeX toolchain")
@pytest.mark.parametrize("name", [*REGISTRY, "study_algebra", "bone_reduction_workspace"])
def test_report_compiles(tmp_path, name):
    for f in (ROOT / "derivations").glob("*"):
        if f.name == f"{name}.tex" or f.suffix == ".png":
            shutil.copy(f, tmp_path)
    out = subprocess.run(["latexmk", "-pdf", "-interaction=nonstopmode", "-halt-on-error",
                          f"{name}.tex"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0, out.stdout[-3000:]
    assert (tmp_path / f"{name}.pdf").stat().st_size > 10_000
    log = (tmp_path / f"{name}.log").read_text(errors="replace")
    assert "Undefined control sequence" not in log
    # issue 14: nothing runs off the page by more than 10 pt, at most 40 pages
    assert layout_problems(log, name) == []
