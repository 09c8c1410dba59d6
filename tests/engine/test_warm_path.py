"""A warm run reads what it needs and builds no sympy expression: each shortcut against the long way.

A warm ``perturb validate disk`` reads a declared parameter map, its mpmath function, a
solution's numbers and compiled coefficients, the order check's moved values and the problems'
index from the disk cache, and imports the construction, the native backend and the oracle's
driven modules only when they run.  Each read is held here against what a cold run (or the
cache bypassed) computes, and a changed input against a miss.
"""

import inspect
import json
import os
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

import perturb.cache
from perturb import EPS, PoincareMethod, QuasilinearSystem
from perturb.case import Case, ParameterMap
from perturb.domain import series_domain

ROOT = Path(__file__).resolve().parents[2]
x, xd, a, sigma, zeta = sp.symbols("x xdot a sigma zeta")
DUFFING = QuasilinearSystem([x], [xd], [1], [-EPS * a * x**3], parameters=[a], name="duffing")


def _forced_map(sigma_of: str = "(Omega - 1)/eps") -> ParameterMap:
    return ParameterMap.declare([sigma, zeta], ["eps", "zeta", "Omega"], {"sigma": sigma_of})


def test_a_declared_map_read_back_is_the_one_parsed(cache_folder):
    with perturb.cache.bypassed():
        parsed = _forced_map()
    cold, warm = _forced_map(), _forced_map()
    assert cold == warm == parsed
    assert [sp.srepr(e) for _, e in warm.symbols] == [sp.srepr(e) for _, e in parsed.symbols]
    assert len(list(cache_folder.glob("parameter-map-*.pkl"))) == 1
    # another declaration is parsed again, and a bad one still raises (nothing is kept)
    assert _forced_map("Omega/eps").expression("sigma") == sp.Symbol(
        "Omega", real=True
    ) / sp.Symbol("eps", real=True)
    assert len(list(cache_folder.glob("parameter-map-*.pkl"))) == 2
    with pytest.raises(ValueError, match="not user parameters"):
        _forced_map("(Omega - 1)/nu")


def test_a_precise_function_read_back_is_the_one_lambdify_generates(cache_folder):
    from perturb._lambdify import mpmath_lambdify

    u, v = sp.symbols("u v", real=True)
    exprs = [sp.sqrt(u * v) / 3 + sp.Rational(1, 7), (u**2 + v**2) ** sp.Rational(1, 4) / u]
    fresh = sp.lambdify([u, v], exprs, modules="mpmath")
    cold, warm = mpmath_lambdify([u, v], exprs), mpmath_lambdify([u, v], exprs)
    assert len(list(cache_folder.glob("lambdified-*.pkl"))) == 1
    assert inspect.getsource(warm) == inspect.getsource(cold) == inspect.getsource(fresh)
    with mpmath.workdps(30):
        point = (mpmath.mpf(0.755155), mpmath.mpf(0.123299))
        assert [str(n) for n in warm(*point)] == [str(n) for n in fresh(*point)]


def test_a_keyed_function_builds_its_expression_only_on_a_miss(cache_folder):
    from perturb._lambdify import numpy_lambdify

    built = []

    def expression():
        built.append(1)
        return [sp.sin(x) * a + 1, sp.cos(x) ** 2]

    fresh = sp.lambdify([x, a], expression(), "numpy")
    cold = numpy_lambdify([x, a], expression, key="k1")
    warm = numpy_lambdify([x, a], expression, key="k1")
    assert len(built) == 2  # the reference and the cold run: the warm one read the source
    assert inspect.getsource(warm) == inspect.getsource(cold)
    assert np.array_equal(warm(0.3, 1.7), fresh(0.3, 1.7))
    numpy_lambdify([x, a], expression, key="k2")  # another key: built again
    assert len(built) == 3


