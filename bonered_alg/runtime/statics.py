"""Actuator efforts that hold a mechanism under a load and its link weights, by virtual work.

For the pose coordinates X as independent coordinates, every body's spatial twist per unit
rate of X follows from its leg: the leg's joint screws S (the twist of its last body, the
platform, per unit rate of each of its joint variables, from the derivatives of the
bodies' Study points) solve ``S V = T`` for the joint rates V, where T is the platform's
twist per unit rate of X (``pose_twist``); a body's twist is then its own screws times V.
A point p of a body moves with ``v0 + omega x p``: its Jacobian P = dp/dX.  With dq/dX = J
(the IK's Jacobian), the principle of virtual work, ``tau . dq + F . dH + sum W_k . dp_k =
0`` for every virtual displacement, gives

    J^T tau = -(P_H^T F + sum_k P_k^T W_k),  W_k = (0, 0, -G_k)  (gravity along -Z),

tau the effort of each actuator on its driven link in the positive sense of its joint
(N for a slide, N mm per rad for a turn), F the load at the end effector's origin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy

from ..algebra import convention as cv
from .inputs import columns, stacked

# a leg's joint rates must reproduce the platform's twist to this (relative) residual;
# otherwise the leg is singular there (its screws do not span the platform's motion)
RATE_RTOL = 1e-9


@dataclass(frozen=True)
class Statics:
    """Kernels and tables of the static model (names as in the generated module).

    ``rates``: per leg ``(kernel, first link index, bodies, variables)``, the kernel giving
    d(Study point)/d(variable) of each body (body-major, 8 coordinates each);
    ``weights``: kernel of the parameters giving ``(G * share, cx, cy, cz)`` per point;
    ``points``: the link index of each point (-1: the end effector's frame);
    ``end_effector``: kernel of the pose giving the end effector's Study point."""

    rates: tuple
    weights: object
    points: tuple[int, ...]
    end_effector: object
    names: tuple[str, ...] = ()


def _parts(a):
    """The coordinates of ``a`` (..., k) as k contiguous arrays (the elementwise formulas
    of the convention run several times faster on them than on strided views)."""
    return list(numpy.ascontiguousarray(numpy.moveaxis(a, -1, 0)))


def spatial_twists(g, dg):
    """``(omega; v)`` (..., 6) of Study points ``g`` (..., 8), any scale, moving with
    ``dg``: omega = 2 vec(x' conj(x)) / |x|^2, v = t' - omega x t."""
    x, dx = _parts(g), _parts(dg)
    n = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]
    dn = 2.0 * (x[0] * dx[0] + x[1] * dx[1] + x[2] * dx[2] + x[3] * dx[3])
    conj = [x[0], -x[1], -x[2], -x[3]]
    omega = [2.0 * c / n for c in cv.quaternion_product(dx[:4], conj)[1:]]
    tn = cv.translation_times_norm(x)
    dtn = [a + b for a, b in zip(cv.translation_times_norm(dx[:4] + x[4:]),
                                 cv.translation_times_norm(x[:4] + dx[4:]))]
    t = [c / n for c in tn]
    dt = [(c - ti * dn) / n for c, ti in zip(dtn, t)]
    v = [a - b for a, b in zip(dt, cv.cross(omega, t))]
    return numpy.stack(omega + v, axis=-1)


def _least_squares(a, b):
    """x with a x = b in the least-squares sense, per row: (..., m, n) and (..., m, k),
    n <= m, by QR (R x = Q^T b); by the pseudo-inverse on the rows whose R is singular (a
    zero on its diagonal, where LAPACK's solve of a triangular R stops; the caller's
    residual check then flags the rows that have no solution).  Each row's numbers are
    those it would get alone: no row changes method because another one is singular."""
    q, r = numpy.linalg.qr(a)
    qtb = numpy.swapaxes(q, -1, -2) @ b
    try:
        return numpy.linalg.solve(r, qtb)
    except numpy.linalg.LinAlgError:
        regular = numpy.all(numpy.diagonal(r, axis1=-2, axis2=-1) != 0.0, axis=-1)
        out = numpy.empty(qtb.shape)
        out[regular] = numpy.linalg.solve(r[regular], qtb[regular])
        out[~regular] = numpy.linalg.pinv(a[~regular]) @ b[~regular]
        return out


def _solve_or_nan(a, b):
    """``numpy.linalg.solve(a, b)`` (..., n, n), (..., n, k), with NaN on the rows whose
    matrix is exactly singular (LAPACK finds a zero pivot) instead of an error for all of
    them: those rows are then solved one by one (each row's numbers are its own either
    way)."""
    try:
        return numpy.linalg.solve(a, b)
    except numpy.linalg.LinAlgError:
        lead = numpy.broadcast_shapes(a.shape[:-2], b.shape[:-2])
        a = numpy.broadcast_to(a, lead + a.shape[-2:])
        b = numpy.broadcast_to(b, lead + b.shape[-2:])
        out = numpy.full(b.shape, numpy.nan)
        for idx in numpy.ndindex(out.shape[:-2]):
            try:
                out[idx] = numpy.linalg.solve(a[idx], b[idx])
            except numpy.linalg.LinAlgError:
                pass
        return out


