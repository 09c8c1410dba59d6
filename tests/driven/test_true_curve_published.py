"""The true curve against published values, each by a second route (issue 29, item 4; slow).

- the twin-well Duffing's period doubling (Jordan & Smith's sequence: period 1 at Γ = 0.20,
  period 2 at 0.27) against a brute-force stroboscopic scan of the original equation;
- Mathieu's characteristic value a₁(1) = 1.85910807 (Abramowitz & Stegun, Table 20.1) as the edge
  of the parametric tongue at q = 1, and the nonlinear parametric branch leaving x = 0 there;
- the forced Duffing's folds against a minimally augmented system solved with DOP853 shooting;
- a two-mode driven problem: the true curve is generic in the number of modes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.oracle import heyoka_available
from perturb.response.model import problem_response
from problems import get_problem
from tests.driven.published import (
    PUBLISHED_PERIOD_ONE,
    PUBLISHED_PERIOD_TWO,
    TwinWell,
    brute_force_period_doubling,
    hill_edges,
    mathieu_edges,
)

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not heyoka_available(), reason="the true curves need heyoka's speed"),
]

#: Abramowitz & Stegun, Table 20.1: Mathieu's characteristic value a_1 at q = 1.
A1_AT_Q1 = 1.85910807


def test_the_twin_well_period_doubling_against_a_brute_force_scan():
    """Continue the period-1 orbit of the well in Γ from a small forcing: a period doubling (a
    multiplier at -1) inside the published bracket (period 1 at 0.20, period 2 at 0.27), equal to
    the brute-force scan's root. The scan's error is its fit's: d^2 is quadratic in Γ to the
    residual 2e-7 over a slope ~10, so ~1e-7 in Γ at the root; 2e-6 leaves a factor of 10 for the
    cubic term the fit leaves out."""
    problem = TwinWell.create()
    result = problem_response(problem, "Gamma", np.linspace(0.02, 0.4, 5), true=1000)
    found = [b for b in result.true_curve.bifurcations if b.kind == "period-doubling"]
    assert found, result.true_curve
    first = found[0]
    assert PUBLISHED_PERIOD_ONE < first.value < PUBLISHED_PERIOD_TWO
    assert abs(first.multiplier + 1) <= 1e-8
    scan = brute_force_period_doubling([0.2665, 0.267, 0.268, 0.269], periods=1500)
    assert max(scan["settled"]) <= 1e-6, scan  # the period-2 orbits had settled
    assert abs(first.value - scan["gamma_pd"]) <= 2e-6, (first.value, scan)


def test_mathieu_a1_at_q_equal_one_is_the_tongue_edge():
    """h eps = 1/a_1(1) puts the tongue's lower edge at q = 4 h eps/Omega^2 = 1 exactly, where
    a = 4/Omega^2 must be the published a_1(1) (8 decimals) and scipy's and the Hill
    determinant's to 1e-9: an eps of 0.5, far from any small parameter, is nothing to the true
    curve."""
    from scipy.special import mathieu_a

    exact = float(mathieu_a(1, 1.0))
    assert abs(exact - A1_AT_Q1) <= 5e-9  # scipy against the table
    eps = 0.5
    problem = get_problem("parametric-duffing").create(zeta=0.0, gamma=0.0, eps=eps, h=2.0 / exact)
    result = problem_response(problem, "Omega", np.linspace(1.3, 1.6, 5), true=200)
    points = [b for b in result.true_curve.bifurcations if b.kind == "branch-point"]
    edge = min(points, key=lambda b: abs(b.value - 2 / math.sqrt(exact)))
    a = 4 / edge.value**2
    assert abs(a - A1_AT_Q1) <= 5e-9
    assert abs(a - exact) <= 1e-9
    assert abs(edge.value - min(hill_edges(1.0 / exact))) <= 1e-9
    assert abs(edge.value - min(mathieu_edges(1.0 / exact))) <= 1e-9


def test_the_parametric_branch_leaves_x_equal_zero_at_the_tongue_edges():
    """The undamped parametric Duffing: its nonlinear branches are born at the tongue's edges
    (a pitchfork of x = 0), where the true curve of the branch meets x = 0 at the edge's Omega."""
    problem = get_problem("parametric-duffing").create(zeta=0.0)
    result = problem_response(problem, "Omega", np.linspace(1.9, 2.1, 11), true=400)
    edges = mathieu_edges(problem.values["h"] * problem.values["eps"])
    curves = result.true_curve.curves
    trivial = [c for c in curves if "trivial" in c.branches]
    others = [c for c in curves if "trivial" not in c.branches]
    assert trivial and others
    born = sorted(b.value for c in others for b in c.bifurcations if b.kind == "branch-point")
    assert born == pytest.approx(edges, abs=1e-8)
    for c in others:
        for b in c.bifurcations:
            if b.kind == "branch-point":
                assert b.norms["x"] <= 1e-4 and "pitchfork" in b.note


