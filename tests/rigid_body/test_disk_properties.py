"""Property tests of the disk over random valid bodies (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from problems import get_problem

Disk = get_problem("disk")

#: Halving eps must shrink an O(eps**2) defect at least by this factor (4 asymptotically).
HALVING_FACTOR = 0.3
SETTINGS = settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def disks(draw):
    A = draw(st.floats(1.0, 10.0))
    B = draw(st.floats(1.0, 10.0))
    x0 = draw(st.floats(-3.0, 3.0))
    y0 = draw(st.floats(-3.0, 3.0).filter(lambda v: abs(v) > 0.1))
    gamma3 = draw(st.floats(-0.8, 0.8))
    k_value = draw(st.floats(0.1, 1.0))
    M = 1.0
    arm = math.hypot(x0, y0)
    C = A + B
    return {
        "A": A, "B": B, "C": C, "x0": x0, "y0": y0, "gamma3_0": gamma3, "M": M,
        "g": C / (M * arm), "R": 3 * C / (k_value * M * arm),
    }  # fmt: skip


def _geometric_defect(problem, solution):
    t = np.linspace(0.0, problem.period(solution), 64)
    s = problem.state(solution, t)
    return np.max(np.abs(s["gamma1"] ** 2 + s["gamma2"] ** 2 + s["gamma3"] ** 2 - 1))


@SETTINGS
@given(body=disks())
def test_geometric_integral_holds_to_second_order(body):
    defects = []
    for eps in (0.01, 0.005):
        problem = Disk.create(r0=1 / eps, **body)
        defects.append(_geometric_defect(problem, problem.solve(1)))
    assert defects[1] <= HALVING_FACTOR * defects[0] + 1e-13


@SETTINGS
@given(body=disks())
def test_closure_after_one_period_and_conserved_integrals(body):
    problem = Disk.create(r0=1 / 0.01, **body)
    solution = problem.solve(1)
    scale = np.array([problem.scale_c()] * 2 + [problem.values["r0"]] + [1.0] * 3)
    start = problem.state_vector(solution, 0.0) / scale
    end = problem.state_vector(solution, problem.period(solution)) / scale
    np.testing.assert_allclose(end, start, atol=1e-11)
    errors = problem.true_motion_errors(solution, periods=1, samples=20)
    assert errors["integrals"] < 1e-9
