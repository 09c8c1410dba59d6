"""LOWER_ORDER (issue 21.2): a solution that cannot gain at order N is "accurate to O(eps^(k+1))",
a separate outcome from INVALID, in Python, JSON and the CLI table; numbers in the verdict
sentences keep their significant digits."""

from __future__ import annotations

import math

import pytest

from perturb.report import validation_as_dict, validation_as_table
from perturb.validation import validate
from perturb.validation.report import Check, OrbitCheck, Verdict
from perturb.validation.verdict import accurate_order, decide, measurement_checks
from problems import get_problem

Duffing = get_problem("duffing")


class TruncatedDuffing(Duffing):
    """Duffing that gives its order-1 solution whatever order is asked: it cannot gain."""

    def solve(self, order: int = 1):
        return super().solve(1)


def test_a_solution_that_cannot_gain_is_lower_order_not_invalid():
    report = validate(TruncatedDuffing.create(eps=0.05), order=2, periods=2)
    assert report.outcome is Verdict.LOWER_ORDER and not report.valid
    assert report.accurate_order == 1
    assert "only to O(eps^2)" in report.verdict and "order 1 < 2 asked" in report.verdict
    assert report.slope.slope == pytest.approx(2.0, abs=0.1)  # the order-1 error, measured
    payload = validation_as_dict(report)
    assert payload["outcome"] == "lower_order" and payload["accurate_order"] == 1
    assert "LOWER_ORDER" in validation_as_table(report)


def test_the_real_order_2_is_valid_and_has_no_accurate_order():
    report = validate(Duffing.create(eps=0.05), order=2, periods=2)
    assert report.outcome is Verdict.VALID and report.accurate_order is None
    assert validation_as_dict(report)["accurate_order"] is None


def _checks(slope: float, order: int, orbit_ok: bool = True):
    least = order + 1 - 0.5
    return (
        Check("existence", 1e-9, 1e-5, True, "exists"),
        Check("orbit_error", 1e-3 if orbit_ok else 0.5, 0.1, orbit_ok, "orbit"),
        Check("period_error", 1e-6, 0.1, True, "period"),
        Check("order", slope, least, slope >= least, f"eps^{slope:.2f}", ">="),
    )


@pytest.mark.parametrize(
    ("slope", "order", "k"),
    [(2.0, 2, 1), (2.9, 3, 2), (3.2, 3, 2), (2.0, 3, 1), (1.2, 2, None), (3.6, 3, None)],
)
def test_accurate_order_from_the_measured_slope(slope, order, k):
    assert accurate_order(_checks(slope, order)) == k
    outcome, _ = decide(_checks(slope, order))
    expected = Verdict.VALID if slope >= order + 0.5 else Verdict.LOWER_ORDER
    assert outcome is (expected if k is not None or slope >= order + 0.5 else Verdict.INVALID)


def test_a_failed_accuracy_check_stays_invalid_whatever_the_slope():
    assert accurate_order(_checks(2.0, 2, orbit_ok=False)) is None
    assert decide(_checks(2.0, 2, orbit_ok=False))[0] is Verdict.INVALID


@pytest.mark.parametrize("value", [1.97e-4, 3.3e-7, 0.0123])
def test_verdict_sentences_keep_significant_digits(value):
    """The issue saw "relative period error 0.000" for 1.97e-4: every figure keeps 3 digits."""
    orbit = OrbitCheck(
        success=True,
        message="",
        status=None,
        period=1.0,
        initial_state={},
        floquet=(),
        n_trivial=1,
        trivial_multiplier_error=0.0,
        trivial_ok=True,
        period_error=value,
        initial_state_error=value,
        orbit_error=value,
        integrator="",
        resolution=1e-9,
        resolution_limit=1e-5,
    )
    checks = measurement_checks(orbit, None, 0.1)
    shown = f"{value:.3g}"
    for name in ("orbit_error", "period_error"):
        sentence = next(c.sentence for c in checks if c.name == name)
        assert shown in sentence and "0.000 " not in sentence + " "
    assert not math.isnan(value)
