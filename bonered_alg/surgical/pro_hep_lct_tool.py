"""The Pro-Hep-LCT tool: mobile platform, redundant insertion ``n`` and the whole robot.

Numeric companion of ``generated/pro_hep_lct.py`` (which solves the two planar mechanisms,
004 eq. 14-16).  The mobile platform (004 eq. 17, Table 3) is the U-P-U body between the
lower universal joint ``Ud = (Xd + c, Yd, 0)`` and the upper one ``Uu = (Xu, Yu, Dz)``:

* platform frame ``P = T(Ud) Rx(u1) Ry(u2) Tz(-Dn)`` (chain 1 of eq. 17);
* the tool axis (platform Z') passes through ``Uu`` (chain 2, free prismatic joint ``p``);
* the tool frame is ``P * Tz(-n)``: the redundant insertion ``n`` along -Z', towards the
  patient (004 Table 5, read as explained in ``derivations/pro_hep_lct.tex``).

The rotation of the platform is the closed form of the universal joints (the direction of
``Uu - Ud``); its dual part comes from the generated ``platform_dual`` (chain 1's linear
generators of the derived ideal G, ``analyses`` in ``bonered_alg.mechanisms.pro_hep_lct``),
and ``tests/test_pro_hep_lct_platform.py`` checks every solution against all of G's
generators (``platform_residuals``).  Platform modes (004 Sect. 3.4, four for the end effector):
bit 0 flips Z' (tool pointing up instead of down), bit 1 turns the platform by a half-turn
about Z' (the second solution of the universal joints).
"""

from __future__ import annotations

import numpy as np

from ..algebra import study_numeric as sn

PLATFORM_MODES = 4
# status codes (in addition to the generated module's IK codes)
NOT_A_UNIVERSAL_JOINT_POSE = 20  # the tool's roll is not one a pair of U joints produces
TOOL_HORIZONTAL = 21  # the tool axis is parallel to the planes of the U joints
_ROLL_TOL = 1e-9


def _par(gen, params: dict, names) -> list[float]:
    if gen is None or not hasattr(gen, "PARAMETERS"):
        raise TypeError("pro_hep_lct: pass the generated module "
                        "(bonered_alg.generated.pro_hep_lct) as gen")
    out = []
    for k in names:
        v = params.get(k, gen.PARAMETERS.get(k))
        if v is None:
            raise ValueError(f"pro_hep_lct: parameter {k!r} has no value; pass it as a keyword")
        out.append(float(v))
    return out


def _planar(gen, params: dict) -> dict:
    """The keyword parameters the generated module knows (it rejects unknown ones)."""
    return {k: v for k, v in params.items() if k in gen.PARAMETERS}


def platform_from_points(points, mode: int = 0, gen=None, **params) -> np.ndarray:
    """Study point of the platform for ``points = (..., 4) = (Xu, Yu, Xd, Yd)``, one mode.

    004 eq. (17)-(18): the platform Z' axis is along ``Uu - Ud``; NaN where ``Uu = Ud``."""
    if not 0 <= mode < PLATFORM_MODES:
        raise ValueError(f"pro_hep_lct: platform mode must be in 0..{PLATFORM_MODES - 1}, "
                         f"got {mode}")
    dz, c = _par(gen, params, ("Dz", "c"))
    pts = np.asarray(points, dtype=float)
    if pts.shape[-1] != 4:
        raise ValueError(f"pro_hep_lct: points must have shape (..., 4) = (Xu, Yu, Xd, Yd), "
                         f"got {pts.shape}")
    ud = np.stack([pts[..., 2] + c, pts[..., 3], np.zeros(pts.shape[:-1])], axis=-1)
    uu = np.stack([pts[..., 0], pts[..., 1], np.full(pts.shape[:-1], dz)], axis=-1)
    with np.errstate(all="ignore"):
        a = (uu - ud) / np.linalg.norm(uu - ud, axis=-1, keepdims=True)
    a = -a if mode & 1 else a
    rot = universal_rotation(a, bool(mode & 2))
    # the dual part from G's linear generators (generated platform_dual)
    xd = np.concatenate([rot[..., :4], pts[..., 2:4]], axis=-1)
    return np.concatenate([rot[..., :4], gen.platform_dual(xd, **_planar(gen, params))],
                          axis=-1)


