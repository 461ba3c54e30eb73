"""Paper 001 (Essomba et al., hybrid tripod-planar mechanism, Mechanical Sciences): its
printed equations and the verdicts of the derivation of ``tripod_planar`` against them.

The paper's (alpha, beta, gamma) are mechanism coordinates (B's roll and pitch, the planar
rotation), not the end effector's Euler angles: the checks convert with the derived zero
torsion of platform B (eq. 10).  Printed forms are transcribed as ``_printed_*`` references;
numeric checks use 40-digit mpmath at random poses (fixed seeds).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_symbolic as ss
from ..algebra.polyring import simplified
from ..algebra.study_symbolic import tan_half_substitution as _tan_half
from ..mechanisms.tripod_planar import (
    _B,
    JOINTS,
    POSE,
    PX,
    b1,
    b2,
    b3,
    d,
    g,
    q1,
    q2,
    q3,
    q4,
    q5,
    q6,
    ra,
    rb,
    s3,
    ta,
    tb,
    v1,
    v2,
    x1,
    y1,
)
from ..verification import Verdict, in_ideal, mpmath_function
from .planar_stage import output_determinant_with_ik

R = {"real": True}

# ------------------------------------------------------------------ printed results of 001
ap, bp, gp_, phi = sp.symbols("alpha_p beta_p gamma_p phi", **R)  # the paper's angles
x2s, y2s = sp.symbols("x2 y2", **R)
_SQ3 = sp.sqrt(3)


def _printed_eq21(xx, yy, gg):
    """001 eq. (21)-(23): q4, q5, q6 of the planar stage."""
    s_, c_ = sp.sin(gg), sp.cos(gg)
    den = s_ + _SQ3 * c_
    return [(rb + (_SQ3 * rb - 2 * xx) * s_ + (rb + 2 * yy) * c_) / den,
            (rb + (_SQ3 * rb + xx - _SQ3 * yy) * s_ + (rb - _SQ3 * xx - yy) * c_) / den,
            (rb + (_SQ3 * rb + xx + _SQ3 * yy) * s_ + (rb + _SQ3 * xx - yy) * c_) / den]


def _rpy_mp(a, b, f):
    """001 eq. (6) in mpmath."""
    import mpmath as mp

    sa, ca, sb, cb, sf, cf = mp.sin(a), mp.cos(a), mp.sin(b), mp.cos(b), mp.sin(f), mp.cos(f)
    return mp.matrix([[cb * cf, sa * sb * cf - ca * sf, ca * sb * cf + sa * sf],
                      [cb * sf, sa * sb * sf + ca * cf, ca * sb * sf - sa * cf],
                      [-sb, sa * cb, ca * cb]])


def _pose_from_paper_mp(paper):
    """Our pose (R = Rz(gamma) Ry(beta) Rx(alpha) of the end effector) from the paper's
    coordinates, with the derived zero torsion tan(phi/2) = tan(alpha_p/2) tan(beta_p/2)."""
    import mpmath as mp

    xx, yy, zz, a, b, gg = paper
    f = 2 * mp.atan(mp.tan(a / 2) * mp.tan(b / 2))
    rz = mp.matrix([[mp.cos(gg), -mp.sin(gg), 0], [mp.sin(gg), mp.cos(gg), 0], [0, 0, 1]])
    r = _rpy_mp(a, b, f) * rz
    return [xx, yy, zz, mp.atan2(r[2, 1], r[2, 2]),
            mp.atan2(-r[2, 0], mp.sqrt(r[0, 0] ** 2 + r[1, 0] ** 2)), mp.atan2(r[1, 0], r[0, 0])]


def _paper_ik(vals):
    """q1..q6 from the paper's coordinates (x, y, z, alpha_p, beta_p, gamma_p) through the
    printed equations only: (1)-(2), (6), (8) solved for (x2, y2, z1), (10)-(13), (21)-(23)."""
    import mpmath as mp

    xx, yy, zz, a, b, gg = vals["pose"]
    rr_a, rr_b, dd = vals["ra"], vals["rb"], vals["d"]
    f = mp.atan(mp.sin(a) * mp.sin(b) / (mp.cos(a) + mp.cos(b)))
    xb = -rr_b * mp.cos(b) * mp.sin(f)
    yb = rr_b * (mp.cos(a) * mp.cos(f) + mp.sin(a) * mp.sin(b) * mp.sin(f)
                 - mp.cos(b) * mp.cos(f)) / 2
    rot = _rpy_mp(a, b, f)
    # eq. (8): (x, y, z) = (x1, y1, z1) + R (x2, y2, d) -> linear in (x2, y2, z1)
    lhs = mp.matrix([[rot[0, 0], rot[0, 1], 0], [rot[1, 0], rot[1, 1], 0],
                     [rot[2, 0], rot[2, 1], 1]])
    rhs = mp.matrix([xx - xb - dd * rot[0, 2], yy - yb - dd * rot[1, 2], zz - dd * rot[2, 2]])
    x2v, y2v, z1v = mp.lu_solve(lhs, rhs)
    o1 = mp.matrix([xb, yb, z1v])
    s3v = mp.sqrt(3)
    a_pts = [(s3v / 2 * rr_a, -rr_a / 2, 0), (0, rr_a, 0), (-s3v / 2 * rr_a, -rr_a / 2, 0)]
    b_pts = [(s3v / 2 * rr_b, -rr_b / 2, 0), (0, rr_b, 0), (-s3v / 2 * rr_b, -rr_b / 2, 0)]
    qs = []
    for ak, bk in zip(a_pts, b_pts):
        v = o1 + rot * mp.matrix(bk) - mp.matrix(ak)
        qs.append(mp.sqrt(sum(c**2 for c in v)))  # eq. (13)
    sub = {x2s: x2v, y2s: y2v, gp_: gg, rb: rr_b}
    qs += [mp.mpf(sp.N(e.subs(sub), 40)) for e in _printed_eq21(x2s, y2s, gp_)]
    return qs, (f, xb, yb, z1v, x2v, y2v, rot)


def _random_paper_poses(n, seed=5):
    import numpy as np

    rng = np.random.default_rng(seed)
    return [(rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(180, 280),
             rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.8, 0.8))
            for _ in range(n)]


GEO = {"ra": 200, "rb": 200, "d": 15}  # d != 0 so that the checks see it


def verify(deriv, gen, studies) -> list:
    """Verdicts for 001 eq. (9)-(13), (17), (21)-(23), (27)-(53)."""
    import mpmath

    with mpmath.workdps(40):
        return _verify(deriv)


def _verify(deriv) -> list:
    import mpmath as mp

    out: list[Verdict] = []
    cs = deriv.constants
    par = deriv.analyses["parasitic"].solved
    tphi = sp.Symbol("t_phi", **R)

    # eq. (10): zero torsion <=> tan(phi/2) = t_alpha t_beta <=> the printed tan(phi)
    quat = ss.product(ss.rotation("z", tphi), ss.rotation("y", tb), ss.rotation("x", ta))
    tphi_d = sp.solve(sp.expand(quat[3]), tphi)
    printed_tan = _tan_half(sp.sin(ap) * sp.sin(bp) / (sp.cos(ap) + sp.cos(bp)),
                            [(ap, ta), (bp, tb)])
    ok10 = (par.get(b3) == 0 and len(tphi_d) == 1
            and simplified(2 * tphi_d[0] / (1 - tphi_d[0] ** 2) - printed_tan) == 0)
    out.append(Verdict(
        "001 eq. (10)", "parasitic rotation phi of platform B",
        "confirmed-symbolic" if ok10 else "erratum", None,
        "lex basis of the revolute-plane conditions with B = T(x1,y1,z1)[1:b1:b2:b3]: "
        + ", ".join(f"{k} = {sp.sstr(v)}" for k, v in par.items())
        + "; b3 = 0 (zero torsion) for Rz(phi)Ry(beta)Rx(alpha) means tan(phi/2) = "
        f"{sp.sstr(tphi_d)}, whose tan(phi) is the printed s_a s_b / (c_a + c_b)"))

    # eq. (11), (12): x1, y1 from the derived parasitic motion, B's rotation from eq. (6)
    qb = ss.product(ss.rotation("z", ta * tb), ss.rotation("y", tb), ss.rotation("x", ta))
    fill = {b1: qb[1] / qb[0], b2: qb[2] / qb[0]}
    sph, cph = 2 * ta * tb / (1 + (ta * tb) ** 2), (1 - (ta * tb) ** 2) / (1 + (ta * tb) ** 2)
    sa_, ca_ = 2 * ta / (1 + ta**2), (1 - ta**2) / (1 + ta**2)
    sb_, cb_ = 2 * tb / (1 + tb**2), (1 - tb**2) / (1 + tb**2)
    printed = {x1: -rb * cb_ * sph, y1: rb * (ca_ * cph + sa_ * sb_ * sph - cb_ * cph) / 2}
    for ref, v in (("001 eq. (11)", x1), ("001 eq. (12)", y1)):
        diff = simplified(sp.sympify(par[v]).subs(fill) - printed[v])
        out.append(Verdict(ref, f"parasitic translation {v} of platform B",
                           "confirmed-symbolic" if diff == 0 else "erratum", None,
                           f"derived {v} = {sp.sstr(par[v])} with (b1, b2) of "
                           f"Rz(phi)Ry(beta)Rx(alpha); minus the printed form = {sp.sstr(diff)}"))

    # eq. (9): B_k in the plane of its revolute joint, as a member of each leg's ideal
    xq = (1, *PX[:3])
    tvec = cv.translation_times_norm((1, *PX))
    rot_n = sp.Matrix(cv.rotation_matrix_times_norm(xq))
    ok9 = True
    for k, r in enumerate(r for r in deriv.legs if r.closure.point == "B"):
        bk = sp.Matrix(tvec) + rot_n * sp.Matrix(_B[k])  # |x|^2 * OB_k
        ang = sp.pi / 2 + [-sp.pi / 6, sp.pi / 2, 7 * sp.pi / 6][k]
        tangent = sp.Matrix([sp.cos(ang), sp.sin(ang), 0]).subs(sp.sqrt(3), s3)
        ok9 &= in_ideal(sp.expand(bk.dot(tangent) * 2), r.result.generators, r.problem.keep)
    out.append(Verdict("001 eq. (9)", "spherical joints B_k in the planes of their revolute "
                       "joints: OB_k . s_k2 = 0", "confirmed-symbolic" if ok9 else "erratum",
                       None, "|x|^2 OB_k . s_k2 (Study coordinates of B) lies in each tripod "
                       f"leg's ideal (normal form 0){'' if ok9 else ': FAILED'}"))

    # eq. (21)-(23): planar IK in (x2, y2, gamma_p), symbolic
    tgp = sp.Symbol("t_gamma_p", **R)
    mp_c = {g: tgp, v1: -(x2s + tgp * y2s) / 2, v2: -(y2s - tgp * x2s) / 2}
    printed21 = _printed_eq21(x2s, y2s, gp_)
    for k, qk in enumerate((q4, q5, q6)):
        st = next(s for s in deriv.steps if s.joint == qk)
        derived = sp.cancel((-st.C / st.B).subs(cs).subs(mp_c))
        diff = simplified(derived - sp.cancel(_tan_half(printed21[k], [(gp_, tgp)])))
        out.append(Verdict(f"001 eq. ({21 + k})", f"planar IK {qk}(x2, y2, gamma)",
                           "confirmed-symbolic" if diff == 0 else "erratum", None,
                           f"derived generator solved for {qk} minus the printed form = "
                           f"{sp.sstr(diff)}"))

    # eq. (17): the printed O1R1 against eq. (21)
    qq, ll = sp.symbols("q_k l_k", **R)
    rz = sp.rot_axis3(-gp_)[:2, :2]
    r1_printed = sp.Matrix([_SQ3 / 2 * rb - qq / 2, rb / 2 + _SQ3 / 2 * qq])
    r1_read = sp.Matrix([_SQ3 / 2 * rb - qq / 2, -rb / 2 + _SQ3 / 2 * qq])
    rp1 = sp.Matrix([x2s, y2s]) + rz * sp.Matrix([_SQ3 / 2 * rb - ll, rb / 2])
    sols = {}
    for lab, r1 in (("printed", r1_printed), ("read", r1_read)):
        sol = sp.solve(list(r1 - rp1), [qq, ll], dict=True)[0]
        sols[lab] = simplified(sp.expand_trig(sol[qq] - printed21[0]))
    out.append(Verdict(
        "001 eq. (17)", "position of the active prismatic joint R1 on platform B",
        "erratum" if sols["printed"] != 0 and sols["read"] == 0 else "confirmed-symbolic", None,
        "with the printed O1R1 = (sqrt3/2 rb - q4/2, rb/2 + sqrt3/2 q4), eq. (20) gives q4 - "
        f"eq.(21) = {sp.sstr(sols['printed'])}; with -rb/2 (the lower corner at -30 deg, as 000 "
        f"eq. 1) the difference is {sp.sstr(sols['read'])}. Corrected: O1R1 = (sqrt3/2 rb - "
        "q4/2, -rb/2 + sqrt3/2 q4, 0)"))

    # eq. (13), (21)-(23) numerically, through the full pose
    ik = deriv.ik_expressions()
    geo = {ra: GEO["ra"], rb: GEO["rb"], d: GEO["d"]}
    f_ik = mpmath_function(POSE, [ik[q].xreplace(geo) for q in JOINTS])
    errs = [0.0] * 6
    for paper in _random_paper_poses(40):
        paper = [mp.mpf(v) for v in paper]
        derived = f_ik(*_pose_from_paper_mp(paper))
        printed_q, _ = _paper_ik({"pose": paper, **GEO})
        for k in range(6):
            errs[k] = max(errs[k], float(abs(derived[k] - printed_q[k])))
    for k in range(6):
        ref = "001 eq. (13)" if k < 3 else f"001 eq. ({18 + k})"
        out.append(Verdict(
            f"{ref}, q{k + 1}", f"IK of q{k + 1} from the paper's (x, y, z, alpha, beta, gamma)",
            "confirmed-numeric" if errs[k] < 1e-9 else "erratum", float(f"{errs[k]:.2e}"),
            "derived IK (end-effector rotation from the paper's angles with the derived zero "
            "torsion) vs the printed chain (10)-(13), (8), (21)-(23) at 40 random poses "
            "(|x|,|y| < 40, z in [180, 280] mm, |alpha|,|beta| < 0.3, |gamma| < 0.8 rad; "
            "ra = rb = 200 mm, d = 15 mm)"))
    out += _verify_velocity(deriv)
    out += _verify_singularities(deriv)
    for ref, what in [("001 eq. (1)-(3)", "joint positions A_k, B_k, C_k"),
                      ("001 eq. (4)-(8)", "loop closure of the tripod and eq. (8)"),
                      ("001 eq. (18)-(20)", "passive prismatic joints R'_k and eq. (20)")]:
        out.append(Verdict(ref, what, "not-checkable", None, "input of the derivation"))
    return out


def _parasitic_of_angles(par):
    """Derived (phi, x1, y1) of platform B as functions of the paper's alpha_p, beta_p."""
    qb = ss.product(ss.rotation("z", ta * tb), ss.rotation("y", tb), ss.rotation("x", ta))
    fill = {b1: qb[1] / qb[0], b2: qb[2] / qb[0]}
    halves = {ta: sp.tan(ap / 2), tb: sp.tan(bp / 2)}
    return (2 * sp.atan(ta * tb).subs(halves),
            sp.sympify(par[x1]).subs(fill).subs(halves),
            sp.sympify(par[y1]).subs(fill).subs(halves), fill, halves)