def body_point(g, local):
    """The base coordinates of the point ``local`` (..., 3) of the frame ``g`` (..., 8)."""
    p = _parts(g)
    n = cv.rotation_norm(p)
    r = cv.rotation_matrix_times_norm(p)
    t = cv.translation_times_norm(p)
    return numpy.stack([(t[i] + sum(r[i][j] * local[..., j] for j in range(3))) / n
                        for i in range(3)], -1)


def point_jacobian(twist, p):
    """dp/dX (..., 3, k) of a body point p (..., 3) of a body with twist (..., 6, k)."""
    omega, v = twist[..., :3, :], twist[..., 3:, :]
    return v + numpy.cross(omega, p[..., :, None], axis=-2)


def _configuration(model, pose, q, passive, par):
    """The bodies' Study points (..., links, 8), each leg's ``(first, count, g, dg,
    owner)`` (its bodies' Study points and their derivatives by each variable, (...,
    count, variables, 8)), the platform's twist per pose rate (..., 6, n) and the end
    effector's Study point (..., 8)."""
    st: Statics = model.statics
    shape = pose.shape[:-1]
    study = model.study_values(pose, par)
    links = model.link_points(study, q, passive, par, shape)
    legs = []
    for kern, first, count, nvars, owner in st.rates:
        d = stacked(kern(*study, *columns(q), *columns(passive), *par), shape).reshape(
            shape + (count, nvars, 8))
        legs.append((first, count, links[..., first:first + count, :], d, owner))
    tx = stacked(model.twist(*columns(pose), *par), shape).reshape(
        shape + (6, len(model.pose)))
    ee = stacked(st.end_effector(*columns(pose), *par), shape)
    return links, legs, tx, ee


def _body_screws(g, d, body):
    """The twists (..., variables, 6) of body ``body`` of a leg per unit rate of each of
    the leg's variables (zero for the variables after it)."""
    dg = d[..., body, :, :]
    return spatial_twists(numpy.broadcast_to(g[..., body, None, :], dg.shape), dg)


def _weight_points(model, links, ee, par, shape):
    """(link index or -1, G * share (..., 1), point (..., 3)) of every weight point."""
    st: Statics = model.statics
    w = stacked(st.weights(*par), shape).reshape(shape + (len(st.points), 4))
    out = []
    for k, link in enumerate(st.points):
        frame = ee if link < 0 else links[..., link, :]
        out.append((link, w[..., k, 0, None], body_point(frame, w[..., k, 1:])))
    return out


def efforts(model, pose, load, q, passive, J, par):
    """The actuator efforts (..., len(JOINTS)) by virtual work at poses ``pose`` (..., n)
    under ``load`` (..., 3) with the joints ``q``, passive joints and dq/dX ``J`` (public
    units) there; NaN where J or a leg's rates are singular."""
    shape = pose.shape[:-1]
    with numpy.errstate(all="ignore"):
        links, legs, tx, ee = _configuration(model, pose, q, passive, par)
        ok = numpy.isfinite(J).all(axis=(-2, -1))
        weighted = {link for link in model.statics.points if link >= 0}
        twists = {}
        for first, count, g, d, _ in legs:
            end = numpy.swapaxes(_body_screws(g, d, count - 1), -1, -2)  # (..., 6, vars)
            safe = numpy.where(numpy.isfinite(end), end, 0.0)
            rates = _least_squares(safe, tx)
            resid = numpy.abs(safe @ rates - tx).max(axis=(-2, -1))
            scale = 1.0 + numpy.abs(tx).max(axis=(-2, -1))
            ok &= numpy.isfinite(end).all(axis=(-2, -1)) & (resid <= RATE_RTOL * scale)
            for b in range(count):
                if first + b in weighted:  # only the bodies that carry a weight
                    twists[first + b] = numpy.swapaxes(_body_screws(g, d, b), -1, -2) @ rates
        origin = body_point(ee, numpy.zeros(shape + (3,)))
        Q = numpy.einsum("...ik,...i->...k", point_jacobian(tx, origin), load)
        for link, gs, p in _weight_points(model, links, ee, par, shape):
            twist = tx if link < 0 else twists[link]
            Q = Q - gs * point_jacobian(twist, p)[..., 2, :]  # W = (0, 0, -G share)
        safe = numpy.where(ok[..., None, None], J, numpy.eye(J.shape[-1]))
        tau = -_solve_or_nan(numpy.swapaxes(safe, -1, -2), Q[..., None])[..., 0]
    return numpy.where(ok[..., None], tau, numpy.nan)


def _wrench(force, point):
    """(f; p x f) (..., 6): a force at a point as a wrench about the base origin."""
    return numpy.concatenate([force, numpy.cross(point, force)], -1)


