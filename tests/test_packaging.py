"""The package list of pyproject.toml names every subpackage (a non-editable install once
lacked ``bonered_alg.surgical`` and the README's Pro-Hep-LCT example failed)."""

import sys

import pytest
from conftest import ROOT


@pytest.mark.skipif(sys.version_info < (3, 11), reason="tomllib is Python 3.11+")
def test_every_subpackage_is_packaged():
    import tomllib

    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    found = {".".join(p.parent.relative_to(ROOT).parts)
             for p in (ROOT / "bonered_alg").rglob("__init__.py")}
    found.add("bonered_alg.generated")
    assert listed == found, (sorted(found - listed), sorted(listed - found))
    assert config["package-dir"]["bonered_alg.generated"] == "generated"
    assert (ROOT / "generated" / "__init__.py").is_file()
    assert "templates/*.j2" in config["package-data"]["bonered_alg.codegen"]
