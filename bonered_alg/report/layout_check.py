"""The layout targets of a compiled report, read from its pdflatex log: no box wider than the
page by more than :data:`MAX_OVERFULL_PT`, at most :data:`MAX_PAGES` pages, no bitmap
(Type 3) font (``make report`` and ``tests/test_report_compiles.py`` fail on worse).

    python -m bonered_alg.report.layout_check derivations/*.log
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

MAX_OVERFULL_PT = 10.0
MAX_PAGES = 40

_OVERFULL = re.compile(r"Overfull \\hbox \(([\d.]+)pt too wide\) (.*)")
_PAGES = re.compile(r"Output written on .*? \((\d+) pages?")
# a bitmap font embedded by pdflatex (it becomes a Type 3 font in the PDF): <.../name.600pk>
_BITMAP = re.compile(r"([A-Za-z0-9_-]+)\.\d+pk>")


def layout_problems(log: str, name: str = "report") -> list[str]:
    """One line per overfull box wider than the limit, and one if there are too many pages."""
    problems = [f"{name}: a box {float(w):.0f} pt too wide {where.strip()}"
                for w, where in _OVERFULL.findall(log) if float(w) > MAX_OVERFULL_PT]
    m = _PAGES.search(log)
    if m is None:
        problems.append(f"{name}: the log names no output file (did it compile?)")
    elif int(m.group(1)) > MAX_PAGES:
        problems.append(f"{name}: {m.group(1)} pages, more than {MAX_PAGES}")
    problems += [f"{name}: bitmap (Type 3) font {font}: a glyph of an encoding without "
                 "Type 1 fonts here (TS1 text symbols: write them as math)"
                 for font in sorted(set(_BITMAP.findall(log.replace("\n", ""))))]
    return problems


def main(argv: list[str]) -> int:
    problems = []
    for path in map(Path, argv):
        problems += layout_problems(path.read_text(errors="replace"), path.stem)
    for p in problems:
        print(p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
