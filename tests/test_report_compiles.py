"""The derivation report compiles with a real LaTeX toolchain (pdflatex via latexmk)."""

import shutil
import subprocess

import pytest

from tests.conftest import ROOT


@pytest.mark.skipif(shutil.which("latexmk") is None, reason="no LaTeX toolchain")
def test_report_compiles(tmp_path):
    shutil.copy(ROOT / "derivations" / "pro_hep_lct.tex", tmp_path)
    out = subprocess.run(["latexmk", "-pdf", "-interaction=nonstopmode", "-halt-on-error",
                          "pro_hep_lct.tex"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0, out.stdout[-3000:]
    assert (tmp_path / "pro_hep_lct.pdf").stat().st_size > 10_000
    log = (tmp_path / "pro_hep_lct.log").read_text(errors="replace")
    assert "Undefined control sequence" not in log
