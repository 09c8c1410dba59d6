"""Stability of order N with the exact Floquet structure (issue 29, deliverable 2).

* Liouville: the product of the printed multipliers of every point is exp(∮ div f dt) over the
  response's period — exp(−2εΣζ T) for linear damping, T = 2πp/Ω — to LIOUVILLE = 1e-10 relative
  (the Magnus steps keep it exactly; what is left is the rounding of a product of 2n numbers and
  of eigenvalues of a matrix of norm ~1, ~1e-14).
* The Magnus monodromy against a second route: DOP853 on the same variational equation along the
  same order-N series (rtol 1e-12): MAGNUS_AGREE = 1e-8, the sixth-order Magnus' error at
  MAGNUS_STEPS = 128 on these orbits (4e-10 measured at the forced Duffing's largest amplitude,
  DOP853's own ~1e-12) with a factor 25 of room.
* A forced van der Pol-Duffing, whose divergence ε μ (1 − x²) varies along the orbit: the product
  against exp of scipy's adaptive quadrature of it along the series, to LIOUVILLE.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from perturb.method.driven import amplitude_equations
from perturb.response import steady_state_of
from perturb.response.model import problem_response
from perturb.steady.compiled import compiled_motion, compiled_series
from perturb.steady.floquet import stability_along
from problems import get_problem, load_problem

LIOUVILLE = 1e-10
MAGNUS_AGREE = 1e-8
HERE = __import__("pathlib").Path(__file__).parent

SLOW = pytest.mark.slow
DAMPED = [
    ("forced-duffing", {}, (0.95, 1.2), ("zeta",)),
    ("forced-duffing", {"gamma": -1.0}, (0.8, 1.05), ("zeta",)),
    pytest.param("parametric-duffing", {}, (1.9, 2.2), ("zeta",), marks=SLOW),
    pytest.param("superharmonic-duffing", {}, (0.3, 0.37), ("zeta",), marks=SLOW),
    pytest.param("autoparametric-absorber", {}, (1.9, 2.1), ("zeta1", "zeta2"), marks=SLOW),
]


@pytest.mark.parametrize(("name", "values", "sweep", "dampers"), DAMPED)
def test_every_printed_multiplier_set_satisfies_liouville(name, values, sweep, dampers):
    problem = get_problem(name).create(**values)
    result = problem_response(problem, "Omega", np.linspace(*sweep, 5), order=1)
    p = problem.system().excitation.p
    eps = problem.epsilon()
    damping = sum(problem.values[d] for d in dampers)

    def expected(omega):
        return math.exp(-2 * eps * damping * 2 * math.pi * p / omega)

    response = result.response
    assert response.points
    for point in response.points:
        product = np.prod(point.multipliers)
        assert abs(product.imag) <= LIOUVILLE
        assert product.real == pytest.approx(expected(point.value), rel=LIOUVILLE)
        assert point.liouville == pytest.approx(expected(point.value), rel=LIOUVILLE)
    for special in response.special:
        product = np.prod(special.multipliers).real
        assert product == pytest.approx(expected(special.value), rel=LIOUVILLE)
    for curve in response.curves:  # every point of the drawn curves too
        products = np.prod(curve.multipliers, axis=1).real
        wanted = np.array([expected(v) for v in curve.values])
        assert np.max(np.abs(products / wanted - 1)) <= LIOUVILLE


def _dop853_multipliers(problem, order, amplitudes):
    """The variational equation along the same order-N series, by DOP853."""
    system = problem.system()
    equations = amplitude_equations(system, order)
    series, motion = compiled_series(equations), compiled_motion(system)
    values = problem.symbol_values()
    params = np.array([values[q.name] for q in system.parameters])
    x = np.concatenate((amplitudes, params, [problem.epsilon()]))[None, :]
    nu, cos, sin = (v[0] for v in series.evaluate(x))
    j = np.arange(cos.shape[-1])
    n = system.n

    def rhs(t, y):
        s = nu * t
        pos = cos @ np.cos(j * s) + sin @ np.sin(j * s)
        vel = nu * ((sin * j) @ np.cos(j * s) - (cos * j) @ np.sin(j * s))
        state = np.concatenate((pos, vel))[None, :]
        a = motion.jacobian(state, np.array([motion.p * s]), params[None, :],
                            np.array([problem.epsilon()]))[0]  # fmt: skip
        return (a @ y.reshape(2 * n, 2 * n)).ravel()

    period = 2 * math.pi / nu
    out = solve_ivp(rhs, (0, period), np.eye(2 * n).ravel(), method="DOP853", rtol=1e-12,
                    atol=1e-14)  # fmt: skip
    phi = out.y[:, -1].reshape(2 * n, 2 * n)
    magnus = stability_along(motion, series, x, params[None, :], np.array([problem.epsilon()]))
    return np.linalg.eigvals(phi), magnus.multipliers[0]


@pytest.mark.parametrize(
    ("name", "omega", "branch"),
    [
        ("forced-duffing", 1.15, "upper"),
        pytest.param("autoparametric-absorber", 1.96, "upper", marks=pytest.mark.slow),
    ],
)
def test_the_magnus_monodromy_is_dop853s(name, omega, branch):
    problem = get_problem(name).create(Omega=omega)
    state = steady_state_of(problem, 3)
    point = state.points[state.names.index(branch)]
    u = np.array(list(point.amplitudes.values()))
    reference, magnus = _dop853_multipliers(problem, 3, u)
    for z in magnus:  # each multiplier has its twin in the other set
        assert np.min(np.abs(reference - z)) <= MAGNUS_AGREE


def test_liouville_along_a_varying_divergence_against_quadrature():
    problem = load_problem(f"{HERE / 'vdp_duffing.py'}:VdPDuffing").create(Omega=1.05)
    system = problem.system()
    state = steady_state_of(problem, 2)
    equations = amplitude_equations(system, 2)
    series = compiled_series(equations)
    values = problem.symbol_values()
    params = [values[q.name] for q in system.parameters]
    eps, mu = problem.epsilon(), values["mu"]
    for point in state.points:
        x = np.array([[*point.amplitudes.values(), *params, eps]])
        nu, cos, sin = (v[0] for v in series.evaluate(x))
        j = np.arange(cos.shape[-1])

        def divergence(t, nu=nu, cos=cos, sin=sin, j=j):
            position = cos[0] @ np.cos(j * nu * t) + sin[0] @ np.sin(j * nu * t)
            return eps * mu * (1 - position**2)

        integral = quad(divergence, 0, 2 * math.pi / nu, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
        assert np.prod(point.multipliers).real == pytest.approx(math.exp(integral), rel=LIOUVILLE)
