"""Command line: ``bonered-alg derive [NAMES] [--force] [--engine E]`` and friends."""

from __future__ import annotations

import argparse
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
    w.add_argument("--chunk", type=int, default=1 << 13, help="samples per chunk")
    w.add_argument("--out", type=Path, default=Path("workspace_out"), help="output folder")
    w.add_argument("--no-progress", action="store_true", help="no progress bar")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonered-alg", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("derive", help="derive mechanisms and write generated/ and derivations/")
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--force", action="store_true", help="re-derive even if up to date")
    p.add_argument("--engine", choices=["singular", "sympy"], help="Groebner engine")
    p.add_argument("--root", type=Path, default=Path("."), help="project root")
    sub.add_parser("list", help="list the mechanisms")
    _workspace_parser(sub)
    c = sub.add_parser("comparison", help="the papers' workspace comparison (000 Table 2, "
                       "001 Table 1): tables and plots in derivations/")
    c.add_argument("--force", action="store_true", help="recompute even if up to date")
    c.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    c.add_argument("--root", type=Path, default=Path("."), help="project root")
    args = parser.parse_args(argv)
    from .registry import REGISTRY

    if args.command == "list":
        print("\n".join(REGISTRY))
        return 0
    if args.command in ("workspace", "comparison"):
        try:
            if args.command == "workspace":
                from .workspace import command

                return command.workspace(args)
            from .studies.comparison_report import write

            written = write(Path(args.root).resolve(), args.workers, args.force)
            print("comparison: " + (", ".join(p.name for p in written) if written
                                    else "up to date"))
            return 0
        except ValueError as exc:
            print(f"bonered-alg {args.command}: error: {exc}", file=sys.stderr)
            return 2
    from .elimination.engines import get_engine
    from .pipeline.runner import derive_all

    try:
        engine = get_engine(args.engine)
        print(f"Groebner engine: {engine.name}", flush=True)
        derive_all(args.root.resolve(), args.names or None, args.force, engine)
    except (BoneredError, KeyError, NotImplementedError) as exc:
        print(f"bonered-alg: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