def _verify_velocity(deriv) -> list:
    import mpmath as mp
    import numpy as np

    out = []
    par = deriv.analyses["parasitic"].solved
    geo = {ra: GEO["ra"], rb: GEO["rb"], d: GEO["d"]}
    phi_d, x1_d, y1_d, fill, halves = _parasitic_of_angles(par)
    sa, ca, sb, cb = sp.sin(ap), sp.cos(ap), sp.sin(bp), sp.cos(bp)
    f_pr = sp.atan(sa * sb / (ca + cb))
    sf, cf = sp.sin(f_pr), sp.cos(f_pr)
    den = 1 + ca * cb
    kk = (sa * sb * cf - ca * sf + cb * sf) / den
    printed = {
        "001 eq. (27)": (phi_d, [sb / den, sa / den]),
        "001 eq. (28)": (x1_d, [-cb * sb * cf / den, rb * (sb * sf - sa * cb * cf / den)]),
        "001 eq. (29)": (y1_d, [rb * (ca * sb * sf - sa * cf + sb * kk) / 2,
                                rb * (sa * cb * sf + sb * cf + sa * kk) / 2]),
    }
    rng = np.random.default_rng(11)
    angles = [(rng.uniform(-0.35, 0.35), rng.uniform(-0.35, 0.35)) for _ in range(30)]
    derived_rows = {}
    for ref, (expr, coeffs) in printed.items():
        der = [sp.diff(expr, v).xreplace(geo) for v in (ap, bp)]
        derived_rows[ref] = der
        f_d = mpmath_function((ap, bp), der)
        f_p = mpmath_function((ap, bp), [c.xreplace(geo) for c in coeffs])
        err = [0.0, 0.0]
        for a, b in angles:
            dv, pv = f_d(a, b), f_p(a, b)
            err = [max(err[i], float(abs(dv[i] - pv[i]))) for i in range(2)]
        worst = max(err)
        which = ["alpha' coefficient", "beta' coefficient"][int(np.argmax(err))]
        out.append(Verdict(
            ref, "time derivative of the parasitic motion",
            "confirmed-numeric" if worst < 1e-9 else "erratum", float(f"{worst:.2e}"),
            "printed coefficients vs the derivatives of the derived phi, x1, y1 (eq. 10-12) at "
            "30 random |alpha|,|beta| < 0.35 rad, rb = 200 mm"
            + ("" if worst < 1e-9 else f"; the {which} differs (errors {err[0]:.3g}, "
               f"{err[1]:.3g})")))

    # eq. (28) with the factor rb, and the two entries where eq. (33) differs from (27)-(29)
    alt = {
        "eq. (28) with rb times the printed alpha' coefficient":
            (derived_rows["001 eq. (28)"][0], rb * printed["001 eq. (28)"][1][0]),
        "eq. (33) row x1, alpha' (printed without rb, as eq. 28)":
            (derived_rows["001 eq. (28)"][0], -cb * sb * cf / den),
        "eq. (33) row y1, beta' (printed s_a c_b s_phi - s_b c_phi + s_a K)":
            (derived_rows["001 eq. (29)"][1], rb * (sa * cb * sf - sb * cf + sa * kk) / 2),
    }
    alt_err = {}
    for label, (dv, pv) in alt.items():
        f_a = mpmath_function((ap, bp), [dv.xreplace(geo), pv.xreplace(geo)])
        alt_err[label] = max(float(abs(u - w)) for u, w in (f_a(a, b) for a, b in angles))
    rb_fix = alt_err["eq. (28) with rb times the printed alpha' coefficient"]
    if rb_fix < 1e-9:
        out[1] = Verdict(out[1].ref, out[1].quantity, out[1].verdict, out[1].max_error,
                         out[1].detail + "; the alpha' coefficient lacks the factor rb: "
                         f"-rb c_b s_b c_phi / (1 + c_a c_b) matches to {rb_fix:.2e}")
    e33 = [alt_err[k] for k in list(alt)[1:]]
    out.append(Verdict(
        "001 eq. (33)", "J_B2, rows of x1' and y1'",
        "confirmed-numeric" if max(e33) < 1e-9 else "erratum", float(f"{max(e33):.2e}"),
        f"row x1, alpha' column: no factor rb (as eq. 28), error {e33[0]:.3g}; row y1, "
        f"beta' column: -s_b c_phi where eq. (29) has +s_b c_phi, error {e33[1]:.3g} against "
        "the derivative of the derived y1; eq. (29) itself is confirmed"))

    # eq. (30)-(33): J_B = J_B1 J_B2 against d(q1, q2, q3)/d(z1, alpha, beta)
    zz = sp.Symbol("z1", **R)
    xq = (1, fill[b1], fill[b2], 0)
    bst = xq + cv.dual_part_from_translation((sp.sympify(par[x1]).subs(fill),
                                               sp.sympify(par[y1]).subs(fill), zz), xq)
    pxs = {s: bst[i + 1] for i, s in enumerate(PX)}
    qk_expr = []
    for qk in (q1, q2, q3):
        st = next(s for s in deriv.steps if s.joint == qk)
        a_, b_, c_ = (sp.sympify(e).subs(deriv.constants).xreplace(pxs) for e in
                      (st.A, st.B, st.C))
        qk_expr.append(((-b_ + sp.sqrt(b_**2 - 4 * a_ * c_)) / (2 * a_)).subs(halves))
    # the geometry is integers: xreplace gives subs's expressions without its search
    jac_qk = sp.Matrix(qk_expr).jacobian([zz, ap, bp]).xreplace(geo)
    jac_d = mpmath_function((zz, ap, bp), jac_qk)
    par_num = mpmath_function((ap, bp), [phi_d, x1_d.xreplace(geo), y1_d.xreplace(geo)])
    # eq. (33) as printed: rows x1', y1' (without rb; -s_b c_phi), z1', w = (a', b', phi')
    jb2_rows = mpmath_function((ap, bp), [alt[k][1].xreplace(geo) for k in list(alt)[1:2]]
                               + [printed["001 eq. (28)"][1][1].xreplace(geo)]
                               + [printed["001 eq. (29)"][1][0].xreplace(geo),
                                  list(alt.values())[2][1].xreplace(geo)]
                               + list(printed["001 eq. (27)"][1]))
    der_rows = mpmath_function((ap, bp), [c for ref in ("001 eq. (28)", "001 eq. (29)",
                                                        "001 eq. (27)")
                                          for c in derived_rows[ref]])
    s3v = mp.sqrt(3)
    a_pts = [mp.matrix(p) for p in ((s3v / 2 * GEO["ra"], -GEO["ra"] / 2, 0), (0, GEO["ra"], 0),
                                    (-s3v / 2 * GEO["ra"], -GEO["ra"] / 2, 0))]
    b_loc = [mp.matrix(p) for p in ((s3v / 2 * GEO["rb"], -GEO["rb"] / 2, 0), (0, GEO["rb"], 0),
                                    (-s3v / 2 * GEO["rb"], -GEO["rb"] / 2, 0))]
    err_p, err_c = 0.0, 0.0
    for (a, b), z1v in zip(angles, np.linspace(180, 280, len(angles))):
        f, xb, yb = par_num(a, b)
        rot = _rpy_mp(a, b, f)
        o1 = mp.matrix([xb, yb, z1v])
        jb1 = mp.matrix(3, 6)
        for k in range(3):
            v = o1 + rot * b_loc[k] - a_pts[k]
            s_k = v / mp.norm(v)
            arm = rot * b_loc[k]
            cross = [arm[1] * s_k[2] - arm[2] * s_k[1], arm[2] * s_k[0] - arm[0] * s_k[2],
                     arm[0] * s_k[1] - arm[1] * s_k[0]]
            for j in range(3):
                jb1[k, j], jb1[k, 3 + j] = s_k[j], cross[j]
        pr = jb2_rows(a, b)
        jb2 = mp.matrix([[0, pr[0], pr[1]], [0, pr[2], pr[3]], [1, 0, 0],
                         [0, 1, 0], [0, 0, 1], [0, pr[4], pr[5]]])
        dr = der_rows(a, b)
        # angular velocity of Rz(phi) Ry(beta) Rx(alpha): w = Rz Ry e_x a' + Rz e_y b' + e_z f'
        ex = _rpy_mp(0, b, f) * mp.matrix([1, 0, 0])
        ey = _rpy_mp(0, 0, f) * mp.matrix([0, 1, 0])
        omega = [[ex[i] + dr[4] * (i == 2), ey[i] + dr[5] * (i == 2)] for i in range(3)]
        jb2c = mp.matrix([[0, dr[0], dr[1]], [0, dr[2], dr[3]], [1, 0, 0],
                          [0, *omega[0]], [0, *omega[1]], [0, *omega[2]]])
        jd = jac_d(z1v, a, b)
        err_p = max(err_p, _maxabs(jb1 * jb2 - jd))
        err_c = max(err_c, _maxabs(jb1 * jb2c - jd))
    out.append(Verdict(
        "001 eq. (30)-(33)", "tripod velocity model J_A q' = J_B1 J_B2 (z1', alpha', beta')",
        "confirmed-numeric" if err_p < 1e-9 else "erratum", float(f"{err_p:.2e}"),
        "printed J_B1 J_B2 (eq. 32-33 as printed) vs the derivative of the derived q1..q3 in "
        "(z1, alpha, beta) at 30 poses. Besides the two entries of eq. (33) above, J_B2 takes "
        "the angular velocity as (alpha', beta', phi'), which holds only at alpha = beta = 0. "
        "Corrected: w = Rz(phi)Ry(beta) e_x alpha' + Rz(phi) e_y beta' + e_z phi' with the "
        f"derived rows of eq. (27)-(29); then J_B1 J_B2 matches to {err_c:.2e}"))

    # eq. (47), Fig. 5: forward singularity of the tripod, det d(q1..q3)/d(z1, alpha, beta)
    out.append(_tripod_forward_singularity(jac_qk, zz))

    # eq. (34)-(46): planar velocity model against the derived q4..q6(x2, y2, gamma)
    tgp = sp.Symbol("t_gamma_p", **R)
    mp_c = {g: tgp, v1: -(x2s + tgp * y2s) / 2, v2: -(y2s - tgp * x2s) / 2}
    qp = []
    for qk in (q4, q5, q6):
        st = next(s for s in deriv.steps if s.joint == qk)
        qp.append((-st.C / st.B).subs(deriv.constants).subs(mp_c).subs(tgp, sp.tan(gp_ / 2)))
    jder = mpmath_function((x2s, y2s, gp_),
                           sp.Matrix(qp).jacobian([x2s, y2s, gp_]).xreplace(geo))
    s_, c_ = sp.sin(gp_), sp.cos(gp_)
    q4p, q5p, q6p = _printed_eq21(x2s, y2s, gp_)
    jc = s_ + _SQ3 * c_
    jd = sp.Matrix([
        [-2 * s_, 2 * c_, (_SQ3 * rb - 2 * x2s) * c_ - (rb + 2 * y2s) * s_
         - q4p * (c_ - _SQ3 * s_)],
        [s_ - _SQ3 * c_, -c_ - _SQ3 * s_, (_SQ3 * rb + x2s - _SQ3 * y2s) * c_
         - (rb - _SQ3 * x2s - y2s) * s_ - q5p * (c_ - _SQ3 * s_)],
        [s_ + _SQ3 * c_, -c_ + _SQ3 * s_, (_SQ3 * rb + x2s + _SQ3 * y2s) * c_
         - (rb + _SQ3 * x2s - y2s) * s_ - q6p * (c_ - _SQ3 * s_)]])
    jpr = mpmath_function((x2s, y2s, gp_), (jd / jc).xreplace(geo))
    err34 = 0.0
    for _ in range(30):
        args = (rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-0.8, 0.8))
        err34 = max(err34, _maxabs(jpr(*args) - jder(*args)))
    out.append(Verdict(
        "001 eq. (34)-(46)", "planar velocity model J_C q' = J_D (x2', y2', gamma')",
        "confirmed-numeric" if err34 < 1e-9 else "erratum", float(f"{err34:.2e}"),
        "J_C^-1 J_D (q4..q6 from eq. 21-23) vs the derivative of the derived q4..q6 at 30 "
        "random (x2, y2, gamma), rb = 200 mm"))
    return out


