"""Benchmarks (`make bench`): derivation steps per engine, incremental derive, and throughput
of the generated functions against a plain ``sympy.lambdify`` of the same expressions.

Results go to the JSON file given by ``--out``; medians of repeated runs, measured in one
process on a shared machine (treat ratios as the meaningful numbers).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[1]

# glibc's allocator without mmap for large blocks and without trimming the heap: a freed
# array's pages are reused, not returned to the kernel and faulted in again.  On this
# project's VM a page faulted in after the host reclaimed it costs microseconds (a fresh
# 288 MB array: 0.4-0.8 s), which made every timing of a 10^6-pose function vary up to 2x
# between runs, the hand-written baselines as much as the generated code.  The same
# setting for both, so the ratios measure the code.  Set before numpy is imported: the
# script re-executes itself with it.
MALLOC_TUNABLES = "glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=68719476736"
if __name__ == "__main__" and os.environ.get("GLIBC_TUNABLES") is None:
    os.execve(sys.executable, [sys.executable, *sys.argv],
              {**os.environ, "GLIBC_TUNABLES": MALLOC_TUNABLES})
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "bench"))

from bonered_alg.generated import pro_hep_lct as gen  # noqa: E402
from hand_written import tripod_planar as paper_ik_tripod_planar  # noqa: E402
from independent_pro_hep_lct import GEOMETRY  # noqa: E402

from bonered_alg.elimination.closure import leg_problem  # noqa: E402
from bonered_alg.elimination.engines import (  # noqa: E402
    SingularEngine,
    SympyEngine,
)
from bonered_alg.elimination.problem import EliminationProblem  # noqa: E402
from bonered_alg.errors import EngineTimeoutError  # noqa: E402
from bonered_alg.fileio import atomic_write_text  # noqa: E402
from bonered_alg.mechanisms import pro_hep_lct as phl  # noqa: E402
from bonered_alg.pipeline.algebra import Algebra  # noqa: E402
from bonered_alg.pipeline.runner import derive  # noqa: E402
from bonered_alg.runtime import compiled  # noqa: E402


def interleaved_medians(fns, repeat):
    """Median time of each of ``fns``, timed in turn within each of ``repeat`` rounds: on a
    shared host whose load drifts, the functions compared see the same conditions (timed in
    separate blocks, a ratio moved by up to 30 % between runs)."""
    times = [[] for _ in fns]
    for _ in range(repeat):
        for k, fn in enumerate(fns):
            t0 = time.perf_counter()
            fn()
            times[k].append(time.perf_counter() - t0)
    return [statistics.median(t) for t in times]


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def elimination_benchmarks(sympy_budget):
    mod = phl
    mech = mod.MECHANISM
    numeric = {mod.l1: 180, mod.l2: 160, mod.d: 60, mod.l3: 170, mod.l4: 150, mod.lq4d: 250}
    rows = []
    for closure in mech.actuated_closures:
        for leg in closure.legs:
            p = leg_problem(mech, closure, leg)
            variants = [("symbolic geometry", p)]
            if closure.point == "Pd":
                variants.append(("numeric geometry", EliminationProblem(
                    p.context, tuple(sp.expand(e.subs(numeric)) for e in p.equations),
                    p.eliminate, tuple(s for s in p.keep if s not in numeric))))
            for label, prob in variants:
                row = {"leg": leg.name, "geometry": label}
                row["singular_s"] = median_time(lambda p=prob: SingularEngine().eliminate(p, 60), 5)
                for method in SympyEngine.METHODS:
                    eng = SympyEngine(method)
                    try:
                        row[f"sympy_{method}_s"] = median_time(
                            lambda e=eng, p=prob: e.eliminate(p, sympy_budget), 1)
                    except EngineTimeoutError:
                        row[f"sympy_{method}_s"] = f"> {sympy_budget:g} (time budget exceeded)"
                rows.append(row)
                print(row, flush=True)
    return rows


def derive_benchmarks():
    """A cold derivation (no elimination cache) of every registered mechanism, one after
    another in this process: the seconds of each stage as the runner reports them and of
    rendering its outputs (``derive --force`` runs the same derivations on every core and
    writes them, then the comparison study), the derivation's finer timings, and
    ``derive`` when everything is current."""
    from bonered_alg.pipeline import outputs
    from bonered_alg.registry import REGISTRY

    per_mechanism = {}
    for name in sorted(REGISTRY):
        stage_s: dict[str, float] = {}

        def progress(line, flush=True, into=stage_s):
            found = re.match(r"\s*\S+: (.+) ([0-9.]+) s \(elapsed", line)
            if found:
                into[found.group(1)] = float(found.group(2))

        t0 = time.perf_counter()
        record = derive(name, use_cache=False, progress=progress)
        # the outputs' text (report, records, modules) as derive --force renders them
        # before writing: a stage of its own, outside the runner's progress lines
        t1 = time.perf_counter()
        outputs.files(record)
        stage_s["outputs rendered"] = round(time.perf_counter() - t1, 1)
        per_mechanism[name] = {"total_s": time.perf_counter() - t0, "stages_s": stage_s,
                               "detail_s": {k: round(v, 3) for k, v in
                                            record.derivation.timings.items()}}
        print(name, per_mechanism[name]["total_s"], stage_s, flush=True)
    cmd = [sys.executable, "-m", "bonered_alg.cli", "derive"]
    t_noop = median_time(lambda: subprocess.run(cmd, cwd=ROOT, check=True,
                                                capture_output=True), 3)
    rounds = cold_derive_force()
    force, comparison, together = (statistics.median(r[k] for r in rounds) for k in range(3))
    return {"cold_one_process": per_mechanism,
            "cold_one_process_sum_s": sum(v["total_s"] for v in per_mechanism.values()),
            "cold_rounds": [{"derive_force_s": a, "comparison_force_s": b,
                             "derive_force_comparison_s": c} for a, b, c in rounds],
            "cold_derive_force_all_cores_s": force,
            "comparison_force_all_cores_s": comparison,
            "derive_then_comparison_s": statistics.median(a + b for a, b, _ in rounds),
            "make_derive_force_s": together,
            "derive_when_up_to_date_s": t_noop}


def _cold_run(args: list[str]) -> float:
    """Wall seconds of ``bonered-alg <args> --root <copy>`` as on a fresh clone (every core,
    an empty elimination cache and no record of earlier derivation times: the registry's
    estimates order the work), into a copy of the outputs."""
    import shutil
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        for folder in ("generated", "derivations"):
            shutil.copytree(ROOT / folder, root / folder)
        shutil.copy(ROOT / "constraints.txt", root)
        env = {**os.environ, "BONERED_CACHE_DIR": str(root / "cache" / "elimination")}
        cmd = [sys.executable, "-m", "bonered_alg.cli", *args, "--quiet", "--root", str(root)]
        t0 = time.perf_counter()
        subprocess.run(cmd, cwd=ROOT, env=env, check=True, capture_output=True)
        return time.perf_counter() - t0


def cold_derive_force(rounds: int = 2) -> list[tuple[float, float, float]]:
    """Per round, wall seconds, each from a cold start (:func:`_cold_run`), of ``derive
    --force`` alone, of the comparison study alone (``comparison --force``, its modules
    derived), and of ``make derive-force``'s command, ``derive --force --comparison`` (the
    comparison started once the three mechanisms it scans are derived, beside the others):
    interleaved, as the host's speed drifts by tens of percent within minutes."""
    out = []
    for _ in range(rounds):
        seconds = _cold_run(["derive", "--force"])
        comparison = _cold_run(["comparison", "--force"])
        together = _cold_run(["derive", "--force", "--comparison"])
        print("cold derive --force on every core", seconds, "comparison --force", comparison,
              "derive --force --comparison", together, flush=True)
        out.append((seconds, comparison, together))
    return out


