"""What produced a mechanism's outputs: the source files its derivation imports.

The derivation hash of a mechanism is the SHA-256 of the generator's version and of every
package module that the derivation of *that* mechanism can execute: the pipeline's stages
and the modules they import, the mechanism's declaration, the checks and studies it names
(by module path), and whatever those import -- the import graph read with ``ast``, function-
level imports included, nothing imported.  So editing one mechanism, its paper checks or a
study re-derives that mechanism only, registering a new mechanism re-derives nothing else,
and an edit of the shared engine re-derives everything.  The Groebner engine program is not
part of it: both engines return the same normalized bases (``tests/test_engines_agree.py``).
"""

from __future__ import annotations

import ast
import hashlib
from functools import lru_cache
from pathlib import Path

PACKAGE = "bonered_alg"
PACKAGE_DIR = Path(__file__).resolve().parents[1]
# the modules every derivation runs (the roots of the import closure)
CORE = ("bonered_alg.pipeline.stages", "bonered_alg.pipeline.outputs",
        "bonered_alg.pipeline.results")


def _module_name(path: Path, package_dir: Path) -> str:
    rel = path.relative_to(package_dir).with_suffix("")
    parts = [PACKAGE, *rel.parts]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(module: str, is_package: bool, level: int, target: str | None) -> str:
    """The absolute module name of ``from <level dots><target> import ...``."""
    if level == 0:
        return target or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (level - 1)] if level > 1 else base
    return ".".join(base + ([target] if target else []))


@lru_cache(maxsize=8)
def module_files(package_dir: Path = PACKAGE_DIR) -> dict[str, Path]:
    """Module name -> file of every module of the package."""
    return {_module_name(p, package_dir): p for p in sorted(package_dir.rglob("*.py"))
            if "__pycache__" not in p.parts}


def imports(name: str, files: dict[str, Path]) -> set[str]:
    """Package modules that module ``name`` imports (anywhere in its body), and the
    modules named by string constants in it (the declarations' ``checks``/``studies``)."""
    path = files[name]
    return {m for m in _named_in(name, path.name == "__init__.py", path.read_text())
            if m in files}


@lru_cache(maxsize=4096)
def _named_in(name: str, is_package: bool, text: str) -> frozenset[str]:
    """Every module name imported or named in the source ``text`` of module ``name`` (parsed
    once per text: hashing the same tree again reads the files but parses nothing)."""
    tree = ast.parse(text, filename=name)
    out: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(name, is_package, node.level, node.module)
            out.add(base)
            out |= {f"{base}.{a.name}" for a in node.names}
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and node.value.startswith(PACKAGE + "."):
            out.add(node.value)
    return frozenset(out)


def closure(roots, files: dict[str, Path]) -> set[str]:
    """Every module reachable from ``roots`` by imports, with the packages containing them
    (importing a module runs its packages' ``__init__``)."""
    seen: set[str] = set()
    todo = [r for r in roots if r in files]
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        parts = m.split(".")
        parents = {".".join(parts[:k]) for k in range(1, len(parts))}
        todo.extend(p for p in parents | imports(m, files) if p in files and p not in seen)
    return seen


def derivation_hash(module: str, generator: str, package_dir: Path = PACKAGE_DIR,
                    extra_roots: tuple[str, ...] = CORE, module_file: Path | None = None) -> str:
    """The hash of everything that produces the outputs of the declaration ``module``
    (a module path; ``module_file`` for a declaration outside the package)."""
    files = module_files(package_dir)
    roots = list(extra_roots)
    h = hashlib.sha256(f"{generator}\n".encode())
    if module_file is not None and module not in files:
        text = Path(module_file).read_bytes()
        h.update(b"external\0" + text + b"\0")
        tree = ast.parse(text)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                roots.append(node.module)
            elif isinstance(node, ast.Import):
                roots += [a.name for a in node.names]
            elif isinstance(node, ast.Constant) and isinstance(node.value, str):
                roots.append(node.value)
    else:
        roots.append(module)
    paths = [files[name] for name in sorted(closure(roots, files))]
    paths += sorted((package_dir / "codegen" / "templates").glob("*.j2"))  # module text
    for path in paths:
        rel = path.relative_to(package_dir).as_posix()
        h.update(rel.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()
