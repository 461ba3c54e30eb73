"""The numeric model behind a generated module: its tables, its kernels, and every public
function of the generated-module contract (DESIGN.md section 4).

A generated module builds one :class:`Model` from its tables and kernels and exposes thin
wrappers around its methods; the algorithms live here, once, linted and unit-tested.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy

from . import fk as fk_solver
from . import inputs as check
from . import statics
from .backsubstitution import backsubstitute, backsubstitute_modes
from .compiled import enabled_by_environment
from .inputs import broadcast, columns, contiguous_columns, rows_last, stacked
from .status import (
    DET_RTOL,
    INPUT_SINGULAR,
    INVALID_INPUT,
    JOINT_AT_INFINITY,
    NO_REAL_SOLUTION,
    NOT_SOLVED,
    OK,
    ON_BOUNDARY,
    PASSIVE_JOINT_LIMIT,
    STROKE_LIMIT,
)

Kernel = Callable[..., tuple]


@dataclass(frozen=True)
class RPSKernels:
    """Kernels of a 3-RPS closure solved through its eliminant (:mod:`.rps`)."""

    coefficients: Kernel
    equations: Kernel
    centres: Kernel
    platform: Kernel
    study: Kernel


@dataclass(frozen=True)
class ForwardKinematics:
    """The forward-kinematics tables: ``modes`` assembly modes (0: not generated, ``note``
    says why), an eliminant closure (``rps``), back-substitution ``steps`` for the
    ``unknowns`` (Study coordinates of the triangular closures) with their Newton kernel,
    ``pose``, the pose coordinates from the solved Study coordinates, and ``charts``,
    other plans of the same unknowns for where a mode of ``steps`` fails its check."""

    modes: int = 0
    note: str = ""
    rps: RPSKernels | None = None
    steps: tuple = ()
    index: tuple[int, ...] = ()
    unknowns: tuple[str, ...] = ()
    mode_bits: tuple = ()
    newton: Kernel | None = None
    pose: Kernel | None = None
    # (steps, index) of the same unknowns from lex bases in other elimination orders
    charts: tuple = ()


@dataclass(frozen=True)
class Model:
    """Tables and kernels of one generated module (names as in the module's constants)."""

    mechanism: str
    parameters: Mapping[str, float]
    parameter_units: Mapping[str, str]
    parameter_notes: Mapping[str, str]
    pose: tuple[str, ...]
    study_pose: tuple[str, ...]
    joints: tuple[str, ...]
    modes: int
    study: Kernel
    steps: tuple
    solve_index: tuple[int, ...]
    jac: Kernel
    ji: Kernel
    jo_study: Kernel
    singularity_kernels: Mapping[str, Kernel]
    pivots: Kernel | None = None
    limits: tuple = ()
    limit_kernel: Kernel | None = None
    passive: tuple = ()  # per leg: ((kind, kernel, output indices), ...)
    passive_names: tuple[str, ...] = ()
    twist: Kernel | None = None
    helical: Kernel | None = None
    links: tuple = ()  # ((kernel, first link index, count), ...)
    link_names: tuple[str, ...] = ()
    fk: ForwardKinematics = field(default_factory=ForwardKinematics)
    parameter_domains: Mapping[str, str] = field(default_factory=dict)
    # index in ``steps`` of each linear step whose pivot the ``pivots`` kernel returns
    pivot_steps: tuple[int, ...] = ()
    # per step, the earlier steps whose unknowns its kernel's coefficients contain (empty:
    # every earlier step, as a kernel's arguments say)
    step_uses: tuple = ()
    # every step's (A, B, C) from one program, where no step reads an earlier root (the
    # module's ``_step_coefficients``), used in place of the step kernels; else None
    step_coefficients: Kernel | None = None
    # singularities that are the determinant of a matrix: name -> (kernel of its n*n
    # entries, row-major, in the Study coordinates and joints; n)
    singularity_matrices: Mapping[str, tuple] = field(default_factory=dict)
    # the compiled IK, limits and Jacobian (runtime.compiled.FastPath), or None
    fast: object | None = None
    # indices of the joints given to users as angles: the algebra solves t = tan(q/2), the
    # public functions take and return q = 2 atan(t) (:meth:`public`, :meth:`algebraic`)
    angles: tuple[int, ...] = ()
    # the static model (runtime.statics.Statics), where the declaration gives link weights
    statics: object | None = None
    # elementary functions of the pose (tan(alpha/2), ...) that ``study``, ``jac`` and
    # ``limit_kernel`` take before their own arguments, computed once (the module's
    # ``_shared``); None where those kernels take the pose alone
    shared: Kernel | None = None

    # ------------------------------------------------------------ pose kernels
    def pose_values(self, pose, par) -> tuple:
        """The values of ``shared`` for poses (..., len(POSE)); () without it."""
        return () if self.shared is None else tuple(self.shared(*columns(pose), *par))

    def study_values(self, pose, par, shared=None):
        """The Study map's outputs (one per STUDY_POSE coordinate) of poses (...,
        len(POSE)); ``shared``: their :meth:`pose_values` where already computed."""
        shared = self.pose_values(pose, par) if shared is None else shared
        return self.study(*shared, *columns(pose), *par)

    def limit_kernel_values(self, pose, q, par, shared=None):
        """The limit kernel's outputs (one per LIMITS row) at poses and joints."""
        shared = self.pose_values(pose, par) if shared is None else shared
        return self.limit_kernel(*shared, *columns(pose), *columns(q), *par)

    # ------------------------------------------------------------ angle joints
    def public(self, q):
        """Joints of the algebra (tan-half-angles where ``angles``) as the user's joints,
        ``q = 2 atan(t)`` in (-pi, pi]; a new array when anything changes."""
        if not self.angles or q is None:
            return q
        q = numpy.array(q, dtype=float, copy=True)
        idx = list(self.angles)
        q[..., idx] = 2.0 * numpy.arctan(q[..., idx])
        return q

    def algebraic(self, q):
        """The user's joints as the algebra's: ``t = tan(q/2)`` for the angle joints."""
        if not self.angles:
            return q
        q = numpy.array(q, dtype=float, copy=True)
        idx = list(self.angles)
        q[..., idx] = numpy.tan(0.5 * q[..., idx])
        return q

    def publish(self, q):
        """In place: the algebra's joints ``q`` (tan-half-angles where ``angles``) as the
        user's: the same numbers as :meth:`public`, without a copy (the hot functions call
        it on each chunk, while it is in cache)."""
        for i in self.angles:
            t = q[..., i]
            numpy.arctan(t, out=t)
            t *= 2.0

    @staticmethod
    def dq_dt(t):
        """``dq/dt = 2 / (1 + t^2)`` of an angle joint ``q = 2 atan(t)``: the factor of its
        row of dq/dX (the C driver of ``generated/<name>.c`` writes the same)."""
        return 2.0 / (1.0 + t ** 2)

    def _public_jacobian(self, t, J):
        """``dq/dX`` from ``dt/dX``: the rows of the angle joints times :meth:`dq_dt`
        (``t`` the algebra's joints)."""
        if not self.angles:
            return J
        idx = list(self.angles)
        J = numpy.array(J, dtype=float, copy=True)
        J[..., idx, :] *= self.dq_dt(t[..., idx])[..., None]
        return J

    # ------------------------------------------------------------ inverse kinematics
    def _fast_path(self, func, fast, par):
        """The compiled fast path to use for this call, or None (numpy).  ``fast``: None
        (use it where available and ``BONERED_ALG_FAST`` does not say 0), False (never),
        True (required: an error where it is unavailable)."""
        if fast is not None and not isinstance(fast, (bool, numpy.bool_)):
            raise TypeError(f"{self.mechanism}.{func}: fast must be None, True or False, got "
                            f"{fast!r}")
        if fast is False:
            return None
        if fast is None and not enabled_by_environment():
            return None
        why = ""
        if self.fast is None:
            why = "this module was not imported from a file with its generated .c beside it"
        elif getattr(par, "vector", None) is None and any(numpy.ndim(v) for v in par):
            why = "geometric parameters given as arrays (the fast path takes scalars)"
        elif self.fast.library() is None:
            why = self.fast.reason
        if not why:
            return self.fast
        if fast:
            raise RuntimeError(f"{self.mechanism}.{func}: fast=True, but the compiled fast "
                               f"path cannot be used: {why}")
        return None

    def solve(self, pose, mode, par, with_status=False, limits=True, fast=None,
              func="ik", public=False):
        """Inverse kinematics of one working mode; NaN at input singularities of linear
        steps and, with ``limits``, outside the ranges of ``LIMITS``.

        A linear step ``B q + C = 0`` is singular where its pivot ``B = dG/dq`` vanishes
        relative to the generator's derivatives (the joint is then undetermined).  Through
        the compiled fast path where available (``fast``), else in numpy, in chunks of
        CHUNK poses (temporaries that stay in cache, memory bounded at any batch size).
        ``public``: the joints in the user's units (:meth:`publish`), else the algebra's."""
        compiled = self._fast_path(func, fast, par)
        if compiled is not None:
            q, status, _ = compiled.solve(pose, par, mode, limits, False, public)
            return q, (status if with_status else None)
        return _chunked(pose, par, lambda p, pr: self._solve(p, mode, pr, with_status,
                                                             limits, public))

    def _solve(self, pose, mode, par, with_status, limits, public=False):
        q, status = self._solve_by_columns(pose, mode, par, with_status, limits)
        if public:
            self.publish(q)  # q's columns are rows of a fresh array: contiguous, in cache
        return q, status

    def _solve_by_columns(self, pose, mode, par, with_status, limits, shared=None):
        """``_solve`` with ``q`` a view whose columns are contiguous (the kernels take one
        column per argument: numpy is about 1.7 times slower on strided ones); ``shared``:
        the poses' :meth:`pose_values` where already computed."""
        if shared is None:
            with numpy.errstate(all="ignore"):
                shared = self.pose_values(pose, par)
        study = self._study_columns(pose, par, shared)
        q, status = backsubstitute(study, self.steps, self.solve_index, len(self.joints), mode,
                                   par, with_status, coefficients=self.step_coefficients)
        if with_status and not numpy.isfinite(pose).all():
            status[~numpy.all(numpy.isfinite(pose), axis=-1)] = INVALID_INPUT
        return self._checked(pose, study, q, status, par, with_status, limits, shared)

    def _study_columns(self, pose, par, shared):
        """The poses' Study coordinates (..., len(STUDY_POSE)), each a contiguous column."""
        shape = pose.shape[:-1]
        with numpy.errstate(all="ignore"):
            values = self.study_values(pose, par, shared)
        study = numpy.empty((len(self.study_pose),) + shape)
        for i, v in enumerate(values):
            study[i] = v
        return rows_last(study)

    def _checked(self, pose, study, q, status, par, with_status, limits, shared):
        """``q`` and the status after the pivot check and, with ``limits``, the limits."""
        if self.pivots is not None:
            q, status = self._pivot_check(study, q, status, par, with_status)
        if limits and self.limits:
            q, status = self._limit_check(pose, q, status, par, with_status, shared)
        return q, status

    def _solve_all(self, pose, par, limits, out):
        """``q`` of every working mode written into ``out`` (k, MODES, len(JOINTS)) in the
        user's units: the numbers of :meth:`_solve` mode by mode, with the Study map
        evaluated once and each IK step once per choice of the roots it reads
        (:func:`backsubstitute_modes`, ``step_uses``)."""
        with numpy.errstate(all="ignore"):
            shared = self.pose_values(pose, par)
        study = self._study_columns(pose, par, shared)
        by_mode = backsubstitute_modes(study, self.steps, self.solve_index, len(self.joints),
                                       range(self.modes), par, self.step_uses or None,
                                       self.step_coefficients)
        for mode, q in by_mode:
            q, _ = self._checked(pose, study, q, None, par, False, limits, shared)
            self.publish(q)
            out[..., mode, :] = q

    def _limit_check(self, pose, q, status, par, with_status, shared=None):
        shape = pose.shape[:-1]
        with numpy.errstate(all="ignore"):
            values = self.limit_kernel_values(pose, q, par, shared)
        violated = {"stroke": numpy.zeros(shape, dtype=bool),
                    "passive": numpy.zeros(shape, dtype=bool)}
        for v, (_, lower, upper, kind, _, _) in zip(values, self.limits):
            v = broadcast(v, shape)
            violated[kind] |= (v < lower) | (v > upper)
        out = violated["stroke"] | violated["passive"]
        if not out.any():  # nothing changes
            return q, status
        ok = numpy.all(numpy.isfinite(q), axis=-1)
        q[out] = numpy.nan
        if with_status:
            status = numpy.where(ok & violated["passive"] & (status == OK),
                                 PASSIVE_JOINT_LIMIT, status)
            status = numpy.where(ok & violated["stroke"] & (status != INVALID_INPUT)
                                 & ((status == OK) | (status == PASSIVE_JOINT_LIMIT)),
                                 STROKE_LIMIT, status).astype(numpy.int8)
        return q, status

    def _pivot_check(self, study, q, status, par, with_status):
        shape = study.shape[:-1]
        with numpy.errstate(all="ignore"):
            values = self.pivots(*columns(study), *columns(q), *par)
            half = len(values) // 2
            singular = numpy.zeros(shape, dtype=bool)
            for d, sc in zip(values[:half], values[half:]):
                singular |= numpy.abs(d) <= DET_RTOL * numpy.abs(sc)
        if not singular.any():  # nothing changes
            return q, status
        singular &= numpy.all(numpy.isfinite(q), axis=-1)
        q[singular] = numpy.nan
        if with_status:
            status = numpy.where(singular & (status == OK), INPUT_SINGULAR, status).astype(
                numpy.int8)
        return q, status

    def _ik_args(self, func, pose, mode, limits, params):
        """The checked arguments of an IK function, all before any work."""
        return (check.pose(self, func, pose), check.mode(self, func, mode),
                check.parameters(self, func, params or {}), check.flag(self, func, "limits",
                                                                       limits))

    def ik(self, pose, mode=0, limits=True, params=None, fast=None):
        pose, mode, par, limits = self._ik_args("ik", pose, mode, limits, params)
        return self.solve(pose, mode, par, False, limits, fast, "ik", True)[0]

    def ik_status(self, pose, mode=0, limits=True, params=None, fast=None):
        pose, mode, par, limits = self._ik_args("ik_status", pose, mode, limits, params)
        return self.solve(pose, mode, par, True, limits, fast, "ik_status")[1]

    def ik_and_status(self, pose, mode=0, limits=True, params=None, fast=None):
        pose, mode, par, limits = self._ik_args("ik_and_status", pose, mode, limits, params)
        return self.solve(pose, mode, par, True, limits, fast, "ik_and_status", True)

    def ik_all(self, pose, limits=True, params=None, fast=None):
        pose, _, par, limits = self._ik_args("ik_all", pose, 0, limits, params)
        compiled = self._fast_path("ik_all", fast, par)
        if compiled is not None:
            q = compiled.solve_all(pose, par, self.modes, limits, True)
            if q is not None:
                return q
            return numpy.stack([self.solve(pose, m, par, False, limits, fast, "ik_all",
                                           True)[0] for m in range(self.modes)], axis=-2)
        return _chunked_into(pose, par, (((self.modes, len(self.joints)), float),),
                             lambda p, pr, out: self._solve_all(p, pr, limits, out))[0]

    # ------------------------------------------------------------ why a pose fails
    def _joint_report(self, pose, mode, par, limits):
        """Each joint's own status (``ik_joint_status``) and the numbers behind it: the
        per-step record of the back-substitution, the pivots, the limit values."""
        shape = pose.shape[:-1]
        n = len(self.joints)
        with numpy.errstate(all="ignore"):
            study = stacked(self.study_values(pose, par), shape)
        info: dict = {}
        backsubstitute(study, self.steps, self.solve_index, n, mode, par, True, info,
                       self.step_coefficients)
        roots = info["roots"]  # every step's own root, before the all-or-nothing rule
        codes = numpy.zeros(shape + (n,), dtype=numpy.int8)
        for k, j in enumerate(self.solve_index):
            codes[..., j] = info["codes"][..., k]
        if self.pivots is not None:
            with numpy.errstate(all="ignore"):
                values = self.pivots(*columns(study), *columns(roots), *par)
            half = len(values) // 2
            for k, d, sc in zip(self.pivot_steps, values[:half], values[half:]):
                j = self.solve_index[k]
                singular = numpy.abs(d) <= DET_RTOL * numpy.abs(sc)
                codes[..., j] = numpy.where(singular & (codes[..., j] == OK), INPUT_SINGULAR,
                                            codes[..., j])
        lims = {}
        if limits and self.limits:
            with numpy.errstate(all="ignore"):
                values = self.limit_kernel_values(pose, roots, par)
            for v, lim in zip(values, self.limits):
                v = numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                lims[lim[0]] = v
                bad = (v < lim[1]) | (v > lim[2])
                free = (codes == OK) | (codes == ON_BOUNDARY)
                if lim[0] in self.joints:
                    j = self.joints.index(lim[0])
                    codes[..., j] = numpy.where(bad & free[..., j], STROKE_LIMIT, codes[..., j])
                else:  # a limit of no actuated joint rejects the configuration as a whole
                    code = STROKE_LIMIT if lim[3] == "stroke" else PASSIVE_JOINT_LIMIT
                    codes = numpy.where(bad[..., None] & free, code, codes).astype(numpy.int8)
        codes[~numpy.all(numpy.isfinite(pose), axis=-1)] = INVALID_INPUT
        return codes, info, roots, lims

    def ik_joint_status(self, pose, mode=0, limits=True, params=None):
        """Status per joint (..., len(JOINTS)): the code of the step that solves it, of its
        own stroke limit, NOT_SOLVED where its step uses a joint that failed, and the code of
        a violated limit of no actuated joint (a passive angle) on every joint that has no
        failure of its own.  ``ik`` returns a configuration as a whole or not at all."""
        pose, mode, par, limits = self._ik_args("ik_joint_status", pose, mode, limits, params)
        return _chunked(pose, par, lambda p, pr: (self._joint_report(p, mode, pr, limits)[0],)
                        )[0]

    def ik_explain(self, pose, mode=0, limits=True, params=None):
        """Why ``ik`` returns NaN (or warns) at each pose, in words: a str for one pose,
        an object array of str of shape pose.shape[:-1] for many."""
        pose, mode, par, limits = self._ik_args("ik_explain", pose, mode, limits, params)
        codes, info, roots, lims = self._joint_report(pose, mode, par, limits)
        shape = pose.shape[:-1]
        order = list(self.solve_index)
        out = numpy.empty(shape, dtype=object)
        for idx in numpy.ndindex(*shape):
            out[idx] = self._explain_one(pose[idx], codes[idx], info, roots[idx], lims, idx,
                                         order)
        return out[()] if not shape else out

    def _explain_one(self, pose, codes, info, roots, lims, idx, order):
        if not numpy.all(numpy.isfinite(pose)):
            bad = [p for p, v in zip(self.pose, pose) if not numpy.isfinite(v)]
            return f"pose coordinate(s) {', '.join(bad)} not finite"
        failed = [self.joints[j] for j in order if codes[j] not in (OK, ON_BOUNDARY,
                                                                     STROKE_LIMIT)]
        lines = []
        for j in order:
            q, c = self.joints[j], int(codes[j])
            k = order.index(j)
            disc = info["discriminants"][k]
            if c == NO_REAL_SOLUTION:
                lines.append(f"{q}: no real root (the discriminant of its quadratic step is "
                             f"{float(disc[idx]):.4g} < 0): the pose is out of the reach of "
                             f"the leg that drives {q}")
            elif c == JOINT_AT_INFINITY:
                lines.append(f"{q}: its step has no finite root (a vanishing leading "
                             "coefficient or an overflow: the joint parameter is at infinity, "
                             "e.g. a tan-half-angle at a half-turn)")
            elif c == INPUT_SINGULAR:
                lines.append(f"{q}: input singularity (the pivot dG/d{q} of its linear step "
                             f"vanishes: {q} is undetermined)")
            elif c == NOT_SOLVED:
                before = [p for p in failed if order.index(self.joints.index(p)) < k]
                lines.append(f"{q}: not solved (its step uses {', '.join(before)}, which "
                             "failed)")
            elif c == ON_BOUNDARY:
                lines.append(f"{q}: double root (on the boundary of its leg's reach: the "
                             "value is valid, the Jacobian is not)")
        for name, lower, upper, kind, unit, source in self.limits:
            if name not in lims or not numpy.isfinite(lims[name][idx]):
                continue
            v = float(lims[name][idx])
            if lower <= v <= upper:
                continue
            side, bound = ("below its lower", lower) if v < lower else ("above its upper",
                                                                         upper)
            lines.append(f"{name} = {v:.6g} {unit} {side} limit {bound:.6g} {unit} ({kind} "
                         f"limit, {source})")
        if not lines:
            return "ok"
        ok = all(int(c) in (OK, ON_BOUNDARY) for c in codes) and not any(
            "limit" in ln for ln in lines)
        return ("ok; " if ok else "") + "; ".join(lines)

    def limit_values(self, pose, q, params=None):
        pose = check.pose(self, "limit_values", pose)
        shape = pose.shape[:-1]
        q = self.algebraic(check.joints(self, "limit_values", q, shape))
        par = check.parameters(self, "limit_values", params or {})
        if not self.limits:
            return {}

        def chunk(p, qq, pr):
            return tuple(numpy.broadcast_to(numpy.asarray(v, dtype=float), p.shape[:-1])
                         for v in self.limit_kernel_values(p, qq, pr))

        values = _chunked_with_joints(pose, q, par, chunk)
        return {lim[0]: v for lim, v in zip(self.limits, values)}

    # ------------------------------------------------------------ velocity model
    def _matrix(self, kern, m, pose, q, par):
        """The (len(JOINTS), m) matrix per pose of ``kern`` (``ji`` or ``jo_study``, row-major
        entries): only the one asked for is evaluated."""
        shape = pose.shape[:-1]
        return stacked(kern(*columns(pose), *columns(q), *par), shape).reshape(
            shape + (len(self.joints), m))

    def input_jacobian(self, pose, q, params=None):
        pose = check.pose(self, "input_jacobian", pose)
        t = self.algebraic(check.joints(self, "input_jacobian", q, pose.shape[:-1]))
        par = check.parameters(self, "input_jacobian", params or {})
        return _chunked_with_joints(pose, t, par, lambda p, tt, pr: (
            self._input_jacobian(p, tt, pr),))[0]

    def _input_jacobian(self, pose, t, par):
        """:meth:`input_jacobian` of one chunk, ``t`` the algebra's joints."""
        ji = self._matrix(self.ji, len(self.joints), pose, t, par)
        if self.angles:  # dG/dq = dG/dt dt/dq, dt/dq = (1 + t^2) / 2
            idx = list(self.angles)
            ji[..., :, idx] *= ((1.0 + t[..., idx] ** 2) / 2.0)[..., None, :]
        return ji

    def output_jacobian(self, pose, q, params=None):
        pose = check.pose(self, "output_jacobian", pose)
        q = self.algebraic(check.joints(self, "output_jacobian", q, pose.shape[:-1]))
        par = check.parameters(self, "output_jacobian", params or {})
        return _chunked_with_joints(pose, q, par, lambda p, qq, pr: (
            self._matrix(self.jo_study, len(self.study_pose), p, qq, pr),))[0]

    def _jac_values(self, pose, q, par, into=None, row_scale=None, shared=None):
        """The Jacobian kernel's outputs (pivots, row scales, dq/dX row-major), one row
        each: (outputs, ...) for poses (..., len(POSE)), evaluated JAC_CHUNK poses at a
        time (its temporaries then stay in cache).  With ``into`` (n, len(JOINTS) *
        len(POSE)), the rows of dq/dX go there directly and only the pivots and row
        scales are returned; ``row_scale`` ({row of dq/dX: array (n,)}) multiplies a row's
        entries on the way (the angle joints' dq/dt, :meth:`publish`); ``shared``: the
        poses' :meth:`pose_values` where already computed."""
        shape = pose.shape[:-1]
        n = int(numpy.prod(shape, dtype=numpy.int64))
        flat_pose = pose.reshape(n, pose.shape[-1])
        flat_q = q.reshape(n, q.shape[-1])

        par_of_chunk = _parameter_chunks(par, shape, n)
        out = None
        nps = 2 * len(self.joints)
        with numpy.errstate(all="ignore"):
            shared_of_chunk = _parameter_chunks(
                self.pose_values(pose, par) if shared is None else shared, shape, n)
            for lo in range(0, n, JAC_CHUNK):
                hi = min(n, lo + JAC_CHUNK)
                values = self.jac(*shared_of_chunk(lo, hi),
                                  *contiguous_columns(flat_pose[lo:hi]),
                                  *columns(flat_q[lo:hi]), *par_of_chunk(lo, hi))
                if out is None:
                    out = numpy.empty((len(values) if into is None else nps, n))
                for k, v in enumerate(values):
                    if into is not None and k >= nps:
                        row = (k - nps) // len(self.pose)
                        if row_scale and row in row_scale:  # the product written in place
                            numpy.multiply(v, row_scale[row][lo:hi], out=into[lo:hi, k - nps])
                        else:
                            into[lo:hi, k - nps] = v
                    else:
                        out[k, lo:hi] = v
        if out is None:  # no poses
            out = numpy.empty((nps + (0 if into is not None else
                                      len(self.joints) * len(self.pose)), 0))
        return out.reshape((out.shape[0],) + shape)

    @staticmethod
    def pivot_singular(pivots, scales, shape):
        """True where a pivot dG_k/dq_k vanishes relative to its row scale (or is not
        finite): an input singularity."""
        regular = numpy.ones(shape, dtype=bool)
        for d, sc in zip(pivots, scales):
            regular &= numpy.abs(d) > DET_RTOL * sc
        return ~regular

    def jacobian_and_status(self, pose, mode=0, limits=True, params=None,
                            func="jacobian_and_status", fast=None):
        """``dq/dX`` by forward substitution (Ji is triangular in the solve order) and the
        status: an IK status, or INPUT_SINGULAR where a pivot vanishes or a quadratic step
        has a double root."""
        _, J, status = self.ik_and_jacobian(pose, mode, limits, params, func, fast)
        return J, status

    def ik_and_jacobian(self, pose, mode=0, limits=True, params=None,
                        func="ik_and_jacobian", fast=None):
        """``(q, dq/dX, status)`` from one solve: ``ik``, ``jacobian`` and
        ``jacobian_status`` together."""
        pose, mode, par, limits = self._ik_args(func, pose, mode, limits, params)
        return self._solve_with_jacobian(pose, mode, par, limits, func, fast, True)

    def _solve_with_jacobian(self, pose, mode, par, limits, func, fast=None, public=False):
        """``(q, dq/dX, status)``, through the compiled fast path where available, else in
        numpy; in the user's units with ``public`` (:meth:`publish`), else the algebra's
        (t = tan(q/2) for angle joints)."""
        compiled = self._fast_path(func, fast, par)
        if compiled is not None:
            q, status, J = compiled.solve(pose, par, mode, limits, True, public)
            return q, J, status
        n, m = len(self.joints), len(self.pose)
        return _chunked_into(pose, par, (((n,), float), ((n, m), float), ((), numpy.int8)),
                             lambda p, pr, *out: self._ik_jacobian(p, mode, pr, limits,
                                                                   public, *out))

    def _ik_jacobian(self, pose, mode, par, limits, public, q_out, J_out, status_out):
        """``q``, ``J`` and the status of poses (k, len(POSE)) written into ``q_out`` (k,
        len(JOINTS)), ``J_out`` (k, len(JOINTS), len(POSE), C-contiguous rows) and
        ``status_out`` (k,); the kernel's rows of dq/dX are written into ``J_out``
        directly."""
        with numpy.errstate(all="ignore"):
            shared = self.pose_values(pose, par)
        q, status = self._solve_by_columns(pose, mode, par, True, limits, shared)
        k = pose.shape[0]
        n, m = len(self.joints), len(self.pose)
        # the angle joints' rows of dq/dX times dq/dt as they are written (the numbers of
        # _public_jacobian, without a pass over strided rows)
        scale = {i: self.dq_dt(q[..., i]) for i in self.angles} if public else None
        values = self._jac_values(pose, q, par, into=J_out.reshape(k, n * m),
                                  row_scale=scale, shared=shared)
        singular = self.pivot_singular(values[:n], values[n:2 * n], (k,))
        singular |= status == ON_BOUNDARY
        J_out[singular] = numpy.nan
        if public:  # on q's rows (contiguous), before they are copied out
            self.publish(q)
        q_out[...] = q
        ik_ok = (status == OK) | (status == ON_BOUNDARY)
        status_out[...] = numpy.where(ik_ok & singular, INPUT_SINGULAR, status)

    def singularities(self, pose, q, params=None):
        pose = check.pose(self, "singularities", pose)
        q = self.algebraic(check.joints(self, "singularities", q, pose.shape[:-1]))
        par = check.parameters(self, "singularities", params or {})
        names = [*self.singularity_kernels, *self.singularity_matrices]
        values = _chunked_with_joints(pose, q, par, lambda p, qq, pr: tuple(
            self._singularities(p, qq, pr).values()))
        return dict(zip(names, values))

    def _singularities(self, pose, q, par):
        """:meth:`singularities` of one chunk, ``q`` the algebra's joints."""
        shape = pose.shape[:-1]
        with numpy.errstate(all="ignore"):
            study = self.study_values(pose, par)
            qc = columns(q)
            out = {name: numpy.broadcast_to(numpy.asarray(kern(*study, *qc, *par)[0],
                                                          dtype=float), shape)
                   for name, kern in self.singularity_kernels.items()}
            for name, (kern, n) in self.singularity_matrices.items():
                mat = stacked(kern(*study, *qc, *par), shape).reshape(shape + (n, n))
                ok = numpy.all(numpy.isfinite(mat), axis=(-2, -1))
                det = numpy.linalg.det(numpy.where(ok[..., None, None], mat, 0.0))
                out[name] = numpy.where(ok, det, numpy.nan)
            return out

    # ------------------------------------------------------------ passive joints, twist
    def _passive(self, pose, mode, par):
        q, _ = self.solve(pose, mode, par, False, False)
        return q, self._passive_of(pose, q, par)

    def _passive_of(self, pose, q, par):
        """The passive joints at poses ``pose`` with the joints ``q`` (algebraic)."""
        shape = pose.shape[:-1]
        with numpy.errstate(all="ignore"):
            study = [numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                     for v in self.study_values(pose, par)]
            out = numpy.full(shape + (len(self.passive_names),), numpy.nan)
            for leg in self.passive:
                solved = []
                for kind, kern, idx in leg:
                    values = [numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                              for v in kern(*study, *columns(q), *solved, *par)]
                    if kind == "linear":
                        vals = [linear_candidates(values)]
                    elif kind == "quadratic":
                        vals = [smaller_root(*values)]
                    else:
                        vals = unit_quaternion(values)
                    for i, v in zip(idx, vals):
                        out[..., i] = v
                    solved += vals
        return out

    def passive_joints(self, pose, mode=0, params=None):
        pose = check.pose(self, "passive_joints", pose)
        mode = check.mode(self, "passive_joints", mode)
        par = check.parameters(self, "passive_joints", params or {})
        return _chunked(pose, par, lambda p, pr: (self._passive(p, mode, pr)[1],))[0]

    def link_poses(self, pose, mode=0, params=None):
        pose = check.pose(self, "link_poses", pose)
        mode = check.mode(self, "link_poses", mode)
        par = check.parameters(self, "link_poses", params or {})
        return _chunked(pose, par, lambda p, pr: (self._link_poses(p, mode, pr),))[0]

    def _link_poses(self, pose, mode, par):
        """:meth:`link_poses` of one chunk of poses (k, len(POSE))."""
        q, passive = self._passive(pose, mode, par)
        with numpy.errstate(all="ignore"):
            out = self.link_points(self.study_values(pose, par), q, passive, par,
                                   pose.shape[:-1])
            out /= numpy.linalg.norm(out[..., :4], axis=-1, keepdims=True)
        return out

    def link_points(self, study, q, passive, par, shape):
        """Every link's Study point (..., links, 8), unnormalized, from the pose's Study
        coordinates, the joints (algebraic) and the passive joints."""
        out = numpy.full(shape + (len(self.link_names), 8), numpy.nan)
        for kern, first, count in self.links:
            values = stacked(kern(*study, *columns(q), *columns(passive), *par), shape)
            out[..., first:first + count, :] = values.reshape(shape + (count, 8))
        return out

    def static_efforts(self, pose, load, mode=0, method="virtual_work", params=None):
        """Actuator efforts (..., len(JOINTS)) holding the pose under ``load`` (..., 3, N,
        base frame, at the end effector's origin) and the link weights, by virtual work or
        by the free-body equilibrium of every body (:mod:`.statics`); NaN where the IK, its
        Jacobian or the equilibrium is not defined."""
        func = "static_efforts"
        if method not in ("virtual_work", "free_body"):
            raise ValueError(f"{self.mechanism}.{func}: method must be 'virtual_work' or "
                             f"'free_body', got {method!r}")
        if self.statics is None:
            raise NotImplementedError(f"{self.mechanism}.{func}: the declaration gives no "
                                      "link weights")
        pose = check.pose(self, func, pose)
        load = check.coordinates(self, func, load, ("Fx", "Fy", "Fz"), "load")
        if not numpy.isfinite(load).all():
            raise ValueError(f"{self.mechanism}.{func}: the load must be finite")
        mode = check.mode(self, func, mode)
        par = check.parameters(self, func, params or {})
        shape = numpy.broadcast_shapes(pose.shape[:-1], load.shape[:-1])
        rows = (numpy.broadcast_to(pose, shape + pose.shape[-1:]),
                numpy.broadcast_to(load, shape + (3,)))
        return _rows_in_chunks(rows, par, lambda p, f, pr: (
            self._efforts(p, f, mode, method, pr, func),),
            FREE_BODY_CHUNK if method == "free_body" else STATICS_CHUNK)[0]

    def _efforts(self, pose, load, mode, method, par, func):
        """:meth:`static_efforts` of one chunk of poses and loads."""
        if method == "free_body":
            q, passive = self._passive(pose, mode, par)
            return statics.free_body(self, pose, load, q, passive, par)
        q, J, _ = self._solve_with_jacobian(pose, mode, par, False, func)  # one solve for both
        return statics.efforts(self, pose, load, q, self._passive_of(pose, q, par),
                               self._public_jacobian(q, J), par)

    def pose_twist(self, pose, params=None):
        pose = check.pose(self, "pose_twist", pose)
        par = check.parameters(self, "pose_twist", params or {})
        with numpy.errstate(all="ignore"):
            values = self.twist(*columns(pose), *par)
        return stacked(values, pose.shape[:-1]).reshape(pose.shape[:-1] + (6, len(self.pose)))

    def twist_jacobian(self, pose, mode=0, limits=True, params=None):
        J, status = self.jacobian_and_status(pose, mode, limits, params, "twist_jacobian")
        t = self.pose_twist(pose, params)
        n = len(self.joints)
        if J.shape[-2:] != (n, n):
            raise NotImplementedError(f"{self.mechanism}.twist_jacobian: dq/dX is {J.shape[-2:]}"
                                      ", not square")
        ok = numpy.isfinite(J).all(axis=(-2, -1))
        safe = numpy.where(ok[..., None, None], J, numpy.eye(n))
        with numpy.errstate(all="ignore"):
            cond = numpy.linalg.cond(safe)
            inv = numpy.linalg.inv(safe)
        ok &= cond < 1e12  # a forward singularity: dq/dX loses rank
        return numpy.where(ok[..., None, None], t @ inv, numpy.nan)

    def helical_residuals(self, pose, mode=0, params=None):
        pose = check.pose(self, "helical_residuals", pose)
        par = check.parameters(self, "helical_residuals", params or {})
        q, passive = self._passive(pose, check.mode(self, "helical_residuals", mode), par)
        with numpy.errstate(all="ignore"):
            values = self.helical(*columns(passive), *columns(q), *par)
        return stacked(values, pose.shape[:-1])

    # ------------------------------------------------------------ forward kinematics
    def _fk_joints(self, func, q):
        if not self.fk.modes:
            raise NotImplementedError(f"{self.mechanism}.{func}: forward kinematics is not "
                                      f"generated for this mechanism: {self.fk.note}")
        return check.coordinates(self, func, q, self.joints, "joints")

    def fk_all(self, q, params=None, with_status=False, func="fk", fast=None):
        """Every assembly mode's pose (and status); the rational kernels through their
        compiled twins where ``fast`` and the parameters allow (:meth:`_fast_path`,
        :meth:`.compiled.FastPath.forward_kinematics`: the same numbers, bit for bit), else
        numpy."""
        q = self.algebraic(self._fk_joints(func, q))
        par = check.parameters(self, func, params or {})
        compiled = self._fast_path(func, fast, par)
        spec = self.fk if compiled is None else compiled.forward_kinematics(self.fk)
        poses, status = _chunked(q, par, lambda qc, pc: fk_solver.solve_all(
            self, qc, pc, with_status, spec), FK_CHUNK)
        if with_status:  # every mode of non-finite joints: NaN, and the input is why
            invalid = ~numpy.isfinite(q).all(axis=-1)
            if invalid.any():
                status[invalid] = INVALID_INPUT
        return poses, status

    # ------------------------------------------------------------ other functions
    def pose_function(self, func, kern, pose, params=None):
        pose, par = check.pose(self, func, pose), check.parameters(self, func, params or {})
        with numpy.errstate(all="ignore"):
            values = kern(*columns(pose), *par)
        return stacked(values, pose.shape[:-1])

    def function(self, func, kern, values, names: Sequence[str], params=None):
        values = check.coordinates(self, func, values, names, "values")
        par = check.parameters(self, func, params or {})
        with numpy.errstate(all="ignore"):
            out = kern(*columns(values), *par)
        return stacked(out, values.shape[:-1])


# poses per numpy evaluation: each kernel temporary (CHUNK doubles, 128 KiB) stays in cache
CHUNK = 16384
# poses per evaluation of the Jacobian kernel, whose temporaries are many more (measured on
# this project's machine: Stewart 610 ns per pose on 4096, 1150 on 16384)
JAC_CHUNK = 8192
# joint configurations per evaluation of forward kinematics: memory bounded at any batch
# size, and the Newton kernels' and the eliminant's temporaries nearer the cache (measured
# against one piece: urrh_rcm 1.14x on 60,000 configurations, tripod_planar 1.30x on
# 20,000); the configurations are independent, so the results are the same to the bit
FK_CHUNK = 4096
# poses per evaluation of the static efforts by virtual work: the legs' screws and twists
# (about 6 KB a pose for lamina_milling) bounded at any batch size (100,000 poses in one
# piece took 645 MB); as fast as one piece (smaller chunks are not: 1,024 took 1.26x as long)
STATICS_CHUNK = 4096
# the same by the free-body equilibrium, whose system and its SVD take about 160 KB a pose
# (100,000 poses in one piece took 16 GB); the time hardly depends on the size
FREE_BODY_CHUNK = 512


def _chunked(pose, par, fn, size=None):
    """``fn(pose, par)`` over chunks of at most ``size`` (default CHUNK) poses, each of
    shape (k, len(POSE)), the results (arrays of k leading rows, any strides, or None)
    copied into contiguous arrays of the poses' leading shape; array parameters are split
    alike."""
    return _rows_in_chunks((pose,), par, fn, size)


def _chunked_with_joints(pose, q, par, fn, size=None):
    """:func:`_chunked` over poses (..., len(POSE)) and their joints ``q`` (the same leading
    shape): ``fn(pose, q, par)`` on each chunk of both."""
    return _rows_in_chunks((pose, q), par, fn, size)


def _rows_in_chunks(arrays, par, fn, size=None):
    """``fn(*chunks, par)`` over chunks of at most ``size`` (default CHUNK) rows of
    ``arrays`` (the same leading shape, each chunk (k, last axis)), the results copied into
    contiguous arrays of that leading shape (:func:`_chunked`)."""
    size = CHUNK if size is None else size
    shape = arrays[0].shape[:-1]
    n = int(numpy.prod(shape, dtype=numpy.int64))
    flats = [a.reshape(n, a.shape[-1]) for a in arrays]
    par_of_chunk = _parameter_chunks(par, shape, n)
    outs = None
    for lo in range(0, max(n, 1), size):  # an empty batch: one empty chunk
        hi = min(n, lo + size)
        part = fn(*(f[lo:hi] for f in flats), par_of_chunk(lo, hi))
        if outs is None:
            outs = [None if r is None else numpy.empty((n,) + r.shape[1:], dtype=r.dtype)
                    for r in part]
        for o, r in zip(outs, part):
            if o is not None:
                _copy_rows(o[lo:hi], r)
    return tuple(None if o is None else o.reshape(shape + o.shape[1:]) for o in outs)


def _copy_rows(dest, r):
    """``dest[...] = r``; a few columns of a transposed view (the kernels' rows as the
    joints' columns) column by column: numpy copies such a view row by row, each row a loop
    of a few elements (a chunk of three joints: 59 us against 16 on this project's
    machine)."""
    if r.ndim == 2 and 1 < r.shape[1] <= 6 and r.strides[0] < r.strides[1]:
        for j in range(r.shape[1]):
            dest[:, j] = r[:, j]
    else:
        dest[...] = r


def _chunked_into(pose, par, specs, fn):
    """:func:`_chunked` for a ``fn(pose, par, *out)`` that writes its results into the
    chunk's rows of arrays allocated here once, one per ``(trailing shape, dtype)`` of
    ``specs`` (no copy from the chunk's own arrays), returned with the poses' leading
    shape."""
    shape = pose.shape[:-1]
    n = int(numpy.prod(shape, dtype=numpy.int64))
    flat = pose.reshape(n, pose.shape[-1])
    par_of_chunk = _parameter_chunks(par, shape, n)
    outs = [numpy.empty((n,) + tail, dtype=dtype) for tail, dtype in specs]
    for lo in range(0, max(n, 1), CHUNK):
        hi = min(n, lo + CHUNK)
        fn(flat[lo:hi], par_of_chunk(lo, hi), *[o[lo:hi] for o in outs])
    return tuple(o.reshape(shape + o.shape[1:]) for o in outs)


def _parameter_chunks(par, shape, n):
    """``chunk(lo, hi)``: the values ``par`` (parameters, or the poses' shared values) of
    poses ``lo:hi`` of the ``n`` flattened poses of leading ``shape``; scalars as they are
    (the same list each time when every one is), arrays broadcast to the poses and
    sliced."""
    if getattr(par, "vector", None) is not None:  # checked parameters, every one a scalar
        return lambda lo, hi: par
    arrays = [i for i, v in enumerate(par) if numpy.ndim(v)]
    if not arrays:
        return lambda lo, hi: par
    flat = list(par)
    for i in arrays:
        flat[i] = numpy.broadcast_to(par[i], shape).reshape(n)

    def chunk(lo, hi):
        out = list(flat)
        for i in arrays:
            out[i] = flat[i][lo:hi]
        return out
    return chunk


def linear_candidates(values):
    """``v = -C/B`` from the candidate ``(B, C, S)`` triples (``S`` the sum of the
    magnitudes of the candidate's terms), per sample the one whose pivot is largest
    relative to its scale (``|B| / S``); a pivot at rounding level (``|B| <= DET_RTOL S``,
    the candidate degenerate there) is never taken: NaN where every candidate is."""
    bs, cs, ss = values[0::3], values[1::3], values[2::3]
    best = numpy.full(numpy.shape(bs[0]), -1.0)
    out = numpy.full(numpy.shape(bs[0]), numpy.nan)
    for b, c, scale in zip(bs, cs, ss):
        with numpy.errstate(all="ignore"):
            score = numpy.abs(b) / scale
            usable = numpy.isfinite(score) & (numpy.abs(b) > DET_RTOL * scale)
            take = usable & (score > best)
            out = numpy.where(take, -c / b, out)
            best = numpy.where(take, score, best)
    return out


def smaller_root(a, b, c):
    """The root of ``a v^2 + b v + c`` of smaller magnitude (NaN where none is real)."""
    with numpy.errstate(all="ignore"):
        disc = b * b - 4.0 * a * c
        sq = numpy.sqrt(numpy.where(disc >= -1e-10 * b * b, numpy.maximum(disc, 0.0), numpy.nan))
        big = -(b + numpy.where(b >= 0, sq, -sq)) / 2.0  # the larger-magnitude combination
        small = numpy.where(big != 0, c / big, numpy.where(a != 0, 0.0, -c / b))
        return numpy.where(a == 0, -c / b, small)


def unit_quaternion(values):
    """``values`` (4 arrays) scaled to a unit quaternion with a non-negative first entry."""
    q = numpy.stack(values, axis=-1)
    with numpy.errstate(all="ignore"):
        q = q / numpy.linalg.norm(q, axis=-1, keepdims=True)
        q = numpy.where(q[..., :1] < 0, -q, q)
    return [q[..., i] for i in range(4)]
