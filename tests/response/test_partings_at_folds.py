"""Where an analytic branch parts from the truth when the true orbit it follows ends at a fold.

Past a true fold the true orbit an analytic branch agreed with is gone and the nearest true orbit
is another one, far off: the difference jumps. Read at the grid alone, the crossing was
interpolated across that jump and put just past the last agreeing grid value (forced Duffing,
ε = 0.2, order 1: Ω = 1.58004 with the true fold at 1.5857, while the two agree to 2 % at
Ω = 1.583). The parting is read at the fold now; the agreement before it is checked here by a
second route (scipy's DOP853 and a Newton solve on the stroboscopic map).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from perturb.cli import main
from perturb.oracle import heyoka_available
from perturb.response import steady_state_of
from problems import get_problem

#: ε, ζ, γ, F of the forced Duffing oscillator whose upper branch ends at a true fold between
#: the grid values 1.58 and 1.59.
EPS, ZETA, GAMMA, FORCE = 0.2, 0.1, 1.0, 1.0
SWEEP = ("forced-duffing", "--set", f"eps={EPS}", "--sweep", "Omega=1.5:1.6:11", "--order", "1")
#: The grid values around the true fold.
BEFORE, AFTER = 1.58, 1.59
#: The scipy shot's tolerances (the peaks compared differ by 2 %).
SHOT_RTOL = 1e-11
#: Samples of a period for the true orbit's peak (its error is far below the 2 % compared).
PEAK_SAMPLES = 4001


def _true_peak(omega: float, guess) -> float:
    """max |x| over a period of the true periodic orbit near ``guess``, by a second route."""

    def field(t, y):
        x, v = y
        return [v, -2 * ZETA * EPS * v - x - GAMMA * EPS * x**3 + FORCE * EPS * np.cos(omega * t)]

    period = 2 * np.pi / omega

    def shot(y0):
        return solve_ivp(field, (0.0, period), y0, method="DOP853", rtol=SHOT_RTOL,
                         atol=SHOT_RTOL).y[:, -1]  # fmt: skip

    y0, _, found, message = fsolve(lambda y: shot(y) - y, guess, full_output=True)
    assert found == 1, message
    orbit = solve_ivp(field, (0.0, period), y0, method="DOP853", rtol=SHOT_RTOL,
                      atol=SHOT_RTOL, dense_output=True)  # fmt: skip
    return float(np.max(np.abs(orbit.sol(np.linspace(0.0, period, PEAK_SAMPLES))[0])))


@pytest.mark.skipif(not heyoka_available(), reason="the true curves take minutes without heyoka")
def test_a_branch_that_agrees_up_to_the_true_fold_parts_at_the_fold(capsys):
    code = main(["response", *SWEEP, "--true", "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    entry = json.loads(out)["true_curve"]
    tol = entry["tolerance"]
    (fold,) = [
        b["value"] for b in entry["bifurcations"]
        if b["kind"] == "fold" and BEFORE < b["value"] < AFTER
    ]  # fmt: skip
    upper = [p for p in entry["partings"] if p["branch"] == "upper"]
    assert upper

    # between the last grid value and the fold, the upper branch still agrees with a true orbit
    between = (BEFORE + fold) / 2
    state = steady_state_of(get_problem("forced-duffing").create(eps=EPS, Omega=between), 1)
    point = state.points[state.names.index("upper")]
    analytic = point.amplitude("x", "peak")
    a, b = point.amplitudes["a_x"], point.amplitudes["b_x"]
    true = _true_peak(between, [a, b * between])  # x ≈ a cos Ωt + b sin Ωt at t = 0
    assert abs(analytic - true) / true <= tol

    for parting in upper:  # so it cannot have parted before; it parts where the truth ends
        assert parting["value"] >= between
        assert parting["value"] == pytest.approx(fold, abs=1e-12)
        assert parting["before"] == pytest.approx(fold, abs=1e-12)
        assert parting["after"] == pytest.approx(AFTER, abs=1e-12)
