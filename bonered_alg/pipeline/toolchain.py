"""The tools the committed outputs were derived with: the Groebner engine and its version,
and the pinned Python packages (``constraints.txt``), recorded in
``derivations/toolchain.json`` by every derivation that writes outputs.

The derivation hash covers the project's sources only; the engine's version is recorded here
instead, so that a machine with another Singular sees it (``tests/test_outputs_current.py``)
rather than silently reproducing, or not, the committed Groebner bases.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

from ..elimination.engines import Engine
from ..fileio import atomic_write_text

RECORD = Path("derivations") / "toolchain.json"
CONSTRAINTS = Path("constraints.txt")


def engine_version(engine: Engine) -> str:
    """The engine and its release (``singular 4.3.1``), without build dates or paths."""
    text = engine.version()
    found = re.search(r"version\s+(\d+(?:\.\d+)+)", text)
    if engine.name == "singular":
        return f"singular {found.group(1) if found else 'unknown'}"
    return text


def current(root: Path, engine: Engine) -> dict[str, str]:
    """The record for this machine."""
    constraints = root / CONSTRAINTS
    digest = (hashlib.sha256(constraints.read_bytes()).hexdigest()
              if constraints.exists() else "none")
    return {"groebner_engine": engine_version(engine),
            "python_constraints_sha256": digest}


def recorded(root: Path) -> dict[str, str] | None:
    path = root / RECORD
    return json.loads(path.read_text()) if path.exists() else None


def write(root: Path, engine: Engine) -> bool:
    """Write this machine's record (atomically; True when the file changed)."""
    return atomic_write_text(root / RECORD,
                             json.dumps(current(root, engine), indent=1, sort_keys=True) + "\n")
