"""Issue 9.5: the verdict never says VALID where its own reported errors exceed its tolerance.

Hypothesis draws parameter points of every registered problem (``problems.problem_names()``) and an
accuracy tolerance; the fast variant (default suite) draws a few points of the cheap problems, the
slow one all problems.
"""

import math
import warnings

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from perturb.validation import Check, Verdict, validate
from perturb.validation.verdict import decide
from problems import get_problem, problem_names

#: The fast-spin bodies at their fast-spin points (eps = c/r0 = 0.004 for the disk, 0.01 for the
#: body); the strategies scale r0 down from there, towards and past the edge of the expansion.
FAST_SPIN = {
    "disk": {"r0": 0.755155, "R": 0.123299, "gamma3_0": 0.25},
    "rigid-body": {},
}


@st.composite
def parameter_points(draw, names):
    """(name, parameters) of a registered problem, its small parameter drawn over a wide range."""
    name = draw(st.sampled_from(names))
    cls = get_problem(name)
    if name in FAST_SPIN:
        base = dict(FAST_SPIN[name])
        r0 = base.get("r0", cls.create().values["r0"])
        base["r0"] = r0 / draw(st.floats(1.0, 30.0, allow_nan=False, allow_infinity=False))
        return name, base
    magnitude = draw(st.floats(0.01, 1.5, allow_nan=False, allow_infinity=False))
    sign = draw(st.sampled_from([1.0, -1.0]))
    return name, {"eps": sign * magnitude}


def _assert_never_valid_beyond_tolerance(name, parameters, tol):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # problems warn at large eps, on purpose
        report = validate(get_problem(name).create(**parameters), periods=1, tol=tol)
    assert report.valid is (report.outcome is Verdict.VALID)
    if report.outcome is Verdict.VALID:
        orbit = report.periodic_orbit
        assert orbit is not None and orbit.resolved
        assert orbit.orbit_error <= tol and abs(orbit.period_error) <= tol
        assert report.slope.consistent is True
        assert all(c.passed is True for c in report.checks)
    # the checks report the orbit's own numbers (no second, different error)
    if report.periodic_orbit is not None and report.periodic_orbit.resolved:
        assert report.check("orbit_error").value == report.periodic_orbit.orbit_error


TOLERANCES = st.floats(1e-4, 0.3, allow_nan=False, allow_infinity=False)


@settings(max_examples=4)
@given(point=parameter_points(["duffing", "van-der-pol", "linear-pair"]), tol=TOLERANCES)
def test_never_valid_beyond_its_tolerance_fast(point, tol):
    name, parameters = point
    if name == "linear-pair" and abs(parameters["eps"]) > 1.0:
        parameters["eps"] /= 2  # keep the pair non-degenerate (eps kappa < (omega^2 - 1)/2)
    _assert_never_valid_beyond_tolerance(name, parameters, tol)


@pytest.mark.slow
@given(point=parameter_points(problem_names()), tol=TOLERANCES)
def test_never_valid_beyond_its_tolerance_all_problems(point, tol):
    name, parameters = point
    if name == "linear-pair" and abs(parameters["eps"]) > 1.0:
        parameters["eps"] /= 2
    _assert_never_valid_beyond_tolerance(name, parameters, tol)


_PASSED = st.sampled_from([True, False, None])


@given(
    passed=st.tuples(_PASSED, _PASSED, _PASSED, _PASSED),
    values=st.tuples(*[st.floats(0, 10) | st.just(math.nan) for _ in range(4)]),
)
def test_the_rule_is_valid_only_when_every_check_passed(passed, values):
    names = ("existence", "orbit_error", "period_error", "order")
    checks = tuple(
        Check(n, v, 0.1, p, f"{n} {v}") for n, p, v in zip(names, passed, values, strict=True)
    )
    outcome, sentence = decide(checks)
    assert (outcome is Verdict.VALID) == all(p is True for p in passed)
    assert (outcome is Verdict.INVALID) == any(p is False for p in passed)
    assert sentence.endswith(".")
