"""The compiled fast path (generated/<name>.c, bonered_alg.runtime.compiled) against the
numpy runtime, the reference: the same status codes pose by pose, the same NaN, values equal
to 1e-12 relative (issue 15, item 2); its switches, its cache and its failures."""

import importlib
import re

import numpy as np
import pytest
from conftest import ROOT, assert_close, in_joint_quantities

from bonered_alg.runtime import compiled
from bonered_alg.runtime import status as st

NAMES = ["planar_tripod", "tripod_planar", "pro_hep_lct", "stewart", "urrh_rcm",
         "lamina_milling"]
# half-widths of the random perturbation of HOME: mm for lengths, rad for angles
SPREAD = {"planar_tripod": (40, 40, 40, 0.3, 0.3, 0.8),
          "tripod_planar": (60, 60, 60, 0.4, 0.4, 0.8),
          "stewart": (60, 60, 60, 0.4, 0.4, 0.8), "pro_hep_lct": (120, 120, 120, 120),
          "urrh_rcm": (0.6, 0.6, 60, 3.0), "lamina_milling": (60, 60, 80)}


def _module(name):
    return importlib.import_module(f"bonered_alg.generated.{name}")


def _poses(name, n, seed=0):
    """HOME perturbed (reachable and unreachable poses: every status the limits give), a
    non-finite row and an exactly repeated row."""
    m = _module(name)
    rng = np.random.default_rng(seed)
    home, spread = np.asarray(m.HOME), np.asarray(SPREAD[name])
    p = home + rng.uniform(-1, 1, (n, len(home))) * spread
    p[0] = home
    p[1, 0] = np.nan
    p[2, -1] = np.inf
    p[3] = p[4]
    return p


def _close(m, a, b, Ja=None, Jb=None):
    """The fast path's joints (and Jacobian) against numpy's: equal NaN patterns and equal
    to 1e-12 relative in the joints' own quantities (tan(theta/2) joints as angles:
    conftest.in_joint_quantities)."""
    ta, Ta = in_joint_quantities(m, a, Ja)
    tb, Tb = in_joint_quantities(m, b, Jb)
    assert_close(ta, tb)
    if Ta is not None:
        assert_close(Ta, Tb)


def test_header_status_codes_are_the_runtime_codes():
    text = (ROOT / "bonered_alg" / "runtime" / "c" / "bonered_fast.h").read_text()
    codes = dict(re.findall(r"#define BF_(\w+) (\S+)", text))
    for name in ("OK", "NO_REAL_SOLUTION", "JOINT_AT_INFINITY", "ON_BOUNDARY", "INPUT_SINGULAR",
                 "INVALID_INPUT", "STROKE_LIMIT", "PASSIVE_JOINT_LIMIT"):
        assert int(codes[name]) == getattr(st, name), name
    assert float(codes["DISC_RTOL"]) == st.DISC_RTOL and float(codes["DET_RTOL"]) == st.DET_RTOL


@pytest.mark.parametrize("name", NAMES)
def test_generated_c_is_of_the_same_derivation(name):
    m = _module(name)
    text = (ROOT / "generated" / f"{name}.c").read_text()
    assert f"Derivation hash: {m.DERIVATION_HASH}" in text
    assert m._MODEL.fast is not None and m._MODEL.fast.library() is not None, \
        m._MODEL.fast.reason


@pytest.mark.parametrize("name", NAMES)
def test_compiled_agrees_with_numpy_in_every_mode(name):
    m = _module(name)
    poses = _poses(name, 3000)
    seen = set()
    for limits in (True, False):
        for mode in range(min(m.MODES, 8)):
            qa, Ja, sa = m.ik_and_jacobian(poses, mode=mode, limits=limits, fast=False)
            qb, Jb, sb = m.ik_and_jacobian(poses, mode=mode, limits=limits, fast=True)
            assert (sa == sb).all(), np.flatnonzero(sa != sb)[:5]
            _close(m, qa, qb, Ja, Jb)
            q1, s1 = m.ik_and_status(poses, mode=mode, limits=limits, fast=True)
            assert (s1 == m.ik_status(poses, mode=mode, limits=limits, fast=False)).all()
            _close(m, m.ik(poses, mode=mode, limits=limits, fast=False), q1)
            seen |= set(np.unique(sa).tolist())
    assert {st.OK, st.INVALID_INPUT} <= seen and len(seen) >= 3, seen
    _close(m, m.ik_all(poses[:200], fast=False), m.ik_all(poses[:200], fast=True))


