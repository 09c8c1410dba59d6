"""validate() on the toy problems: verdicts, the JSON contract, bad input (issue 4 items 1, 3, 6)."""

import json
import math

import numpy as np
import pytest

from perturb.errors import InvalidParameterError, UnknownNameError
from perturb.oracle import heyoka_available
from perturb.validation import (
    EPSILON_LIMIT,
    FLOQUET_TOL,
    MAX_RELATIVE_ERROR,
    SLOPE_TOLERANCE,
    original_system,
    validate,
)
from problems import get_problem

TOYS = ["duffing", "van-der-pol", "linear-pair", "resonant-pair"]

#: Keys the JSON contract guarantees (docs/validation.md).
CONTRACT_KEYS = {
    "epsilon",
    "valid",
    "verdict",
    "errors",
    "slope",
    "periodic_orbit",
    "invariants",
    "integrator",
}


@pytest.mark.parametrize("name", TOYS)
def test_toy_problem_valid_at_small_eps(name):
    report = validate(get_problem(name).create(eps=0.05), periods=5)
    assert report.completed and report.valid, report.verdict
    assert report.errors["max_relative"] <= MAX_RELATIVE_ERROR
    # O(eps^(n+1)) error: slope ~ order + 1 = 2
    assert report.slope.consistent
    assert abs(report.slope.slope - 2.0) < SLOPE_TOLERANCE
    orbit = report.periodic_orbit
    assert orbit.success and orbit.trivial_ok
    assert orbit.trivial_multiplier_error <= FLOQUET_TOL
    # the analytic orbit is O(eps^2) from the true one (coefficient <= 1 on these problems)
    assert orbit.orbit_error < 0.05**2


@pytest.mark.parametrize("name", TOYS)
def test_toy_problem_invalid_at_large_eps(name):
    eps = 2.0
    assert eps > EPSILON_LIMIT
    report = validate(get_problem(name).create(eps=eps), periods=3)
    assert not report.valid
    assert "not small" in report.verdict
    assert report.completed  # the comparison still ran (under a step budget)
    # shooting and slope are skipped when the expansion cannot hold
    assert report.periodic_orbit is None and report.slope is None


def test_duffing_numbers_against_the_elliptic_period():
    """The true period found by shooting equals the exact 4K(m)/sqrt(1 + eps A^2) period."""
    from scipy.special import ellipk

    eps, amplitude = 0.1, 1.0
    report = validate(get_problem("duffing").create(eps=eps), periods=2, slope=False)
    m = eps * amplitude**2 / (2 * (1 + eps * amplitude**2))
    exact = 4 * ellipk(m) / math.sqrt(1 + eps * amplitude**2)
    assert report.periodic_orbit.period == pytest.approx(exact, rel=1e-11)
    # energy x'^2/2 + x^2/2 + eps x^4/4 is derived and conserved: to round-off with heyoka, to a few
    # times rtol = 1e-12 with the DOP853 fallback
    energy = report.invariants["energy"]
    assert energy.initial == pytest.approx(0.5 + eps / 4)
    assert energy.relative_drift < (1e-12 if "heyoka" in report.integrator else 1e-10)


def test_van_der_pol_floquet_multiplier():
    """One trivial multiplier; the other is exp(-eps T) to first order (a stable limit cycle)."""
    eps = 0.1
    report = validate(get_problem("van-der-pol").create(eps=eps), periods=2, slope=False)
    orbit = report.periodic_orbit
    assert orbit.n_trivial == 1
    assert abs(orbit.floquet[1]) == pytest.approx(math.exp(-eps * 2 * math.pi), rel=0.05)
    assert report.invariants == {}  # dissipative: no first integral


def test_json_contract():
    report = validate(get_problem("resonant-pair").create(eps=0.05), periods=2)
    data = json.loads(json.dumps(report.as_dict()))
    assert CONTRACT_KEYS <= set(data)
    assert isinstance(data["valid"], bool)
    assert data["verdict"].endswith(".")
    assert set(data["periodic_orbit"]) >= {"period", "initial_state", "floquet"}
    assert set(data["periodic_orbit"]["initial_state"]) == {"x", "y", "xdot", "ydot"}
    assert len(data["periodic_orbit"]["floquet"]) == 4
    assert data["integrator"] == report.integrator and data["integrator"]
    assert data["completed"] is True
    assert "I0" in data["invariants"]
    assert report.as_table().count("\n") > 5