def reachable_poses(n, rng):
    g = GEOMETRY
    th1 = rng.uniform(-1.0, 1.0, n)
    th2 = rng.uniform(-2.4, -0.4, n)
    xd = g["l1"] * np.cos(th1) + g["l2"] * np.cos(th1 + th2)
    yd = g["l1"] * np.sin(th1) + g["l2"] * np.sin(th1 + th2) + g["d"] / 2
    q5 = rng.uniform(100, 300, n)
    q4 = q5 - rng.uniform(20, 180, n)
    xu = g["lq5"] + np.sqrt(g["ld4"] ** 2 - (q5 - q4) ** 2)
    poses = np.stack([xu, q5, xd, yd], axis=-1)
    # keep the poses that chain 2 reaches too (the generated code would give NaN elsewhere)
    r = np.hypot(xd, yd + g["d"] / 2 - g["lq4d"])
    ok = (abs(g["l3"] - g["l4"]) + 1 < r) & (r < g["l3"] + g["l4"] - 1)
    return poses[ok]


def lambdify_baseline(derivation):
    """Plain sympy.lambdify of the same mode-0 IK roots and of -Ji^{-1} Jo."""
    mech = derivation.mechanism
    par = list(mech.geometric)
    pose, joints = mech.pose.coordinates, mech.joints
    sub = dict(derivation.pose_to_study)
    solved = {}
    for step in derivation.steps:
        solved[step.joint] = step.roots()[0].subs(sub).subs(solved)
    q_exprs = [solved[j] for j in joints]
    ik = sp.lambdify([*pose, *par], q_exprs, modules="numpy")
    gens = sp.Matrix([sp.expand(s.generator).subs(sub) for s in derivation.steps])
    ji = sp.lambdify([*pose, *joints, *par],
                     list(gens.jacobian(sp.Matrix(joints))), modules="numpy")
    jo = sp.lambdify([*pose, *joints, *par],
                     list(gens.jacobian(sp.Matrix(pose))), modules="numpy")
    # the test geometry, the module's defaults for the parameters it does not set (the
    # tool's c and Dn), in the declaration's order
    values = [{**gen.PARAMETERS, **GEOMETRY}[str(p)] for p in par]

    def ik_fn(poses):
        cols = [poses[:, i] for i in range(4)]
        return np.stack(np.broadcast_arrays(*ik(*cols, *values)), axis=-1)

    def jac_fn(poses):
        q = ik_fn(poses)
        cols = [poses[:, i] for i in range(4)] + [q[:, i] for i in range(4)]
        n = len(poses)
        a = np.stack(np.broadcast_arrays(*ji(*cols, *values), np.empty(n)))[:-1]
        b = np.stack(np.broadcast_arrays(*jo(*cols, *values), np.empty(n)))[:-1]
        return -np.linalg.solve(a.T.reshape(n, 4, 4), b.T.reshape(n, 4, 4))

    return ik_fn, jac_fn


def throughput_benchmarks(n, derivation):
    rng = np.random.default_rng(1)
    poses = reachable_poses(3 * n, rng)[:n]
    n = len(poses)
    ik_fn, jac_fn = lambdify_baseline(derivation)
    out = {"poses": n}
    t_gen_ik = median_time(lambda: gen.ik(poses, 0, **GEOMETRY), 5)
    t_lam_ik = median_time(lambda: ik_fn(poses), 5)
    t_gen_jac = median_time(lambda: gen.jacobian(poses, 0, **GEOMETRY), 3)
    t_lam_jac = median_time(lambda: jac_fn(poses), 3)
    q_all = gen.ik(poses, 0, **GEOMETRY)
    t_fk = median_time(lambda: gen.fk(q_all, **GEOMETRY), 3)
    agree_ik = float(np.nanmax(np.abs(gen.ik(poses, 0, **GEOMETRY) - ik_fn(poses))))
    agree_j = float(np.nanmax(np.abs(gen.jacobian(poses, 0, **GEOMETRY) - jac_fn(poses))))
    out.update({
        "generated_ik_poses_per_s": n / t_gen_ik,
        "lambdify_ik_poses_per_s": n / t_lam_ik,
        "ik_speedup_vs_lambdify": t_lam_ik / t_gen_ik,
        "generated_ik_plus_jacobian_poses_per_s": n / t_gen_jac,
        "lambdify_ik_plus_jacobian_poses_per_s": n / t_lam_jac,
        "jacobian_speedup_vs_lambdify": t_lam_jac / t_gen_jac,
        "generated_fk_all_modes_configurations_per_s": n / t_fk,
        "fk_modes": gen.FK_MODES,
        "max_abs_difference_ik": agree_ik,
        "max_abs_difference_jacobian": agree_j,
        "generated_operation_count": gen.OPERATION_COUNT,
    })
    print(out, flush=True)
    return out


def lambdified_ik(pose, exprs, cse):
    """``sympy.lambdify`` of IK expressions and of their Jacobian: the baseline."""
    n = len(exprs)
    lam_ik = sp.lambdify(pose, exprs, modules="numpy", cse=cse)
    lam_jac = sp.lambdify(pose, list(sp.Matrix(exprs).jacobian(sp.Matrix(pose))),
                          modules="numpy", cse=cse)

    def ik(p):
        return np.stack(np.broadcast_arrays(*lam_ik(*p.T)), axis=-1)

    def ik_jac(p):
        jac = np.stack(np.broadcast_arrays(*lam_jac(*p.T)), axis=-1).reshape(len(p), n, len(pose))
        return ik(p), jac

    return ik, ik_jac


def paper_ik_planar_tripod(p, ra=190.0, rb=190.0):
    """Hand-written numpy of 000 eq. (17) and (21): the baseline a user would write."""
    x, y, z, a, b, g = (p[:, i] for i in range(6))
    sa, ca, sb, cb, sg, cg = np.sin(a), np.cos(a), np.sin(b), np.cos(b), np.sin(g), np.cos(g)
    s3 = np.sqrt(3.0)
    den = sg + s3 * cg
    q1 = (ra + ra * cg + 2 * y * cg - 2 * x * sg + s3 * ra * sg) / den
    q2 = (ra + ra * cg + s3 * ra * sg - y * cg + x * sg - s3 * y * sg - s3 * x * cg
          - s3 * rb * sa * sb) / den
    q3 = (ra + ra * cg + s3 * ra * sg - y * cg + x * sg + s3 * y * sg + s3 * x * cg
          + s3 * rb * sa * sb) / den
    q4 = np.sqrt((z - rb * sb) ** 2 + (ra - rb * cb + rb * sa * sb) ** 2)
    q5 = np.sqrt((z + rb * sa * cb) ** 2 + (ra - rb * ca) ** 2)
    q6 = np.sqrt((z + rb * sb) ** 2 + (ra - rb * cb - rb * sa * sb) ** 2)
    return np.stack([q1, q2, q3, q4, q5, q6], axis=-1)


