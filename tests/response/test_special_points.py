"""Folds and Neimark-Sacker points on the order-N curves converge with N to the true ones, found
by the shooting alone (a second route: bisection on where the true orbit exists, or where its
largest multiplier crosses the unit circle); a sweep reports them whatever it brackets, and the
response's defaults print no branch past the true jump-down.

Bisection stops at BISECT = 1e-9 in Ω, far below the order-3 errors it measures (1e-4 ... 1e-6).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from perturb.cli import main
from perturb.method.driven import amplitude_equations
from perturb.response.model import problem_response
from perturb.response.truth import shoot_point
from perturb.steady.continued import continued_response
from perturb.steady.line import line_of_problem
from problems import get_problem, load_problem

BISECT = 1e-9
HERE = Path(__file__).parent


def _response(problem, low, high, order, points=5):
    system = problem.system()
    grid = np.linspace(low, high, points)
    line = line_of_problem(problem, "Omega", [p.name for p in system.parameters], low, high)
    return continued_response(amplitude_equations(system, order), order, line, grid)


def _bisect(inside, outside, holds) -> float:
    while abs(outside - inside) > BISECT:
        middle = 0.5 * (inside + outside)
        inside, outside = (middle, outside) if holds(middle) else (inside, middle)
    return 0.5 * (inside + outside)


def _true_fold(result, fold) -> float:
    """Where the true orbit near the order-N fold stops existing: shot from the fold's state, a
    true orbit of nearly its amplitude exists on one side and not on the other."""
    u = np.array(list(fold.amplitudes.values()))
    top = max(fold.peak.values())

    def exists(lam):
        shot = shoot_point(result.evaluator, result.traced.line, u, lam)
        return shot["success"] and abs(max(shot["peak"].values()) - top) < 0.1 * top

    step = 2e-3
    low, high = fold.value - step, fold.value + step
    inside, outside = (low, high) if exists(low) else (high, low)
    assert exists(inside) and not exists(outside)
    return _bisect(inside, outside, exists)


@pytest.mark.slow
def test_the_forced_duffings_jump_down_converges_with_the_order():
    """The jump-down fold of the defaults (the issue's 1.2629): each order nearer the true fold."""
    problem = get_problem("forced-duffing").create()
    folds = {}
    for order in (1, 2, 3):
        result = _response(problem, 1.2, 1.3, order)
        (fold,) = [s for s in result.special if s.kind == "fold"]
        folds[order] = (fold, result)
    truth = _true_fold(folds[3][1], folds[3][0])
    errors = [abs(folds[order][0].value - truth) for order in (1, 2, 3)]
    assert errors[2] < errors[1] < errors[0]


def test_no_branch_past_the_true_jump_down_at_the_defaults(capsys):
    problem = get_problem("forced-duffing").create()
    result = _response(problem, 1.2, 1.3, 3)
    (fold,) = [s for s in result.special if s.kind == "fold"]
    truth = _true_fold(result, fold)
    assert main(["response", "forced-duffing", "--sweep", f"Omega={truth:.6f}:1.46:41",
                 "--format", "json"]) == 0  # fmt: skip
    import json

    data = json.loads(capsys.readouterr().out)
    assert {p["branch"] for p in data["points"]} == {"response"}  # one branch: the lower one
    assert max(p["peak"]["x"] for p in data["points"]) < 0.2


def test_a_fold_outside_the_first_order_bracket_is_found_and_one_beside_the_sweep_reported():
    """A sweep ending between the order-N jump-down and the first-order one (the issue's case
    of `folds: []`) reports the order-N fold; a sweep ending just before it reports it as beside
    the sweep."""
    problem = get_problem("forced-duffing").create()
    inside = problem_response(problem, "Omega", np.linspace(1.2, 1.265, 6), order=3).response
    (fold,) = [f for f in inside.folds if f.inside]
    assert 1.262 < fold.value < 1.264
    beside = problem_response(problem, "Omega", np.linspace(1.2, 1.26, 6), order=3).response
    assert [f.inside for f in beside.folds] == [False]
    assert beside.folds[0].value == pytest.approx(fold.value, abs=1e-9)


@pytest.mark.slow
def test_the_entrainment_boundary_converges_with_the_order():
    """A forced van der Pol-Duffing's Neimark-Sacker point (the slow flow's Hopf, where a pair of
    multipliers leaves the unit circle): each order nearer where the true orbit's does."""
    problem = load_problem(f"{HERE / 'vdp_duffing.py'}:VdPDuffing").create()
    found = {}
    for order in (1, 2, 3):
        result = _response(problem, 0.98, 1.03, order)
        (ns,) = [s for s in result.special if s.kind == "neimark-sacker"]
        found[order] = (ns, result)
    ns, result = found[3]
    u = np.array(list(ns.amplitudes.values()))

    def stable(lam):
        shot = shoot_point(result.evaluator, result.traced.line, u, lam)
        assert shot["success"]
        return max(abs(z) for z in shot["multipliers"]) < 1

    low, high = ns.value - 2e-3, ns.value + 2e-3
    inside, outside = (low, high) if stable(low) else (high, low)
    assert stable(inside) and not stable(outside)
    truth = _bisect(inside, outside, stable)
    errors = [abs(found[order][0].value - truth) for order in (1, 2, 3)]
    assert errors[2] < errors[1] < errors[0]
