#!/usr/bin/env bash
# Builds the wheel, installs it into a clean virtual environment (not editable, outside the
# work tree) and imports every subpackage and generated module from there.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
.venv/bin/python -m pip wheel -q --no-deps -w "$tmp/wheel" .
$PY -m venv "$tmp/venv"
"$tmp/venv/bin/python" -m pip install -q "$tmp"/wheel/*.whl
cd "$tmp"
BONERED_ALG_CACHE="$tmp/cache" "$tmp/venv/bin/python" - <<'PY'
import importlib, pkgutil, sys
import bonered_alg
names = sorted(m.name for m in pkgutil.walk_packages(bonered_alg.__path__, "bonered_alg."))
assert "bonered_alg.generated.pro_hep_lct" in names and "bonered_alg.surgical.pro_hep_lct_tool" in names, names
for name in names:
    importlib.import_module(name)
assert not any(p.startswith("/work") for p in bonered_alg.__path__), bonered_alg.__path__
from bonered_alg.generated import planar_tripod as m
print(f"wheel: {len(names)} modules import from {bonered_alg.__path__[0]}; ik at home:",
      m.ik([0.0, 0.0, 200.0, 0.0, 0.0, 0.0]).round(3).tolist())
# the compiled fast path builds from the installed wheel's C files (package data)
assert m._MODEL.fast.library() is not None, m._MODEL.fast.reason
assert abs(m.ik([0.0, 0.0, 200.0, 0.0, 0.0, 0.0], fast=True)
           - m.ik([0.0, 0.0, 200.0, 0.0, 0.0, 0.0], fast=False)).max() < 1e-9
print("wheel: compiled fast path", m._MODEL.fast.library()._name)
PY
