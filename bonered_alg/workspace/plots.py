"""Workspace plots (matplotlib, Agg): projections of scanned reachable sets, overlaid as in
000 Figs. 10-11 and 001 Figs. 9-10 (hybrid red, Stewart blue), written as PNG and PDF
byte for byte deterministic (no dates or versions in the metadata) and atomically."""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..fileio import atomic_write_bytes  # noqa: E402
from .grid import user_unit, user_value  # noqa: E402
from .scan import ScanResult  # noqa: E402

COLOURS = {"stewart": "tab:blue"}  # any hybrid mechanism: tab:red

LABELS = {"alpha": "alpha", "beta": "beta", "gamma": "gamma"}


def projection(res: ScanResult, a: str, b: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mask projected on the axes ``a`` (rows) and ``b`` (columns): reachable for some
    value of the other axes; with the axes' sample values in user units."""
    names = [ax.name for ax in res.grid.axes]
    i, j = names.index(a), names.index(b)
    other = tuple(k for k in range(len(names)) if k not in (i, j))
    m = res.mask.any(axis=other) if other else res.mask
    if i > j:
        m = m.T
    va = np.array([user_value(a, v) for v in res.grid.axes[i].values()])
    vb = np.array([user_value(b, v) for v in res.grid.axes[j].values()])
    return m, va, vb


def _save(fig, stem: Path) -> list[Path]:
    out = []
    for ext, meta in (("png", {"Software": None}),
                      ("pdf", {"Creator": None, "Producer": None, "CreationDate": None})):
        buf = io.BytesIO()
        fig.savefig(buf, format=ext, dpi=120, metadata=meta)
        path = stem.with_suffix(f".{ext}")
        atomic_write_bytes(path, buf.getvalue())
        out.append(path)
    plt.close(fig)
    return out


def overlay(results: Sequence[ScanResult], a: str, b: str, title: str, stem: Path) -> list[Path]:
    """Filled outlines of each result's projection on (``b``, ``a``), one colour each."""
    with plt.rc_context({"svg.hashsalt": "bonered", "pdf.compression": 6}):
        fig, ax = plt.subplots(figsize=(5.2, 4.4))
        for res in results:
            m, va, vb = projection(res, a, b)
            colour = COLOURS.get(res.mechanism, "tab:red")
            if m.any():
                ax.contourf(vb, va, m.astype(float), levels=[0.5, 1.5], colors=[colour],
                            alpha=0.35)
                ax.contour(vb, va, m.astype(float), levels=[0.5], colors=[colour],
                           linewidths=1.2)
            ax.plot([], [], color=colour, label=res.mechanism)
        ax.set_xlabel(f"{LABELS.get(b, b)} ({user_unit(b)})")
        ax.set_ylabel(f"{LABELS.get(a, a)} ({user_unit(a)})")
        hidden = sorted({ax_.name for r in results for ax_ in r.grid.axes} - {a, b})
        ax.set_title(title + ("\nprojection: reachable for some " + ", ".join(hidden)
                              if hidden else ""), fontsize=9)
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(True, lw=0.3)
        fig.tight_layout()
        return _save(fig, stem)


def joint_paths(results: dict, stroke_ranges: dict, title: str, stem: Path) -> list[Path]:
    """One panel per result: the joints over time, stroke ranges dashed, samples outside
    the workspace marked."""
    with plt.rc_context({"svg.hashsalt": "bonered", "pdf.compression": 6}):
        fig, axes = plt.subplots(len(results), 1, figsize=(6.4, 2.6 * len(results)),
                                 sharex=True)
        for ax, (label, r) in zip(np.atleast_1d(axes), results.items()):
            for k in range(r.q.shape[1]):
                ax.plot(r.t, r.q[:, k], lw=1.0, label=f"q{k + 1}")
            for n, (lo, hi) in enumerate(stroke_ranges[label]):
                ax.axhline(lo, color="k", ls="--", lw=0.6,
                           label="stroke range" if n == 0 else None)
                ax.axhline(hi, color="k", ls="--", lw=0.6)
            bad = r.code != 0
            if bad.any():
                ax.plot(r.t[bad], np.zeros(bad.sum()) + ax.get_ylim()[0], "x", color="k",
                        ms=3, label="outside")
            ax.set_ylabel("stroke (mm)")
            ax.set_title(label, fontsize=9)
            ax.grid(True, lw=0.3)
            ax.legend(fontsize=6, ncol=4, loc="upper left")
        np.atleast_1d(axes)[-1].set_xlabel("step (time unit per step)")
        fig.suptitle(title, fontsize=9)
        fig.tight_layout()
        return _save(fig, stem)


def singular_slice(res: ScanResult, signs: dict, title: str, stem: Path) -> list[Path]:
    """A 2-D scan: the reachable set filled, and the zero set of every singularity
    polynomial that changes sign on the slice drawn as a line (001 Fig. 5 style)."""
    a, b = (ax.name for ax in res.grid.axes)
    m, va, vb = projection(res, a, b)
    with plt.rc_context({"svg.hashsalt": "bonered", "pdf.compression": 6}):
        fig, ax = plt.subplots(figsize=(5.6, 4.4))
        ax.contourf(va, vb, m.T.astype(float), levels=[0.5, 1.5], colors=["tab:red"],
                    alpha=0.3)
        ax.plot([], [], color="tab:red", lw=6, alpha=0.3, label=f"{res.mechanism} workspace")
        cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        k = 0
        for name, s in signs.items():
            if (s > 0).any() and (s < 0).any():
                colour = cycle[k % len(cycle)]
                ax.contour(va, vb, s.T.astype(float), levels=[0.0], colors=[colour],
                           linewidths=1.2)
                ax.plot([], [], color=colour, label=f"{name} = 0")
                k += 1
        ax.set_xlabel(f"{a} ({user_unit(a)})")
        ax.set_ylabel(f"{b} ({user_unit(b)})")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
        ax.grid(True, lw=0.3)
        fig.tight_layout()
        return _save(fig, stem)