def _tripod_forward_singularity(jac, zz):
    """Where det d(q1, q2, q3)/d(z1, alpha_p, beta_p) of the derived tripod IK (``jac``, at
    the geometry GEO) changes sign for |alpha_p|, |beta_p| <= 20 deg (001 eq. 47 and Fig.
    5), scanned in z1."""
    import numpy as np

    f = sp.lambdify((zz, ap, bp), list(jac), modules="numpy", cse=True)
    grid = np.radians(np.linspace(-20.0, 20.0, 17))
    a, b, zv = np.meshgrid(grid, grid, np.linspace(0.5, 400.0, 800), indexing="ij")
    vals = np.stack(np.broadcast_arrays(*f(zv, a, b)), axis=-1).reshape(a.shape + (3, 3))
    det = np.linalg.det(vals)
    change = np.sign(det[..., 1:]) != np.sign(det[..., :-1])
    z_sing = zv[..., 1:][change]
    lo, hi = (float(z_sing.min()), float(z_sing.max())) if z_sing.size else (0.0, 0.0)
    detail = ("det of the derivative of the derived q1..q3 in (z1, alpha_p, beta_p), ra = rb = "
              "200 mm, on a 17 x 17 grid of |alpha_p|, |beta_p| <= 20 deg and z1 in (0, 400] "
              "mm (step 0.5 mm): ")
    if z_sing.size:
        detail += (f"sign changes (forward singularities) for z1 between {lo:.1f} and {hi:.1f} "
                   "mm; the paper reports a risk of singularity for z from 0 to 111.8 mm. The "
                   "paper's z is not defined for this plot (O1 or O2) and its grid is unknown")
    else:
        detail += "no sign change"
    return Verdict("001 eq. (47), Fig. 5", "forward singularity of the tripod over the "
                   "workspace", "not-checkable", None, detail)


