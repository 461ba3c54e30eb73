"""Engines: missing engine, time budget, cache behaviour, safe parsing."""

import json
import time

import pytest
import sympy as sp

from bonered_alg.elimination import polyterms as pt
from bonered_alg.elimination.cache import eliminate
from bonered_alg.elimination.engines import SingularEngine, SympyEngine, get_engine
from bonered_alg.elimination.problem import EliminationProblem
from bonered_alg.errors import EngineTimeoutError, EngineUnavailableError

x, y, z, a = sp.symbols("x y z a")
SMALL = EliminationProblem("mechanism 'toy', leg 'L'", (x**2 + y - a, x * y - z), (x,),
                           (y, z, a))


def hard_problem():
    v = sp.symbols("v0:7")
    eqs = tuple(sum(v[i] ** (k + 2) * v[(i + k) % 7] for i in range(7)) - k - 1
                for k in range(7))
    return EliminationProblem("mechanism 'heavy', leg 'H'", eqs, v[:4], v[4:])


def test_missing_engine_is_a_clear_error():
    eng = SingularEngine(executable="no-such-singular-binary")
    with pytest.raises(EngineUnavailableError, match=r"mechanism 'toy', leg 'L'.*singular"):
        eng.eliminate(SMALL, 10)
    with pytest.raises(EngineUnavailableError, match="unknown Groebner engine 'maple'"):
        get_engine("maple")


@pytest.mark.parametrize("engine", [SympyEngine(), SingularEngine()], ids=["sympy", "singular"])
def test_time_budget(engine):
    if not engine.available():
        pytest.skip("engine missing")
    t0 = time.perf_counter()
    with pytest.raises(EngineTimeoutError, match=r"mechanism 'heavy', leg 'H'.*time budget of 1"):
        engine.eliminate(hard_problem(), 1.0)
    assert time.perf_counter() - t0 < 30


def test_cache_hit_and_damaged_entry(tmp_path, monkeypatch):
    monkeypatch.setenv("BONERED_CACHE_DIR", str(tmp_path))
    r1 = eliminate(SMALL, SympyEngine(), 30)
    assert not r1.cached
    r2 = eliminate(SMALL, SympyEngine(), 30)
    assert r2.cached and r2.basis == r1.basis and r2.dimension == r1.dimension == 2
    entry = next(tmp_path.glob("*.json"))
    entry.write_text(json.dumps({"basis": [[[[1, 0, 0], "__import__('os')"]]],
                                 "dimension": 0, "seconds": 0}))
    r3 = eliminate(SMALL, SympyEngine(), 30)
    assert not r3.cached and r3.basis == r1.basis


def test_rational_parser_rejects_code():
    assert pt.parse_rational("-12/7") == pt.Fraction(-12, 7)
    for bad in ("1e5", "__import__('os')", "1/x", ""):
        with pytest.raises(ValueError):
            pt.parse_rational(bad)


def test_normal_form_is_unique():
    f = [((2, 0), pt.Fraction(1, 3)), ((0, 1), pt.Fraction(-2, 3))]
    g = [((0, 1), pt.Fraction(4)), ((2, 0), pt.Fraction(-2))]
    assert pt.normal_form(f) == pt.normal_form(g) == (((2, 0), 1), ((0, 1), -2))