@pytest.mark.parametrize("name", NAMES)
def test_compiled_ik_all_is_compiled_ik_mode_by_mode(name, monkeypatch):
    """ik_all on the fast path (bonered_solve_all: each IK step once per choice of the
    earlier roots, both roots of a quadratic from one set of coefficients) gives the
    numbers of ik mode by mode bit for bit, with and without limits, over threads and any
    leading shape; and it is that entry that answers, not the loop over the modes."""
    m = _module(name)
    assert hasattr(m._MODEL.fast.library(), "bonered_solve_all")
    poses = _poses(name, 2 * compiled.MIN_PER_THREAD + 11, seed=5)
    monkeypatch.setenv("BONERED_ALG_THREADS", "2")
    for limits in (True, False):
        every = m.ik_all(poses.reshape(-1, 1, len(m.POSE)), limits=limits, fast=True)
        assert every.shape == (len(poses), 1, m.MODES, len(m.JOINTS))
        for mode in range(m.MODES):
            one = m.ik(poses, mode=mode, limits=limits, fast=True)
            assert np.array_equal(every[:, 0, mode], one, equal_nan=True), (limits, mode)
        assert np.isfinite(every).any() and np.isnan(every).any()
    single = m.ik_all(poses[0], fast=True)
    assert single.shape == (m.MODES, len(m.JOINTS))
    assert np.array_equal(single, m.ik_all(poses[:1], fast=True)[0], equal_nan=True)


@pytest.mark.parametrize("name", NAMES)
def test_a_poses_numbers_do_not_depend_on_its_batch(name):
    """The fast path hands its stages whole vector lanes only (bonered_fast.h, BF_LANES:
    a batch's partial last block overlaps the block before, a batch under 8 poses is
    padded), so no pose goes through a loop's scalar remainder (scalar libm, a few ulp from
    libmvec): a pose alone, in batches of 13 and of 203, at any place in them, gets the
    same joints, Jacobian and status to the bit, and ik_all the same in batches of 5."""
    m = _module(name)
    poses = _poses(name, 203, seed=9)

    def same(a, b):
        return all(np.array_equal(x, y, equal_nan=True) for x, y in zip(a, b))

    whole = m.ik_and_jacobian(poses, fast=True)
    for k in range(0, 203, 7):
        assert same([r[0] for r in m.ik_and_jacobian(poses[k:k + 1], fast=True)],
                    [r[k] for r in whole]), k
    thirteens = [m.ik_and_jacobian(poses[k:k + 13], fast=True) for k in range(0, 203, 13)]
    assert same([np.concatenate(r) for r in zip(*thirteens)], whole)
    every = m.ik_all(poses, limits=False, fast=True)
    fives = np.concatenate([m.ik_all(poses[k:k + 5], limits=False, fast=True)
                            for k in range(0, 203, 5)])
    assert np.array_equal(fives, every, equal_nan=True)
    assert np.isfinite(whole[0]).any() and (whole[2] != 0).any()


def test_large_batches_split_over_threads_give_the_same_answer(monkeypatch):
    m = _module("planar_tripod")
    poses = _poses("planar_tripod", 3 * compiled.MIN_PER_THREAD + 7, seed=3)
    monkeypatch.setenv("BONERED_ALG_THREADS", "1")
    q1, J1, s1 = m.ik_and_jacobian(poses, fast=True)
    monkeypatch.setenv("BONERED_ALG_THREADS", "3")
    q3, J3, s3 = m.ik_and_jacobian(poses.reshape(-1, 1, 6), fast=True)  # any leading shape
    assert q3.shape == (len(poses), 1, 6) and J3.shape == (len(poses), 1, 6, 6)
    assert np.array_equal(q1, q3[:, 0], equal_nan=True) and (s1 == s3[:, 0]).all()
    assert np.array_equal(J1, J3[:, 0], equal_nan=True)