def test_a_solutions_numbers_read_back_are_the_ones_evaluated(cache_folder):
    solution = PoincareMethod(order=3, amplitudes={"x": 1}).solve(DUFFING)
    values = {"a": 0.7}
    with perturb.cache.bypassed():
        expected = series_domain(solution, 0.1, values)
        fresh = solution.evaluate([0.0, 1.0, 2.5], 0.1, values)
    cold = series_domain(solution, 0.1, values)
    again = PoincareMethod(order=3, amplitudes={"x": 1}).solve(DUFFING)  # read back
    warm = series_domain(again, 0.1, values)
    assert warm == cold == expected
    assert len(list(cache_folder.glob("series-numbers-*.pkl"))) == 1
    assert np.array_equal(again.evaluate([0.0, 1.0, 2.5], 0.1, values), fresh)
    assert again.numeric_digest == solution.numeric_digest
    # other values, or another solution, are evaluated again
    assert series_domain(again, 0.1, {"a": 0.8}) != warm
    other = PoincareMethod(order=2, amplitudes={"x": 1}).solve(DUFFING)
    assert other.numeric_digest != solution.numeric_digest


def test_moved_values_read_back_are_the_ones_solved(cache_folder):
    system = QuasilinearSystem(
        [x], [xd], [1], [-EPS * (zeta * xd + x**3 - sigma * x)], parameters=[sigma, zeta]
    )
    case = Case(system, _forced_map(), {"eps": 0.05, "zeta": 0.1, "Omega": 1.1})
    with perturb.cache.bypassed():
        expected = [case.with_epsilon(e) for e in (0.025, 0.1)]
    cold = [case.with_epsilon(e) for e in (0.025, 0.1)]
    warm = [case.with_epsilon(e) for e in (0.025, 0.1)]
    assert [c.values for c in warm] == [c.values for c in cold] == [c.values for c in expected]
    assert len(list(cache_folder.glob("moved-values-*.pkl"))) == 2


def test_the_templates_and_the_oracles_names_are_there_when_asked_for():
    import perturb.method.poincare as poincare
    import perturb.oracle
    from perturb.frame import DrivenFrame, FreeFrame
    from perturb.method.construction import OrderByOrder
    from perturb.method.given_period import DrivenOrderByOrder

    assert poincare.TEMPLATES == {FreeFrame: OrderByOrder, DrivenFrame: DrivenOrderByOrder}
    assert poincare.TEMPLATES is poincare.TEMPLATES  # one dict: an addition stays
    for name in perturb.oracle.__all__:
        assert getattr(perturb.oracle, name) is not None
    with pytest.raises(AttributeError):
        perturb.oracle.no_such_name  # noqa: B018


@pytest.mark.slow
def test_a_warm_validate_disk_loads_only_what_it_uses(tmp_path):
    """The construction, symengine, sympy's tensor and combinatorics modules (its first evaluated
    sum imports them) and its code printer's AST are not loaded by a warm run, and its report is
    the cold one's."""
    code = (
        "import json, sys\n"
        "from perturb.cli import main\n"
        "code = main(['validate', 'disk', '--set', 'r0=0.755155', '--set', 'R=0.123299',\n"
        "             '--set', 'gamma3_0=0.25', '--format', 'json', '--quiet'])\n"
        "sys.stderr.write('MODULES ' + json.dumps(sorted(sys.modules)) + '\\n')\n"
    )
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT),
        "PERTURB_CACHE_DIR": str(tmp_path / "cache"),
        "PERTURB_CACHE_KEY_FILE": str(tmp_path / "cache.key"),
    }
    runs = [
        subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT
        )
        for _ in range(2)
    ]
    reports = [json.loads(run.stdout) for run in runs]
    for report in reports:
        report.pop("timings", None)
    assert reports[0] == reports[1]
    line = next(x for x in runs[1].stderr.splitlines() if x.startswith("MODULES "))
    loaded = set(json.loads(line.removeprefix("MODULES ")))
    unused = {
        "symengine",
        "perturb.native",
        "perturb.method.construction",
        "perturb.algebra",
        "perturb.oracle.driven_family",
        "sympy.tensor.tensor",
        "sympy.combinatorics",
        "sympy.codegen.ast",
    }
    assert not loaded & unused