def tripod_fk_benchmark(module, poses, n_fk=10_000):
    """All-modes forward kinematics of a tripod mechanism on the joints of n_fk poses:
    configurations per second and the largest error of the mode closest to the pose."""
    p = poses[:n_fk]
    q = module.ik(p, limits=False)
    t = median_time(lambda: module.fk(q), 3)
    sols = module.fk(q)
    err = np.abs(sols - p[:, None, :])
    err[..., 3:] = np.abs(np.angle(np.exp(1j * (sols[..., 3:] - p[:, None, 3:]))))
    return {"fk_configurations": len(p), "fk_modes": module.FK_MODES,
            "generated_fk_all_modes_configurations_per_s": len(p) / t,
            "fk_median_us_per_configuration": 1e6 * t / len(p),
            "fk_max_error_of_nearest_mode": float(np.nanmax(np.nanmin(err.max(axis=-1),
                                                                       axis=1)))}


def hybrid_ik_benchmark(gen, poses, lambdify_ik, lambdify_ik_jac, paper_ik, lam):
    """IK and IK+Jacobian of a hybrid mechanism's generated module against lambdify (named
    ``lam`` in the keys) and the hand-written paper formulas (``paper_ik()``)."""
    n = len(poses)
    t_gen = median_time(lambda: gen.ik(poses), 5)
    t_gen_nolim = median_time(lambda: gen.ik(poses, limits=False), 5)
    t_lam = median_time(lambda: lambdify_ik(poses), 5)
    t_paper = median_time(paper_ik, 5)
    t_gen_j = median_time(lambda: (gen.ik(poses), gen.jacobian(poses)), 3)
    t_lam_j = median_time(lambda: lambdify_ik_jac(poses), 3)
    return {
        "poses": n,
        "generated_ik_with_limits_poses_per_s": n / t_gen,
        "generated_ik_poses_per_s": n / t_gen_nolim,
        f"{lam}_ik_poses_per_s": n / t_lam,
        "paper_formulas_numpy_ik_poses_per_s": n / t_paper,
        f"ik_speedup_vs_{lam}": t_lam / t_gen_nolim,
        "ik_ratio_vs_paper_formulas": t_paper / t_gen_nolim,
        "generated_ik_plus_jacobian_poses_per_s": n / t_gen_j,
        f"{lam}_ik_plus_jacobian_poses_per_s": n / t_lam_j,
        f"ik_plus_jacobian_speedup_vs_{lam}": t_lam_j / t_gen_j,
        "max_abs_difference_vs_paper_formulas_mm": float(np.nanmax(np.abs(
            gen.ik(poses, limits=False) - paper_ik()))),
        "fraction_within_limits": float(np.mean(np.all(np.isfinite(gen.ik(poses)), axis=-1))),
    }


def planar_tripod_benchmarks(n):
    from bonered_alg.generated import planar_tripod as pt

    from bonered_alg.mechanisms import planar_tripod as mod

    d = derive("planar_tripod").derivation
    rng = np.random.default_rng(5)
    poses = np.column_stack([rng.uniform(-40, 40, n), rng.uniform(-40, 40, n),
                             rng.uniform(190, 235, n), rng.uniform(-0.15, 0.15, n),
                             rng.uniform(-0.15, 0.15, n), rng.uniform(-0.6, 0.6, n)])
    ik_exprs = d.ik_expressions()
    geo = {mod.ra: 190.0, mod.rb: 190.0}
    exprs = [ik_exprs[q].subs(geo) for q in mod.JOINTS]
    lambdify_ik, lambdify_ik_jac = lambdified_ik(mod.POSE, exprs, cse=False)
    out = {
        **hybrid_ik_benchmark(pt, poses, lambdify_ik, lambdify_ik_jac,
                              lambda: paper_ik_planar_tripod(poses), "lambdify"),
        **tripod_fk_benchmark(pt, poses),
        "derivation_s": median_time(lambda: derive("planar_tripod", use_cache=False), 1),
    }
    print(out, flush=True)
    return out


def tripod_planar_benchmarks(n):
    from bonered_alg.generated import tripod_planar as tp

    from bonered_alg.mechanisms import tripod_planar as mod

    d = derive("tripod_planar").derivation
    rng = np.random.default_rng(6)
    paper = np.column_stack([rng.uniform(-40, 40, n), rng.uniform(-40, 40, n),
                             rng.uniform(190, 260, n), rng.uniform(-0.15, 0.15, n),
                             rng.uniform(-0.15, 0.15, n), rng.uniform(-0.6, 0.6, n)])
    poses = tp.pose_from_paper_coordinates(paper)
    ik_exprs = d.ik_expressions()
    geo = {mod.ra: 200.0, mod.rb: 200.0, mod.d: 0.0}
    exprs = [ik_exprs[q].subs(geo) for q in mod.JOINTS]
    lambdify_ik, lambdify_ik_jac = lambdified_ik(mod.POSE, exprs, cse=True)
    out = {
        **hybrid_ik_benchmark(tp, poses, lambdify_ik, lambdify_ik_jac,
                              lambda: paper_ik_tripod_planar(paper), "lambdify_cse"),
        "max_abs_difference_vs_lambdify_mm": float(np.nanmax(np.abs(
            tp.ik(poses, limits=False) - lambdify_ik(poses)))),
        "generated_operation_count": tp.OPERATION_COUNT,
        **tripod_fk_benchmark(tp, poses),
        "derivation_s": median_time(lambda: derive("tripod_planar", use_cache=False), 1),
    }
    print(out, flush=True)
    return out


WORKSPACE_MEMORY_SCRIPT = """
import json, resource, sys, time
from bonered_alg.workspace.grid import Axis, Grid
from bonered_alg.workspace.scan import scan
from bonered_alg.generated import tripod_planar as t
n = int(sys.argv[1])
g = Grid(t.POSE, (Axis("x", -150.0, 150.0, n), Axis("y", -150.0, 150.0, n),
                  Axis("gamma", -1.5, 1.5, n)), {"z": 240.0, "alpha": 0.0, "beta": 0.1})
t0 = time.perf_counter()
res = scan("tripod_planar", g, workers=2)
dt = time.perf_counter() - t0
# VmHWM, not ru_maxrss: Linux keeps ru_maxrss across fork + exec, so a process started
# from the (large) benchmark process would report the benchmark's own peak
hwm = next(int(line.split()[1]) for line in open("/proc/self/status")
           if line.startswith("VmHWM:"))
print(json.dumps({"samples": g.size, "reachable": res.count, "seconds": dt,
                  "samples_per_s": g.size / dt, "mask_bytes": int(res.mask.size / 8),
                  "peak_rss_parent_mb": hwm / 1024,
                  "peak_rss_largest_worker_mb":
                      resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024}))
"""


