"""Command line: ``bonered-alg derive [NAMES] [--force] [--engine E]`` and friends."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .errors import BoneredError


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonered-alg", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("derive", help="derive mechanisms and write generated/ and derivations/")
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--force", action="store_true", help="re-derive even if up to date")
    p.add_argument("--engine", choices=["singular", "sympy"], help="Groebner engine")
    p.add_argument("--root", type=Path, default=Path("."), help="project root")
    sub.add_parser("list", help="list the mechanisms")
    args = parser.parse_args(argv)
    from .mechanisms import REGISTRY

    if args.command == "list":
        print("\n".join(REGISTRY))
        return 0
    from .elimination.engines import get_engine
    from .pipeline import derive_all

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
