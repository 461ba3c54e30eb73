"""``bonered-alg workspace`` and ``bonered-alg comparison``: argument parsing and output."""

from __future__ import annotations

import csv
import io
import itertools
import math
import sys

import numpy as np

from ..fileio import atomic_write_text
from .grid import ANGLES, Axis, Grid, fixed_from_user, user_unit, user_value
from .membership import Criteria
from .plots import overlay
from .scan import ScanResult, scan

POINTS_LIMIT = 2_000_000  # reachable samples written to the points CSV at most


FORMS = {"--axis": "NAME=LO:HI:STEP", "--limit": "PATTERN=LO:HI", "--fix": "NAME=VALUE",
         "--param": "NAME=VALUE"}


def _pair(text: str, what: str) -> tuple[str, str]:
    name, sep, value = text.partition("=")
    if not sep or not name or not value:
        raise ValueError(f"{what} {text!r}: expected {FORMS.get(what, 'NAME=VALUE')}")
    return name.strip(), value.strip()


def _module(name: str):
    """The generated module of ``name``, with an error that says which names exist."""
    import importlib
    import pkgutil

    from .. import generated
    from ..registry import REGISTRY

    present = sorted(m.name for m in pkgutil.iter_modules(generated.__path__))
    if name not in present:
        if name in REGISTRY:
            raise ValueError(f"no generated module for mechanism {name!r}; run `make derive` "
                             "(or `bonered-alg derive`) first")
        raise ValueError(f"unknown mechanism {name!r}; generated: {', '.join(present)}")
    return importlib.import_module(f"bonered_alg.generated.{name}")


def _dask_client(address: str):
    """A dask client for ``address``, or one clear error."""
    try:
        from dask.distributed import Client
    except ImportError:
        raise ValueError("--dask needs dask.distributed: pip install 'bonered_alg[cluster]'"
                         ) from None
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise ValueError(f"--dask {address!r}: no dask scheduler reachable there "
                         f"({type(exc).__name__}: {exc})") from None


def _numbers(text: str, count: int, what: str) -> list[float]:
    parts = text.split(":")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not {count} numbers separated by ':'") from None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise ValueError(f"{what}: expected {count} finite numbers separated by ':', got "
                         f"{text!r}")
    return values


def parse_axes(items: list[str]) -> list[Axis]:
    axes = []
    for item in items:
        name, spec = _pair(item, "--axis")
        lo, hi, step = _numbers(spec, 3, f"--axis {name}")
        axes.append(Axis.from_user(name, lo, hi, step))
    return axes


def parse_limits(items: list[str]) -> dict[str, tuple[float, float]]:
    out = {}
    for item in items:
        pattern, spec = _pair(item, "--limit")
        lo, hi = _numbers(spec, 2, f"--limit {pattern}")
        if pattern.startswith("phi"):  # joint angles: degrees at the command line
            lo, hi = math.radians(lo), math.radians(hi)
        out[pattern] = (lo, hi)
    return out


def parse_params(items: list[str], module) -> dict[str, float]:
    out = {}
    for item in items:
        name, value = _pair(item, "--param")
        if name not in module.PARAMETERS:
            raise ValueError(f"{module.MECHANISM}: unknown parameter {name!r}; expected some "
                             f"of {list(module.PARAMETERS)}")
        (out[name],) = _numbers(value, 1, f"--param {name}")
    return out


def progress_bar(done: int, total: int, stream=sys.stderr) -> None:
    width = 40
    filled = int(width * done / max(total, 1))
    stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {100 * done / max(total, 1):5.1f}%"
                 f" ({done}/{total} chunks)")
    if done >= total:
        stream.write("\n")
    stream.flush()


