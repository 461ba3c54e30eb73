"""Every mechanism at home and on its singularity loci: a drawing and a table (issue 14).

Run for every mechanism that declares a home pose (``Mechanism.home``), from the generated
module alone: ``link_poses`` gives each leg's bodies; the origins of the bodies after its
joints, read base to platform, draw the leg, and the last joint of each leg of a closure
draws its platform.  Bodies given in another body's frame (a leg standing on a moving
platform) are carried into the base frame by that platform's pose, the last body of a leg
of the closure that carries it.

For each singularity polynomial, a configuration where it vanishes is searched along the
pose axes through home (each coordinate in turn, the others at home; mm coordinates
within +-SPAN_MM, angles within +-SPAN_RAD): the sign change nearest home
between two samples where the IK holds (limits off) is bisected to the last bit and kept
where the polynomial is below MAX_RELATIVE of its largest value on the line (a pole or
a failure of the IK is not a zero).  Where none
is found the table says so; that is not a proof that the polynomial never vanishes.
"""

from __future__ import annotations

import numpy as np

from ..algebra import study_numeric as sn
from ..pipeline.results import Study
from ..report.latex_util import tex_escape
from .files import number, png, pyplot

SPAN_MM = 250.0
SPAN_RAD = 1.4
SAMPLES = 281
HALVINGS = 60
MAX_RELATIVE = 1e-8  # |p| at the bisected point against its largest value on the line
# distances (fractions of the span) closer than this are a tie, which the first point found
# (pose axis order, then along the axis) wins: symmetric points (alpha and beta of a
# symmetric mechanism) otherwise turn on rounding in the last bit
TIE = 1e-9


def _line(home: np.ndarray, axis: int, units) -> np.ndarray:
    span = SPAN_RAD if units[axis] == "rad" else SPAN_MM
    poses = np.tile(home, (SAMPLES, 1))
    poses[:, axis] = home[axis] + np.linspace(-span, span, SAMPLES)
    return poses


def vanishing_configurations(gen, names, home: np.ndarray) -> dict:
    """Per singularity polynomial of ``names``: ``(pose, axis, |p| relative, note)`` where
    it vanishes (a sign change bisected), nearest home along the pose axes; else the
    nearest sign change where the IK fails before a zero (with a note saying so); else
    None.  Every sign change of every polynomial is bisected at once, one IK and one
    evaluation of the polynomials per halving for all of them (each bracket's numbers are
    those of bisecting it alone: every pose is its own)."""
    def values(p):
        return gen.singularities(p, gen.ik(p, limits=False))

    lines = [_line(home, axis, gen.POSE_UNITS) for axis in range(len(home))]
    on_lines = values(np.concatenate(lines))
    brackets = []  # (name, axis, largest |p| on the line), in the order they are read
    a_rows, b_rows, va = [], [], []
    for name in names:
        for axis, poses in enumerate(lines):
            v = on_lines[name][axis * SAMPLES:(axis + 1) * SAMPLES]
            s = np.sign(v)
            ok = np.isfinite(v[:-1]) & np.isfinite(v[1:]) & (s[:-1] * s[1:] < 0)
            for i in np.flatnonzero(ok):
                brackets.append((name, axis, float(np.nanmax(np.abs(v)))))
                a_rows.append(poses[i])
                b_rows.append(poses[i + 1])
                va.append(v[i])
    if brackets:
        a, b, va = np.array(a_rows), np.array(b_rows), np.array(va, dtype=float)
        of = np.array([names.index(br[0]) for br in brackets])  # each bracket's polynomial
        active = np.ones(len(brackets), dtype=bool)
        for _ in range(HALVINGS):
            if not active.any():
                break
            at = np.flatnonzero(active)
            mid = (a[at] + b[at]) / 2
            got = values(mid)
            vm = np.stack([got[name] for name in names])[of[at], np.arange(len(at))]
            # the IK fails there (e.g. an input singularity): that bracket stops
            stop = ~np.isfinite(vm)
            active[at[stop]] = False
            go, mid, vm = at[~stop], mid[~stop], vm[~stop]
            same = np.sign(vm) == np.sign(va[go])
            a[go[same]], va[go[same]] = mid[same], vm[same]
            b[go[~same]] = mid[~same]
    found: dict = {}
    for k, (name, axis, scale) in enumerate(brackets):
        best, jump = found.get(name, (None, None))
        pose = a[k]  # the last point of the bracket where the IK holds
        dist = abs(pose[axis] - home[axis]) / (SPAN_RAD if gen.POSE_UNITS[axis] == "rad"
                                               else SPAN_MM)
        rel = float(abs(va[k]) / scale) if scale > 0 else float("nan")
        if not rel <= MAX_RELATIVE:  # a pole, or the IK fails before the zero
            if jump is None or dist < jump[0] - TIE:
                jump = (dist, pose, gen.POSE[axis], rel, "sign change where the IK "
                        "fails (not bisected to a zero)")
        elif best is None or dist < best[0] - TIE:
            best = (dist, pose, gen.POSE[axis], rel, "")
        found[name] = (best, jump)
    out = {}
    for name in names:
        best, jump = found.get(name, (None, None))
        pick = best or jump
        out[name] = None if pick is None else pick[1:]
    return out