def _maxabs(m) -> float:
    return float(max(abs(e) for e in m))


def _verify_singularities(deriv) -> list:
    out = []
    cs = deriv.constants
    sing = {s.name: s for s in deriv.singularities}
    # eq. (48)-(49): det J_C = (s g + sqrt3 c g)^3 -> gamma = 2 pi/3, -pi/3
    det_c = sing["det_Ji_C"]
    roots = set()
    for f, _ in det_c.factors:
        f = sp.expand(f.subs(cs))
        if f.free_symbols == {g}:
            roots |= {sp.nsimplify(2 * sp.atan(r)) for r in sp.solve(f, g)}
    ok49 = roots == {2 * sp.pi / 3, -sp.pi / 3}
    tgp = sp.Symbol("t_gamma_p", **R)
    printed48 = sp.factor(sp.cancel(_tan_half((sp.sin(gp_) + _SQ3 * sp.cos(gp_)) ** 3,
                                              [(gp_, tgp)])), extension=_SQ3)
    out.append(Verdict(
        "001 eq. (48)-(49)", "planar input singularity det J_C = 0",
        "confirmed-symbolic" if ok49 else "erratum", None,
        "derived det Ji of the planar closure = "
        f"{sp.sstr(sp.factor(det_c.expression.subs(cs), extension=_SQ3))} (g = tan(gamma/2)); "
        f"printed (s g + sqrt3 c g)^3 = {sp.sstr(printed48)}; roots gamma in "
        f"{sorted(map(str, roots))}"))

    # eq. (50)-(51): the printed determinant of J_D and its sum form
    s_, c_ = sp.sin(gp_), sp.cos(gp_)
    j13, j23, j33, qs4, qs5, qs6 = sp.symbols("J_D13 J_D23 J_D33 q4 q5 q6", **R)
    jd = sp.Matrix([[-2 * s_, 2 * c_, j13], [s_ - _SQ3 * c_, -c_ - _SQ3 * s_, j23],
                    [s_ + _SQ3 * c_, -c_ + _SQ3 * s_, j33]])
    ok50 = simplified(jd.det() - 2 * _SQ3 * (j13 + j23 + j33)) == 0
    out.append(Verdict("001 eq. (50)", "det J_D = 2 sqrt3 (J_D13 + J_D23 + J_D33)",
                       "confirmed-symbolic" if ok50 else "erratum", None,
                       "cofactor expansion of the printed J_D (eq. 37-46) along column 3"))
    entries = [(_SQ3 * rb - 2 * x2s) * c_ - (rb + 2 * y2s) * s_ - qs4 * (c_ - _SQ3 * s_),
               (_SQ3 * rb + x2s - _SQ3 * y2s) * c_ - (rb - _SQ3 * x2s - y2s) * s_
               - qs5 * (c_ - _SQ3 * s_),
               (_SQ3 * rb + x2s + _SQ3 * y2s) * c_ - (rb + _SQ3 * x2s - y2s) * s_
               - qs6 * (c_ - _SQ3 * s_)]
    sum51 = 3 * rb * (_SQ3 * c_ - s_) - (qs4 + qs5 + qs6) * (c_ - _SQ3 * s_)
    ok51 = simplified(sum(entries) - sum51) == 0
    ok51_det = sp.simplify(jd.det().subs(dict(zip((j13, j23, j33), entries))) - sum51) == 0
    out.append(Verdict(
        "001 eq. (51)", "det J_D = 3 rb (sqrt3 c g - s g) - (q4 + q5 + q6)(c g - sqrt3 s g)",
        "confirmed-symbolic" if ok51_det else "erratum", None,
        ("the right side is J_D13 + J_D23 + J_D33, the sum of the printed eq. (40), (43), (46) "
         "(checked symbolically), which by eq. (50) is det J_D / (2 sqrt3), not det J_D: the "
         "left side should read J_D13 + J_D23 + J_D33 (or the right side carry the factor "
         "2 sqrt3); the zeros, and so eq. (52)-(53), are not affected" if ok51 else
         "the right side is not the sum of the printed eq. (40), (43), (46), and not det J_D")
        + (" (eq. (50) itself is confirmed)" if ok50 else "")))
    # eq. (52)-(53): substitute eq. (21)-(23)
    q_sub = dict(zip((qs4, qs5, qs6), _printed_eq21(x2s, y2s, gp_)))
    got = sp.simplify(sp.expand_trig(sum51.subs(q_sub)))
    correct = 3 * rb * (2 - c_ + _SQ3 * s_) / (s_ + _SQ3 * c_)
    printed52 = (2 - c_ - _SQ3 * s_) / (s_ + _SQ3 * c_)
    ok_correct = simplified(got - correct) == 0
    ok52 = sp.simplify(got - printed52) == 0
    # independently: the derived output Jacobian of the planar closure with the IK inserted
    fwd, fwd_roots = output_determinant_with_ik(deriv, "det_Jo_C", (q4, q5, q6), g)
    out.append(Verdict(
        "001 eq. (52)", "det J_D with the IK inserted",
        "confirmed-symbolic" if ok52 else "erratum", None,
        f"eq. (51) with eq. (21)-(23) inserted is {sp.sstr(got)}"
        + (" = 3 rb (2 - c g + sqrt3 s g)/(s g + sqrt3 c g)" if ok_correct else "")
        + ", not the printed (2 - c g - sqrt3 s g)/(s g + sqrt3 c g): the sign of sqrt3 s g "
        "and the factor 3 rb differ. The derived output Jacobian of the planar closure (Study "
        f"coordinates) with the derived IK inserted factors as {sp.sstr(fwd)}, vanishing only "
        f"at gamma in {fwd_roots}"))
    out.append(Verdict(
        "001 eq. (53)", "planar forward singularity gamma = pi/3 + 2k pi",
        "erratum" if not ok52 else "confirmed-symbolic", None,
        "2 - c g + sqrt3 s g = 2 - 2 cos(gamma + pi/3) vanishes at gamma = -pi/3 + 2k pi, "
        "where s g + sqrt3 c g = 0 as well (the input singularity of eq. 49): the planar "
        "stage has no forward singularity of its own, which agrees with the paper's sentence "
        "that eq. (48) and (52) lead to the same configuration (Fig. 7); gamma = pi/3 is "
        "regular (det J_D = 3 rb (2 - 1/2 + 3/2)/sqrt3 != 0)"))
    return out