def test_switches(monkeypatch):
    m = _module("planar_tripod")
    home = np.asarray(m.HOME)
    monkeypatch.delenv("BONERED_ALG_FAST", raising=False)  # `bonered-alg derive` sets it
    assert m._MODEL._fast_path("ik", None, [190.0, 190.0]) is m._MODEL.fast
    monkeypatch.setenv("BONERED_ALG_FAST", "0")
    assert m._MODEL._fast_path("ik", None, [190.0, 190.0]) is None
    assert m._MODEL._fast_path("ik", True, [190.0, 190.0]) is m._MODEL.fast  # keyword wins
    monkeypatch.delenv("BONERED_ALG_FAST")
    # array parameters: numpy; required fast path: a clear error
    ra = np.array([190.0, 195.0])
    q = m.ik(np.stack([home, home]), ra=ra)
    assert np.isfinite(q).all()
    with pytest.raises(RuntimeError, match="planar_tripod.ik: fast=True.*arrays"):
        m.ik(np.stack([home, home]), ra=ra, fast=True)


def test_module_without_its_c_file_falls_back_and_says_why(tmp_path):
    """An in-memory module (the pipeline's own import) has no .c beside it; a stale .c (of
    another derivation) is refused."""
    src = (ROOT / "generated" / "pro_hep_lct.py").read_text()
    ns = {}
    exec(compile(src, "<in memory>", "exec"), ns)  # noqa: S102 - our own generated output
    home = np.asarray(ns["HOME"])
    assert np.isfinite(ns["ik"](home)).all()
    with pytest.raises(RuntimeError, match="not imported from a file"):
        ns["ik"](home, fast=True)
    (tmp_path / "pro_hep_lct.c").write_text("/* Derivation hash: 0123 */\n")
    fp = compiled.FastPath.beside(str(tmp_path / "pro_hep_lct.py"), "pro_hep_lct",
                                  ns["DERIVATION_HASH"], 4, 4, 1)
    assert fp.library() is None and "stale" in fp.reason


def test_the_library_is_built_once_into_the_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("BONERED_ALG_CACHE", str(tmp_path / "cache"))
    m = _module("pro_hep_lct")
    args = (str(ROOT / "generated" / "pro_hep_lct.py"), "pro_hep_lct", m.DERIVATION_HASH,
            len(m.POSE), len(m.JOINTS), len(m.PARAMETERS))
    assert compiled.FastPath.beside(*args).library() is not None
    built = list((tmp_path / "cache").glob("pro_hep_lct-*.so"))
    assert len(built) == 1
    stamp = built[0].stat().st_mtime_ns
    assert compiled.FastPath.beside(*args).library() is not None
    assert built[0].stat().st_mtime_ns == stamp  # loaded, not rebuilt
    monkeypatch.setenv("CC", str(tmp_path / "no-such-compiler"))
    monkeypatch.setenv("BONERED_ALG_CACHE", str(tmp_path / "other"))
    fp = compiled.FastPath.beside(*args)
    assert fp.library() is None and "no-such-compiler" in fp.reason


def test_the_file_built_in_parts_is_the_file_built_whole(tmp_path, monkeypatch):
    """generated/<name>.c is built as two translation units compiled at once (the Jacobian
    stage, BF_PART 2, beside the rest), which is what keeps the first call within 5 s
    (bench: fast_path_build); compiled whole, as one compiler call without BF_PART, the
    file is the same program: the same joints, Jacobians and codes bit for bit."""
    import subprocess

    name = "lamina_milling"  # angle joints: the Jacobian stage takes ``public`` too
    m = _module(name)
    source = ROOT / "generated" / f"{name}.c"
    assert b"BF_PART == 1" in source.read_bytes() and b"BF_PART == 2" in source.read_bytes()
    args = (str(ROOT / "generated" / f"{name}.py"), name, m.DERIVATION_HASH, len(m.POSE),
            len(m.JOINTS), len(m.PARAMETERS))
    units = []
    popen = subprocess.Popen

    def counted(cmd, *a, **k):
        units.extend(c for c in cmd if c.startswith("-DBF_PART="))  # (and cc --version, link)
        return popen(cmd, *a, **k)

    monkeypatch.setattr(compiled.subprocess, "Popen", counted)
    monkeypatch.setenv("BONERED_ALG_CACHE", str(tmp_path / "parts"))
    parts = compiled.FastPath.beside(*args)
    assert parts.library() is not None, parts.reason
    assert sorted(units) == ["-DBF_PART=1", "-DBF_PART=2"]
    build = compiled._build  # noqa: SLF001
    monkeypatch.setattr(compiled, "_build", lambda cc, flags, src, text, out: build(
        cc, flags, src, b"", out))  # no parts declared: one compiler call on the whole file
    monkeypatch.setenv("BONERED_ALG_CACHE", str(tmp_path / "whole"))
    whole = compiled.FastPath.beside(*args)
    assert whole.library() is not None, whole.reason
    assert len(units) == 2
    poses = _poses(name, 3000, seed=4)
    par = [m.PARAMETERS[k] for k in m.PARAMETERS]
    for limits, public in ((True, True), (False, False)):
        a = parts.solve(poses, par, 0, limits, True, public)
        b = whole.solve(poses, par, 0, limits, True, public)
        for x, y in zip(a, b):
            assert np.array_equal(x, y, equal_nan=True)
        assert st.OK in a[1] and (a[1] != st.OK).any()


