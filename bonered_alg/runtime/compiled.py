"""The compiled fast path of a generated module (``generated/<name>.c``).

On first use the C file is compiled with the system C compiler (``$CC``, else ``cc``) into
a shared library in the cache directory (``$BONERED_ALG_CACHE``, else
``$XDG_CACHE_HOME/bonered_alg`` or ``~/.cache/bonered_alg``), named by a hash of the
sources, the compiler and its flags, and loaded with ctypes; later imports load it
directly.  Large batches are split over threads (ctypes releases the GIL during the call):
``$BONERED_ALG_THREADS``, else the number of cores.  ``BONERED_ALG_FAST=0`` switches the
fast path off (the numpy runtime is the reference and the fallback); where no compiler is
found or compiling fails, the numpy runtime is used and :attr:`FastPath.reason` says why.

Flags: ``-O3 -ffp-contract=off -fno-math-errno -fno-trapping-math -fopenmp-simd`` and no
``-ffast-math``: IEEE arithmetic in the order the kernels are written (no fused
multiply-adds, NaN and infinity kept), vectorized across the poses of a block
(``generated/<name>.c``'s block loops; ``-fno-trapping-math`` lets the compiler evaluate
both sides of a select, which changes no value), with the elementary functions from glibc's
vector math library where ``bonered_fast.h`` declares them (at most 4 ulp from scalar libm:
the library agrees with the numpy kernels to rounding, ``tests/test_fast_path.py``).  On
x86-64 the instruction set is the build machine's (``-march=native``, the CPU's model and
flags in the cache key, so a cache shared between machines holds one library per CPU);
``BONERED_ALG_MARCH`` overrides it (e.g. ``x86-64-v3``; empty: the compiler's default), and
AVX-512 CPUs get 512-bit vectors (:func:`isa_flags`).
"""

from __future__ import annotations

import ctypes
import dataclasses
import hashlib
import math
import os
import shutil
import subprocess
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy

FLAGS = ("-O3", "-fPIC", "-shared", "-ffp-contract=off", "-fno-math-errno",
         "-fno-trapping-math", "-fopenmp-simd", "-std=c99")
HEADER_DIR = Path(__file__).resolve().parent / "c"
C_ABI = 3
# poses per thread below which one thread does the whole batch
MIN_PER_THREAD = 20_000
# numpy operations on arrays of a kernel (its scalar preludes, Python floats, cost little)
# below which its compiled twin (FastPath.rows) is not used: on a few rows numpy costs
# about a microsecond per array operation, the twin's wrapper 20-50
ROW_KERNEL_MIN_OPERATIONS = 40

_lock = threading.Lock()
_pool: ThreadPoolExecutor | None = None


def enabled_by_environment() -> bool:
    return os.environ.get("BONERED_ALG_FAST", "1").strip().lower() not in ("0", "false", "no",
                                                                           "off")


def _cpu_identity() -> bytes:
    """The CPU's model and instruction-set flags (Linux ``/proc/cpuinfo``; elsewhere what
    :mod:`platform` knows): part of the cache key of a ``-march=native`` build."""
    try:
        text = Path("/proc/cpuinfo").read_text(errors="replace")
    except OSError:
        import platform
        return f"{platform.machine()} {platform.processor()}".encode()
    keep = []
    for line in text.splitlines():
        key = line.split(":", 1)[0].strip()
        if key in ("model name", "flags", "Features", "CPU part", "isa") and line not in keep:
            keep.append(line)
        if not line.strip() and keep:
            break  # the first processor's entry is enough
    return "\n".join(keep).encode()


def isa_flags() -> tuple[str, ...]:
    """``-march=...`` for this machine: ``$BONERED_ALG_MARCH`` if set (empty for none),
    else ``native`` on x86-64 (other architectures: the compiler's default).  On x86-64 also
    ``-mprefer-vector-width=512``: gcc's default for AVX-512 CPUs is 256-bit vectors, and the
    kernels are arithmetic-bound (on this machine's AVX-512 Xeon, IK + Jacobian 6-11 %
    faster on one thread; without AVX-512 the flag changes nothing)."""
    import platform
    x86 = platform.machine() in ("x86_64", "AMD64")
    wide = ("-mprefer-vector-width=512",) if x86 else ()
    env = os.environ.get("BONERED_ALG_MARCH")
    if env is not None:
        march = env.strip()
        if march and not all(ch.isalnum() or ch in "-_." for ch in march):
            raise RuntimeError(f"BONERED_ALG_MARCH must name an architecture, got {env!r}")
        return ((f"-march={march}",) if march else ()) + wide
    return ("-march=native", *wide) if x86 else ()