def report_sections(deriv, studies) -> list[str]:
    """What the derived parasitic motion means for 001 eq. (10)-(12), and the pose
    convention."""
    out = ["So platform B never twists ($b_3 = 0$, zero torsion): for "
           "$R_z(\\varphi)R_y(\\beta)R_x(\\alpha)$ this is "
           "$\\tan(\\varphi/2) = \\tan(\\alpha/2)\\tan(\\beta/2)$, eq. (10); "
           "$x_1 = -r_b R_{21}$ and $y_1 = r_b (R_{22} - R_{11})/2$ are eq. (11)-(12)."]
    out += [r"\section{Pose convention}",
            "The paper's $(\\alpha, \\beta, \\gamma)$ are mechanism coordinates: the end "
            "effector turns by $R_z(\\varphi)R_y(\\beta_p)R_x(\\alpha_p)R_z(\\gamma_p)$. The "
            "generated functions take the actual rotation "
            "$R = R_z(\\gamma)R_y(\\beta)R_x(\\alpha)$ "
            "(DESIGN.md), so that every mechanism of the project (and the Stewart platform of the "
            "workspace comparison) reads a pose the same way. Because $B$ has no torsion, the "
            "split is rational: $\\tan(\\gamma_p/2) = x_3/x_0$ of the end effector's Study point, "
            "and $B$'s rotation is $[x_0^2 + x_3^2 : x_0x_1 - x_2x_3 : x_0x_2 + x_1x_3 : 0]$. "
            "\\texttt{paper\\_coordinates} and \\texttt{pose\\_from\\_paper\\_coordinates} "
            "convert between the two.",
            "The Study coordinates the IK needs are built from the pose in this order: "
            "$e = R_z(t_\\gamma)R_y(t_\\beta)R_x(t_\\alpha)$ (tan-half-angles); "
            "$g = e_3/e_0$; $b = [e_0^2+e_3^2 : e_0e_1-e_2e_3 : e_0e_2+e_1e_3 : 0]$; "
            "$(x_1, y_1)$ from the parasitic motion above; "
            "$z_1 = (n\\cdot(x - x_1, y - y_1, z) - d)/n_z$ with $n$ the normal of B; "
            "$(x_2, y_2) = $ the first two rows of $R_B^T (x - x_1, y - y_1, z - z_1)$; "
            "B's Study point is $[1:b_1:b_2:0] + \\varepsilon\\,(-\\tfrac12 t\\,[1:b_1:b_2:0])$ "
            "and C's is $[1:0:0:g:dg/2:v_1:v_2:-d/2]$ with $v_1 = -(x_2+gy_2)/2$, "
            "$v_2 = -(y_2-gx_2)/2$."]
    return out