# the grids of `workspace_benchmarks`: (mechanism, fixed z) on x, y in [-100, 100] mm and
# gamma in [-1, 1] rad, alpha 0.05 and beta -0.05 rad
SCAN_GRIDS = (("planar_tripod", 212.5), ("tripod_planar", 240.0), ("stewart", 220.0))


def scan_grid(name: str, z: float, n_side: int):
    """The benchmark's grid of ``n_side``^3 samples for ``name`` (:data:`SCAN_GRIDS`)."""
    from bonered_alg.workspace.grid import Axis, Grid

    mod = __import__(f"bonered_alg.generated.{name}", fromlist=["POSE"])
    return Grid(mod.POSE, (Axis("x", -100.0, 100.0, n_side), Axis("y", -100.0, 100.0, n_side),
                           Axis("gamma", -1.0, 1.0, n_side)),
                {"z": z, "alpha": 0.05, "beta": -0.05})


# A process that scans the benchmark's grid on one core each time a line arrives on its
# stdin and answers "done": two of them at once measure what two cores of this host give two
# independent one-core scans (its other loads, shared caches and clocks), the ceiling for a
# scan on both cores, in the same minutes as the scans it bounds.
SCAN_WORKER_SCRIPT = """
import sys
sys.path.insert(0, "bench")
from run import scan_grid
from bonered_alg.workspace.scan import scan
name, z, n = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
g = scan_grid(name, z, n)
scan(name, g, workers=1)
print("ready", flush=True)
for line in sys.stdin:
    scan(name, g, workers=1)
    print("done", flush=True)
"""


