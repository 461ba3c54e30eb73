"""The README's Python examples run, in order, as written."""

import re

import numpy as np
from conftest import ROOT, bind_derive, record_of

from bonered_alg.pipeline import runner


def test_readme_examples_run(monkeypatch):
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 4
    monkeypatch.chdir(ROOT)
    # the README derives the worked example: share the session's derivation of it
    bind_derive()  # the runner's own derive, for record_of, before it is patched
    monkeypatch.setattr(runner, "derive", record_of)
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)  # noqa: S102 - our README
    # the first example's results are what the README says they are
    m = namespace["m"]
    assert namespace["q"].shape[-1] == 6 and m.MODES == 8
    assert np.isfinite(namespace["everything"]).any()
    assert namespace["res"].count > 0
    assert namespace["g"].MODES == 8


def test_readme_documents_every_status_code():
    """The README's table of status codes lists each code of the runtime under its name."""
    from bonered_alg.runtime import status as st

    text = (ROOT / "README.md").read_text()
    names = {v: k for k, v in vars(st).items() if k.isupper() and isinstance(v, int)
             and k not in ("DISC_RTOL", "DET_RTOL")}
    rows = dict(re.findall(r"^\| (\d+) \| `([A-Z_]+)` \|", text, flags=re.M))
    assert {int(c): n for c, n in rows.items()} == {c: names[c] for c in st.STATUS}