def test_integrator_choice_is_reported():
    problem = get_problem("duffing").create(eps=0.05)
    report = validate(problem, integrator="dop853", periods=2, shoot=False, slope=False)
    assert report.integrator.startswith("scipy DOP853")
    expected = "heyoka" if heyoka_available() else "scipy DOP853"
    assert validate(problem, periods=1, shoot=False, slope=False).integrator.startswith(expected)


def test_rk4_gives_the_same_verdict():
    problem = get_problem("duffing").create(eps=0.05)
    report = validate(problem, integrator="rk4", periods=2, shoot=False, slope=False)
    assert report.valid and report.integrator.startswith("rk4")


def test_stiff_problem_switches_to_radau():
    """van der Pol at eps = 10: Jacobian decay rate ~30x the oscillation rate."""
    report = validate(get_problem("van-der-pol").create(eps=10.0), periods=1)
    assert report.stiffness.stiff and report.stiffness.ratio > 10
    assert not report.valid
    # preconditions fail, so the run is budgeted and explicit; it must still finish quickly
    assert report.completed


def test_stiff_problem_with_preconditions_forced():
    """Forcing the checks on a stiff case runs Radau and reports finite numbers."""
    from problems.van_der_pol import VanDerPol

    problem = VanDerPol.create(eps=10.0)
    orig = original_system(problem, np.array([2.0, 0.0]))
    assert orig.symbolic
    report = validate(problem, periods=1, shoot=False, slope=False, integrator="radau")
    assert report.integrator.startswith("scipy Radau")
    assert math.isfinite(report.errors["max_abs"])


# ------------------------------------------------------------------------------- bad input (item 6)


@pytest.fixture(scope="module")
def duffing():
    return get_problem("duffing").create(eps=0.05)


def test_unknown_integrator_lists_names(duffing):
    with pytest.raises(UnknownNameError, match="integrator.*dop853.*heyoka"):
        validate(duffing, integrator="euler")


@pytest.mark.parametrize("rtol", [0.0, -1e-10, math.nan, math.inf])
def test_non_positive_tolerance(duffing, rtol):
    with pytest.raises(InvalidParameterError, match="`rtol`"):
        validate(duffing, rtol=rtol)


@pytest.mark.parametrize("periods", [0, -3, math.nan, "ten"])
def test_bad_periods(duffing, periods):
    with pytest.raises(InvalidParameterError, match="`periods`"):
        validate(duffing, periods=periods)


@pytest.mark.parametrize("order", [0, -1, 1.5, True])
def test_bad_order(duffing, order):
    with pytest.raises(InvalidParameterError, match="`order`"):
        validate(duffing, order=order)


@pytest.mark.parametrize("state", [[math.nan, 0.0], [1.0, math.inf], [1.0], "x"])
def test_bad_initial_state(duffing, state):
    with pytest.raises(InvalidParameterError, match="`initial_state`"):
        validate(duffing, initial_state=state)


def test_errors_are_value_errors_for_the_cli(duffing):
    """The CLI turns ValueError subclasses into exit 2."""
    from perturb.cli import main

    assert main(["validate", "duffing", "--integrator", "euler"]) == 2
    for exc in (UnknownNameError, InvalidParameterError):
        assert issubclass(exc, ValueError)


def test_cli_json(capsys):
    from perturb.cli import main

    assert main(["validate", "duffing", "--set", "eps=0.05", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["valid"] is True and data["epsilon"] == 0.05


def test_initial_state_override_is_compared_with_the_analytic_solution(duffing):
    """Starting off the orbit by 1e-3 gives an error of at least that size."""
    report = validate(duffing, initial_state=[1.001, 0.0], periods=2, shoot=False, slope=False)
    assert report.errors["components"]["x"]["abs"] >= 1e-3 * 0.9