class _ScanWorker:
    """A :data:`SCAN_WORKER_SCRIPT` process."""

    def __init__(self, name: str, z: float, n_side: int):
        self.proc = subprocess.Popen(
            [sys.executable, "-c", SCAN_WORKER_SCRIPT, name, repr(z), str(n_side)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=ROOT)
        self._expect("ready")

    def _expect(self, word: str) -> None:
        line = self.proc.stdout.readline().strip()
        if line != word:
            self.close()
            raise RuntimeError(f"scan worker: expected {word!r}, got {line!r}")

    def start(self) -> None:
        self.proc.stdin.write("\n")
        self.proc.stdin.flush()

    def wait(self) -> None:
        self._expect("done")

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


def _scans_at_once(workers: list[_ScanWorker]) -> None:
    """One scan in each of ``workers``, all started before any is awaited."""
    for w in workers:
        w.start()
    for w in workers:
        w.wait()


def workspace_benchmarks(n_side=160, repeat=7):
    """Full workspace test (IK + strokes + passive joint ranges) per mechanism on one and on
    both cores (grid of n_side^3 samples), beside the host's ceiling for two cores (two
    independent one-core scans in two processes at once, against one alone), and the memory
    of a 10^8-sample scan (run in a fresh process, so the peak RSS is the scan's own)."""
    from bonered_alg.workspace.scan import scan

    out = {}
    for name, z in SCAN_GRIDS:
        g = scan_grid(name, z, n_side)
        res = scan(name, g, workers=1)
        pair = [_ScanWorker(name, z, n_side) for _ in range(2)]
        try:
            t1, t2, t_alone, t_together = interleaved_medians(
                [lambda n=name, g=g: scan(n, g, workers=1),
                 lambda n=name, g=g: scan(n, g, workers=2),
                 lambda p=pair: _scans_at_once(p[:1]), lambda p=pair: _scans_at_once(p)],
                repeat)
        finally:
            for w in pair:
                w.close()
        speedup, ceiling = t1 / t2, 2 * t_alone / t_together
        out[name] = {"samples": g.size, "reachable": res.count,
                     "samples_per_s_1_core": g.size / t1, "samples_per_s_2_cores": g.size / t2,
                     "speedup_2_cores": speedup,
                     "two_independent_scans_speedup": ceiling,
                     "speedup_2_cores_of_ceiling": speedup / ceiling}
        print(name, out[name], flush=True)
    from bonered_alg.generated import stewart as st

    rng = np.random.default_rng(11)
    poses = np.column_stack([rng.uniform(-40, 40, 200_000), rng.uniform(-40, 40, 200_000),
                             rng.uniform(190, 250, 200_000),
                             *(rng.uniform(-0.2, 0.2, (3, 200_000)))])
    out["stewart_functions"] = {
        "poses": len(poses), "operation_count": st.OPERATION_COUNT,
        "ik_us_per_pose": median_time(lambda: st.ik(poses), 3) / len(poses) * 1e6,
        "ik_and_limits_us_per_pose": median_time(lambda: st.ik_and_status(poses), 3)
        / len(poses) * 1e6,
        "jacobian_us_per_pose": median_time(lambda: st.jacobian(poses[:20_000]), 3)
        / 20_000 * 1e6}
    print(out["stewart_functions"], flush=True)
    side = 465  # 465^3 = 1.005e8 samples
    run = subprocess.run([sys.executable, "-c", WORKSPACE_MEMORY_SCRIPT, str(side)],
                         capture_output=True, text=True, cwd=ROOT, check=True)
    out["scan_1e8_tripod_planar"] = json.loads(run.stdout.strip().splitlines()[-1])
    print(out["scan_1e8_tripod_planar"], flush=True)
    return out


def pro_hep_lct_tool_benchmarks(n=100_000, n_fk=10_000, sympy_budget=120.0):
    """Issue 5: the mobile platform's ideal G per engine (no cache), tool IK throughput and
    the whole robot's forward kinematics (16 assembly modes) per configuration."""
    from bonered_alg.papers import p004_pro_hep_lct as paper
    from bonered_alg.surgical import pro_hep_lct_tool as tool

    out = {"G_derivation": {}}
    for eng in [SingularEngine()] + [SympyEngine(k) for k in SympyEngine.METHODS]:
        label = eng.name + (f"_{eng.method}" if hasattr(eng, "method") else "")
        try:
            t = median_time(lambda e=eng: platform_ideal(e, sympy_budget), 3
                            if isinstance(eng, SingularEngine) else 1)
            out["G_derivation"][label + "_s"] = t
        except EngineTimeoutError:
            out["G_derivation"][label + "_s"] = f"> {sympy_budget:g} (time budget exceeded)"
        print(label, out["G_derivation"][label + "_s"], flush=True)
    rng = np.random.default_rng(0)
    dirs = np.column_stack([rng.uniform(-0.4, 0.4, n), rng.uniform(-0.4, 0.4, n), np.ones(n)])
    origin = np.column_stack([rng.uniform(260, 300, n), rng.uniform(160, 200, n),
                              rng.uniform(-150, -110, n)])
    poses = tool.tool_pose(origin, dirs)
    mode = paper.TABLE5_MODE
    t_ik = median_time(lambda: tool.tool_ik(poses, gen, mode=mode, limits=False), 5)
    joints, status = tool.tool_ik(poses, gen, mode=mode, limits=False)
    ok = joints[status == 0][:n_fk]
    t_fk = median_time(lambda: tool.tool_fk(ok, gen), 3)
    out.update({"tool_ik_poses_per_s": n / t_ik, "tool_ik_us_per_pose": t_ik / n * 1e6,
                "tool_ik_reachable_fraction": float(np.mean(status == 0)),
                "tool_fk_configurations": len(ok),
                "tool_fk_us_per_configuration_all_16_modes": t_fk / len(ok) * 1e6})
    print(out, flush=True)
    return out


def _hand_written_cases(n, rng):
    """``(cases, six)``: per mechanism ``(generated module, poses (n, len(POSE)), parameters,
    hand(jacobian))``, ``n`` poses in its workspace and the hand-written numpy of
    bench/hand_written.py on the same poses; ``six``: tripod_planar's poses in 001's own
    coordinates (the hand form's; the generated module's are converted)."""
    import hand_written as hw
    from bonered_alg.generated import lamina_milling as lm
    from bonered_alg.generated import planar_tripod as pt
    from bonered_alg.generated import pro_hep_lct as ph
    from bonered_alg.generated import stewart as st
    from bonered_alg.generated import tripod_planar as tp
    from bonered_alg.generated import urrh_rcm as ur
    from independent_pro_hep_lct import GEOMETRY as G

    six = np.column_stack([rng.uniform(-40, 40, n), rng.uniform(-40, 40, n),
                           rng.uniform(190, 235, n), rng.uniform(-0.15, 0.15, n),
                           rng.uniform(-0.15, 0.15, n), rng.uniform(-0.6, 0.6, n)])
    ph_poses = np.array(reachable_pro_hep_lct(n, rng))
    lifted = six + [0, 0, 10.0, 0, 0, 0]
    ur_poses = reachable_urrh_rcm(n, rng)
    lm_poses = np.column_stack([rng.uniform(-15, 15, n), rng.uniform(100, 125, n),
                                rng.uniform(20, 90, n)])  # 003: around Table 2's path
    return {
        "planar_tripod": (pt, six, {}, lambda j: hw.planar_tripod(six, jacobian=j)),
        "stewart": (st, lifted, {}, lambda j: hw.stewart(lifted, jacobian=j)),
        "pro_hep_lct": (ph, ph_poses, G,
                        lambda j: hw.pro_hep_lct(ph_poses, G, (1.0, -1.0, 1.0), jacobian=j)),
        "tripod_planar": (tp, tp.pose_from_paper_coordinates(six), {},
                          lambda j: hw.tripod_planar(six, jacobian=j)),
        "urrh_rcm": (ur, ur_poses, {},
                     lambda j: hw.urrh_rcm(ur_poses, ur.PARAMETERS, jacobian=j)),
        "lamina_milling": (lm, lm_poses, {},
                           lambda j: hw.lamina_milling(lm_poses, lm.PARAMETERS, jacobian=j)),
    }, six


def hand_written_benchmarks(n=1_000_000):
    """Issue 15's baseline: the generated functions (limits off) against hand-written numpy
    of the same closed forms (bench/hand_written.py), IK and IK + Jacobian, on the same
    poses: the numpy runtime (``fast=False``) and the compiled fast path (``fast=True``, all
    cores); ratio = hand-written time / generated time (>= 1: the generated code is as
    fast).  IK + Jacobian is ``ik_and_jacobian`` (one solve for both).  Where the module has
    forward kinematics, ``fk`` of every assembly mode on the joints of a fiftieth of the
    poses (mode 0, limits off)."""
    import hand_written as hw
    from bonered_alg.generated import urrh_rcm as ur

    rng = np.random.default_rng(15)
    cases, six = _hand_written_cases(n, rng)
    out = {"poses": n, "threads": compiled.threads()}
    for name, (m, poses, par, hand) in cases.items():
        row = {"poses": len(poses)}
        for fast in (False, True):
            m.ik(poses[:10], limits=False, fast=fast, **par)  # built before timing
        t_hand, *t_gen = interleaved_medians(
            [lambda h=hand: h(False)] + [lambda m=m, p=poses, k=par, f=fast: m.ik(
                p, limits=False, fast=f, **k) for fast in (False, True)], 7)
        row["hand_written_ik_poses_per_s"] = len(poses) / t_hand
        for (label, fast), t in zip((("numpy", False), ("compiled", True)), t_gen):
            row[f"{label}_ik_poses_per_s"] = len(poses) / t
            row[f"{label}_ik_ratio_vs_hand_written"] = t_hand / t
            row[f"{label}_max_rel_difference_ik"] = _max_rel(
                m.ik(poses, limits=False, fast=fast, **par), hand(False))
        t_hand_j, *t_gen = interleaved_medians(
            [lambda h=hand: h(True)] + [lambda m=m, p=poses, k=par, f=fast:
                                        m.ik_and_jacobian(p, limits=False, fast=f, **k)
                                        for fast in (False, True)], 5)
        row["hand_written_ik_plus_jacobian_poses_per_s"] = len(poses) / t_hand_j
        ref = hand(True)[1]
        for (label, fast), t in zip((("numpy", False), ("compiled", True)), t_gen):
            row[f"{label}_ik_plus_jacobian_poses_per_s"] = len(poses) / t
            row[f"{label}_ik_plus_jacobian_ratio_vs_hand_written"] = t_hand_j / t
            jac = m.ik_and_jacobian(poses, limits=False, fast=fast, **par)[1]
            if name == "tripod_planar":  # the hand form's J is in 001's coordinates
                jac, ref = _tripod_planar_in_paper_coordinates(m, six, jac, ref)
                row["jacobian_compared_on_poses"] = len(ref)
            row[f"{label}_max_rel_difference_jacobian"] = _max_rel(jac, ref)
        # every working mode: ik_all against ik mode by mode, on a tenth of the poses, in
        # numpy and on the compiled path
        sub = poses[: len(poses) // 10]
        row["ik_all_modes"] = m.MODES
        for label, fast in (("numpy", False), ("compiled", True)):
            t_modes, t_all = interleaved_medians(
                [lambda m=m, p=sub, k=par, f=fast: [m.ik(p, mode=j, limits=False, fast=f, **k)
                                                    for j in range(m.MODES)],
                 lambda m=m, p=sub, k=par, f=fast: m.ik_all(p, limits=False, fast=f, **k)], 3)
            row.update({f"{label}_ik_all_poses_per_s": len(sub) / t_all,
                        f"{label}_ik_all_speedup_vs_ik_mode_by_mode": t_modes / t_all})
        if m.FK_MODES:  # forward kinematics, every assembly mode, in numpy (the only path)
            qf = m.ik(poses[: n // 50], limits=False, fast=False, **par)
            qf = qf[np.all(np.isfinite(qf), axis=-1)]
            t_fk = median_time(lambda m=m, q=qf, k=par: m.fk(q, **k), 3)
            row.update({"fk_modes": m.FK_MODES, "fk_all_modes_configurations": len(qf),
                        "generated_fk_all_modes_configurations_per_s": len(qf) / t_fk})
        if name == "urrh_rcm":  # forward kinematics, every assembly mode
            q = ur.ik(poses, limits=False)[: n // 10]
            t_hand_fk = median_time(lambda q=q: hw.urrh_rcm_fk(q, ur.PARAMETERS), 3)
            t_fk = median_time(lambda q=q: ur.fk(q), 3)
            row.update({"fk_configurations": len(q),
                        "hand_written_fk_4_modes_per_s": len(q) / t_hand_fk,
                        "generated_fk_8_modes_per_s": len(q) / t_fk,
                        "fk_ratio_vs_hand_written": t_hand_fk / t_fk})
        if name == "lamina_milling":  # 003's statics: both methods against the hand form
            row.update(_statics_benchmark(m, poses[: len(poses) // 10], rng, hw))
        out[name] = row
        print(name, row, flush=True)
    return out


def lambdified_mechanism(name, m, par):
    """``(ik, ik_and_jacobian, build_s)`` of plain ``sympy.lambdify`` and of
    ``lambdify(cse=True)`` (keys "plain", "cse"): the mode-0 IK of the derivation's steps
    (``Derivation.ik_expressions``, each later step's root with the earlier ones inserted,
    angle joints as 2 atan(t)) in the module's joint order, with the module's parameters
    (``par`` over its defaults), and d(IK)/d(pose) by sympy; the baseline a user of sympy
    would write.  ``ik(p)`` -> (n, joints), ``ik_and_jacobian(p)`` -> (q, (n, joints,
    pose))."""
    d = derive(name).derivation
    mech = d.mechanism
    roots: dict = {}
    for q, e in d.ik_expressions().items():
        roots[q] = e.xreplace(roots)
    values = {**m.PARAMETERS, **par}
    geo = {p: values[str(p)] for p in mech.geometric}
    pose = list(mech.pose.coordinates)
    by_name = {mech.public_joint(q): 2 * sp.atan(e) if q in mech.angle_joints else e
               for q, e in roots.items()}
    exprs = [by_name[j].xreplace(geo) for j in m.JOINTS]
    extra = set().union(*(e.free_symbols for e in exprs)) - set(pose)
    if extra:
        raise ValueError(f"{name}: the IK expressions still contain {sorted(map(str, extra))}")
    jac = list(sp.Matrix(exprs).jacobian(sp.Matrix(pose)))
    nq, nx = len(exprs), len(pose)
    out = {}
    for label, cse in (("plain", False), ("cse", True)):
        t0 = time.perf_counter()
        lam_ik = sp.lambdify(pose, exprs, modules="numpy", cse=cse)
        lam_j = sp.lambdify(pose, [*exprs, *jac], modules="numpy", cse=cse)
        build = time.perf_counter() - t0

        def ik(p, f=lam_ik):
            return np.stack(np.broadcast_arrays(*f(*p.T)), axis=-1)

        def ik_j(p, f=lam_j):
            r = np.broadcast_arrays(*f(*p.T))
            return (np.stack(r[:nq], axis=-1),
                    np.stack(r[nq:], axis=-1).reshape(len(p), nq, nx))

        out[label] = (ik, ik_j, build)
    return out


def batch_size_benchmarks(sizes=(1_000, 10_000, 100_000), plain_at=10_000):
    """IK and IK + Jacobian per batch size (limits off), interleaved medians: the
    hand-written numpy (bench/hand_written.py), ``sympy.lambdify(cse=True)`` of the
    derivation's IK (plain ``lambdify`` too at ``plain_at`` poses only: it is 10-1000x
    slower), the numpy runtime and the compiled fast path.  Ratios are hand-written time /
    time (>= 1: as fast as the hand form).  hand_written_benchmarks gives 10^6 poses; at
    these sizes the hand form's temporaries stay in cache too."""
    lam: dict = {}
    out: dict = {"sizes": list(sizes)}
    for n in sizes:
        cases, _ = _hand_written_cases(n, np.random.default_rng(16))
        for name, (m, poses, par, hand) in cases.items():
            if name not in lam:
                lam[name] = lambdified_mechanism(name, m, par)
                out.setdefault(name, {})["lambdify_build_s"] = {
                    k: v[2] for k, v in lam[name].items()}
            labels = ["hand_written", "lambdify_cse", "numpy", "compiled"]
            with_plain = n == plain_at
            if with_plain:
                labels.append("lambdify")
            row = {"poses": len(poses)}
            for what, jac in (("ik", False), ("ik_plus_jacobian", True)):
                gen = m.ik_and_jacobian if jac else m.ik
                k = 0 if not jac else 1
                fns = [lambda h=hand, j=jac: h(j),
                       lambda f=lam[name]["cse"][k], p=poses: f(p),
                       *[lambda g=gen, p=poses, a=par, f=fast: g(p, limits=False, fast=f, **a)
                         for fast in (False, True)]]
                if with_plain:
                    fns.append(lambda f=lam[name]["plain"][k], p=poses: f(p))
                for fn in fns:
                    fn()  # built and warm
                # about 0.2 s a round for the fastest; plain lambdify once or twice
                t = interleaved_medians(fns, 3 if with_plain and jac else 5)
                for label, tk in zip(labels, t):
                    row[f"{label}_{what}_poses_per_s"] = len(poses) / tk
                    row[f"{label}_{what}_ratio_vs_hand_written"] = t[0] / tk
                ref = gen(poses, limits=False, fast=False, **par)
                got = fns[1]()
                row[f"lambdify_cse_{what}_max_rel_difference_vs_numpy"] = (
                    _max_rel(got[1], ref[1]) if jac else _max_rel(got, ref))
            out[name][str(n)] = row
            print(name, n, row, flush=True)
    return out


def one_pose_benchmarks(calls=2000):
    """The cost of one call on one pose (a control loop's use): microseconds per call of the
    hand-written numpy, the numpy runtime and the compiled fast path, IK and IK + Jacobian,
    limits off (median over 7 interleaved rounds of ``calls`` calls each); where the module
    has forward kinematics, ``fk`` and ``fk_status`` of that pose's joints (numpy, the only
    path; ``calls // 20`` calls a round), and urrh_rcm's hand-written FK of them."""
    import hand_written as hw

    out = {"calls_per_round": calls}
    for name, (m, poses, par, hand) in _hand_written_cases(1, np.random.default_rng(15))[0].items():
        if poses.shape[0] != 1:
            raise RuntimeError(f"one_pose: {name} has {poses.shape[0]} poses, not one")
        row = {}
        if m.FK_MODES:
            q = m.ik(poses, limits=False, **par)
            fns = [lambda f=f, q=q, k=par: f(q, **k) for f in (m.fk, m.fk_status)]
            labels = ["fk", "fk_status"]
            if name == "urrh_rcm":
                fns.append(lambda q=q, g=m.PARAMETERS: hw.urrh_rcm_fk(q, g))
                labels.append("hand_written_fk")
            for fn in fns:
                fn()
            times = interleaved_medians([lambda fn=fn: [fn() for _ in range(calls // 20)]
                                         for fn in fns], 7)
            for label, t in zip(labels, times):
                row[f"{label}_one_configuration_us"] = t / (calls // 20) * 1e6
        for label, jac in (("ik", False), ("ik_plus_jacobian", True)):
            gen = m.ik_and_jacobian if jac else m.ik
            fns = [lambda h=hand, j=jac: h(j)] + [
                lambda g=gen, p=poses, k=par, f=fast: g(p, limits=False, fast=f, **k)
                for fast in (False, True)]
            for fn in fns:
                fn()  # built and warm before timing

            def calls_of(fn):
                return lambda: [fn() for _ in range(calls)]
            times = interleaved_medians([calls_of(fn) for fn in fns], 7)
            for who, t in zip(("hand_written", "numpy", "compiled"), times):
                row[f"{who}_{label}_us"] = t / calls * 1e6
            for who, t in zip(("numpy", "compiled"), times[1:]):
                row[f"{who}_{label}_ratio_vs_hand_written"] = times[0] / t
        out[name] = row
        print(name, {k: round(v, 2) for k, v in row.items()}, flush=True)
    return out


def _tripod_planar_in_paper_coordinates(m, paper, jac, ref, k=2000):
    """The generated dq/dX of the first ``k`` poses as dq/dp in 001's coordinates p
    (``paper``), dq/dp = dq/dX dX/dp with dX/dp by central differences of the module's
    ``pose_from_paper_coordinates`` (step 1e-6: an error of about 1e-9 relative, far below
    what the comparison is for), next to the hand form's ``ref`` of those poses."""
    p = paper[:k]
    dxdp = np.empty((len(p), 6, 6))
    for i in range(6):
        e = np.zeros(6)
        e[i] = 1e-6
        dxdp[:, :, i] = (m.pose_from_paper_coordinates(p + e)
                         - m.pose_from_paper_coordinates(p - e)) / 2e-6
    return jac[:k] @ dxdp, ref[:k]


def _statics_benchmark(m, poses, rng, hw):
    """003's static_efforts, both methods, against hand_written.lamina_milling_statics."""
    load = rng.normal(scale=5.0, size=poses.shape)
    t_hand = median_time(lambda: hw.lamina_milling_statics(poses, load, m.PARAMETERS), 3)
    ref = hw.lamina_milling_statics(poses, load, m.PARAMETERS)
    row = {"statics_poses": len(poses), "hand_written_statics_poses_per_s": len(poses) / t_hand}
    for method in ("virtual_work", "free_body"):
        t = median_time(lambda f=method: m.static_efforts(poses, load, method=f), 3)
        row[f"{method}_statics_poses_per_s"] = len(poses) / t
        row[f"{method}_statics_ratio_vs_hand_written"] = t_hand / t
        row[f"{method}_max_rel_difference_statics"] = _max_rel(
            m.static_efforts(poses, load, method=method), ref)
    # memory bounded at any batch size (runtime.model.STATICS_CHUNK, FREE_BODY_CHUNK): the
    # peak of numpy's allocations at two batch sizes, ten times apart
    for method, sizes in (("virtual_work", (10_000, 100_000)), ("free_body", (1_000, 10_000))):
        for k in sizes:
            row[f"{method}_statics_peak_mb_at_{k}_poses"] = _peak_mb(
                lambda f=method, k=k: m.static_efforts(poses[:k], load[:k], method=f))
    return row


def _peak_mb(fn) -> float:
    """The peak of the memory allocated while ``fn()`` runs (tracemalloc: numpy reports its
    arrays' data to it), in MB."""
    import tracemalloc

    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


def reachable_urrh_rcm(n, rng):
    """n poses of the +-30 deg workspace (002 Sect. 5.2) where mode 0 is real."""
    from bonered_alg.generated import urrh_rcm as ur

    out, have = [], 0
    while have < n:
        p = np.column_stack([rng.uniform(-0.45, 0.45, n), rng.uniform(-0.45, 0.45, n),
                             rng.uniform(60, 90, n), rng.uniform(-1.5, 1.5, n)])
        p = p[np.isfinite(ur.ik(p, limits=False, fast=False)).all(axis=-1)]
        out.append(p)
        have += len(p)
    return np.concatenate(out)[:n]


def _max_rel(a, b):
    """max |a - b| / (1 + |b|) over the entries both give (per matrix: relative to its
    largest entry, so that an entry near zero in a near-singular matrix is not divided by
    itself)."""
    scale = 1 + (np.nanmax(np.abs(b), axis=(-2, -1), keepdims=True) if b.ndim == 3
                 else np.abs(b))
    return float(np.nanmax(np.abs(a - b) / scale))


def bandwidth_bound(n_bytes=400_000_000):
    """Memory bandwidth of this process (numpy copy and triad on arrays far larger than the
    caches, one thread): bytes moved per second, the median of 5."""
    a = np.ones(n_bytes // 8)
    b = np.empty_like(a)
    c = np.full_like(a, 2.0)
    t_copy = median_time(lambda: np.copyto(b, a), 5)
    # a = b + 3 c in two passes (numpy cannot fuse them): 5 streams of n_bytes
    t_triad = median_time(lambda: (np.multiply(c, 3.0, out=a), np.add(a, b, out=a)), 5)
    return {"copy_bytes_per_s": 2 * n_bytes / t_copy, "triad_bytes_per_s": 5 * n_bytes / t_triad,
            "array_bytes": n_bytes}


def membership_benchmarks(n=4_000_000):
    """The workspace membership test (IK and every limit: ``ik_and_status``, limits on) of
    the compiled fast path on one thread and on every core, against the memory-bandwidth
    bound of the same run: a pose is read (len(POSE) doubles) and its joints and status
    written (len(JOINTS) doubles + 1 byte), so bandwidth / bytes per pose bounds the rate."""
    from bonered_alg.generated import planar_tripod as pt
    from bonered_alg.generated import stewart as st
    from bonered_alg.generated import tripod_planar as tp

    bw = bandwidth_bound()
    out = {"bandwidth": bw, "poses": n, "threads": compiled.threads()}
    rng = np.random.default_rng(8)
    for name, m in (("planar_tripod", pt), ("tripod_planar", tp), ("stewart", st)):
        poses = np.asarray(m.HOME) + rng.uniform(-1, 1, (n, 6)) * [40, 40, 30, 0.15, 0.15, 0.6]
        m.ik_and_status(poses[:10], fast=True)
        rates = {}
        for threads in (1, compiled.threads()):
            os.environ["BONERED_ALG_THREADS"] = str(threads)
            rates[threads] = n / median_time(lambda m=m, p=poses: m.ik_and_status(p, fast=True),
                                             5)
        os.environ.pop("BONERED_ALG_THREADS")
        t_np = median_time(lambda m=m, p=poses[: n // 4]: m.ik_and_status(p, fast=False), 3)
        per_pose = 8 * (len(m.POSE) + len(m.JOINTS)) + 1
        bound = bw["copy_bytes_per_s"] / per_pose
        best = max(rates.values())
        row = {"compiled_poses_per_s_1_thread": rates[1],
               "compiled_poses_per_s_all_cores": best,
               "speedup_all_cores": best / rates[1],
               "numpy_poses_per_s": (n // 4) / t_np,
               "bytes_per_pose": per_pose, "bandwidth_bound_poses_per_s": bound,
               "fraction_of_bandwidth_bound": best / bound,
               "inside": float(np.mean(m.ik_status(poses[:100_000]) == m.OK))}
        out[name] = row
        print(name, row, flush=True)
    return out


def reachable_pro_hep_lct(n, rng):
    """n poses of the Pro-Hep-LCT's planar chains (test geometry) built forward from joints
    reachable by both lower chains and the upper rod.  Candidates are drawn max(3n, 64) at
    a time until n are reachable (about a third are).  Before 2026-12-07 they were drawn
    3n once: the bench then timed a few per cent fewer poses than asked (969 for 1,000 in
    batch_sizes, 997,082 in hand_written: each row's ``poses``), and for the one-pose
    bench (3 candidates) none at all."""
    from independent_pro_hep_lct import GEOMETRY as g
    from independent_pro_hep_lct import lower_leg1, upper

    kept = []
    while sum(p.shape[1] for p in kept) < n:
        k = max(3 * n, 64)
        th1, th2 = rng.uniform(-1.2, 1.2, k), rng.uniform(-2.6, -0.2, k)
        pd = lower_leg1(th1, th2)
        r = np.hypot(pd[0], pd[1] + g["d"] / 2 - g["lq4d"])
        kept.append(pd[:, (abs(g["l3"] - g["l4"]) + 5 < r) & (r < g["l3"] + g["l4"] - 5)])
    pd = np.concatenate(kept, axis=1)[:, :n]
    q5 = rng.uniform(100, 300, pd.shape[1])
    q4 = q5 - rng.uniform(20, 150, pd.shape[1])
    xu, yu = upper(q4, q5)
    return np.column_stack([xu, yu, pd[0], pd[1]])


def platform_ideal(engine, budget_s):
    """The mobile platform's ideal G of pro_hep_lct (both mounted chains), no cache."""
    from bonered_alg.solvers.legs import Elimination

    mech = phl.MECHANISM
    closure = mech.closure("platform")
    algebra = Algebra(engine, budget_s, use_cache=False)
    return [Elimination().derive(mech, closure, leg, algebra) for leg in closure.legs]


FAST_PATH_PROBE = """
import sys, time
t0 = time.perf_counter()
import importlib
import numpy
t1 = time.perf_counter()
m = importlib.import_module("bonered_alg.generated." + sys.argv[1])
t2 = time.perf_counter()
pose = numpy.array([getattr(m, "HOME", None) or [0.0] * len(m.POSE)])
m.ik(pose, limits=False, fast=True)  # fast=True: an error where the fast path is missing
t3 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2)
"""


def fast_path_build_benchmarks(repeat=3):
    """Issue 15: the compiled fast path costs at most 5 s on the first call after a fresh
    install and 0.3 s per later import.  Each mechanism in fresh processes: the import of
    numpy, of its generated module, then its first ``ik(..., fast=True)``, with an empty
    library cache (the first call builds the library) and with the cache that build left
    (a later import: the first call only loads it); medians of ``repeat`` runs of each.
    ``first_call_after_install_s`` is the whole process's cost after a fresh install
    (imports included), ``fast_path_later_s`` what the fast path adds to a later import."""
    import tempfile

    from bonered_alg.registry import REGISTRY
    out = {}
    for name in REGISTRY:
        cold, warm = [], []
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as cache:
                env = {**os.environ, "BONERED_ALG_CACHE": cache}
                for into in (cold, warm):
                    run = subprocess.run([sys.executable, "-c", FAST_PATH_PROBE, name],
                                         capture_output=True, text=True, env=env, check=True,
                                         cwd=ROOT)
                    into.append([float(v) for v in run.stdout.split()])
        out[name] = {
            "first_call_after_install_s": statistics.median(sum(r) for r in cold),
            "first_call_build_s": statistics.median(r[2] for r in cold),
            "later_import_and_first_call_s": statistics.median(sum(r) for r in warm),
            "later_module_import_s": statistics.median(r[1] for r in warm),
            "fast_path_later_s": statistics.median(r[2] for r in warm),
        }
    out["compiler_flags"] = " ".join((*compiled.FLAGS, *compiled.isa_flags()))
    print(out, flush=True)
    return out


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def _machine() -> dict:
    """What the figures depend on: the interpreter, numpy, sympy, Singular, the CPU, its
    count and the malloc settings."""
    return {"python": platform.python_version(), "numpy": np.__version__,
            "cpu": _cpu_model(), "glibc_tunables": os.environ.get("GLIBC_TUNABLES"),
            "sympy": sp.__version__, "cpus": os.cpu_count(),
            "singular": SingularEngine().version() if SingularEngine().available() else None}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results.json")
    ap.add_argument("--poses", type=int, default=1_000_000)
    ap.add_argument("--sympy-budget", type=float, default=60.0)
    ap.add_argument("--only", choices=["workspace", "pro_hep_lct_tool", "hand_written",
                                       "one_pose", "membership", "derive",
                                       "fast_path_build", "batch_sizes"],
                    default=None,
                    help="re-run one section and merge it into the --out file (a new file gets "
                         "that section and the machine)")
    args = ap.parse_args()
    if args.only:
        # merged into the file's other sections; a new file gets the machine's description
        results = (json.loads(args.out.read_text()) if args.out.exists()
                   else {"machine": _machine()})
        results[args.only] = {"workspace": workspace_benchmarks,
                              "pro_hep_lct_tool": pro_hep_lct_tool_benchmarks,
                              "hand_written": hand_written_benchmarks,
                              "one_pose": one_pose_benchmarks,
                              "membership": membership_benchmarks,
                              "derive": derive_benchmarks,
                              "fast_path_build": fast_path_build_benchmarks,
                              "batch_sizes": batch_size_benchmarks}[args.only]()
        atomic_write_text(args.out, json.dumps(results, indent=2, sort_keys=True) + "\n")
        print(f"wrote {args.out} ({args.only} section)")
        return
    derivation = derive("pro_hep_lct").derivation
    results = {
        "machine": _machine(),
        "elimination": elimination_benchmarks(args.sympy_budget),
        "derive": derive_benchmarks(),
        "throughput": throughput_benchmarks(args.poses, derivation),
        "planar_tripod": planar_tripod_benchmarks(args.poses),
        "tripod_planar": tripod_planar_benchmarks(args.poses),
        "workspace": workspace_benchmarks(),
        "hand_written": hand_written_benchmarks(),
        "batch_sizes": batch_size_benchmarks(),
        "one_pose": one_pose_benchmarks(),
        "membership": membership_benchmarks(),
        "fast_path_build": fast_path_build_benchmarks(),
        "pro_hep_lct_tool": pro_hep_lct_tool_benchmarks(sympy_budget=args.sympy_budget),
    }
    atomic_write_text(args.out, json.dumps(results, indent=2, sort_keys=True) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
