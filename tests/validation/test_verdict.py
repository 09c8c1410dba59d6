"""The verdict (issue 9.1): the rule, the scaling invariance, and the four known defects, each on
systems defined here."""

import json
import math

import pytest
import sympy as sp

from perturb import EPS, PoincareMethod, QuasilinearSystem, Status
from perturb.errors import InvalidParameterError
from perturb.validation import DEFAULT_TOL, SLOPE_TOLERANCE, Check, SystemModel, Verdict, validate
from perturb.validation.verdict import decide, measurement_checks
from problems import get_problem

X, XD, Y, YD = sp.symbols("x xd y yd")


# ---------------------------------------------------------------------------------- the rule


def _check(name, passed, value=0.01):
    return Check(name, value, 0.1, passed, f"{name} sentence {value:.3g}")


@pytest.mark.parametrize(
    ("passed", "outcome"),
    [
        ((True, True, True, True), Verdict.VALID),
        ((True, False, True, True), Verdict.INVALID),
        ((None, None, None, True), Verdict.UNDECIDED),
        ((True, True, True, None), Verdict.UNDECIDED),
        ((None, None, None, False), Verdict.INVALID),  # a measured failure outranks a missing check
    ],
)
def test_valid_only_when_every_check_passed(passed, outcome):
    names = ("existence", "orbit_error", "period_error", "order")
    checks = tuple(_check(n, p) for n, p in zip(names, passed, strict=True))
    verdict, sentence = decide(checks)
    assert verdict is outcome and verdict.success is (outcome is Verdict.VALID)
    for check in checks:  # the sentence names what failed or could not run
        if check.passed is not True and outcome is not Verdict.VALID:
            assert check.name in sentence


def test_missing_measurements_are_undecided_with_the_reason():
    checks = measurement_checks(None, None, DEFAULT_TOL, "no scan here", "no orbit here")
    assert all(c.passed is None for c in checks)
    verdict, sentence = decide(checks)
    assert (
        verdict is Verdict.UNDECIDED and "no scan here" in sentence and "no orbit here" in sentence
    )


def test_breakdown_and_failure_decide_before_the_checks():
    passing = tuple(_check(n, True) for n in ("existence", "orbit_error", "period_error", "order"))
    assert decide(passing, breakdown="period -1")[0] is Verdict.INVALID
    assert decide(passing, failure="integration stopped")[0] is Verdict.UNDECIDED


# ------------------------------------------------------------------ scaling invariance (9.1)


@pytest.mark.parametrize(("eps", "amplitude"), [(0.3, 1.0), (-0.2, 1.0)])
def test_same_motion_same_verdict_whatever_the_scaling(eps, amplitude):
    """Duffing (eps, A) and (4 eps, A/2) are the same motion (x -> 2x): same verdict, same numbers.

    The former precondition |eps| <= 0.3 called the first VALID and the second INVALID.
    """
    duffing = get_problem("duffing")
    one = validate(duffing.create(eps=eps, amplitude=amplitude), periods=1)
    other = validate(duffing.create(eps=4 * eps, amplitude=amplitude / 2), periods=1)
    assert one.outcome is other.outcome, (one.verdict, other.verdict)
    # relative measurements of the same motion agree to the shooting's and oracle's accuracy
    # (1e-12 relative; a 1e-6 margin leaves room for the integrator's step sequence)
    for name in ("orbit_error", "period_error", "order"):
        assert one.check(name).value == pytest.approx(other.check(name).value, rel=1e-6), name


# ------------------------------------------------------ defect (a): an orbit that does not exist


def _obstructed_system():
    """ẍ + x = ε(x² + x ẋ): the first-order conditions hold for every amplitude, the second-order
    ones for none (a Liénard focus, not a centre): no periodic orbit through x(0) = 1."""
    return QuasilinearSystem([X], [XD], [1], [EPS * (X**2 + X * XD)], parameter=EPS, name="focus")


def test_defect_a_a_first_order_orbit_that_does_not_exist_is_not_valid():
    system = _obstructed_system()
    amplitudes = {"amplitudes": {"x": 1}}
    # the premise: SUCCESS at order 1, obstructed at order 2
    assert PoincareMethod(order=1, **amplitudes).solve(system).status is Status.SUCCESS
    assert PoincareMethod(order=2, **amplitudes).solve(system).status is Status.INCONSISTENT
    report = validate(system, values={"epsilon": 0.05}, options=amplitudes, periods=1)
    # the trajectory over a period agrees (the first order describes the motion that long) ...
    assert report.errors["max_relative"] < DEFAULT_TOL
    # ... but no true periodic orbit is there: formerly VALID, now not
    assert report.outcome in (Verdict.INVALID, Verdict.UNDECIDED), report.verdict
    assert report.check("existence").passed is not True
    assert "existence" in report.verdict