def cache_dir() -> Path:
    env = os.environ.get("BONERED_ALG_CACHE")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "bonered_alg"


def threads() -> int:
    env = os.environ.get("BONERED_ALG_THREADS")
    if env:
        try:
            return max(1, int(env))
        except ValueError:
            raise ValueError(f"BONERED_ALG_THREADS must be a positive integer, got {env!r}") \
                from None
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
               else (os.cpu_count() or 1))


def _build(cc: str, flags: tuple[str, ...], source: Path, text: bytes, out: str) -> None:
    """Compile ``source`` into the shared library ``out``.  A file written in translation
    units (``BF_PART``, :mod:`bonered_alg.codegen.c_module`) is compiled one compiler
    process per unit, all at once, then linked: the first call's cost is the largest
    unit's, not the sum (tripod_planar on this project's 2-core machine: 2.7 s, not 5.2)."""
    parts = [p for p in (1, 2) if b"BF_PART == %d" % p in text]

    def failed(run) -> RuntimeError:
        return RuntimeError(f"{cc} failed: {run.stderr.decode(errors='replace')[:2000]}")

    if not parts:
        run = subprocess.run([cc, *flags, "-I", str(HEADER_DIR), "-o", out, str(source),
                              "-lm"], capture_output=True, timeout=300)
        if run.returncode != 0:
            raise failed(run)
        return
    compile_flags = [f for f in flags if f != "-shared"]
    with tempfile.TemporaryDirectory(dir=Path(out).parent) as tmp:
        objects = [str(Path(tmp) / f"part{p}.o") for p in parts]
        procs = [subprocess.Popen([cc, *compile_flags, f"-DBF_PART={p}", "-I", str(HEADER_DIR),
                                   "-c", "-o", o, str(source)],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                 for p, o in zip(parts, objects)]
        errors = []
        for proc in procs:
            try:
                _, err = proc.communicate(timeout=300)
            except subprocess.TimeoutExpired:
                for other in procs:
                    other.kill()
                    other.wait()
                raise
            if proc.returncode != 0:
                errors.append(err.decode(errors="replace"))
        if errors:
            raise RuntimeError(f"{cc} failed: {errors[0][:2000]}")
        run = subprocess.run([cc, *flags, "-o", out, *objects, "-lm"], capture_output=True,
                             timeout=300)
        if run.returncode != 0:
            raise failed(run)


def _over_threads(n: int, work: int, run) -> None:
    """``run(lo, hi)`` over ``[0, n)``: in one call, or split evenly over up to
    :func:`threads` threads where ``work`` (in poses of ``bonered_solve``) gives each at
    least MIN_PER_THREAD."""
    k = max(1, work // MIN_PER_THREAD)
    if k > 1:  # reading the environment and the CPU affinity only where it can matter
        k = min(threads(), k)
    if k == 1:
        run(0, n)
        return
    bounds = [n * i // k for i in range(k + 1)]
    futures = [_executor(k).submit(run, bounds[i], bounds[i + 1]) for i in range(k)]
    for f in futures:
        f.result()


def _parameter_vector(par) -> numpy.ndarray:
    """The parameters as a contiguous float64 array: ``check.parameters``' own where it
    made one (scalars), else built."""
    vector = getattr(par, "vector", None)
    if vector is not None:
        return vector
    return numpy.ascontiguousarray([float(v) for v in par], dtype=numpy.float64)


def _rows(a: numpy.ndarray) -> tuple[int, int]:
    """``(address of row 0, bytes per row)`` of a C-contiguous array: row ``lo`` starts at
    ``address + lo * bytes`` (what ``a[lo:].ctypes.data`` gives, without building a ctypes
    view per call)."""
    if not a.flags.c_contiguous:
        raise ValueError("the compiled fast path takes C-contiguous arrays")
    return _address(a), a.itemsize * (math.prod(a.shape[1:]))


def _address(a: numpy.ndarray) -> int:
    """The address of an array's first element: ``a.ctypes.data`` (about 0.8 microsecond a
    call, four calls in each compiled call), through the buffer protocol where the array is
    C-contiguous, writable and not empty (about 0.3; a strided array goes to ctypes.data
    directly: the buffer protocol's refusal costs 0.5 more)."""
    if not a.flags.c_contiguous:
        return a.ctypes.data
    try:
        return ctypes.addressof(ctypes.c_char.from_buffer(a))
    except (TypeError, ValueError, BufferError):  # read-only or empty
        return a.ctypes.data


_last_parameters: tuple = (None, 0)  # (the last parameter vector, its address)


def _parameter_address(vector: numpy.ndarray) -> int:
    """The address of a parameter vector, kept for the last one (a module's checked
    defaults are one read-only vector, passed on every call)."""
    global _last_parameters
    last, address = _last_parameters
    if vector is not last:
        address = vector.ctypes.data
        _last_parameters = (vector, address)
    return address


def _executor(n: int) -> ThreadPoolExecutor:
    global _pool
    with _lock:
        if _pool is None or _pool._max_workers < n:  # noqa: SLF001
            _pool = ThreadPoolExecutor(max_workers=n, thread_name_prefix="bonered_fast")
        return _pool


class FastPath:
    """The compiled IK, limits and Jacobian of one generated module, built lazily."""

    def __init__(self, source: Path, mechanism: str, derivation_hash: str, n_pose: int,
                 n_joints: int, n_par: int):
        self.source = source
        self.mechanism = mechanism
        self.derivation_hash = derivation_hash
        self.n_pose, self.n_joints, self.n_par = n_pose, n_joints, n_par
        self.reason = ""  # why the fast path is unavailable, once tried
        self._lib = None
        self._tried = False
        self._rows: dict[str, RowKernel | None] = {}
        self._fk = None  # (a ForwardKinematics, its twin with compiled kernels)

    @classmethod
    def beside(cls, module_file: str | None, mechanism: str, derivation_hash: str,
               n_pose: int, n_joints: int, n_par: int) -> FastPath | None:
        """The fast path of the generated module at ``module_file`` (``<name>.c`` beside
        it), None where the module was not imported from a file."""
        if not module_file:
            return None
        return cls(Path(module_file).with_suffix(".c"), mechanism, derivation_hash, n_pose,
                   n_joints, n_par)

    # ------------------------------------------------------------ building
    def library(self):
        """The loaded library, or None (``reason`` says why)."""
        if self._tried:
            return self._lib
        with _lock:
            if not self._tried:
                try:
                    self._lib = self._load()
                except (OSError, RuntimeError, subprocess.SubprocessError) as exc:
                    self.reason = f"{self.mechanism}: compiled fast path unavailable: {exc}"
                    self._lib = None
                self._tried = True
        return self._lib

    def _load(self):
        if not self.source.is_file():
            raise RuntimeError(f"{self.source} not found")
        text = self.source.read_bytes()
        if self.derivation_hash.encode() not in text:
            raise RuntimeError(f"{self.source} is not of derivation {self.derivation_hash[:12]}"
                               " (stale: run `make derive`)")
        header = (HEADER_DIR / "bonered_fast.h").read_bytes()
        cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
        if not cc:
            raise RuntimeError("no C compiler (cc, gcc or $CC) found")
        version = subprocess.run([cc, "--version"], capture_output=True, timeout=30).stdout
        flags = (*FLAGS, *isa_flags())
        cpu = _cpu_identity() if "-march=native" in flags else b""
        key = hashlib.sha256(b"\0".join([text, header, version, " ".join(flags).encode(), cpu]))
        lib = cache_dir() / f"{self.mechanism}-{key.hexdigest()[:16]}.so"
        if not lib.is_file():
            lib.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(suffix=".so", dir=lib.parent)
            os.close(fd)
            try:
                _build(cc, flags, self.source, text, tmp)
                os.replace(tmp, lib)  # atomic: a concurrent build writes the same bytes
            finally:
                if os.path.exists(tmp):
                    os.unlink(tmp)
        handle = ctypes.CDLL(str(lib))
        if handle.bonered_abi() != C_ABI:
            raise RuntimeError(f"{lib} has C ABI {handle.bonered_abi()}, expected {C_ABI}")
        found = (ctypes.c_char * (len(self.derivation_hash) + 1)).in_dll(
            handle, "bonered_derivation_hash")
        if found.value.decode() != self.derivation_hash:
            raise RuntimeError(f"{lib} is of another derivation")
        fn = handle.bonered_solve
        fn.restype = None
        fn.argtypes = [ctypes.c_long, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int,
                       ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                       ctypes.c_int]
        fn = handle.bonered_scan
        fn.restype = ctypes.c_long
        fn.argtypes = [ctypes.c_long, ctypes.c_long, ctypes.c_int, *[ctypes.c_void_p] * 5,
                       ctypes.c_int, *[ctypes.c_void_p] * 6]
        if hasattr(handle, "bonered_solve_all"):  # not for a tree of roots too large
            fn = handle.bonered_solve_all
            fn.restype = None
            fn.argtypes = [ctypes.c_long, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int,
                           ctypes.c_void_p, ctypes.c_int]
        return handle

    # ------------------------------------------------------------ calling
    def solve(self, pose: numpy.ndarray, par, mode: int, limits: bool, jacobian: bool,
              public: bool = False):
        """IK (and dq/dX) of poses (..., n_pose) with scalar parameters: (q, status, J or
        None), shapes as the numpy runtime returns them; with ``public``, the angle joints
        as angles and their rows of dq/dX in radians (``Model.publish``'s conversion, done
        in C), else the algebra's tan-half-angles."""
        lib = self.library()
        shape = pose.shape[:-1]
        n = math.prod(shape)
        flat = numpy.ascontiguousarray(pose, dtype=numpy.float64).reshape(n, self.n_pose)
        parv = _parameter_vector(par)
        q = numpy.empty((n, self.n_joints))
        status = numpy.empty(n, dtype=numpy.int8)
        jac = numpy.empty((n, self.n_joints, self.n_pose)) if jacobian else None
        # addresses of row 0 and bytes per row (rows lo: start at base + lo * row)
        (fp, fr), (qp, qr), (sp, sr) = (_rows(a) for a in (flat, q, status))
        jp, jr = _rows(jac) if jacobian else (None, 0)
        pp, mode, limits, public = (_parameter_address(parv), int(mode), int(bool(limits)),
                                    int(bool(public)))

        def run(lo: int, hi: int) -> None:
            lib.bonered_solve(hi - lo, fp + lo * fr, pp, mode, limits, qp + lo * qr,
                              sp + lo * sr, None if jp is None else jp + lo * jr, public)

        _over_threads(n, n, run)
        return (q.reshape(shape + (self.n_joints,)), status.reshape(shape),
                None if jac is None else jac.reshape(shape + (self.n_joints, self.n_pose)))

    def solve_all(self, pose: numpy.ndarray, par, modes: int, limits: bool,
                  public: bool = True):
        """Every working mode's joints of poses (..., n_pose): (..., modes, n_joints), the
        numbers :meth:`solve` gives mode by mode, each IK step's coefficients evaluated
        once per choice of the roots its kernel reads (``bonered_solve_all``); None where
        the library has no such entry (the caller then solves mode by mode)."""
        lib = self.library()
        if not hasattr(lib, "bonered_solve_all"):
            return None
        shape = pose.shape[:-1]
        n = math.prod(shape)
        flat = numpy.ascontiguousarray(pose, dtype=numpy.float64).reshape(n, self.n_pose)
        parv = _parameter_vector(par)
        q = numpy.empty((n, modes, self.n_joints))
        (fp, fr), (qp, qr) = _rows(flat), _rows(q)
        pp, limits, public = _parameter_address(parv), int(bool(limits)), int(bool(public))

        def run(lo: int, hi: int) -> None:
            lib.bonered_solve_all(hi - lo, fp + lo * fr, pp, limits, qp + lo * qr, public)

        _over_threads(n, n * modes, run)  # a pose costs about ``modes`` poses of solve
        return q.reshape(shape + (modes, self.n_joints))

    def rows(self, kern):
        """The compiled twin of the numpy kernel ``kern`` (``bonered_rows_<name>``): a
        :class:`RowKernel` taking the same arguments, or None where the library has none."""
        name = getattr(kern, "__name__", "")
        if name not in self._rows:
            lib = self.library()
            fn = getattr(lib, f"bonered_rows_{name}", None) if lib is not None else None
            if fn is not None:
                shape = (ctypes.c_int * 4).in_dll(lib, f"bonered_rows_{name}_shape")
                n_in, n_out, n_numbers, array_ops = (int(v) for v in shape)
                if array_ops < ROW_KERNEL_MIN_OPERATIONS:
                    fn = None  # numpy's cost per call is below the wrapper's
                else:
                    fn.restype = None
                    fn.argtypes = [ctypes.c_long, ctypes.c_void_p, ctypes.c_void_p,
                                   ctypes.c_void_p]
                    numbers = (ctypes.c_int * max(n_numbers, 1)).in_dll(
                        lib, f"bonered_rows_{name}_numbers")
                    fn = RowKernel(fn, kern, n_in, n_out,
                                   frozenset(int(numbers[i]) for i in range(n_numbers)))
            self._rows[name] = fn
        return self._rows[name]

    def forward_kinematics(self, fk):
        """``fk`` (a :class:`~.model.ForwardKinematics`) with its back-substitution steps,
        charts, Newton system and 3-RPS kernels evaluated by their compiled twins
        (:meth:`rows`) where the library has them; kept for the next call."""
        if self._fk is not None and self._fk[0] is fk:
            return self._fk[1]

        def steps(rows):
            return tuple((degree, self.rows(kern) or kern, bit) for degree, kern, bit in rows)

        rps = fk.rps
        if rps is not None:
            rps = dataclasses.replace(rps, **{
                f.name: self.rows(getattr(rps, f.name)) or getattr(rps, f.name)
                for f in dataclasses.fields(rps)})
        out = dataclasses.replace(
            fk, steps=steps(fk.steps), rps=rps,
            charts=tuple((steps(rows), index) for rows, index in fk.charts),
            newton=None if fk.newton is None else (self.rows(fk.newton) or fk.newton))
        self._fk = (fk, out)
        return out

    def scan(self, start: int, stop: int, axes: list[tuple[int, float, float, int]],
             fixed: numpy.ndarray, modes, par, keep_mask: bool):
        """Samples ``start:stop`` of a grid (C order) classified by working modes ``modes``
        with the module's own limits, in one call without the GIL (``bonered_scan`` of
        ``generated/<name>.c``).  ``axes``: per grid axis ``(pose index, lo, step, n)``;
        ``fixed``: a full pose holding the fixed coordinates.  Returns ``(count, lo, hi,
        reasons, packed)``: the reached samples, each axis's extremes over them (inf, -inf
        where none), ``{code: samples}``, and the mask as ``numpy.packbits`` bytes or
        None."""
        lib = self.library()
        naxes = len(axes)
        shape = numpy.array([a[3] for a in axes], dtype=numpy.int64)
        lo = numpy.array([a[1] for a in axes], dtype=numpy.float64)
        step = numpy.array([a[2] for a in axes], dtype=numpy.float64)
        coord = numpy.array([a[0] for a in axes], dtype=numpy.intc)
        fixed = numpy.ascontiguousarray(fixed, dtype=numpy.float64)
        modes = numpy.array(list(modes), dtype=numpy.intc)
        parv = _parameter_vector(par)
        axis_lo = numpy.full(naxes, numpy.inf)
        axis_hi = numpy.full(naxes, -numpy.inf)
        reasons = numpy.zeros(128, dtype=numpy.int64)
        m = max(stop - start, 0)
        packed = numpy.zeros((m + 7) // 8, dtype=numpy.uint8) if keep_mask else None
        count = lib.bonered_scan(
            start, stop, naxes, shape.ctypes.data, lo.ctypes.data, step.ctypes.data,
            coord.ctypes.data, fixed.ctypes.data, len(modes), modes.ctypes.data,
            parv.ctypes.data, axis_lo.ctypes.data, axis_hi.ctypes.data, reasons.ctypes.data,
            packed.ctypes.data if keep_mask else None)
        found = numpy.flatnonzero(reasons)
        return (int(count), axis_lo, axis_hi,
                {int(c): int(reasons[c]) for c in found},
                packed.tobytes() if keep_mask else None)


class RowKernel:
    """A kernel of the numpy module evaluated by its C twin (``bonered_rows_<name>`` of
    ``generated/<name>.c``): called as the numpy kernel is (each argument a number or an
    array, broadcast together), it returns what the numpy kernel returns, an array per
    output of the arguments' shape (a number for an output of the parameters alone).  The
    C program is the numpy program operation for operation (integer powers as products in
    both: the same numbers, bit for bit), without a temporary array per operation and
    without numpy's cost per call, about a microsecond, per operation: urrh_rcm's Newton
    system (1,884 operations, 55 outputs) on 8 rows took 6.3 us in C against 0.95-1.17 ms
    in numpy, and this wrapper about 50 us more (20-30 for a step's three outputs)."""

    def __init__(self, fn, kern, n_in: int, n_out: int, numbers: frozenset[int]):
        self.fn, self.n_in, self.n_out = fn, n_in, n_out
        # the outputs of the parameters alone, which the numpy kernel returns as numbers
        self.numbers = numbers
        self._numbers = sorted(numbers)
        self.__name__ = kern.__name__
        self.__doc__ = kern.__doc__
        self._pointers = ctypes.c_void_p * n_in
        self._steps = ctypes.c_long * n_in
        self._row_offsets = 8 * numpy.arange(n_out, dtype=numpy.uint64)  # times the rows

    def __call__(self, *args):
        out, shape, n = self.matrix(*args)
        values = list(out[:, :n].reshape((self.n_out,) + shape))
        if self._numbers:
            for m, v in zip(self._numbers, out[self._numbers, 0].tolist()):
                values[m] = v
        return tuple(values)

    def matrix(self, *args):
        """``(out, shape, n)``: every output of the ``n`` rows of the arguments' broadcast
        ``shape`` as a row of ``out`` (n_out, max(n, 1)), the numbers' rows too (the values
        :meth:`__call__` returns, without a view per output)."""
        if len(args) != self.n_in:
            raise TypeError(f"{self.__name__}: {len(args)} arguments, expected {self.n_in}")
        shape, arrays, scalars = None, [], []
        for j, a in enumerate(args):
            if isinstance(a, numpy.ndarray) and a.ndim:
                if a.dtype != numpy.float64:
                    a = a.astype(numpy.float64)
                if shape is None:
                    shape = a.shape
                elif a.shape != shape:
                    shape = numpy.broadcast_shapes(shape, a.shape)
                arrays.append((j, a))
            else:
                scalars.append(float(a))
        shape = () if shape is None else shape
        n = math.prod(shape)
        run = max(n, 1 if self.numbers else 0)  # no row: one, for the numbers
        pointers, steps = self._pointers(), self._steps()
        keep = [numpy.array(scalars or [0.0]), numpy.zeros(1)]  # alive through the call
        address = _address(keep[0])
        at_arrays, k = {i for i, _ in arrays}, 0
        for j in range(self.n_in):  # the scalar arguments in order: one value for every row
            if j not in at_arrays:
                pointers[j] = address + 8 * k
                k += 1
        for j, a in arrays:
            if n == 0:  # nothing to read: the numbers' row reads a zero
                pointers[j] = _address(keep[1])
                continue
            if a.shape != shape:
                a = numpy.broadcast_to(a, shape)
            if a.ndim != 1:
                a = a.reshape(n)  # a view where the strides allow, else a copy
            if a.strides[0] % 8:
                a = numpy.ascontiguousarray(a)
            keep.append(a)
            pointers[j] = _address(a)
            steps[j] = a.strides[0] // 8
        out = numpy.empty((self.n_out, run))
        rows = _address(out) + self._row_offsets * run  # each output's row
        if run:
            self.fn(run, pointers, steps, _address(rows))
        return out, shape, n
