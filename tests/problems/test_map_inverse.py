"""The declared map's inverses: every root of a map that is not monotone, the range a symbol
covers along a parameter, and the move to another epsilon that continues from the point."""

from __future__ import annotations

import math

import pytest
import sympy as sp

from perturb.case import ParameterMap
from perturb.validation import with_epsilon
from tests.helpers import REF_RTOL

SIGMA = sp.Symbol("sigma")
#: Omega^2 = 1 + 2 eps sigma: sigma is not monotone in Omega (the two roots +-Omega).
SQUARED = ParameterMap.declare([SIGMA], ["eps", "Omega"], {"sigma": "(Omega**2 - 1)/(2*eps)"})


def test_every_root_of_a_map_that_is_not_monotone():
    values = {"eps": 0.1, "Omega": 1.05}
    low, high = SQUARED.user_roots("Omega", "sigma", 1.0, values)
    assert (low, high) == pytest.approx((-math.sqrt(1.2), math.sqrt(1.2)), rel=REF_RTOL)
    assert SQUARED.solve_user("Omega", "sigma", 1.0, values) == high  # the nearest to 1.05
    assert SQUARED.user_roots("Omega", "sigma", -6.0, values) == ()  # Omega^2 < 0: none


def test_the_range_a_symbol_covers_includes_its_stationary_points():
    """Over Omega in [-0.5, 1.2] sigma dips to its minimum -1/(2 eps) at Omega = 0, inside the
    interval: the ends alone would give [-3.75, 2.2]."""
    values = {"eps": 0.1, "Omega": 1.0}
    low, high = SQUARED.span("Omega", "sigma", -0.5, 1.2, values)
    assert low == pytest.approx(-5.0, rel=REF_RTOL) and high == pytest.approx(2.2, rel=REF_RTOL)


def test_another_epsilon_continues_from_the_point():
    """eps = a^2 has the moves a = +-sqrt(eps): the one nearest the point is taken, on either
    side of zero."""
    mapping = ParameterMap.declare([], ["a"], {"epsilon": "a**2"})
    assert mapping.with_epsilon({"a": 0.3}, 0.04)["a"] == pytest.approx(0.2, rel=REF_RTOL)
    assert mapping.with_epsilon({"a": -0.3}, 0.04)["a"] == pytest.approx(-0.2, rel=REF_RTOL)
    assert mapping.with_epsilon({"a": 0.3}, -0.04) is None  # no real move


_UNREADABLE = """
import math

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem, positive

X, XDOT = sp.symbols("x xdot")


class Pendulum(Problem):
    name = "pendulum"
    summary = "eps computed with math.pow: sympy cannot read it"
    parameter_specs = (ParameterSpec("amplitude", 0.3, "theta(0)", positive),)

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [EPS * X**3 / 6], name="pendulum")

    def epsilon(self):
        return math.pow(self.values["amplitude"], 2)

    def method_options(self):
        return {"amplitudes": {"x": 1}}
"""


def test_an_epsilon_sympy_cannot_read_says_how_to_declare_it(tmp_path):
    """Code that needs numbers declares nothing: the order is then undecided, and the verdict
    names the fix (declare epsilon in the map) instead of a silent wrong move."""
    from perturb.validation import Verdict, validate
    from problems.loading import load_problem

    (tmp_path / "pendulum.py").write_text(_UNREADABLE)
    problem = load_problem(f"{tmp_path / 'pendulum.py'}:Pendulum").create()
    assert problem.epsilon() == pytest.approx(0.09, rel=REF_RTOL)
    assert with_epsilon(problem, 0.04) is None
    report = validate(problem, periods=1)
    assert report.outcome is Verdict.UNDECIDED
    (order,) = [check for check in report.checks if check.name == "order"]
    assert "declare epsilon in its parameter_map" in order.sentence


def test_a_problem_computing_its_symbols_is_read_the_same_by_its_case():
    """A subclass computing its symbols' values itself (its stiffness doubled, with a name the
    system does not have besides): its case, which the response and the sweep ask, gives the
    same numbers at every point, not the parameters of the same names."""
    from perturb import EPS, QuasilinearSystem
    from problems.base import ParameterSpec, Problem

    x, v, c = sp.symbols("x v c")

    class Doubled(Problem):
        name = "doubled"
        summary = "x'' + x = -eps (2c) x^3"
        parameter_specs = (ParameterSpec("eps", 0.1, "eps"), ParameterSpec("c", 1.0, "c"))

        @classmethod
        def build_system(cls):
            return QuasilinearSystem([x], [v], [1], [-EPS * c * x**3], parameters=[c])

        def symbol_values(self):
            return {"c": 2 * self.values["c"], "note": 1.0}

    problem = Doubled.create(c=1.5)
    assert problem.case().symbol_values == {"c": 3.0}
    point = problem.case().at(c=0.25)
    assert point.symbol_values["c"] == point.model.symbol_values()["c"] == 0.5
