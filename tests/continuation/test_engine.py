"""The pseudo-arclength engine on curves known in closed form: a circle, the cubic's S-curve, a
pitchfork and a transcritical crossing; and the ways it stops.

Every located point is checked against its closed form; every value read off a curve against an
independent route (numpy's companion-matrix roots of the cubic, the circle's formula). The
tolerances: the corrector stops when its Newton step is below CORRECTOR_TOL = 1e-10 relative, so
its error is of the step's square (rounding); a located event is within EVENT_TOL = 1e-13 of its
segment's arclength, and a fold's λ moves by the square of that (a branch point's linearly);
LOCATED = 1e-10 leaves room for the conditioning of each closed form near its singular point.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from perturb.continuation import (
    ContinuationStatus,
    CurveEquations,
    TestFunction,
    continue_both,
    continue_curve,
)
from perturb.errors import ContinuationError, InvalidParameterError

#: See the module notes.
LOCATED = 1e-10
#: On the curve: the corrector's residual after its last (tiny) Newton step, with rounding.
ON_CURVE = 1e-12

CIRCLE = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1.0], lambda x: [[2 * x[0], 2 * x[1]]])
CUBIC = CurveEquations(lambda x: [x[0] ** 3 - x[0] - x[1]], lambda x: [[3 * x[0] ** 2 - 1, -1.0]])
FOLD_LAMBDA = 2 / (3 * math.sqrt(3))


def test_the_circle_closes_with_its_two_folds_and_every_point_on_it():
    curve = continue_both(CIRCLE, [1.0, 0.0], lam_range=(-2.0, 2.0))
    assert curve.status is ContinuationStatus.CLOSED and curve.success
    radius = np.hypot(curve.points[:, 0], curve.points[:, 1])
    assert np.max(np.abs(radius - 1)) <= ON_CURVE
    folds = sorted(curve.of_kind("fold"), key=lambda p: p.value)
    assert [p.value for p in folds] == pytest.approx([-1.0, 1.0], abs=LOCATED)
    assert all(abs(p.x[0]) <= 1e-6 for p in folds)  # u = ±sqrt(1 - λ²): |u| ~ sqrt(|δλ|)
    assert not curve.of_kind("branch-point")
    # the fold's tangent is along u: its λ-component is the located zero
    assert all(abs(p.tangent[-1]) <= LOCATED for p in folds)


@pytest.mark.parametrize("lam", [-0.999999, -0.5, 0.0, 0.3, 0.9, 0.99999999])
def test_values_read_off_the_circle_are_both_points_even_beside_a_fold(lam):
    curve = continue_both(CIRCLE, [1.0, 0.0], lam_range=(-2.0, 2.0))
    (found,) = curve.values_at([lam])
    assert sorted(found[:, 0]) == pytest.approx(
        [-math.sqrt(1 - lam**2), math.sqrt(1 - lam**2)], abs=1e-9
    )
    assert np.all(found[:, 1] == lam)


def test_the_cubic_s_curve_turns_exactly_at_its_folds():
    curve = continue_curve(CUBIC, [-1.5, -1.875], lam_range=(-2.0, 2.0))
    assert curve.status is ContinuationStatus.LEFT_RANGE
    assert curve.points[-1][-1] == pytest.approx(2.0, abs=LOCATED)  # stopped on the boundary
    folds = curve.of_kind("fold")
    assert [p.value for p in folds] == pytest.approx([FOLD_LAMBDA, -FOLD_LAMBDA], abs=LOCATED)
    assert [p.x[0] for p in folds] == pytest.approx([-1 / math.sqrt(3), 1 / math.sqrt(3)], abs=1e-6)
    assert not curve.of_kind("branch-point")
    # the fold is a point of the curve, in order
    assert all(np.array_equal(curve.points[p.index], p.x) for p in folds)
    assert np.all(np.diff(curve.arclength) > 0)


@pytest.mark.parametrize(
    "lam", [-1.9, -FOLD_LAMBDA - 1e-9, -0.2, 0.0, 0.1, FOLD_LAMBDA - 1e-9, FOLD_LAMBDA + 1e-9, 1.7]
)
def test_values_read_off_the_s_curve_are_the_cubics_roots(lam):
    curve = continue_both(CUBIC, [-1.5, -1.875], lam_range=(-2.0, 2.0))
    (found,) = curve.values_at([lam])
    roots = np.roots([1.0, 0.0, -1.0, -lam])
    real = np.sort(roots[np.abs(roots.imag) <= 1e-7].real)
    assert sorted(found[:, 0]) == pytest.approx(real, abs=1e-9)
    assert np.max(np.abs(found[:, 0] ** 3 - found[:, 0] - lam)) <= ON_CURVE


def test_a_pitchfork_on_the_trivial_branch_is_a_branch_point():
    # G = λu - u³: u = 0 for every λ, crossed at λ = 0 by λ = u²
    pitchfork = CurveEquations(lambda x: [x[1] * x[0] - x[0] ** 3],
                               lambda x: [[x[1] - 3 * x[0] ** 2, x[0]]])  # fmt: skip
    curve = continue_curve(pitchfork, [0.0, -1.0], lam_range=(-1.0, 1.0))
    assert curve.status is ContinuationStatus.LEFT_RANGE
    (point,) = curve.of_kind("branch-point")
    assert point.value == pytest.approx(0.0, abs=LOCATED)
    assert not curve.of_kind("fold")
    assert np.max(np.abs(curve.points[:, 0])) == 0.0  # it stayed on the trivial branch


def test_a_transcritical_crossing_off_zero_is_a_branch_point():
    # G = (u - 1)² - (λ - 2)²: the lines u - 1 = ±(λ - 2) cross at (1, 2)
    crossing = CurveEquations(lambda x: [(x[0] - 1) ** 2 - (x[1] - 2) ** 2],
                              lambda x: [[2 * (x[0] - 1), -2 * (x[1] - 2)]])  # fmt: skip
    curve = continue_curve(crossing, [0.5, 1.5], lam_range=(1.0, 3.0))
    (point,) = curve.of_kind("branch-point")
    assert point.x == pytest.approx([1.0, 2.0], abs=LOCATED)
    assert curve.points[-1] == pytest.approx([2.0, 3.0], abs=LOCATED)  # went straight through


def test_a_clients_test_function_is_located_and_classified():
    quarter = TestFunction("u=0.6", lambda x, t, j: x[0] - 0.6)
    named = TestFunction(
        "u=-0.6", lambda x, t, j: x[0] + 0.6, classify=lambda x, t, j: "low" if x[1] > 0 else None
    )
    curve = continue_both(CIRCLE, [1.0, 0.0], lam_range=(-2.0, 2.0), tests=[quarter, named])
    located = sorted(p.value for p in curve.of_kind("u=0.6"))
    assert located == pytest.approx([-0.8, 0.8], abs=LOCATED)
    (low,) = curve.of_kind("low")  # the one at λ < 0 was dropped by its classify
    assert low.x == pytest.approx([-0.6, 0.8], abs=LOCATED)
    assert not curve.of_kind("u=-0.6")


def test_a_curve_that_ends_in_a_cusp_fails_at_the_step_floor_and_says_where():
    cusp = CurveEquations(lambda x: [x[0] ** 2 - x[1] ** 3],
                          lambda x: [[2 * x[0], -3 * x[1] ** 2]])  # fmt: skip
    curve = continue_curve(cusp, [1.0, 1.0], lam_range=(-1.0, 2.0), direction=-1)
    assert curve.status is ContinuationStatus.STEP_FLOOR and not curve.success
    assert "λ = " in curve.message and "floor" in curve.message
    assert abs(curve.points[-1][-1]) < 0.05  # it got to the cusp and kept what it had
    assert np.max(np.abs(curve.points[:, 0] ** 2 - curve.points[:, 1] ** 3)) <= ON_CURVE
    with pytest.raises(ContinuationError, match="STEP_FLOOR"):
        curve.raise_for_status()


def test_the_domain_the_budget_and_a_start_off_every_curve():
    outside = continue_curve(
        CIRCLE, [1.0, 0.0], lam_range=(-2.0, 2.0),
        domain=lambda x: "u below 0.5" if x[0] < 0.5 else "",
    )  # fmt: skip
    assert outside.status is ContinuationStatus.LEFT_DOMAIN and outside.success
    assert "u below 0.5" in outside.message and np.all(outside.points[:, 0] >= 0.5)
    budget = continue_curve(CIRCLE, [1.0, 0.0], lam_range=(-2.0, 2.0), max_points=5)
    assert budget.status is ContinuationStatus.MAX_POINTS and len(budget.points) == 5
    nowhere = CurveEquations(lambda x: [x[0] ** 2 + 1.0], lambda x: [[2 * x[0], 0.0]])
    failed = continue_curve(nowhere, [0.3, 0.0], lam_range=(-1.0, 1.0))
    assert failed.status is ContinuationStatus.START_FAILED and "λ = 0" in failed.message
    nan = CurveEquations(lambda x: [math.nan], lambda x: [[1.0, 0.0]])
    assert continue_curve(nan, [0.0, 0.0], lam_range=(-1, 1)).status.name == "NOT_FINITE"


@pytest.mark.parametrize(
    ("options", "argument"),
    [
        ({"lam_range": (1.0, -1.0)}, "lam_range"),
        ({"lam_range": (2.0, 3.0)}, "start"),
        ({"lam_range": (-2.0, 2.0), "direction": 0}, "direction"),
        ({"lam_range": (-2.0, 2.0), "step": -1.0}, "step"),
    ],
)
def test_bad_input_is_one_line_naming_the_argument(options, argument):
    with pytest.raises(InvalidParameterError, match=f"`{argument}`"):
        continue_curve(CIRCLE, [1.0, 0.0], **options)


def test_a_start_on_a_fold_is_corrected_by_least_norm_newton():
    """At a fold G_u is singular (Newton at fixed λ cannot start there); the least-norm step
    corrects the start with λ free and the curve is followed both ways."""
    curve = continue_both(CUBIC, [-1 / math.sqrt(3), FOLD_LAMBDA + 1e-3], lam_range=(-1.0, 1.0))
    assert curve.success
    assert (
        np.max(np.abs(curve.points[:, 0] ** 3 - curve.points[:, 0] - curve.points[:, 1]))
        <= ON_CURVE
    )
    assert sorted(p.value for p in curve.of_kind("fold")) == pytest.approx(
        [-FOLD_LAMBDA, FOLD_LAMBDA], abs=LOCATED
    )


@pytest.mark.parametrize("n", [2, 3, 4])
def test_the_small_solves_are_lapacks(n):
    """Cramer's rule for the 2 x 2 and 3 x 3 systems of a step against numpy's LAPACK (another
    route), on well-conditioned random systems: agreement to 1e-12 relative (a few roundings of
    O(1) numbers divided by a determinant of O(1))."""
    from perturb.continuation.newton import _solve

    rng = np.random.default_rng(7)
    for _ in range(50):
        a = rng.normal(size=(n, n)) + n * np.eye(n)
        b = rng.normal(size=n)
        assert _solve(a, b) == pytest.approx(np.linalg.solve(a, b), rel=1e-12, abs=1e-12)
    with pytest.raises(np.linalg.LinAlgError):
        _solve(np.zeros((n, n)), np.ones(n))


def test_a_step_past_the_range_where_the_equations_are_undefined_is_shortened():
    """A curve whose equations are not defined below λ = 0 (a forcing level F > 0), followed down
    to the range's end 0.01 with long steps: a predictor past the end, where the residual is not
    finite, shortens the step (it used to stop the curve short of the end: F = 0.237)."""
    import math

    import numpy as np

    from perturb.continuation import ContinuationStatus, CurveEquations, continue_curve

    def residual(x):
        return [x[0] - x[1] ** 2] if x[1] >= 0 else [math.nan]

    def jacobian(x):
        return [[1.0, -2 * x[1]]] if x[1] >= 0 else [[math.nan, math.nan]]

    curve = continue_curve(CurveEquations(residual, jacobian), [0.25, 0.5], lam_range=(0.01, 1.0),
                           direction=-1.0, step=0.3, max_step=0.3)  # fmt: skip
    assert curve.status is ContinuationStatus.LEFT_RANGE, curve.message
    assert curve.points[-1][-1] == 0.01
    assert abs(curve.points[-1][0] - 1e-4) < 1e-12
    assert np.all(curve.points[:, -1] >= 0.01)