def _trailing(d, leg, pose) -> np.ndarray:
    """The fixed offsets after a leg's last moving joint (to its closure's platform frame),
    as a 4x4 transform at the default parameters and ``pose`` (an offset may depend on the
    closure's coordinates, e.g. a collar's position along a shaft)."""
    import sympy as sp

    from ..algebra import study_symbolic as ss

    moving = [k for k, j in enumerate(leg.joints) if j.kind != "offset"]
    factors = [f.study() for j in leg.joints[moving[-1] + 1:] for f in j.factors]
    point = ss.product(*factors) if factors else (1, 0, 0, 0, 0, 0, 0, 0)
    values = {p.symbol: p.value for p in d.mechanism.parameters} | d.constants
    if any(sp.sympify(c).free_symbols - set(values) for c in point):
        at = dict(zip(d.mechanism.pose.coordinates, map(float, pose))) | values
        values |= {k: sp.sympify(v).subs(at) for k, v in d.pose_to_study.items()}
    num = np.array([float(sp.sympify(c).subs(values)) for c in point])
    return sn.transform_from_study(num)


def _legs(d, gen, pose):
    """Per leg: its closure's point and the polyline of its body origins (base frame)."""
    links = gen.link_poses(pose)
    names = list(gen.LINKS)
    frames = {"base": np.eye(4)}
    out = []
    todo = [c for c in d.mechanism.closures if not c.driven]
    order = []
    while todo:  # a closure after the one that carries the body it stands on
        ready = [c for c in todo if c.base == "base" or c.base in {o.point for o in order}]
        if not ready:
            break
        order += ready
        todo = [c for c in todo if c not in ready]
    for closure in order:
        for leg in closure.legs:
            own = [i for i, n in enumerate(names) if n.startswith(f"{leg.name}.")]
            frame = frames.get(closure.base)
            if not own or frame is None:
                continue
            mats = [frame @ sn.transform_from_study(links[i]) for i in own]
            frames.setdefault(closure.point, mats[-1] @ _trailing(d, leg, pose))
            out.append((closure.point, np.array([t[:3, 3] for t in mats])))
    return out