def universal_rotation(axis, half_turn: bool = False) -> np.ndarray:
    """Study point ``[x:0]`` of the rotation ``Rx(alpha) Ry(beta)`` of a pair of universal
    joints (004 Table 3, P2 P3) that turns Z' onto the unit vector ``axis`` (..., 3); with
    ``half_turn`` the other solution (``Rx(alpha + pi) Ry(pi - beta)``, a half-turn about
    Z').  NaN where ``axis`` is not finite."""
    a = np.asarray(axis, dtype=float)
    with np.errstate(all="ignore"):
        # R e_z = (sin b, -sin a cos b, cos a cos b)
        cb = np.sqrt(np.maximum(a[..., 1] ** 2 + a[..., 2] ** 2, 0.0))
        if half_turn:
            cb = -cb
        beta = np.arctan2(a[..., 0], cb)
        alpha = np.arctan2(-a[..., 1] / cb, a[..., 2] / cb)
    rot = sn.product(sn.rotation("x", np.tan(alpha / 2)), sn.rotation("y", np.tan(beta / 2)))
    return rot / np.linalg.norm(rot[..., :4], axis=-1, keepdims=True)


def tool_pose(point, direction) -> np.ndarray:
    """Tool Study point with its origin at ``point`` (..., 3) and its Z' axis along
    ``direction`` (..., 3; need not be unit, pointing from the tool tip towards the robot),
    with the roll the universal joints give it (the only roll the robot can reach)."""
    d = np.asarray(direction, dtype=float)
    a = d / np.linalg.norm(d, axis=-1, keepdims=True)
    return sn.product(sn.translation(np.asarray(point, dtype=float)), universal_rotation(a))


def platform_velocity(points, mode: int = 0, gen=None, **params):
    """``(dX/dp, sigma)``: the platform's Study-point velocity per input velocity,
    ``(..., 8, 4)`` for ``p = (Xu, Yu, Xd, Yd)``, from ``Ji,3 p' + Jo,3 X' = 0`` (004 eq. 21)
    restricted to the tangent space of ``|x|^2 = 1`` (solved in least squares: G has more
    generators than unknowns), and ``sigma``, the smallest singular value of Jo,3 with its
    rows and columns normalized: near 0 at an output singularity, where the result is not
    valid."""
    pts = np.asarray(points, dtype=float)
    plat = platform_from_points(pts, mode, gen, **params)
    planar = _planar(gen, params)
    vals = np.concatenate([pts, plat], axis=-1)
    ji = gen.platform_input_jacobian(vals, **planar).reshape(pts.shape[:-1] + (-1, 4))
    jo = gen.platform_output_jacobian(vals, **planar).reshape(pts.shape[:-1] + (-1, 8))
    scale = np.linalg.norm(np.concatenate([ji, jo], axis=-1), axis=-1, keepdims=True)
    scale = np.where(scale > 0, scale, 1.0)
    ji, jo = ji / scale, jo / scale
    cols = np.linalg.norm(jo, axis=-2, keepdims=True)  # equilibrate x (1) against y (mm)
    sigma = np.linalg.svd(jo / np.where(cols > 0, cols, 1.0), compute_uv=False)[..., -1]
    dx = -np.linalg.pinv(jo) @ ji
    return dx, sigma


def tool_from_platform(platform, n) -> np.ndarray:
    """Tool frame ``P * Tz(-n)`` (insertion ``n`` towards the patient)."""
    n = np.asarray(n, dtype=float)
    t = np.zeros(n.shape + (3,))
    t[..., 2] = -n
    return sn.product(platform, sn.translation(t))


