"""Property tests of the fast-spin body over random valid bodies (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from perturb.errors import InvalidParameterError
from problems import get_problem

Body = get_problem("rigid-body")

HALVING_FACTOR = 0.3
#: Keep away from omega = 1 so that eps = 0.01 is small against the divisor 1 - omega**2.
MIN_DIVISOR = 0.2
SETTINGS = settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def bodies(draw):
    A = draw(st.floats(1.0, 10.0))
    B = draw(st.floats(1.0, 10.0))
    # draw omega**2 = (C - A)(C - B)/(AB) directly, away from 0 and 1, and solve for C: no rejection
    w2 = draw(st.floats(MIN_DIVISOR, 1 - MIN_DIVISOR))
    oblate = draw(st.booleans())
    root = math.sqrt((A - B) ** 2 + 4 * A * B * w2)
    C = (A + B + root) / 2 if oblate else (A + B - root) / 2
    assume(C >= abs(A - B))  # the prolate root can break the triangle inequality
    x0 = draw(st.floats(-3.0, 3.0))
    y0 = draw(st.floats(-3.0, 3.0).filter(lambda v: abs(v) > 0.1))
    z0 = draw(st.floats(-1.0, 1.0))
    gamma3 = draw(st.floats(-0.8, 0.8))
    k_value = draw(st.floats(0.0, 1.0))
    arm = math.hypot(x0, y0)
    return {
        "A": A, "B": B, "C": C, "x0": x0, "y0": y0, "z0": z0, "gamma3_0": gamma3, "M": 1.0,
        "g": C / arm, "R": 3 * C / (k_value * arm) if k_value > 0 else math.inf,
    }  # fmt: skip


def _create(eps, body):
    try:
        return Body.create(r0=1 / eps, **body)
    except InvalidParameterError:
        assume(False)


@SETTINGS
@given(body=bodies())
def test_geometric_integral_holds_to_second_order(body):
    defects = []
    for eps in (0.01, 0.005):
        problem = _create(eps, body)
        solution = problem.solve(1)
        t = np.linspace(0.0, problem.period(solution), 64)
        s = problem.state(solution, t)
        defects.append(np.max(np.abs(s["gamma1"] ** 2 + s["gamma2"] ** 2 + s["gamma3"] ** 2 - 1)))
    assert defects[1] <= HALVING_FACTOR * defects[0] + 1e-13


@SETTINGS
@given(body=bodies())
def test_closure_after_one_period_and_conserved_integrals(body):
    problem = _create(0.01, body)
    solution = problem.solve(1)
    scale = np.array([problem.scale_c()] * 2 + [problem.values["r0"]] + [1.0] * 3)
    start = problem.state_vector(solution, 0.0) / scale
    end = problem.state_vector(solution, problem.period(solution)) / scale
    np.testing.assert_allclose(end, start, atol=1e-11)
    errors = problem.true_motion_errors(solution, periods=1, samples=20)
    assert errors["integrals"] < 1e-9
