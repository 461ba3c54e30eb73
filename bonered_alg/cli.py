"""Command line: ``bonered-alg derive [NAMES] [--force] [--engine E]`` and friends
(``list``, ``info``, ``workspace``, ``comparison``, ``report``, ``--version``)."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from .errors import BoneredError


def _workspace_parser(sub) -> None:
    w = sub.add_parser(
        "workspace", help="scan a mechanism's workspace: summary and points (CSV), plots",
        description="Scan the workspace of a generated mechanism on a grid. Example: "
                    "bonered-alg workspace stewart --axis x=-100:100:2 --axis y=-100:100:2 "
                    "--fix z=210 --fix alpha=0 --fix beta=0 --fix gamma=0")
    w.add_argument("mechanism")
    w.add_argument("--axis", action="append", default=[], metavar="NAME=LO:HI:STEP",
                   help="a scanned pose coordinate (mm; deg for angles); repeat")
    w.add_argument("--fix", action="append", default=[], metavar="NAME=VALUE",
                   help="a fixed pose coordinate (mm; deg for angles); repeat")
    w.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="a geometric parameter of the generated module (mm)")
    w.add_argument("--limit", action="append", default=[], metavar="PATTERN=LO:HI",
                   help="override LIMITS entries matching PATTERN (mm; deg for joint "
                        "angles), e.g. 'q*=175:250' or 'phi_s*=-20:20'")
    w.add_argument("--mode", action="append", type=int, default=[],
                   help="working mode(s) allowed (default 0)")
    w.add_argument("--min-margin", type=float, default=0.0,
                   help="exclude poses closer to a singularity (inverse condition number)")
    w.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    w.add_argument("--dask", default=None, metavar="local|ADDRESS",
                   help="run the chunks on a dask cluster: 'local' or a scheduler address")
    w.add_argument("--chunk", type=int, default=None,
                   help="samples per chunk (default: 8192, 32768 with the compiled fast path)")
    w.add_argument("--out", type=Path, default=Path("workspace_out"), help="output folder")
    w.add_argument("--no-progress", action="store_true", help="no progress bar")


def default_root() -> Path:
    """The project the package was installed from (an editable install: the folder holding
    ``pyproject.toml`` above the package), else the current directory."""
    here = Path(__file__).resolve().parents[1]
    return here if (here / "pyproject.toml").is_file() and (here / "bonered_alg").is_dir() \
        else Path(".").resolve()


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("bonered_alg")
    except PackageNotFoundError:  # run from a source tree that is not installed
        return "unknown (not installed)"


def info(name: str) -> str:
    """What the generated module of ``name`` offers: its pose, joints, modes, parameters,
    functions and status codes."""
    import importlib

    module = importlib.import_module(f"bonered_alg.generated.{name}")
    units = dict(zip(module.POSE, module.POSE_UNITS))
    lines = [f"{module.MECHANISM}: {module.SOURCE}",
             f"  module      bonered_alg.generated.{name} (derivation "
             f"{module.DERIVATION_HASH[:12]}, {module.OPERATION_COUNT} operations)",
             "  pose        " + ", ".join(f"{c} [{units[c]}]" for c in module.POSE),
             "  joints      " + ", ".join(f"{q} [{u}]" for q, u in
                                         zip(module.JOINTS, module.JOINT_UNITS)),
             f"  IK modes    {module.MODES} (bits: " + ", ".join(
                 f"{q}: bit {b}" for q, b in module.MODE_BITS) + ")",
             "  FK modes    " + (str(getattr(module, "FK_MODES", 0) or "none generated"))
             + (f" ({module.FK_NOTE})" if getattr(module, "FK_NOTE", "") else ""),
             "  parameters  " + ", ".join(
                 f"{k} = {v:g} {module.PARAMETER_UNITS.get(k, '').strip('1 ')}".rstrip()
                 for k, v in module.PARAMETERS.items()),
             "  limits      " + (", ".join(str(lim[0]) for lim in module.LIMITS)
                                 if getattr(module, "LIMITS", ()) else "none declared"),
             "  fast path   " + _fast_path_state(module),
             "  per pose    " + ", ".join(f"{f} {n} operations" for f, n in getattr(
                 module, "FUNCTION_OPERATIONS", {}).items()),
             "  functions   " + ", ".join(sorted(
                 n for n, v in vars(module).items() if callable(v) and not n.startswith("_")
                 and getattr(v, "__module__", None) == module.__name__)),
             "  status codes"]
    lines += [f"    {code:2d} {text}" for code, text in sorted(module.STATUS.items())]
    return "\n".join(line for line in lines if line)


def _fast_path_state(module) -> str:
    """Whether the module's compiled fast path is built (and where), or why not."""
    fast = getattr(getattr(module, "_MODEL", None), "fast", None)
    if fast is None:
        return "not available (no generated .c beside the module)"
    lib = fast.library()
    if lib is None:
        return f"not available: {fast.reason}"
    return f"compiled ({getattr(lib, '_name', 'loaded')})"


def report(root: Path, names: list[str]) -> int:
    """Compile ``derivations/<name>.tex`` to PDF and check the layout targets."""
    import shutil
    import subprocess

    from .report.layout_check import layout_problems

    if shutil.which("latexmk") is None:
        print("bonered-alg report: error: latexmk is not installed (Debian: apt-get install "
              "latexmk texlive-latex-base texlive-latex-recommended, or run make report)",
              file=sys.stderr)
        return 2
    folder = root / "derivations"
    problems = []
    for name in names:
        tex = folder / f"{name}.tex"
        run = subprocess.run(["latexmk", "-pdf", "-interaction=nonstopmode", "-halt-on-error",
                              "-quiet", tex.name], cwd=folder, capture_output=True, text=True,
                             env={**os.environ, "SOURCE_DATE_EPOCH": "0"})
        if run.returncode != 0:
            problems.append(f"{name}: pdflatex failed (see derivations/{name}.log)")
            continue
        problems += layout_problems((folder / f"{name}.log").read_text(errors="replace"), name)
        print(f"{name}: derivations/{name}.pdf", flush=True)
    for line in problems:
        print(f"bonered-alg report: {line}", file=sys.stderr)
    return 1 if problems else 0


