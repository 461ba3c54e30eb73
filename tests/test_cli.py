"""The command line a new user meets first (issue 14, item 4): --version, info, and names
checked before any work starts."""

import subprocess
import sys

import pytest

from bonered_alg import cli
from bonered_alg.registry import REGISTRY


def test_version():
    out = subprocess.run([sys.executable, "-m", "bonered_alg.cli", "--version"],
                         capture_output=True, text=True)
    assert out.returncode == 0
    assert out.stdout.startswith("bonered_alg ") and out.stdout.split()[1][0].isdigit()


@pytest.mark.parametrize("command", ["derive", "info", "report"])
def test_unknown_mechanism_is_one_line_and_exit_2(command, capsys, monkeypatch):
    from bonered_alg.pipeline import runner

    def no_work(*args, **kwargs):
        raise AssertionError("work started before the names were checked")

    monkeypatch.setattr(runner, "derive_all", no_work)
    assert cli.main([command, "nosuch"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "'nosuch'" in err
    assert all(name in err for name in REGISTRY)


def test_derive_jobs_must_be_positive(capsys, monkeypatch):
    from bonered_alg.pipeline import runner

    def no_work(*args, **kwargs):
        raise AssertionError("work started before --jobs was checked")

    monkeypatch.setattr(runner, "derive_all", no_work)
    assert cli.main(["derive", "--jobs", "0"]) == 2
    assert "--jobs must be a positive integer, got 0" in capsys.readouterr().err


def test_derive_comparison_hands_the_study_to_the_runner(capsys, monkeypatch, tmp_path):
    """derive --comparison gives the runner the comparison study and the three mechanisms
    it scans (forced with --force); its ValueError is reported as the comparison command
    reports it, exit 2."""
    from bonered_alg.pipeline import runner
    from bonered_alg.studies import comparison_report

    seen = {}

    def fake_derive_all(root, names, force, engine, progress=None, jobs=None, then=None):
        seen.update(force=force, needs=tuple(then[0]))
        then[1]()

    def fake_write(root, workers, force, progress):
        seen["comparison_force"] = force
        raise ValueError("no generated module for mechanism 'stewart'")

    monkeypatch.setattr(runner, "derive_all", fake_derive_all)
    monkeypatch.setattr(comparison_report, "write", fake_write)
    assert cli.main(["derive", "--force", "--comparison", "--root", str(tmp_path)]) == 2
    assert seen == {"force": True, "needs": comparison_report.MECHANISMS,
                    "comparison_force": True}
    err = capsys.readouterr().err
    assert "bonered-alg comparison: error: no generated module for mechanism 'stewart'" in err


def test_info_describes_the_generated_module(capsys):
    from bonered_alg.generated import planar_tripod as m

    assert cli.main(["info", "planar_tripod"]) == 0
    text = capsys.readouterr().out
    for joint in m.JOINTS:
        assert joint in text
    assert f"IK modes    {m.MODES}" in text
    for code, meaning in m.STATUS.items():
        assert f"{code:2d} {meaning}" in text
    assert "jacobian" in text and "ik_status" in text
    assert "fast path   compiled (" in text and ".so)" in text
    assert f"per pose    ik {m.FUNCTION_OPERATIONS['ik']} operations" in text


def test_default_root_is_the_project_not_the_current_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    root = cli.default_root()
    assert (root / "pyproject.toml").is_file() and (root / "bonered_alg" / "cli.py").is_file()