def test_numpy_chunks_give_the_unchunked_answer():
    """A batch larger than CHUNK (evaluated chunk by chunk, array parameters split alike)
    equals the same poses evaluated in small batches, which are never chunked."""
    from bonered_alg.runtime import model

    m = _module("planar_tripod")
    n = 2 * model.CHUNK + 5
    poses = _poses("planar_tripod", n, seed=9).reshape(n, 1, 6)
    ra = np.linspace(185.0, 195.0, n).reshape(n, 1)
    q, J, s = m.ik_and_jacobian(poses, ra=ra, fast=False)
    assert q.shape == (n, 1, 6) and J.shape == (n, 1, 6, 6) and s.shape == (n, 1)
    step = 1000
    for lo in range(0, n, step):
        part = m.ik_and_jacobian(poses[lo:lo + step], ra=ra[lo:lo + step], fast=False)
        assert np.array_equal(part[0], q[lo:lo + step], equal_nan=True)
        assert np.array_equal(part[1], J[lo:lo + step], equal_nan=True)
        assert np.array_equal(part[2], s[lo:lo + step])
    assert np.array_equal(m.ik(poses, ra=ra, fast=False), q, equal_nan=True)


def test_elementary_functions_several_c_kernels_take_are_computed_once():
    """codegen.c_module: tan(alpha/2), taken by two kernels (one through a temporary), is
    computed once in ``_shared`` and passed in; a function of a joint, or one kernel's only,
    is left where it is."""
    import sympy as sp

    from bonered_alg.codegen.kernels import (
        c_function,
        kernel,
        shareable_functions,
        shared_functions,
    )

    a, b, q = sp.symbols("alpha beta q", real=True)
    k1 = kernel("_k1", [a, b], [sp.tan(a / 2) ** 2 + sp.tan(a / 2), sp.cos(b)], "", c=True)
    k2 = kernel("_k2", [a, b, q], [sp.tan(a / 2) * q + sp.sin(q), sp.tan(a / 2 + q)], "",
                c=True)
    found = [shareable_functions(k, {"alpha", "beta"}) for k in (k1, k2)]
    shared = shared_functions(found)
    assert shared == [sp.tan(a / 2)]
    f = {shared[0]: sp.Symbol("_f0")}
    for k, applications in zip((k1, k2), found):
        source, args = c_function(k, f, applications)
        assert args == ("_f0", *k.arguments)
        assert "tan((0.5)*v_alpha)" not in source and "v__f0" in source
    source, _ = c_function(k2, f, found[1])
    assert "sin(v_q)" in source and "tan(" in source  # tan(alpha/2 + q) stays
    assert "cos(v_beta)" in c_function(k1, f, found[0])[0]


FK_NAMES = ["planar_tripod", "tripod_planar", "pro_hep_lct", "urrh_rcm", "lamina_milling"]


