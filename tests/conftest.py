import importlib
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

_RECORDS: dict = {}
_DERIVE = None


def record_of(target):
    """The in-memory derivation record of a registered mechanism (or a declaration module),
    derived once per test session (through the elimination cache) and shared by every test
    that needs it."""
    key = target if isinstance(target, str) else target.__name__
    if key not in _RECORDS:
        bind_derive()  # the runner's own, even where a test has patched it
        _RECORDS[key] = _DERIVE(target)
    return _RECORDS[key]


_SYMBOLIC: dict = {}


def symbolic_of(name: str):
    """The symbolic derivation of a registered mechanism: elimination, IK plan, Jacobians,
    singularities, forward kinematics, passive joints, analyses, pose map and limits, but no
    code generation, studies or verification (the committed outputs hold those).  That is
    what a test of the derived algebra needs, in a fraction of the time (tripod_planar: 50 s
    of 210 s)."""
    if name not in _SYMBOLIC:
        from bonered_alg.pipeline import stages
        from bonered_alg.pipeline.algebra import Algebra
        from bonered_alg.pipeline.results import Derivation
        from bonered_alg.pipeline.runner import current_hash
        from bonered_alg.pipeline.seeding import seeded_sympy_random
        from bonered_alg.registry import load

        algebra = Algebra.default(None)
        with seeded_sympy_random():  # as derive() does: the same factoring work every run
            d = Derivation(stages.build(load(name)), current_hash(name))
            for stage in (stages.eliminate, stages.plan, stages.analyse):
                d = stage(d, algebra)
            _SYMBOLIC[name] = stages.specify(d)
    return _SYMBOLIC[name]


def in_joint_quantities(module, q, J=None):
    """Joints (..., n) and dq/dX (..., n, m) in the joints' own quantities: a joint given as
    ``u = tan(theta/2)`` (its JOINT_UNITS say ``tan(``) as its angle ``theta = 2 atan(u)``,
    its Jacobian row as ``dtheta/dX = 2 / (1 + u^2) du/dX``; other joints unchanged.

    Comparing two correct evaluations needs this near a half-turn: there ``u`` amplifies a
    change of theta by ``(1 + u^2) / 2`` (the chart's conditioning, not the solver's), so
    elementary functions a few ulp apart give u's 1e-12 apart relative for angles one ulp
    apart."""
    half = np.array(["tan(" in unit for unit in module.JOINT_UNITS])
    q = np.asarray(q, dtype=float)
    theta = np.where(half, 2.0 * np.arctan(q), q)
    if J is None:
        return theta, None
    scale = np.where(half, 2.0 / (1.0 + q * q), 1.0)
    return theta, np.asarray(J) * scale[..., :, None]


def assert_close(a, b, tol=1e-12):
    """Equal NaN patterns and ``|a - b| <= tol (1 + |a|)`` elementwise."""
    a, b = np.asarray(a), np.asarray(b)
    assert (np.isnan(a) == np.isnan(b)).all(), "NaN patterns differ"
    ok = ~np.isnan(a)
    err = np.abs(a[ok] - b[ok]) / (1 + np.abs(a[ok]))
    assert err.size == 0 or err.max() <= tol, err.max()


def verification_of(name: str) -> list[SimpleNamespace]:
    """The rows of the committed ``derivations/<name>.verification.json`` (ref, quantity,
    verdict, max_error, detail)."""
    import json

    rows = json.loads((ROOT / "derivations" / f"{name}.verification.json").read_text())
    return [SimpleNamespace(**row) for row in rows]


def bind_derive() -> None:
    """Keep the runner's own ``derive`` for :func:`record_of` before a test patches it."""
    global _DERIVE
    if _DERIVE is None:
        from bonered_alg.pipeline.runner import derive

        _DERIVE = derive


def verdicts_of(name: str) -> dict[str, str]:
    """Verdict per printed reference from the committed ``derivations/<name>.verification.json``
    (CI re-derives it with ``derive --force`` and fails on any difference)."""
    import json

    rows = json.loads((ROOT / "derivations" / f"{name}.verification.json").read_text())
    return {row["ref"]: row["verdict"] for row in rows}


@pytest.fixture(scope="session")
def gen():
    """The committed generated module ``bonered_alg.generated.pro_hep_lct``."""
    return importlib.import_module("bonered_alg.generated.pro_hep_lct")


@pytest.fixture(scope="session")
def verification():
    """The verdicts of pro_hep_lct against paper 004, from the committed record (CI
    re-derives it and fails on any difference)."""
    return verification_of("pro_hep_lct")


@pytest.fixture(scope="session")
def derivation():
    """The symbolic derivation of pro_hep_lct (:func:`symbolic_of`)."""
    return symbolic_of("pro_hep_lct")


# pytest-xdist (make test: -n auto --dist loadgroup): every test module runs on one worker, so
# its module and session fixtures derive once there; modules sharing an expensive derivation
# run together, as one group
SHARED_GROUPS = {"test_readme": "worked_example", "test_worked_example": "worked_example",
                 **{m: "pro_hep_lct" for m in ("test_engines_agree", "test_generated_pro_hep_lct",
                                               "test_paper_pro_hep_lct",
                                               "test_pro_hep_lct_platform")}}
# the groups that take longest (pytest --durations on a fresh clone), handed out first so that
# the short ones fill in behind them on both workers (longest-processing-time-first)
LONGEST_FIRST = ("pro_hep_lct", "test_tripod_planar", "test_planar_tripod", "worked_example",
                 "test_workspace", "test_stewart", "test_fk_trust", "test_tripod_forward")


def group_of(nodeid: str) -> str:
    """The scheduling group of a test: its module's, or the shared one of SHARED_GROUPS."""
    module = nodeid.split("::", 1)[0].rsplit("/", 1)[-1].removesuffix(".py")
    return SHARED_GROUPS.get(module, module)


def _rank(group: str) -> int:
    return LONGEST_FIRST.index(group) if group in LONGEST_FIRST else len(LONGEST_FIRST)


def pytest_collection_modifyitems(config, items):
    """Each group's tests together, the longest groups first (a stable sort: the order within
    a group is the collection order)."""
    items.sort(key=lambda item: _rank(group_of(item.nodeid)))


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadgroup`` scheduled by :func:`group_of`.  xdist's own loadgroup reads the
    ``xdist_group`` marker into a node-id suffix, which pytest 9 ignores (``Item.nodeid`` is
    no longer ``_nodeid``): the marker silently stopped grouping and a shared derivation ran
    on both workers."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class SharedDerivationScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return group_of(nodeid)

    config.option.loadscopereorder = False  # keep LONGEST_FIRST, not the number of tests
    return SharedDerivationScheduling(config, log)