def _names(given: list[str], known: tuple[str, ...], command: str,
           extra: tuple[str, ...] = ()) -> list[str]:
    """``given`` checked against ``known`` before any work starts."""
    unknown = [n for n in given if n not in known + extra]
    if unknown:
        raise BoneredError(f"{command}: unknown mechanism {', '.join(map(repr, unknown))}; "
                           f"known: {', '.join(known + extra)}")
    return list(given)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonered-alg", description=__doc__)
    parser.add_argument("--version", action="version", version=f"bonered_alg {_version()}")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("derive", help="derive mechanisms and write generated/ and derivations/")
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--force", action="store_true", help="re-derive even if up to date")
    p.add_argument("--engine", choices=["singular", "sympy"], help="Groebner engine")
    p.add_argument("--root", type=Path, default=None,
                   help="project root (default: the project the package was installed from)")
    p.add_argument("--quiet", action="store_true", help="no per-stage progress")
    p.add_argument("--jobs", type=int, default=None,
                   help="worker processes, one mechanism each (default: $BONERED_ALG_JOBS, "
                   "else all cores; 1: in this process)")
    p.add_argument("--comparison", action="store_true",
                   help="also the comparison study (as `comparison`, forced with --force), "
                   "started as soon as the mechanisms it scans are derived")
    sub.add_parser("list", help="list the mechanisms")
    i = sub.add_parser("info", help="what a generated module offers (pose, joints, modes, "
                       "parameters, functions, status codes)")
    i.add_argument("mechanism")
    r = sub.add_parser("report", help="compile the derivation reports to PDF (latexmk) and "
                       "check that nothing runs off the page")
    r.add_argument("names", nargs="*", help="reports (default: all)")
    r.add_argument("--root", type=Path, default=None, help="project root")
    _workspace_parser(sub)
    c = sub.add_parser("comparison", help="the papers' workspace comparison (000 Table 2, "
                       "001 Table 1): tables and plots in derivations/")
    c.add_argument("--force", action="store_true", help="recompute even if up to date")
    c.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    c.add_argument("--root", type=Path, default=None, help="project root")
    c.add_argument("--quiet", action="store_true", help="no progress per part")
    args = parser.parse_args(argv)
    from .registry import REGISTRY

    if getattr(args, "root", None) is None and args.command in ("derive", "report",
                                                                  "comparison"):
        args.root = default_root()
    if args.command in ("derive", "comparison"):
        # committed outputs come from the numpy runtime, the reference, on every machine
        # (the compiled fast path agrees to rounding, not to the bit)
        os.environ["BONERED_ALG_FAST"] = "0"
    if args.command == "list":
        print("\n".join(REGISTRY))
        return 0
    try:
        if args.command == "info":
            _names([args.mechanism], REGISTRY, "info")
            print(info(args.mechanism))
            return 0
        if args.command == "report":
            reports = ("study_algebra", "bone_reduction_workspace")
            names = _names(args.names, REGISTRY, "report", reports) or [*REGISTRY, *reports]
            return report(Path(args.root).resolve(), names)
        if args.command == "derive":
            _names(args.names, REGISTRY, "derive")
            if args.jobs is not None and args.jobs < 1:
                print(f"bonered-alg derive: error: --jobs must be a positive integer, got "
                      f"{args.jobs}", file=sys.stderr)
                return 2
    except BoneredError as exc:
        print(f"bonered-alg: error: {exc}", file=sys.stderr)
        return 2
    if args.command in ("workspace", "comparison"):
        try:
            if args.command == "workspace":
                from .workspace import command

                return command.workspace(args)
            _comparison(Path(args.root).resolve(), args.workers, args.force, args.quiet)
            return 0
        except ValueError as exc:
            print(f"bonered-alg {args.command}: error: {exc}", file=sys.stderr)
            return 2
    from .elimination.engines import get_engine
    from .pipeline.runner import derive_all

    try:
        engine = get_engine(args.engine)
        print(f"Groebner engine: {engine.name}", flush=True)
        then = None
        if args.comparison:
            from .studies.comparison_report import MECHANISMS

            root = args.root.resolve()

            def comparison() -> None:
                try:
                    _comparison(root, None, args.force, args.quiet)
                except ValueError as exc:  # reported as the comparison command reports it
                    raise _ComparisonFailed(str(exc)) from exc

            then = (MECHANISMS, comparison)
        derive_all(args.root.resolve(), args.names or None, args.force, engine,
                   progress=None if args.quiet else print, jobs=args.jobs, then=then)
    except (BoneredError, KeyError, NotImplementedError) as exc:
        print(f"bonered-alg: error: {exc}", file=sys.stderr)
        return 2
    except _ComparisonFailed as exc:
        print(f"bonered-alg comparison: error: {exc}", file=sys.stderr)
        return 2
    return 0


class _ComparisonFailed(Exception):
    """A ValueError of the comparison run by ``derive --comparison``."""


def _comparison(root: Path, workers: int | None, force: bool, quiet: bool) -> None:
    """The comparison study written (unless up to date) and what was written printed."""
    from .studies.comparison_report import write

    written = write(root, workers, force, None if quiet else print)
    print("comparison: " + (", ".join(p.name for p in written) if written
                            else "up to date"), flush=True)


if __name__ == "__main__":
    sys.exit(main())
