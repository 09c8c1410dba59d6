"""The ``rigid-body`` problem (classical fast spin, non-resonant) and the small-divisor demo."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.cli import main
from perturb.errors import InvalidParameterError
from problems import get_problem
from problems.rigid_body.equations import b, k, z0p
from problems.rigid_body.reduction import gamma3_0
from problems.rigid_body.small_divisor import first_order_laurent

Body = get_problem("rigid-body")
Disk = get_problem("disk")

EPSILONS = (0.04, 0.02, 0.01, 0.005)
PERIODS = 5
SLOPE_SLACK = 0.15
M3 = sp.sqrt(1 - gamma3_0**2)


def reference_set(eps: float, **overrides):
    """A=9, B=11, C=16 (omega = 0.595), z0 = 0.5, c = 1, k = 0.5, gamma3_0 = 0.3."""
    arm, C, M = math.hypot(1, 6), overrides.pop("C", 16.0), 200.0
    return Body.create(
        C=C, g=C / (M * arm), R=3 * C / (0.5 * M * arm), r0=1 / eps, gamma3_0=0.3, **overrides
    )


@pytest.fixture(scope="module")
def solution():
    return Body.create().solve(1)


# ---------------------------------------------------------------------------- inputs
@pytest.mark.parametrize(
    ("overrides", "fragment"),
    [
        ({"C": 20.0}, "use the problem `disk`"),
        ({"C": 20.0 * (1 - 1e-6)}, "disk"),
        ({"C": 10.0}, "intermediate"),
        ({"C": 11.0}, "intermediate"),
        ({"C": 25.0}, "triangle"),
        ({"A": -1.0}, "`A` = -1"),
        ({"r0": 0.0}, "`r0` = 0"),
        ({"gamma3_0": -1.2}, "`gamma3_0` = -1.2"),
        ({"C": 20.0 * (1 - 1e-4)}, "small divisor"),
        ({"A": 9.0, "B": 9.0, "C": 9.0 + 1e-6}, "within"),
    ],
)
def test_bad_input(overrides, fragment):
    with pytest.raises(InvalidParameterError) as info:
        Body.create(**overrides)
    assert fragment in str(info.value) and "\n" not in str(info.value)


def test_defaults_are_a_fast_spin_body():
    problem = Body.create()
    assert problem.epsilon() == pytest.approx(0.01, rel=1e-3)
    assert problem.omega() == pytest.approx(math.sqrt(35 / 99))
    assert problem.values["z0"] == 0.5 and problem.values["gamma3_0"] == 0.25
    extras = problem.report_extras()
    assert extras["mu"] == pytest.approx(100, rel=1e-3) and "NOT" not in extras["regime"]


def test_cli_solve_rigid_body(capsys, solution):
    assert main(["solve", "rigid-body", "--times", "0,1", "--format", "csv", "--euler"]) == 0
    header = capsys.readouterr().out.splitlines()[0]
    assert header == "t,p,q,r,gamma1,gamma2,gamma3,theta,psi,phi"


# ---------------------------------------------------------------------------- true motion
@pytest.fixture(scope="module")
def runs(solution):
    return {
        eps: reference_set(eps).true_motion_errors(reference_set(eps).solve(1), periods=PERIODS)
        for eps in EPSILONS
    }


@pytest.mark.parametrize("name", ["p", "q", "r", "gamma1", "gamma2", "gamma3"])
def test_errors_fall_at_least_like_eps_squared(runs, name):
    eps = np.array(EPSILONS)
    err = np.array([runs[e][name] for e in EPSILONS])
    assert np.polyfit(np.log(eps), np.log(err), 1)[0] > 2 - SLOPE_SLACK


def test_integrals_conserved_and_closure(runs, solution):
    assert max(r["integrals"] for r in runs.values()) < 1e-10
    problem = reference_set(0.01)
    period = problem.period(solution)
    np.testing.assert_allclose(
        problem.state_vector(solution, period) / problem.state_vector(solution, 0.0).clip(1e-300),
        1.0,
        rtol=1e-10,
    )


@pytest.mark.slow
def test_second_order_improves_gamma_to_eps_cubed():
    errors = [
        reference_set(eps).true_motion_errors(reference_set(eps).solve(2), periods=PERIODS)
        for eps in EPSILONS
    ]
    err = np.array([e["gamma1"] for e in errors])
    assert np.polyfit(np.log(EPSILONS), np.log(err), 1)[0] > 3 - SLOPE_SLACK


# ---------------------------------------------------------------------------- small divisor
def test_first_order_pole_is_the_z0_term_only(solution):
    laurent = first_order_laurent(solution)
    # cos(tau) coefficient of P1: residue -z0' M3 (2b - 1) at delta = a + b - 1 = ab(1 - omega**2)
    assert sp.simplify(laurent.residues[1] + z0p * M3 * (2 * b - 1)) == 0
    assert laurent.residues[0] == 0
    # with z0 = 0 the k-term is finite: k A1 gamma0'' M3 (1 + B1)/(1 - omega**2) -> k a gamma0'' M3
    a_disk = 1 - b
    assert sp.simplify(laurent.regular_z0_zero[1] - k * a_disk * gamma3_0 * M3) == 0
    # the constant term tends to x0' gamma0''/b: the paper's shift p2 = p1 - eps x0' gamma0''/b
    x0p = sp.Symbol("x0p")
    assert sp.simplify(laurent.regular_z0_zero[0] - x0p * gamma3_0 / b) == 0


def test_amplitude_grows_like_one_over_one_minus_omega_squared(solution):
    """Numerically: the cos(tau) amplitude of P1 times (1 - omega**2) tends to a constant (z0 != 0)."""
    amp = solution.terms[0][1].coefficient(1)[0]
    amplitudes, divisors = [], []
    for c_value in (19.0, 19.6, 19.9, 19.97):
        problem = reference_set(0.01, C=c_value)
        values = problem.symbol_values()
        amplitudes.append(
            float(sp.sympify(amp).subs({s: values[s.name] for s in solution.system.parameters}))
        )
        divisors.append(1 - problem.omega() ** 2)
    products = np.abs(np.array(amplitudes) * np.array(divisors))
    assert products[-1] == pytest.approx(products[-2], rel=0.02)
    assert abs(amplitudes[-1] / amplitudes[0]) > 0.5 * divisors[0] / divisors[-1] > 10


def test_disk_solution_has_no_small_divisor():
    """Every denominator of the disk's solution is a product of a, b, k and M3: no a + b - 1."""
    solution = Disk.create().solve(1)
    exprs = [w for w in solution.frequency]
    for row in solution.terms:
        for term in row:
            for c, s in term.terms.values():
                exprs += [c, s]
    for expr in exprs:
        den = sp.fraction(sp.factor(sp.together(sp.sympify(expr))))[1]
        _, factors = sp.factor_list(den)
        for factor, _power in factors:
            assert len(factor.free_symbols) <= 1, (factor, expr)