def _draw(ax, d, gen, pose, title):
    colours = {}
    tips: dict[str, list] = {}
    for point, line in _legs(d, gen, pose):
        c = colours.setdefault(point, f"C{len(colours)}")
        if len(line):
            ax.plot(line[:, 0], line[:, 1], line[:, 2], "-o", color=c, ms=2.5, lw=1.4)
            tips.setdefault(point, []).append(line[-1])
    for point, pts in tips.items():
        if len(pts) > 1:  # two legs: the link between them; more: the platform polygon
            p = np.array(pts + [pts[0]] if len(pts) > 2 else pts)
            ax.plot(p[:, 0], p[:, 1], p[:, 2], "--", color=colours[point], lw=1.0)
    handles = [ax.plot([], [], "-o", color=c, ms=2.5, label=f"legs closing on {p}")[0]
               for p, c in colours.items()]
    handles.append(ax.plot([], [], "--", color="0.3", label="last joints of a closure's "
                                                             "legs (its platform)")[0])
    ax.legend(handles=handles, fontsize=6, loc="upper left")
    ax.set(xlabel="x (mm)", ylabel="y (mm)", zlabel="z (mm)", title=title)
    ax.title.set_fontsize(8)


def _relative(rel: float) -> str:
    """|p| at the found point: below MAX_RELATIVE is a zero, printed as the bound (its
    digits are floating-point noise, which differs between machines); a larger value (a
    sign change where the IK fails) at two digits."""
    return f"$<10^{{{round(np.log10(MAX_RELATIVE))}}}$" if rel <= MAX_RELATIVE else \
        number(rel, ".1e")


def _pose_text(gen, pose) -> str:
    return ", ".join(f"{n} = {number(v, '.4f')}" + (" rad" if u == "rad" else f" {u}")
                     for n, v, u in zip(gen.POSE, pose, gen.POSE_UNITS))


def run(d, gen) -> Study:
    m = d.mechanism
    home = np.asarray(m.home, dtype=float)
    rows = list(vanishing_configurations(gen, list(gen.SINGULARITY_MEANING), home).items())
    zeros = [(name, f[0]) for name, f in rows if f is not None and not f[3]]
    # drawn: a forward (type II) singularity where one was found, else the first zero
    typeii = [z for z in zeros if z[0].startswith(("det_forward", "det_Jo"))]
    first = (typeii or zeros or [None])[0]
    files = {}
    plt = pyplot()
    panels = [("home", home)] + ([(f"on {first[0]}", first[1])] if first else [])
    fig = plt.figure(figsize=(5.2 * len(panels), 4.6))
    for k, (label, pose) in enumerate(panels, 1):
        ax = fig.add_subplot(1, len(panels), k, projection="3d")
        _draw(ax, d, gen, pose, f"{m.name} {label}")
    files[f"{m.name}.configurations.png"] = png(fig)
    drawn = (f" and on {tex_escape(first[0])} at {tex_escape(_pose_text(gen, first[1]))}"
             if first else "")
    report = [r"\section{Configurations at home and on the singularity loci}"
              r"\label{sec:configurations}",
              "The drawing on the first page comes from the generated "
              "\\texttt{link\\_poses} (the origins of the bodies after each joint, base to "
              "platform; dashed: the last joints of each closure's legs), at home "
              f"({tex_escape(_pose_text(gen, home))}){drawn}.",
              "For each singularity polynomial, a configuration where it vanishes, searched "
              "along the pose axes through home (mm coordinates within "
              f"$\\pm{SPAN_MM:g}$ mm, angles within $\\pm{SPAN_RAD:g}$ rad, {SAMPLES} samples, "
              f"the sign change bisected {HALVINGS} times; $|p|$ relative to its largest value "
              "on the line). None found is not a proof that it never vanishes.",
              r"\begin{longtable}{lp{0.58\textwidth}ll}\toprule",
              r"polynomial & configuration & along & $|p|$ rel.\\\midrule"]
    for name, found in rows:
        if found is None:
            report.append(f"{tex_escape(name)} & none found along the pose axes & -- & --\\\\")
        else:
            pose, axis, rel, note = found
            report.append(f"{tex_escape(name)} & {tex_escape(_pose_text(gen, pose))}"
                          + (f" ({tex_escape(note)})" if note else "")
                          + f" & {tex_escape(axis)} & {_relative(rel)}\\\\")
    report.append(r"\bottomrule\end{longtable}")
    return Study("configurations", data={"rows": rows, "drawn": first}, files=files,
                 report=tuple(report))