def free_body(model, pose, load, q, passive, par):
    """The actuator efforts (..., len(JOINTS)) from the equilibrium of every body: the
    reaction wrench w_j of each joint (on its child body, about the base origin) is an
    unknown; each body's wrenches sum to zero (its joints', its weights', the load on the
    platform), and each joint freedom with screw S does no work, w_j . S = 0, or the
    actuator's, w_j . S = tau (reciprocal product f . v + m . omega).  The reactions of
    redundant constraints are not determined; the efforts are, where the mechanism is not
    singular (checked on the null space of the system); NaN elsewhere."""
    shape = pose.shape[:-1]
    n_act = len(model.joints)
    with numpy.errstate(all="ignore"):
        links, legs, tx, ee = _configuration(model, pose, q, passive, par)
        # bodies: the platform (0) and every other body of the legs; joints: parent, child
        body_of = {}
        joints = []  # (parent body or None, child body, leg, index in leg)
        for li, (first, count, *_) in enumerate(legs):
            body_of[first + count - 1] = 0
            for b in range(count - 1):
                body_of[first + b] = 1 + sum(leg[1] - 1 for leg in legs[:li]) + b
            for b in range(count):
                parent = None if b == 0 else body_of[first + b - 1]
                joints.append((parent, body_of[first + b], li, b))
        n_bodies = len(set(body_of.values()))
        n_free = sum(len(leg[4]) for leg in legs)
        n_unk = 6 * len(joints) + n_act
        A = numpy.zeros(shape + (6 * n_bodies + n_free, n_unk))
        rhs = numpy.zeros(shape + (6 * n_bodies + n_free,))
        for j, (parent, child, _, _) in enumerate(joints):
            A[..., 6 * child:6 * child + 6, 6 * j:6 * j + 6] += numpy.eye(6)
            if parent is not None:
                A[..., 6 * parent:6 * parent + 6, 6 * j:6 * j + 6] -= numpy.eye(6)
        origin = body_point(ee, numpy.zeros(shape + (3,)))
        rhs[..., 0:6] -= _wrench(load, origin)
        for link, gs, p in _weight_points(model, links, ee, par, shape):
            b = 0 if link < 0 else body_of[link]
            force = numpy.zeros(shape + (3,))
            force[..., 2] = -gs[..., 0]
            rhs[..., 6 * b:6 * b + 6] -= _wrench(force, p)
        row = 6 * n_bodies
        index = {(li, b): j for j, (_, _, li, b) in enumerate(joints)}
        for li, (_, _, g, d, owner) in enumerate(legs):
            for v, (b, act) in enumerate(owner):
                s = spatial_twists(g[..., b, :], d[..., b, v, :])  # the joint's own screw
                j = index[li, b]
                A[..., row, 6 * j:6 * j + 3] = s[..., 3:]  # f . v
                A[..., row, 6 * j + 3:6 * j + 6] = s[..., :3]  # m . omega
                if act >= 0:
                    per_rad = (1.0 + q[..., act] ** 2) / 2.0 if act in model.angles \
                        else 1.0
                    A[..., row, 6 * len(joints) + act] = -1.0 / per_rad
                row += 1
        ok = numpy.isfinite(A).all(axis=(-2, -1)) & numpy.isfinite(rhs).all(-1)
        A = numpy.where(ok[..., None, None], A, 0.0)
        rhs = numpy.where(ok[..., None], rhs, 0.0)
        # equilibrate (rows, then columns, to unit length): forces in N and moments in
        # N mm side by side make the system needlessly ill-conditioned
        rows = numpy.sqrt((A * A).sum(-1, keepdims=True))
        rows = numpy.where(rows > 0, rows, 1.0)
        A, rhs = A / rows, rhs / rows[..., 0]
        cols = numpy.sqrt((A * A).sum(-2, keepdims=True))
        cols = numpy.where(cols > 0, cols, 1.0)
        A = A / cols
        u, sv, vh = numpy.linalg.svd(A)
        tol = sv[..., :1] * 1e-10
        inv = numpy.where(sv > tol, 1.0 / numpy.where(sv > tol, sv, 1.0), 0.0)
        k = sv.shape[-1]
        x = numpy.einsum("...ji,...j,...j->...i", vh[..., :k, :], inv,
                         numpy.einsum("...jk,...j->...k", u[..., :, :k], rhs))
        resid = numpy.abs(A @ x[..., None] - rhs[..., None])[..., 0].max(-1)
        scale = 1.0 + numpy.abs(rhs).max(-1)
        # the efforts are determined where no null vector of A moves them
        null = numpy.concatenate([numpy.where((sv <= tol)[..., None], vh[..., :k, :], 0.0),
                                  vh[..., k:, :]], -2)
        free_tau = numpy.abs(null[..., 6 * len(joints):]).max(axis=(-2, -1))
        ok &= (resid <= 1e-8 * scale) & (free_tau <= 1e-8)
        tau = x[..., 6 * len(joints):] / cols[..., 0, 6 * len(joints):]
    return numpy.where(ok[..., None], tau, numpy.nan)