def points_from_tool(tool, gen=None, **params) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inverse of the platform: ``(points (..., 4) = (Xu, Yu, Xd, Yd), n, status)`` for tool
    Study points ``(..., 8)``.  Status 0 = OK, ``NOT_A_UNIVERSAL_JOINT_POSE`` where the roll
    about the tool axis is not produced by the U joints (x0 x3 - x1 x2 != 0, a generator of
    G), ``TOOL_HORIZONTAL`` where Z' has no vertical component."""
    dz, c, dn = _par(gen, params, ("Dz", "c", "Dn"))
    tool = np.asarray(tool, dtype=float)
    m = sn.transform_from_study(tool)
    a, t = m[..., :3, 2], m[..., :3, 3]
    x = tool[..., :4] / np.linalg.norm(tool[..., :4], axis=-1, keepdims=True)
    roll = x[..., 0] * x[..., 3] - x[..., 1] * x[..., 2]
    status = np.zeros(tool.shape[:-1], dtype=np.int8)
    status[np.abs(roll) > _ROLL_TOL] = NOT_A_UNIVERSAL_JOINT_POSE
    horizontal = np.abs(a[..., 2]) < 1e-12
    status[horizontal] = TOOL_HORIZONTAL
    with np.errstate(all="ignore"):
        k_d = -t[..., 2] / a[..., 2]  # Ud = T + k_d a on the plane Z = 0
        k_u = (dz - t[..., 2]) / a[..., 2]  # Uu on the plane Z = Dz
        ud = t + k_d[..., None] * a
        uu = t + k_u[..., None] * a
        n = k_d - dn
    pts = np.stack([uu[..., 0], uu[..., 1], ud[..., 0] - c, ud[..., 1]], axis=-1)
    bad = status != 0
    pts[bad] = np.nan
    n = np.where(bad, np.nan, n)
    return pts, n, status


def tool_ik(tool, gen, mode: int = 0, limits: bool = True, **params):
    """Active joints ``(t1, w1, q4, q5, n)`` for tool Study points ``(..., 8)`` in one working
    mode of the planar mechanisms (``gen.MODES``); returns ``(joints (..., 5), status)``.
    The tool's Z' points from its tip towards the robot (platform modes 0 and 2, as at the
    entry point O of 004 Sect. 4); status codes are ``gen.STATUS``'s and this module's."""
    pts, n, status = points_from_tool(tool, gen, **params)
    planar = _planar(gen, params)
    q, st = gen.ik_and_status(pts, mode=mode, limits=limits, **planar)
    status = np.where(status != 0, status, st).astype(np.int8)
    joints = np.concatenate([q, n[..., None]], axis=-1)
    joints[status != 0] = np.nan
    return joints, status


def tool_fk(joints, gen, **params) -> np.ndarray:
    """Every assembly mode of the whole robot: tool Study points
    ``(..., gen.FK_MODES * PLATFORM_MODES, 8)`` for ``joints = (..., 5) = (t1, w1, q4, q5, n)``;
    NaN where a mode is not real.  Mode ``k`` is planar mode ``k // 4``, platform ``k % 4``."""
    joints = np.asarray(joints, dtype=float)
    planar = _planar(gen, params)
    pts = gen.fk(joints[..., :4], **planar)  # (..., FK_MODES, 4)
    out = []
    for i in range(pts.shape[-2]):
        for m in range(PLATFORM_MODES):
            plat = platform_from_points(pts[..., i, :], m, gen, **params)
            out.append(tool_from_platform(plat, joints[..., 4]))
    return np.stack(out, axis=-2)


def rcm_path(entry, axis: str, angles, depth: float) -> np.ndarray:
    """Tool poses of an RCM path (004 eq. 10, 12): rotations by ``angles`` (rad, as
    everywhere in the API; ``numpy.radians`` converts the paper's degrees) about the tool
    axis ``axis`` ('x' or 'y') of the entry-point pose ``entry``, each followed by an
    insertion of ``depth`` mm towards the patient (along -Z'), shape (len(angles), 8),
    normalized (|x| = 1, x0 >= 0)."""
    from . import manipulation as mp

    if axis not in ("x", "y"):
        raise ValueError(f"pro_hep_lct.rcm_path: axis must be 'x' or 'y' (a tool axis), got "
                         f"{axis!r}")
    u = np.tan(np.asarray(angles, dtype=float) / 2)
    return sn.normalize(mp.rcm(np.asarray(entry, dtype=float), u, axis, -float(depth)))


