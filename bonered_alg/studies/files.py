"""Deterministic tables and plots: the same bytes on every machine.

Numbers are printed at a stated resolution (significant digits, or an absolute step where a
value is a residual whose last digits are floating-point noise), and a value that prints as
zero never keeps a sign (``-0``), so the bytes do not depend on the machine's floating-point
path.  Figures are PNG without a software stamp.
"""

from __future__ import annotations

import io
from collections.abc import Sequence


def number(value: float, fmt: str = ".10g") -> str:
    """``value`` formatted with ``fmt``; ``-0`` (of any precision) printed as ``0``."""
    text = format(float(value), fmt)
    if text.startswith("-") and float(text) == 0.0:
        text = text[1:]
    return text


def csv_text(header: Sequence[str], rows, fmt: str | Sequence[str] = ".10g") -> str:
    """CSV with ``\\n`` line ends; ``fmt`` one format for all columns or one per column."""
    fmts = [fmt] * len(header) if isinstance(fmt, str) else list(fmt)
    lines = [",".join(header)]
    for row in rows:
        lines.append(",".join(v if isinstance(v, str) else number(v, f)
                              for v, f in zip(row, fmts)))
    return "\n".join(lines) + "\n"


def png(fig, dpi: int = 110) -> bytes:
    """The figure as PNG bytes (no software stamp), then closed."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