def _bits_equal(a, b):
    """The same float64 bits everywhere (NaN as NaN, of any sign)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    both = np.isnan(a) & np.isnan(b)
    return a.shape == b.shape and np.array_equal(np.where(both, 0.0, a).view(np.uint64),
                                                 np.where(both, 0.0, b).view(np.uint64))


@pytest.mark.parametrize("name", FK_NAMES)
def test_compiled_fk_kernels_are_the_numpy_kernels_to_the_bit(name):
    """Every kernel forward kinematics evaluates through the library (the back-substitution
    steps of every chart, the Newton system and the 3-RPS kernels: ``bonered_rows_<name>``)
    returns the numpy kernel's numbers bit for bit: the same program, operation for
    operation (integer powers as products in both, SMALL_POWER), on arguments from 1e-3 to
    1e3 in magnitude and of both signs, arrays and numbers mixed; its numbers are numbers
    where numpy's are.  A kernel below ROW_KERNEL_MIN_OPERATIONS stays numpy."""
    import ctypes
    import inspect

    m = _module(name)
    fast, spec = m._MODEL.fast, m._MODEL.fk
    kernels = [k for rows, _ in ((spec.steps, None), *spec.charts) for _, k, _ in rows]
    kernels += [spec.newton] if spec.newton is not None else []
    if spec.rps is not None:
        kernels += [getattr(spec.rps, f) for f in ("coefficients", "equations", "centres",
                                                   "platform", "study")]
    assert kernels
    rng = np.random.default_rng(15)
    twins = 0
    for kern in kernels:
        twin = fast.rows(kern)
        if twin is None:  # numpy's cost per call below the twin's: numpy
            shape = (ctypes.c_int * 4).in_dll(fast.library(),
                                              f"bonered_rows_{kern.__name__}_shape")
            assert shape[3] < compiled.ROW_KERNEL_MIN_OPERATIONS  # operations on arrays
            continue
        twins += 1
        args = [m.PARAMETERS[a] if a in m.PARAMETERS
                else rng.choice([-1, 1], 300) * 10.0 ** rng.uniform(-3, 3, 300)
                for a in inspect.signature(kern).parameters]
        assert len(args) == twin.n_in
        first = next(i for i, a in enumerate(args) if np.ndim(a))
        args[first] = args[first][:1]  # broadcast from one row
        for a, b in zip(kern(*args), twin(*args)):
            assert isinstance(b, float) == isinstance(a, float), kern.__name__
            assert _bits_equal(np.broadcast_to(a, (300,)), np.broadcast_to(b, (300,))), \
                kern.__name__
    assert twins >= 2


@pytest.mark.parametrize("name", FK_NAMES)
def test_compiled_fk_is_numpy_fk_to_the_bit(name):
    """fk and fk_status through the compiled kernels: the same poses and statuses as numpy,
    bit for bit, on configurations from the IK, perturbed ones (some modes not real), NaN
    joints, one configuration at a time and a leading shape of two axes."""
    m = _module(name)
    poses = _poses(name, 300, seed=9)
    q = np.concatenate([m.ik(poses, mode=k, limits=False) for k in range(min(m.MODES, 4))])
    q = q[np.isfinite(q).all(axis=-1)][:300]
    rng = np.random.default_rng(9)
    q = np.concatenate([q, q * rng.uniform(0.9, 1.1, q.shape), np.full((2, q.shape[1]),
                                                                        np.nan)])
    for batch in (q, q[:1], q[-1], q[:24].reshape(4, 6, -1)):
        a, sa = m.fk(batch, fast=False), m.fk_status(batch, fast=False)
        b, sb = m.fk(batch, fast=True), m.fk_status(batch, fast=True)
        assert _bits_equal(a, b) and np.array_equal(sa, sb)
    assert (sa == st.OK).any()


def test_compiled_fk_switches():
    """``fast`` of fk as of ik: a bad value is refused, True with parameters per
    configuration (numpy only) is a clear error, None then takes numpy."""
    m = _module("urrh_rcm")
    q = m.ik(np.asarray(m.HOME, dtype=float))
    with pytest.raises(TypeError, match="urrh_rcm.fk: fast must be None, True or False"):
        m.fk(q, fast="yes")
    p = np.array([m.PARAMETERS["p"], m.PARAMETERS["p"]])
    with pytest.raises(RuntimeError, match="urrh_rcm.fk_status: fast=True.*arrays"):
        m.fk_status(np.stack([q, q]), p=p, fast=True)
    assert _bits_equal(m.fk(np.stack([q, q]), p=p), m.fk(np.stack([q, q]), fast=False))
