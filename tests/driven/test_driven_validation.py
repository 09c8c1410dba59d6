"""Driven problems against the true motion (issue 18): forced shooting, Floquet against the slow
flow, the order slope, and the jumps of slow sweeps against the folds."""

from __future__ import annotations

import numpy as np
import pytest

from perturb import validate
from perturb.oracle import heyoka_available
from perturb.response.hysteresis import slow_sweep
from perturb.response.model import problem_response
from perturb.validation import Verdict
from problems import get_problem

pytestmark = pytest.mark.skipif(
    not heyoka_available(), reason="the shooting takes minutes without heyoka"
)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_forced_duffing_error_falls_as_eps_to_the_order_plus_one(order):
    report = validate(get_problem("forced-duffing").create(Omega=1.05), order=order, periods=2)
    assert report.outcome is Verdict.VALID, report.verdict
    assert report.slope.slope >= order + 1 - report.slope.band


@pytest.mark.parametrize(
    ("name", "values", "family", "stable"),
    [
        ("forced-duffing", {"Omega": 1.05}, "upper", True),
        ("forced-duffing", {"Omega": 1.05}, "middle", False),
        ("forced-duffing", {"Omega": 1.05, "gamma": -1.0}, None, True),  # softening
        ("parametric-duffing", {}, "trivial", False),
        ("parametric-duffing", {}, "response", True),
        ("superharmonic-duffing", {}, None, True),
        ("autoparametric-absorber", {}, "lower", False),
        ("autoparametric-absorber", {}, "upper", True),
    ],
)
def test_the_slow_flow_and_the_floquet_multipliers_agree(name, values, family, stable):
    problem = get_problem(name).create(**values, family=family)
    report = validate(problem, periods=2, slope=False)
    check = report.check("stability")
    assert check.passed is True, check.sentence
    assert (check.value < 1) is stable
    assert report.check("orbit_error").passed, report.verdict


def test_slow_sweeps_jump_at_the_folds():
    """Hysteresis: sweeping Omega up, the response falls off the upper branch just past the upper
    fold; sweeping down, it jumps up just past the lower fold (a finite rate delays a jump, never
    advances it). Within 1 % of Omega, as the issue asks; ~0.15 % is measured."""
    problem = get_problem("forced-duffing").create(eps=0.02, F=0.5, zeta=0.1, gamma=1.0)
    folds = problem_response(problem, "Omega", np.linspace(0.98, 1.07, 4), order=2).response.folds
    low, high = sorted(f.value for f in folds)
    values, eps = problem.symbol_values(), problem.epsilon()
    up = slow_sweep(problem.system(), values, eps, 0.98, 1.07, rate=2e-6)
    down = slow_sweep(problem.system(), values, eps, 1.07, 0.98, rate=2e-6)
    assert up.jump_size < 0 < down.jump_size
    assert high <= up.jump <= high * 1.01
    assert low * 0.99 <= down.jump <= low