def interpolated_deviation(entry, joints, gen, mode_hint, samples: int = 50, **params):
    """RCM deviation between control points when the active joints are interpolated linearly.

    ``joints`` (k, 5) are the control points ``(t1, w1, q4, q5, n)``; between consecutive ones
    the joint angles ``q2 = 2 atan(t1)``, ``q3 = 2 atan(w1)`` and ``q4, q5, n`` move linearly
    (``samples`` steps per segment).  Each intermediate configuration is solved by the
    forward kinematics (``tool_fk``), keeping the assembly mode nearest to the previous pose
    (starting from ``mode_hint``, a tool Study point).  Returns ``(s, dev)``: the path
    parameter (segment index + fraction) and, per sample, the vector from the entry point to
    the nearest point of the tool axis (mm, (..., 3)); its norm is the RCM deviation."""
    from . import manipulation as mp

    joints = np.asarray(joints, dtype=float)
    ang = joints.copy()
    ang[:, :2] = 2 * np.arctan(joints[:, :2])
    s = np.linspace(0, len(joints) - 1, (len(joints) - 1) * samples + 1)
    k = np.minimum(np.floor(s).astype(int), len(joints) - 2)
    f = (s - k)[:, None]
    q = ang[k] * (1 - f) + ang[k + 1] * f
    q[:, :2] = np.tan(q[:, :2] / 2)
    poses = tool_fk(q, gen, **params)  # (N, modes, 8)
    e = mp.point(np.asarray(entry, dtype=float))
    prev = np.asarray(mode_hint, dtype=float)
    dev = np.empty((len(s), 3))
    for i in range(len(s)):
        cand = poses[i]
        ok = np.all(np.isfinite(cand), axis=-1)
        dist = np.where(ok, np.linalg.norm(np.where(ok[:, None], cand, 0) - prev, axis=-1),
                        np.inf)
        prev = cand[int(np.argmin(dist))]
        m = sn.transform_from_study(prev)
        a, t = m[:3, 2], m[:3, 3]
        foot = t + np.dot(e - t, a) * a
        dev[i] = foot - e
    return s, dev


def cone_directions(cone_deg: float, tilts: int = 6, azimuths: int = 36) -> np.ndarray:
    """Unit tool directions (k, 3) tilted by ``cone_deg * i / tilts`` (i = 1..tilts) from the
    vertical, at ``azimuths`` equally spaced azimuths (the vertical itself excluded)."""
    th = np.radians(np.linspace(0.0, cone_deg, tilts + 1)[1:])
    az = np.radians(np.linspace(0.0, 360.0, azimuths, endpoint=False))
    t, a = np.meshgrid(th, az, indexing="ij")
    return np.stack([np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)],
                    axis=-1).reshape(-1, 3)


def reachable(points, directions, gen, mode: int = 0, **params) -> np.ndarray:
    """``(..., k)`` bool: the tool with its origin at ``points`` (..., 3) and its axis along
    each of ``directions`` (k, 3) has a solution in working ``mode`` (joint ranges are not
    published, so only the reach of the mechanisms bounds it)."""
    pts = np.asarray(points, dtype=float)[..., None, :]
    dirs = np.asarray(directions, dtype=float)
    pose = tool_pose(np.broadcast_to(pts, pts.shape[:-2] + dirs.shape),
                     np.broadcast_to(dirs, pts.shape[:-2] + dirs.shape))
    _, status = tool_ik(pose, gen, mode=mode, limits=False, **params)
    return status == 0


def reachable_in_every(points, directions, gen, mode: int = 0, batch: int = 36,
                       **params) -> np.ndarray:
    """``reachable(points, directions, gen, mode).all(axis=-1)`` (the points' shape): the
    directions taken ``batch`` at a time, the last first (a cone's widest tilt), each batch
    only at the points every earlier one reached.  Each pose's status is its own, so the
    answer is the same as testing every pair; pro_hep_lct's dexterous workspace (2 % of
    11,921 points through 216 directions) costs about a quarter of that."""
    pts = np.asarray(points, dtype=float)
    dirs = np.asarray(directions, dtype=float)
    flat = pts.reshape(-1, 3)
    alive = np.arange(len(flat))
    for hi in range(len(dirs), 0, -batch):
        if alive.size == 0:
            break
        ok = reachable(flat[alive], dirs[max(0, hi - batch):hi], gen, mode, **params)
        alive = alive[ok.all(axis=-1)]
    out = np.zeros(len(flat), dtype=bool)
    out[alive] = True
    return out.reshape(pts.shape[:-1])