def summary_csv(res: ScanResult, statuses: dict[int, str]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["quantity", "value", "unit"])
    w.writerow(["mechanism", res.mechanism, ""])
    w.writerow(["grid", res.grid.describe(), ""])
    w.writerow(["samples", res.samples, ""])
    w.writerow(["reachable", res.count, ""])
    units = [user_unit(a.name) for a in res.grid.axes]
    # the volume in the units of the ranges below (mm and degrees), and in mm and radians
    scanned = [a for a in res.grid.axes if a.n > 1]
    user_cell = math.prod(user_value(a.name, a.step) for a in scanned)
    w.writerow(["volume", f"{res.count * user_cell:.6g}",
                "*".join(user_unit(a.name) for a in scanned)])
    w.writerow(["volume_mm_rad", f"{res.volume:.6g}", "*".join(
        "mm" if a.name not in ANGLES else "rad" for a in scanned)])
    for a, unit in zip(res.grid.axes, units):
        lo, hi = res.ranges.get(a.name, (math.nan, math.nan))
        w.writerow([f"{a.name}_min", f"{user_value(a.name, lo):.6g}", unit])
        w.writerow([f"{a.name}_max", f"{user_value(a.name, hi):.6g}", unit])
        w.writerow([f"{a.name}_range", f"{user_value(a.name, hi - lo):.6g}", unit])
        w.writerow([f"{a.name}_step", f"{user_value(a.name, a.step):.6g}", unit])
    for code, n in res.reasons.items():
        w.writerow([f"samples with status {code} ({statuses.get(code, 'near singularity')})",
                    n, ""])
    return buf.getvalue()


def points_csv(res: ScanResult) -> str | None:
    if res.mask is None or res.count > POINTS_LIMIT:
        return None
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([f"{a.name} ({user_unit(a.name)})" for a in res.grid.axes])
    idx = np.nonzero(res.mask.ravel())[0]
    for start in range(0, idx.size, 1 << 16):
        sub = np.unravel_index(idx[start:start + (1 << 16)], res.grid.shape)
        cols = [np.array([user_value(a.name, a.lo + a.step * i) for i in s])
                for a, s in zip(res.grid.axes, sub)]
        for row in zip(*cols):
            w.writerow([f"{v:.6g}" for v in row])
    return buf.getvalue()


def workspace(args) -> int:
    module = _module(args.mechanism)
    axes = parse_axes(args.axis)
    if not axes:
        raise ValueError("give at least one --axis NAME=LO:HI:STEP")
    fixed = fixed_from_user(module.POSE, dict(_pair(f, "--fix") for f in args.fix))
    grid = Grid(tuple(module.POSE), tuple(axes), fixed)
    params = parse_params(args.param, module)
    if args.limit and not getattr(module, "LIMITS", ()):
        raise ValueError(f"{module.MECHANISM} declares no LIMITS: --limit has nothing to "
                         "override")
    criteria = Criteria(tuple(args.mode) or (0,), parse_limits(args.limit), args.min_margin)
    criteria.check(module)  # modes and limit names, before the scan starts
    client = None
    if args.dask:
        client = "local" if args.dask == "local" else _dask_client(args.dask)
    print(f"{module.MECHANISM}: {grid.size} samples: {grid.describe()}", file=sys.stderr)
    res = scan(module.MECHANISM, grid, criteria, chunk=args.chunk, workers=args.workers,
               client=client, progress=None if args.no_progress else progress_bar, **params)
    out = args.out
    written = []
    path = out / f"{module.MECHANISM}_summary.csv"
    atomic_write_text(path, summary_csv(res, module.STATUS))
    written.append(path)
    pts = points_csv(res)
    if pts is not None:
        path = out / f"{module.MECHANISM}_points.csv"
        atomic_write_text(path, pts)
        written.append(path)
    if res.mask is not None:
        scanned = [a.name for a in axes if a.n > 1]
        for a, b in itertools.combinations(scanned, 2):
            written += overlay([res], b, a, f"{module.MECHANISM}: ({a}, {b})",
                               out / f"{module.MECHANISM}_{a}_{b}")
    print(f"{res.count} of {res.samples} samples reachable in {res.seconds:.2f} s "
          f"({res.rate:.3g} samples/s)")
    if res.count == 0:
        print("  no reachable sample: widen the axes, move the fixed coordinates into the "
              "workspace, or relax --limit / --mode")
    for a in axes if res.count else ():
        lo, hi = res.ranges.get(a.name, (math.nan, math.nan))
        unit = user_unit(a.name)
        edge = [side for side, at in (("lower", lo <= a.lo + a.step / 2),
                                      ("upper", hi >= a.hi - a.step / 2)) if at and a.n > 1]
        print(f"  {a.name}: [{user_value(a.name, lo):.4g}, {user_value(a.name, hi):.4g}] {unit}"
              f" (step {user_value(a.name, a.step):.4g})"
              + (f"; cut by the {' and '.join(edge)} grid edge: the workspace may extend "
                 "beyond it" if edge else ""))
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


