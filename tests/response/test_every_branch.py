"""Every order-N branch at every grid value, whatever the sweep brackets.

A sweep wholly inside a hysteresis band used to list one branch of three: the continuation was
seeded from the first-order census at the window's ends, and the first-order band lies elsewhere
(O(ε) in σ from the order-N one). Now the order-N equations' own certified roots at the window's
ends seed it too, and the curves are followed beyond the window to the first-order folds nearby.

Checked against the truth by a route that knows nothing of the series: every periodic orbit of
the equations of motion at the sweep's middle, found by scipy's DOP853 and Newton's method on the
period map from a ring of initial states (written here), is matched by one analytic branch, and
every analytic branch by one orbit, within the series' error; and the narrow sweep lists what a
wide sweep lists at the same values.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from perturb.response.model import problem_response
from problems import get_problem, load_problem

HERE = Path(__file__).parent
#: Newton on the period map converged: a step below this (the integration's rtol is 1e-11).
NEWTON_TOL = 1e-10
#: Two true orbits are one when their initial states agree to this (Newton's accuracy, far
#: below any two distinct orbits here: 0.03 apart at least).
SAME = 1e-6
#: An analytic branch matches a true orbit when their peaks agree within this many of the
#: series' own error estimates, plus the shooting's resolution.
SAFETY, FLOOR = 3.0, 1e-6


def _rhs(kind, v):
    eps, zeta, gamma, f, omega = v["eps"], v["zeta"], v["gamma"], v["F"], v["Omega"]
    alpha = v.get("alpha", 0.0)

    def field(t, y):
        x, xd = y[0], y[1]
        acc = -x + eps * (-2 * zeta * xd - alpha * x**2 - gamma * x**3 + f * math.cos(omega * t))
        k = -1 + eps * (-2 * alpha * x - 3 * gamma * x**2)
        c = -2 * eps * zeta
        m = y[2:].reshape(2, 2)
        dm = np.array([[0.0, 1.0], [k, c]]) @ m
        return [xd, acc, *dm.ravel()]

    return field


def _true_orbits(values):
    """Every periodic orbit of period 2π/Ω reached by Newton from a ring of initial states."""
    field = _rhs(None, values)
    period = 2 * math.pi / values["Omega"]

    def shot(y0):
        sol = solve_ivp(field, (0, period), [*y0, 1.0, 0.0, 0.0, 1.0], method="DOP853",
                        rtol=1e-11, atol=1e-13)  # fmt: skip
        end = sol.y[:, -1]
        return end[:2], end[2:].reshape(2, 2)

    found = []
    for a in (0.15, 0.45, 0.75, 1.05, 1.35, 1.65):
        for phase in np.linspace(0, 2 * math.pi, 6, endpoint=False):
            y = np.array([a * math.cos(phase), -a * values["Omega"] * math.sin(phase)])
            for _ in range(25):
                end, mono = shot(y)
                step = np.linalg.solve(mono - np.eye(2), -(end - y))
                y = y + step * min(1.0, 0.5 / max(float(np.max(np.abs(step))), 1e-300))
                if float(np.max(np.abs(step))) < NEWTON_TOL or float(np.max(np.abs(y))) > 5:
                    break
            if float(np.max(np.abs(step))) >= NEWTON_TOL or float(np.max(np.abs(y))) > 5:
                continue
            if not any(float(np.max(np.abs(y - z))) < SAME for z, _ in found):
                sol = solve_ivp(field, (0, period), [*y, 1.0, 0.0, 0.0, 1.0], method="DOP853",
                                rtol=1e-11, atol=1e-13, dense_output=True)  # fmt: skip
                t = np.linspace(0, period, 2001)
                found.append((y, float(np.max(np.abs(sol.sol(t)[0])))))
    return found


CASES = [
    ("forced-duffing", {"eps": 0.1, "F": 0.3}, (1.0358, 1.0362)),  # hardening, jump-up band
    ("forced-duffing", {"gamma": -1.0, "eps": 0.1, "zeta": 0.1, "F": 0.2}, (0.9585, 0.9615)),
    ("helmholtz_duffing.py:HelmholtzDuffing", {"F": 0.3}, (1.030, 1.035)),
]


def _problem(name, values):
    cls = load_problem(f"{HERE / name}") if name.endswith("HelmholtzDuffing") else get_problem(name)
    return cls.create(**values)


@pytest.mark.parametrize(("name", "values", "sweep"), CASES)
def test_a_sweep_inside_a_band_lists_every_branch(name, values, sweep):
    problem = _problem(name, values)
    grid = np.linspace(*sweep, 3)
    narrow = problem_response(problem, "Omega", grid, order=3).response
    wide_grid = np.concatenate((np.linspace(sweep[0] - 0.05, sweep[0], 26)[:-1], grid,
                                np.linspace(sweep[1], sweep[1] + 0.05, 26)[1:]))  # fmt: skip
    wide = problem_response(problem, "Omega", wide_grid, order=3).response
    for value in grid:
        here = narrow.at(value)
        assert len(here) == len(wide.at(value)) == 3, (value, len(here), len(wide.at(value)))
        for p, q in zip(here, sorted(wide.at(value), key=lambda p: p.peak["x"]), strict=True):
            assert abs(p.peak["x"] - q.peak["x"]) <= 1e-8 * max(1.0, q.peak["x"])
    # the folds bounding the band, just outside the sweep, are still reported (marked outside)
    outside = [f for f in narrow.folds if not f.inside]
    assert any(f.value < sweep[0] for f in outside) or any(f.value > sweep[1] for f in outside)

    middle = float(grid[1])
    analytic = narrow.at(middle)
    true = _true_orbits({**problem.values, "Omega": middle})
    assert len(true) == len(analytic), [t for _, t in true]
    for point in analytic:
        error = point.error["x"]
        assert math.isfinite(error)
        nearest = min(abs(peak - point.peak["x"]) for _, peak in true)
        assert nearest <= SAFETY * error + FLOOR, (point.peak["x"], nearest, error)
