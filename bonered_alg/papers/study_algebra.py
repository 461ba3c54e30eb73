"""004 Sect. 2 (Vaida, Pisla et al., Symmetry 11, 1491, 2019): the Study-parameter framework
itself, eq. (3)-(7) and (13), checked against the algebra every mechanism uses.

These verdicts belong to no mechanism: they have their own record,
``derivations/study_algebra.verification.json`` with a short report beside it, derived
again only when the algebra or this module changes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import sympy as sp

from ..algebra import convention as cv
from ..algebra import study_numeric as sn
from ..verification import Verdict, noise_bound

NAME = "study_algebra"


def algebra_verdicts(seed: int = 4) -> list[Verdict]:
    """Checks of 004 eq. (3), (4), (5), (7), (13): the Study-parameter framework."""
    x = sp.symbols("x0:4", real=True)
    y = sp.symbols("y0:4", real=True)
    t = sp.symbols("t_x t_y t_z", real=True)
    n = cv.rotation_norm(x)
    out = []

    # eq. (4): each ratio row is proportional to x (row k = 4 x_k x / |x|^2)
    rmat = [[c / n for c in row] for row in cv.rotation_matrix_times_norm(x)]
    rows = cv.rotation_ratios(rmat)
    ok4 = all(sp.cancel(rows[k][i] - 4 * x[k] * x[i] / n) == 0 for k in range(4) for i in range(4))
    out.append(Verdict("004 eq. (4)", "rotation matrix -> x0:x1:x2:x3, four ratios",
                       "confirmed-symbolic" if ok4 else "erratum", None,
                       "each of the four ratios equals 4 x_k (x0:x1:x2:x3) for the rotation "
                       "matrix of x, so every ratio is correct and at least one is non-zero"))

    # eq. (5) as printed
    tx, ty, tz = t
    x0, x1, x2, x3 = x
    printed5 = (-(tz * x3 + ty * x2 + tx * x1) / 2, -(tz * x2 - ty * x3 + tx * x0) / 2,
                -(-tz * x1 - ty * x0 + tx * x3) / 2, -(-tz * x0 + ty * x1 - tx * x2) / 2)
    residual = sp.factor(sp.expand(sum(a * b for a, b in zip(x, printed5))))
    ours = cv.dual_part_from_translation(t, x)
    plus_half = tuple(-c for c in ours)  # the y = +1/2 t x convention
    diff_plus = [sp.expand(p - q) for p, q in zip(printed5, plus_half)]
    out.append(Verdict(
        "004 eq. (5)", "translation -> y0:y1:y2:y3",
        "erratum" if residual != 0 else "confirmed-symbolic", None,
        "printed y0, y2, y3 are those of y = +1/2 t x, the opposite sign of eq. (13) and of "
        "Tables 1-3 (translation t along X is [1:0:0:0:0:-t/2:0:0]); printed y1 differs from "
        f"that convention by {sp.sstr(diff_plus[1])}, so the printed point is off the Study "
        f"quadric: x0 y0 + ... + x3 y3 = {sp.sstr(residual)}. Corrected (y = -1/2 t x): "
        + ", ".join(f"y{i} = {sp.sstr(sp.factor(c))}" for i, c in enumerate(ours)),
        evidence=r"x_0y_0+x_1y_1+x_2y_2+x_3y_3 = " + sp.latex(residual)
        + r"\neq 0 \text{ for eq. (5) as printed.}"))

    # eq. (13) inverts y = -1/2 t x
    ok13 = all(sp.expand(a - n * b) == 0
               for a, b in zip(cv.translation_times_norm(x + tuple(ours)), t))
    out.append(Verdict("004 eq. (13)", "Study point -> translation", "confirmed-symbolic"
                       if ok13 else "erratum", None,
                       "t = -2 y conj(x) / |x|^2 recovers t from y = -1/2 t x exactly"))

    # eq. (7): Q * conj(Q) = [|x|^2 : 0 : 0 : 0 : 2 (x.y) : 0 : 0 : 0]
    q = tuple(x) + tuple(y)
    qq = [sp.expand(c) for c in cv.study_product(q, cv.study_conjugate(q))]
    target = [sp.expand(n), 0, 0, 0, sp.expand(2 * cv.study_quadric(q)), 0, 0, 0]
    ok7 = all(sp.expand(a - b) == 0 for a, b in zip(qq, target))
    out.append(Verdict("004 eq. (7)", "conjugate is the inverse", "confirmed-symbolic"
                       if ok7 else "erratum", None,
                       "Q conj(Q) = [|x|^2:0:0:0:2(x.y):0:0:0], i.e. [1:0:...:0] on the quadric "
                       "(eq. 3) with normalization (eq. 2)"))

    # numeric round trip of eq. (4)-(5 corrected)-(13) at random transforms and half-turns
    rng = np.random.default_rng(seed)
    mats = []
    for k in range(200):
        qr, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        qr *= np.sign(np.linalg.det(qr))
        if k < 3:  # half-turns about the frame axes
            qr = np.diag(np.where(np.arange(3) == k, 1.0, -1.0))
        m = np.eye(4)
        m[:3, :3] = qr
        m[:3, 3] = rng.normal(scale=200.0, size=3)
        mats.append(m)
    mats = np.array(mats)
    back = sn.transform_from_study(sn.study_from_transform(mats))
    err = noise_bound(float(np.max(np.abs(back - mats))))
    out.append(Verdict("004 eq. (4)+(13)", "round trip transform -> Study -> transform",
                       "confirmed-numeric", err,
                       "200 random transforms (translations ~200 mm) including half-turns; "
                       f"largest-pivot ratio of eq. (4); the error is below {err:.0e} "
                       "(floating-point noise)"))
    return out


def record_hash() -> str:
    """The hash of what produces this record (this module and what it imports)."""
    from ..pipeline.provenance import derivation_hash
    from ..pipeline.stages import GENERATOR

    return derivation_hash(__name__, GENERATOR, extra_roots=("bonered_alg.pipeline.outputs",))


def report(verdicts, digest: str) -> str:
    """A short LaTeX report: the verdicts and the evidence for the errata."""
    from ..report.latex_report import PREAMBLE, section_verification

    body = [PREAMBLE, r"\title{The Study-parameter framework (004 Sect. 2): verification}",
            r"\author{bonered\_alg (generated by \texttt{make derive})}", r"\date{}",
            r"\begin{document}", r"\maketitle",
            f"Derivation hash: \\texttt{{{digest}}}. The convention of every mechanism "
            r"(\texttt{bonered\_alg.algebra.convention}): $[x_0:x_1:x_2:x_3:y_0:y_1:y_2:y_3]$ "
            r"with $y = -\tfrac12 t\,x$ (004 eq. 13), checked here against the printed "
            "equations of 004 Sect. 2."]
    body += section_verification(verdicts)
    body.append(r"\end{document}")
    return "\n".join(body) + "\n"


def write_record(root: Path, force: bool = False, log=print) -> str:
    """Write the record (JSON and report) when missing or out of date."""
    from ..pipeline.outputs import verification_json, write

    digest = record_hash()
    tex = root / "derivations" / f"{NAME}.tex"
    js = root / "derivations" / f"{NAME}.verification.json"
    if not force and tex.is_file() and js.is_file() and digest in tex.read_text():
        log(f"{NAME}: up to date ({digest[:12]})")
        return "up to date"
    verdicts = algebra_verdicts()
    write({f"derivations/{NAME}.verification.json": verification_json(verdicts),
           f"derivations/{NAME}.tex": report(verdicts, digest)}, root)
    log(f"{NAME}: derived ({digest[:12]})")
    return "derived"
