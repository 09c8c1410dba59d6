"""Each fold with its uncertainty when the series stands alone.

The series' own estimate of a fold's error is the distance to the same fold one order lower; the
points within that band are marked (their note, the table, stderr), a fold whose band the series
cannot tell is said to be so, and `--true` gives the true fold beside it. The true folds here come
from a route that shares nothing with perturb: scipy's DOP853 at rtol 1e-12 and fsolve on the
minimally augmented system {φ_T(y) − y = 0, det(M − I) = 0} in (y, Ω).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from perturb.cli import main
from perturb.response.model import problem_response
from problems import get_problem, load_problem

HERE = Path(__file__).parent
EPS, ZETA, GAMMA, FORCE = 0.05, 0.1, 1.0, 1.0  # forced-duffing's defaults


def _shot(y, omega, eps=EPS, force=FORCE):
    def field(t, z):
        x, v = z[0], z[1]
        m = z[2:].reshape(2, 2)
        jac = np.array([[0.0, 1.0], [-1.0 - 3 * eps * GAMMA * x * x, -2 * eps * ZETA]])
        acc = -x + eps * (-2 * ZETA * v - GAMMA * x**3 + force * math.cos(omega * t))
        return [v, acc, *(jac @ m).ravel()]

    sol = solve_ivp(field, (0, 2 * math.pi / omega), [*y, 1.0, 0.0, 0.0, 1.0], method="DOP853",
                    rtol=1e-12, atol=1e-14)  # fmt: skip
    return sol.y[:2, -1], sol.y[2:, -1].reshape(2, 2)


def _true_fold(fold, eps=EPS, force=FORCE) -> float:
    omega0 = fold.value
    a, b = fold.amplitudes["a_x"], fold.amplitudes["b_x"]

    def system(z):
        end, mono = _shot(z[:2], z[2], eps, force)
        return [*(end - z[:2]), np.linalg.det(mono - np.eye(2))]

    z, info, ier, message = fsolve(system, [a, omega0 * b, omega0], xtol=1e-13, full_output=True)
    assert ier == 1, message
    return float(z[2])


@pytest.fixture(scope="module")
def duffing():
    return get_problem("forced-duffing").create()


def test_the_true_fold_lies_within_the_series_band(duffing):
    grid = np.linspace(0.95, 1.3, 36)
    folds = {order: problem_response(duffing, "Omega", grid, order=order).response.folds
             for order in (1, 2, 3)}  # fmt: skip
    truths = [_true_fold(f) for f in folds[3]]
    assert truths == pytest.approx([1.0415983541, 1.2628787], abs=1e-7)
    for order in (2, 3):
        assert len(folds[order]) == 2
        for fold, lower, truth in zip(folds[order], folds[order - 1], truths, strict=True):
            # the band is the order below's distance: the truth lies within it
            assert fold.uncertainty == pytest.approx(abs(fold.value - lower.value), rel=1e-9)
            assert abs(fold.value - truth) <= fold.uncertainty
    # at order 1 the jump-down fold has no first-order fold beside it: the series cannot tell
    jump_up, jump_down = folds[1]
    assert abs(jump_up.value - truths[0]) <= jump_up.uncertainty
    assert math.isnan(jump_down.uncertainty) and math.isnan(jump_down.first_order)


def test_at_a_smaller_eps_the_band_narrows_and_still_holds_the_truth():
    """ε = 0.02, F = 0.5 at order 3: bands of 3e-10 and 1e-6, the true folds 6e-12 and 2e-8 away."""
    problem = get_problem("forced-duffing").create(eps=0.02, F=0.5)
    folds = problem_response(problem, "Omega", np.linspace(1.0, 1.06, 61), order=3).response.folds
    assert len(folds) == 2
    for fold in folds:
        assert 0 < fold.uncertainty < 1e-5
        assert abs(fold.value - _true_fold(fold, 0.02, 0.5)) <= fold.uncertainty


def test_points_within_the_band_are_marked_table_json_and_stderr(capsys):
    argv = ["response", "forced-duffing", "--sweep", "Omega=1.26:1.265:11"]
    assert main([*argv, "--format", "json"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    (fold,) = [f for f in data["folds"] if f["inside"]]
    band = fold["uncertainty"]
    assert 1e-4 < band < 1e-2
    marked = [p for p in data["points"] if "the branch set may change within" in p["note"]]
    assert marked and all(abs(p["value"] - fold["value"]) <= band for p in marked)
    unmarked = [p for p in data["points"] if p not in marked]
    assert all(abs(p["value"] - fold["value"]) > band for p in unmarked)
    assert "the branch set may change within" in captured.err
    assert main(argv) == 0
    table = capsys.readouterr().out
    assert f"± {band:.2g}" in table and "point(s) there are marked" in table


def test_two_folds_never_share_a_first_order_fold():
    problem = load_problem(f"{HERE / 'helmholtz_duffing.py:HelmholtzDuffing'}").create(F=0.3)
    folds = problem_response(problem, "Omega", np.linspace(0.9, 1.1, 41)).response.folds
    assert len(folds) == 2
    firsts = [f.first_order for f in folds if math.isfinite(f.first_order)]
    assert len(set(firsts)) == len(firsts)