# ------------------------------------------- defect (b): the error measured against the true orbit


def test_defect_b_orbit_error_is_the_distance_to_the_exact_orbit():
    """Linear pair ẍ + x = εκy, ÿ + ω²y = εκx: the true orbit is the normal mode
    x = A cos λt, y = A r cos λt with λ² = [1 + ω² − √((ω²−1)² + 4ε²κ²)]/2, r = εκ/(ω² − λ²).
    The reported orbit error equals the analytic orbit's distance from it at equal phase."""
    import numpy as np

    eps, kappa, omega, amp = 0.3, 1.0, 2.5, 1.0
    problem = get_problem("linear-pair").create(eps=eps, kappa=kappa, omega=omega, amplitude=amp)
    report = validate(problem, periods=1)
    lam = math.sqrt((1 + omega**2 - math.sqrt((omega**2 - 1) ** 2 + 4 * (eps * kappa) ** 2)) / 2)
    ratio = eps * kappa / (omega**2 - lam**2)
    phase = np.linspace(0.0, 1.0, 41)
    solution = problem.solve(1)
    analytic = problem.state(solution, phase * problem.period(solution))
    s = 2 * math.pi * phase
    exact = {
        "x": amp * np.cos(s),
        "y": amp * ratio * np.cos(s),
        "xdot": -amp * lam * np.sin(s),
        "ydot": -amp * ratio * lam * np.sin(s),
    }
    distance = max(np.max(np.abs(analytic[n] - exact[n])) / np.max(np.abs(exact[n])) for n in exact)
    assert report.periodic_orbit.period == pytest.approx(2 * math.pi / lam, rel=1e-10)
    assert report.check("orbit_error").value == pytest.approx(distance, rel=1e-6)


# ------------------------------------------------------------------ defect (c): any sign of eps


def test_defect_c_negative_eps_is_measured_with_its_slope():
    """Softening Duffing (eps < 0): formerly a LAPACK error from log(eps) in the slope fit."""
    report = validate(get_problem("duffing").create(eps=-0.05), periods=1)
    assert report.outcome is Verdict.VALID, report.verdict
    assert all(e < 0 for e in report.slope.epsilons)  # |eps| scaled, sign kept
    assert abs(report.slope.slope - 2.0) < SLOPE_TOLERANCE


def test_defect_c_negative_eps_on_a_bare_system():
    system = QuasilinearSystem([X], [XD], [1], [-EPS * X**3], parameter=EPS)
    model = SystemModel(system, {"epsilon": -0.05}, {"amplitudes": {"x": 1}})
    report = validate(model, periods=1)
    assert report.outcome is Verdict.VALID and report.slope.consistent


# ----------------------------------------------------------- defect (d): extreme input, one line


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"eps": 0.0}, "epsilon"),
    ],
)
def test_defect_d_zero_eps_is_one_clear_line(kwargs, argument):
    with pytest.raises(InvalidParameterError, match=f"`{argument}`"):
        validate(get_problem("duffing").create(**kwargs), periods=1)


def test_defect_d_tiny_horizon_is_measured():
    report = validate(get_problem("duffing").create(eps=0.05), periods=1e-308)
    assert report.completed and report.outcome is Verdict.VALID  # the checks do not use the horizon
    assert report.errors["max_relative"] == 0.0 or math.isfinite(report.errors["max_relative"])


@pytest.mark.parametrize(
    "argv",
    [
        ["validate", "duffing", "--set", "eps=0"],
        ["validate", "duffing", "--periods", "1e308"],
        ["validate", "duffing", "--periods", "-1"],
        ["validate", "duffing", "--tol", "0"],
        ["validate", "duffing", "--tol", "-1e-3"],
        ["validate", "duffing", "--tol", "nan"],
    ],
)
def test_defect_d_cli_exits_2_with_one_line(capsys, argv):
    from perturb.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert "LAPACK" not in err and "Overflow" not in err


def test_defect_d_cli_tiny_horizon_answers(capsys):
    from perturb.cli import main

    argv = ["validate", "duffing", "--set", "eps=0.05", "--periods", "1e-308", "--format", "json"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["completed"] is True
