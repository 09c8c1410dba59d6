"""validate() on the toy problems: verdicts, the JSON contract, bad input (issues 4, 9)."""

import json
import math

import numpy as np
import pytest

from perturb.errors import InvalidParameterError, UnknownNameError
from perturb.oracle import heyoka_available
from perturb.report import validation_as_dict, validation_as_table
from perturb.validation import (
    DEFAULT_TOL,
    FLOQUET_TOL,
    MAX_RELATIVE_ERROR,
    SLOPE_TOLERANCE,
    Verdict,
    original_equations,
    validate,
)
from problems import get_problem

TOYS = ["duffing", "van-der-pol", "linear-pair", "resonant-pair"]

#: Keys the JSON contract guarantees (docs/validation.md); `outcome`, `checks`, `tol` are new.
CONTRACT_KEYS = {
    "epsilon",
    "valid",
    "verdict",
    "errors",
    "slope",
    "periodic_orbit",
    "invariants",
    "integrator",
    "completed",
    "outcome",
    "checks",
    "tol",
}


@pytest.mark.parametrize("name", TOYS)
def test_toy_problem_valid_at_small_eps(name):
    eps = 0.05
    report = validate(get_problem(name).create(eps=eps), periods=1)
    assert report.completed and report.valid, report.verdict
    assert report.outcome is Verdict.VALID and report.tol == DEFAULT_TOL
    assert all(c.passed for c in report.checks)
    # O(eps^(n+1)) error: slope ~ order + 1 = 2
    assert report.slope.consistent
    assert abs(report.slope.slope - 2.0) < SLOPE_TOLERANCE
    orbit = report.periodic_orbit
    assert orbit.success and orbit.resolved and orbit.trivial_ok
    assert orbit.trivial_multiplier_error <= FLOQUET_TOL
    # the analytic orbit is O(eps^2) from the true one (coefficient <= 1 on these problems)
    assert orbit.orbit_error < eps**2
    assert abs(orbit.period_error) < eps**2


def test_van_der_pol_large_eps_is_invalid_by_measurement():
    """eps = 1: no precondition rejects it; the measured distance from the limit cycle does."""
    report = validate(get_problem("van-der-pol").create(eps=1.0), periods=1)
    assert report.outcome is Verdict.INVALID and not report.valid
    orbit_check = report.check("orbit_error")
    assert orbit_check.passed is False and orbit_check.value > DEFAULT_TOL
    assert orbit_check.value == report.periodic_orbit.orbit_error
    assert f"{orbit_check.value:.3g}" in report.verdict  # the verdict names the figure


@pytest.mark.parametrize("name", ["van-der-pol", "resonant-pair"])
def test_series_broken_down_is_invalid_without_shooting(name):
    """eps = 10: the frequency series gives a negative period; that decides, cheaply."""
    report = validate(get_problem(name).create(eps=10.0), periods=1)
    assert report.outcome is Verdict.INVALID and "breaks down" in report.verdict
    assert report.periodic_orbit is None and report.slope is None


def test_duffing_numbers_against_the_elliptic_period():
    """The true period found by shooting equals the exact 4K(m)/sqrt(1 + eps A^2) period."""
    from scipy.special import ellipk

    eps, amplitude = 0.1, 1.0
    report = validate(get_problem("duffing").create(eps=eps), periods=2, slope=False)
    m = eps * amplitude**2 / (2 * (1 + eps * amplitude**2))
    exact = 4 * ellipk(m) / math.sqrt(1 + eps * amplitude**2)
    assert report.periodic_orbit.period == pytest.approx(exact, rel=1e-11)
    # the check reports the same period error as the exact period gives
    assert report.check("period_error").value == pytest.approx(
        abs(report.period - exact) / exact, rel=1e-8
    )
    # energy x'^2/2 + x^2/2 + eps x^4/4 is derived and conserved: to round-off with heyoka, to a few
    # times rtol = 1e-12 with the DOP853 fallback
    energy = report.invariants["energy"]
    assert energy.initial == pytest.approx(0.5 + eps / 4)
    assert energy.relative_drift < (1e-12 if "heyoka" in report.integrator else 1e-10)
    # without the scan the order is not measured: never VALID
    assert report.outcome is Verdict.UNDECIDED and report.check("order").passed is None


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
    data = json.loads(json.dumps(validation_as_dict(report)))
    assert CONTRACT_KEYS <= set(data)
    assert isinstance(data["valid"], bool) and data["outcome"] == "valid"
    assert data["verdict"].endswith(".")
    assert set(data["checks"]) == {"existence", "orbit_error", "period_error", "order"}
    for check in data["checks"].values():
        assert set(check) >= {"value", "tolerance", "passed"}
    assert data["checks"]["orbit_error"]["tolerance"] == data["tol"] == DEFAULT_TOL
    assert set(data["periodic_orbit"]) >= {"period", "initial_state", "floquet", "status"}
    assert data["periodic_orbit"]["status"] == 0 and data["status"] == 0  # integer codes kept
    assert set(data["periodic_orbit"]["initial_state"]) == {"x", "y", "xdot", "ydot"}
    assert len(data["periodic_orbit"]["floquet"]) == 4
    assert data["integrator"] == report.integrator and data["integrator"]
    assert data["completed"] is True
    assert "I0" in data["invariants"]
    assert validation_as_table(report).count("\n") > 5