def _fold_by_augmented_system(problem, guess_omega: float, guess_state) -> tuple[float, float]:
    """The fold of the forced Duffing's true response as a zero of {phi_T(y0) - y0, det(M - I)}
    in (y0, Omega): scipy's DOP853 (rtol 1e-12) on the original equation in physical time, the
    Jacobian by differences, Newton by scipy's fsolve. Returns (Omega, |(x(0), xdot(0)/Omega)|)."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import fsolve

    v = problem.values
    eps, zeta, gamma, force = v["eps"], v["zeta"], v["gamma"], v["F"]

    def flow(y0, omega):
        def rhs(t, z):
            x, xd = z[0], z[1]
            a = -x + eps * (-2 * zeta * xd - gamma * x**3 + force * math.cos(omega * t))
            da_dx = -1 - 3 * eps * gamma * x**2
            m = z[2:].reshape(2, 2)
            jac = np.array([[0.0, 1.0], [da_dx, -2 * eps * zeta]])
            return np.concatenate(([xd, a], (jac @ m).ravel()))

        start = np.concatenate((y0, np.eye(2).ravel()))
        sol = solve_ivp(rhs, (0, 2 * math.pi / omega), start, method="DOP853", rtol=1e-12,
                        atol=1e-13)  # fmt: skip
        end = sol.y[:, -1]
        return end[:2], end[2:].reshape(2, 2)

    def equations(z):
        end, m = flow(z[:2], z[2])
        return [*(end - z[:2]), np.linalg.det(m - np.eye(2))]

    z = fsolve(equations, [*guess_state, guess_omega], xtol=1e-13)
    assert np.max(np.abs(equations(z))) <= 1e-10
    return float(z[2]), math.hypot(z[0], z[1] / z[2])


def test_the_forced_duffing_folds_against_a_minimally_augmented_system():
    """The shipped forced Duffing (the README's sweep): the true curve's folds at Omega = 1.0416 and
    1.2629 (the issue's independent shooting) against the augmented system's zeros, to 1e-8 (each
    route converges to 1e-10; the augmented system's differences cost two more digits)."""
    problem = get_problem("forced-duffing").create()
    result = problem_response(problem, "Omega", np.linspace(0.95, 1.3, 15), true=400)
    folds = [b for b in result.true_curve.bifurcations if b.kind == "fold"]
    assert [round(b.value, 4) for b in folds] == [1.0416, 1.2629]
    for fold in folds:
        curve = next(c for c in result.true_curve.curves if fold in c.bifurcations)
        near = min(
            curve.points, key=lambda p: abs(p.value - fold.value) + abs(p.norm() - fold.norms["x"])
        )
        omega, amplitude = _fold_by_augmented_system(problem, near.value, near.state)
        assert abs(omega - fold.value) <= 1e-8
        assert abs(amplitude - fold.norms["x"]) <= 1e-6


X1, X2, V1, V2, TH = sp.symbols("u w udot wdot theta")
Z, K, G, F, S = sp.symbols("zeta kappa gamma F sigma")


def test_a_two_mode_problem():
    """Two coupled Duffing oscillators, the first forced near its frequency (a problem typed here):
    the true curve is followed in a state of 4, every point a periodic orbit (a shot returns to
    it), and its multipliers' product is exp(-4 zeta eps T) (Liouville: div f = -4 zeta eps)."""
    from perturb import EPS, Excitation, QuasilinearSystem
    from problems.base import ParameterSpec, positive
    from problems.driven import DrivenProblem, non_negative, positive_frequency

    class TwoModes(DrivenProblem):
        name = "two-coupled-duffings"
        summary = "two coupled forced Duffing oscillators"
        parameter_specs = (
            ParameterSpec("eps", 0.05, "scale", positive),
            ParameterSpec("zeta", 0.1, "damping", non_negative),
            ParameterSpec("kappa", 1.0, "coupling"),
            ParameterSpec("gamma", 1.0, "stiffness"),
            ParameterSpec("F", 1.0, "forcing", positive),
            ParameterSpec("Omega", 1.0, "frequency", positive_frequency),
        )  # fmt: skip
        parameter_map = {"sigma": "(Omega - 1)/eps"}

        @classmethod
        def build_system(cls):
            return QuasilinearSystem(
                coordinates=[X1, X2], velocities=[V1, V2], frequencies=[1, sp.Rational(5, 2)],
                rhs=[EPS * (-2 * Z * V1 - K * (X1 - X2) - G * X1**3 + F * sp.cos(TH)),
                     EPS * (-2 * Z * V2 - K * (X2 - X1) - G * X2**3)],
                parameters=[Z, K, G, F, S],
                excitation=Excitation(phase=TH, ratio=1, detuning=S),
                name="two-coupled-duffings",
            )  # fmt: skip

    problem = TwoModes.create()
    result = problem_response(problem, "Omega", np.linspace(0.98, 1.1, 5), true=300)
    curves = result.true_curve
    assert curves.curves and not curves.failures
    eps, zeta = problem.values["eps"], problem.values["zeta"]
    for curve in curves.curves:
        assert curve.success, curve.message
        for p in curve.points[:: max(1, len(curve.points) // 10)]:
            assert len(p.state) == 4 and len(p.multipliers) == 4
            product = np.prod(np.asarray(p.multipliers)).real
            liouville = math.exp(-4 * zeta * eps * 2 * math.pi / p.value)
            assert abs(product / liouville - 1) <= 1e-10


def test_the_forced_van_der_pol_loses_its_entrainment_at_neimark_sacker_points():
    """A complex pair of multipliers on the unit circle at each end of the entrainment band, at
    the Omega where the oracle's forced shooting (DOP853, physical time) finds max|mu| = 1, to
    1e-8 (the secant locates the test function to 1e-13 of a step, Brent to 1e-12; the DOP853
    multipliers are good to ~1e-10, over a slope of max|mu| in Omega of order 1); the amplitude
    there is the first-order slow flow's Hopf amplitude sqrt 2 to O(eps)."""
    from tests.driven.published import ForcedVanDerPol, neimark_sacker_by_forced_shooting

    problem = ForcedVanDerPol.create()
    result = problem_response(problem, "Omega", np.linspace(0.9, 1.1, 9), true=400)
    found = [b for b in result.true_curve.bifurcations if b.kind == "neimark-sacker"]
    assert len(found) == 2, result.true_curve
    for b in found:
        assert abs(abs(b.multiplier) - 1) <= 1e-9 and abs(b.multiplier.imag) > 0.1
        assert abs(b.norms["x"] - math.sqrt(2)) <= problem.values["eps"]
        curve = next(c for c in result.true_curve.curves if b in c.bifurcations)
        near = min(curve.points, key=lambda p: abs(p.value - b.value))
        omega = neimark_sacker_by_forced_shooting(
            problem, b.value - 0.005, b.value + 0.005, near.state
        )
        assert abs(omega - b.value) <= 1e-8
