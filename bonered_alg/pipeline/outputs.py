"""The files a derivation writes, rendered in memory first, then written atomically.

``generated/<name>.py`` (and ``.c``, its compiled fast path), ``derivations/<name>.tex``,
``derivations/<name>.verification.json``, ``derivations/<name>.algebra.json`` (the long
polynomials the report summarizes) and the studies' files beside the report. :func:`write`
writes nothing unless every file rendered, each through a temporary file and a rename, and
skips files whose bytes are unchanged.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from pathlib import Path

from ..fileio import atomic_write_bytes, atomic_write_text
from .results import Record


def verification_json(verdicts) -> str:
    """The machine-readable record of the verdicts (DESIGN.md section 5)."""
    return json.dumps([v.as_json() for v in verdicts], indent=2, sort_keys=True) + "\n"


def files(record: Record) -> dict[str, str | bytes]:
    """Relative path -> content of every output of ``record``."""
    from ..report.algebra_record import algebra_json
    from ..report.latex_report import render_report

    name = record.derivation.mechanism.name
    out: dict[str, str | bytes] = {
        f"generated/{name}.py": record.generated.source,
        f"generated/{name}.c": record.generated.c_source,
        f"derivations/{name}.tex": render_report(record),
        f"derivations/{name}.verification.json": verification_json(record.verification),
        f"derivations/{name}.algebra.json": algebra_json(record.derivation),
    }
    for study in record.studies.values():
        for rel, content in study.files.items():
            path = f"derivations/{rel}"
            if path in out:
                raise ValueError(f"{name}: two outputs write {path}")
            out[path] = content
    return out


def write(outputs: Mapping[str, str | bytes], root: Path) -> list[Path]:
    """Write ``outputs`` under ``root`` atomically; returns the files that changed."""
    changed = []
    for rel, content in outputs.items():
        path = root / rel
        writer = atomic_write_bytes if isinstance(content, bytes) else atomic_write_text
        if writer(path, content):
            changed.append(path)
    return changed


_HASH_RE = re.compile(r"^DERIVATION_HASH = '([0-9a-f]{64})'$", re.M)


def recorded_hash(root: Path, name: str) -> str | None:
    """The derivation hash recorded in ``generated/<name>.py`` and the report, if they agree
    and the verification record exists."""
    gen = root / "generated" / f"{name}.py"
    tex = root / "derivations" / f"{name}.tex"
    js = root / "derivations" / f"{name}.verification.json"
    if not (gen.is_file() and tex.is_file() and js.is_file()):
        return None
    m = _HASH_RE.search(gen.read_text())
    if not m or m.group(1) not in tex.read_text():
        return None
    return m.group(1)