def test_integrator_choice_is_reported():
    problem = get_problem("duffing").create(eps=0.05)
    report = validate(problem, integrator="dop853", periods=2, shoot=False, slope=False)
    assert report.integrator.startswith("scipy DOP853")
    expected = "heyoka" if heyoka_available() else "scipy DOP853"
    assert validate(problem, periods=1, shoot=False, slope=False).integrator.startswith(expected)


def test_rk4_trajectory_is_information_only():
    problem = get_problem("duffing").create(eps=0.05)
    report = validate(problem, integrator="rk4", periods=2, shoot=False, slope=False)
    assert report.integrator.startswith("rk4") and report.completed
    assert report.errors["max_relative"] < MAX_RELATIVE_ERROR
    # nothing measured the existence, accuracy or order: undecided, never valid
    assert report.outcome is Verdict.UNDECIDED and not report.valid
    assert "shoot=False" in report.verdict


def test_periods_do_not_change_the_verdict():
    """Issue 9.1: trajectory drift over the horizon is information only."""
    problem = get_problem("duffing").create(eps=0.05)
    short = validate(problem, periods=1)
    long = validate(problem, periods=300, samples_per_period=4)
    assert long.errors["max_relative"] > 10 * short.errors["max_relative"]  # the phase drifts
    assert short.outcome is long.outcome is Verdict.VALID


def test_stiff_problem_switches_to_radau():
    """van der Pol at eps = 10: Jacobian decay rate ~30x the oscillation rate."""
    report = validate(get_problem("van-der-pol").create(eps=10.0), periods=1)
    assert report.stiffness.stiff and report.stiffness.ratio > 10
    assert not report.valid
    assert report.completed


def test_stiff_problem_with_radau_forced():
    """Forcing Radau on a stiff case reports finite numbers."""
    from problems.van_der_pol import VanDerPol

    problem = VanDerPol.create(eps=10.0)
    orig = original_equations(problem, np.array([2.0, 0.0]))
    assert orig.symbolic
    report = validate(problem, periods=1, shoot=False, slope=False, integrator="radau")
    assert report.integrator.startswith("scipy Radau")
    assert math.isfinite(report.errors["max_abs"])


# ------------------------------------------------------------------------------- bad input


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


@pytest.mark.parametrize("tol", [0.0, -0.1, math.nan, math.inf, "small", True])
def test_bad_accuracy_tolerance(duffing, tol):
    with pytest.raises(InvalidParameterError, match="`tol`"):
        validate(duffing, tol=tol)


@pytest.mark.parametrize("periods", [0, -3, math.nan, "ten", 1e308, math.inf])
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
    assert data["valid"] is True and data["epsilon"] == 0.05 and data["outcome"] == "valid"


def test_cli_tol_is_passed_and_an_invalid_verdict_still_exits_0(capsys):
    """A completed run exits 0 whatever the verdict; --tol sets the accuracy tolerance."""
    from perturb.cli import main

    argv = ["validate", "duffing", "--set", "eps=0.05", "--periods", "1", "--format", "json"]
    assert main([*argv, "--tol", "1e-6"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["tol"] == 1e-6 and data["outcome"] == "invalid" and data["valid"] is False
    assert data["checks"]["orbit_error"]["passed"] is False


def test_initial_state_override_is_compared_with_the_analytic_solution(duffing):
    """Starting off the orbit by 1e-3 gives an error of at least that size."""
    report = validate(duffing, initial_state=[1.001, 0.0], periods=2, shoot=False, slope=False)
    assert report.errors["components"]["x"]["abs"] >= 1e-3 * 0.9
