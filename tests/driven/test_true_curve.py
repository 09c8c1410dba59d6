"""The true curve past the series (issue 29, item 4): the fixed-period shooting map, its Floquet
test functions, and the continued curves of ``perturb response --true``.

Fast representatives here; the published values and the long curves are in
``test_true_curve_published.py`` (slow).
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
import pytest
import sympy as sp

from perturb.oracle import heyoka_available
from perturb.oracle.bifurcation import (
    fold_test,
    is_neimark_sacker,
    neimark_sacker_test,
    period_doubling_test,
)
from perturb.oracle.driven_family import DrivenFamily
from perturb.response.model import problem_response
from problems import get_problem

pytestmark = pytest.mark.skipif(
    not heyoka_available(), reason="the true curves take minutes without heyoka"
)

X1, X2, V1, V2, TH = sp.symbols("x1 x2 v1 v2 theta")
ZETA, K, GAMMA, F, W = sp.symbols("zeta k gamma F Omega")


def two_mode_family() -> DrivenFamily:
    """Two coupled forced Duffing oscillators (a state of 4): the map is generic in its size."""
    f1 = -2 * ZETA * V1 - X1 - K * (X1 - X2) - GAMMA * X1**3 + F * sp.cos(TH)
    f2 = -2 * ZETA * V2 - 2 * X2 - K * (X2 - X1) - GAMMA * X2**3
    return DrivenFamily.build((X1, X2, V1, V2), TH, (V1, V2, f1, f2), W, (ZETA, K, GAMMA, F, W))


def test_the_jacobian_of_the_shooting_map_is_its_derivative():
    """[M - I | s] against centred differences of the defect, in the state and along a direction
    of the parameters (two of them moving at once). The differences' error is h^2 |R'''|/6 plus the
    integration noise over h: with h = 1e-5, R''' of order 10 and noise 1e-14, below 1e-8 of the
    Jacobian's size; 1e-7 leaves a factor 10."""
    family = two_mode_family()
    values = np.array([0.05, 0.3, 0.5, 0.4, 1.1])
    direction = np.array([0.0, 0.0, 0.0, 1.0, -0.5])  # F up, Omega down
    y0 = np.array([0.3, -0.1, 0.2, 0.4])
    shot = family.shoot(y0, values, direction)
    jac = shot.jacobian
    assert jac.shape == (4, 5)
    h = 1e-5
    fd = np.empty_like(jac)
    for j in range(4):
        e = np.zeros(4)
        e[j] = h
        up, down = family.shoot(y0 + e, values, direction), family.shoot(y0 - e, values, direction)
        fd[:, j] = (up.defect - down.defect) / (2 * h)
    up = family.shoot(y0, values + h * direction, direction)
    down = family.shoot(y0, values - h * direction, direction)
    fd[:, 4] = (up.defect - down.defect) / (2 * h)
    assert np.max(np.abs(fd - jac)) <= 1e-7 * np.max(np.abs(jac))


def test_the_monodromy_satisfies_liouville_and_agrees_with_forced_shooting():
    """Two routes to the same orbit: the family's shot in the phase as time, and the oracle's
    forced shooting in physical time (its own Newton and variational equations). The monodromy's
    determinant is exp(-2 zeta eps T) exactly (Liouville; div f = -2 zeta eps); both hold to the
    integrations' accuracy (machine precision: 1e-12 allows for the growth over a period)."""
    from perturb.oracle import SymbolicRHS, find_forced_orbit

    x, v, th = sp.symbols("x v theta")
    zeta, eps, gamma, force, omega = 0.1, 0.05, 1.0, 1.0, 1.1
    f = eps * (-2 * zeta * v - gamma * x**3 + force * sp.cos(th)) - x
    orbit = find_forced_orbit(
        SymbolicRHS((x, v, th), (v, f, omega)), [2.0, 1.5], 2 * math.pi / omega
    )
    assert orbit.success, orbit.message
    p = sp.symbols("omega_")
    family = DrivenFamily.build((x, v), th, (v, f), p, (p,))
    shot = family.shoot(orbit.initial_state, [omega], [1.0])
    assert np.max(np.abs(shot.defect)) <= 1e-11
    assert np.max(np.abs(shot.monodromy - orbit.monodromy)) <= 1e-11
    liouville = math.exp(-2 * zeta * eps * 2 * math.pi / omega)
    assert abs(np.linalg.det(shot.monodromy) / liouville - 1) <= 1e-12


def _second_compound(m: np.ndarray) -> np.ndarray:
    """The matrix of 2x2 minors (the map's bialternate product M (.) M): eigenvalues mu_i mu_j."""
    pairs = list(combinations(range(m.shape[0]), 2))
    return np.array([[m[p, r] * m[q, s] - m[p, s] * m[q, r] for r, s in pairs] for p, q in pairs])


@pytest.mark.parametrize("size", [2, 3, 4, 6])
def test_the_test_functions_are_determinants(size):
    """det(M - I), det(M + I) and the Neimark-Sacker product over pairs against determinants
    built another way (the second compound matrix of 2x2 minors), on random matrices."""
    rng = np.random.default_rng(size)
    for _ in range(5):
        m = rng.normal(size=(size, size))
        n = _second_compound(m).shape[0]
        ns = np.linalg.det(_second_compound(m) - np.eye(n))
        assert neimark_sacker_test(m) == pytest.approx(ns, rel=1e-9, abs=1e-12)
        assert fold_test(m) == pytest.approx(np.prod(np.linalg.eigvals(m) - 1).real, rel=1e-9)
        assert period_doubling_test(m) == pytest.approx(
            np.prod(np.linalg.eigvals(m) + 1).real, rel=1e-9
        )


def test_a_neutral_saddle_is_not_neimark_sacker():
    c, s = math.cos(0.4), math.sin(0.4)
    on_circle = np.array([[c, -s, 0], [s, c, 0], [0, 0, 0.5]])
    saddle = np.diag([2.0, 0.5, 0.3])
    assert abs(neimark_sacker_test(on_circle)) < 1e-14
    assert abs(neimark_sacker_test(saddle)) < 1e-14
    assert is_neimark_sacker(on_circle, 1e-9)[0] is True
    assert is_neimark_sacker(saddle, 1e-9)[0] is False


def _mathieu_edges(h_eps: float) -> list[float]:
    """The Omega of the first tongue's edges of x'' + (1 + 2 h eps cos Omega t) x = 0.

    With tau = Omega t/2 it is Mathieu's x'' + (a - 2q cos 2 tau) x = 0, a = 4/Omega^2,
    |q| = 4 h eps/Omega^2; the edges are a = a_1(|q|) and a = b_1(|q|) (scipy's characteristic
    values; q's sign swaps the two).
    """
    from scipy.optimize import brentq
    from scipy.special import mathieu_a, mathieu_b

    out = []
    for f in (mathieu_a, mathieu_b):
        out.append(brentq(lambda w, f=f: 4 / w**2 - f(1, 4 * h_eps / w**2), 1.5, 2.5, xtol=1e-15))
    return sorted(out)


def _hill_edges(h_eps: float) -> list[float]:
    """The same edges from the Hill determinant (a second route): the 2 pi-periodic solutions
    sum A_k cos((2k+1) tau) or sin, (a - (2k+1)^2) A_k = q (A_{k-1} + A_{k+1}) with the reflected
    first term; 40 harmonics converge to machine precision at |q| < 1."""
    from scipy.optimize import brentq

    def lowest(q, sign):
        n = 40
        m = np.diag([(2.0 * k + 1) ** 2 for k in range(n)])
        m += np.diag([q] * (n - 1), 1) + np.diag([q] * (n - 1), -1)
        m[0, 0] += sign * q
        return np.linalg.eigvalsh(m)[0]

    return sorted(
        brentq(lambda w, s=s: 4 / w**2 - lowest(4 * h_eps / w**2, s), 1.5, 2.5, xtol=1e-15)
        for s in (1, -1)
    )


def test_the_mathieu_tongue_edges_are_branch_points_of_the_trivial_response():
    """Continue x = 0 of the undamped linear parametric oscillator over Omega: the branch points
    (a multiplier at +1 over the response's two forcing periods) are the first instability
    tongue's edges, Mathieu's characteristic values a_1 and b_1, to 1e-9 (the test function is
    located to 1e-13 of a step; the monodromy is exact to ~1e-14)."""
    problem = get_problem("parametric-duffing").create(zeta=0.0, gamma=0.0)
    result = problem_response(problem, "Omega", np.linspace(1.9, 2.1, 5), true=100)
    curves = result.true_curve
    assert curves is not None and not curves.failures
    (curve,) = curves.curves
    assert curve.success and curve.branches == ("trivial",)
    points = [b for b in curves.bifurcations if b.kind == "branch-point"]
    h_eps = problem.values["h"] * problem.values["eps"]
    expected, hill = _mathieu_edges(h_eps), _hill_edges(h_eps)
    assert np.max(np.abs(np.array(expected) - hill)) <= 1e-12  # the two references agree
    assert [b.value for b in points] == pytest.approx(expected, abs=1e-9)
    for b in points:
        assert b.inside and b.norms["x"] == 0.0
        assert abs(b.multiplier - 1) <= 1e-6  # a double multiplier: its error is a square root
    low, high = expected
    for p in curve.points:  # undamped: unstable inside the tongue, on the circle outside it
        if low + 1e-6 < p.value < high - 1e-6:
            assert p.stable is False
        elif not low - 1e-6 <= p.value <= high + 1e-6:
            assert p.stable is None


def test_a_problem_with_its_own_original_equations_is_not_continued():
    """The true curve follows the quasilinear system's orbits: a problem whose original equations
    are its own (here the same ones, given as original_symbolic) is refused with the reason, and
    the analytic response stands."""
    from problems.parametric_duffing import ParametricDuffing

    class OwnEquations(ParametricDuffing):
        def original_symbolic(self):
            x, v, th = sp.symbols("x xdot theta")
            return (x, v, th), (v, -x, 2.0)

    problem = OwnEquations.create(zeta=0.0, gamma=0.0)
    result = problem_response(problem, "Omega", np.linspace(1.9, 2.1, 3), true=50)
    assert result.response.points and result.true_curve.curves == ()
    (failure,) = result.true_curve.failures
    assert "gives its own original equations" in failure


def test_the_three_measures_agree_on_a_linear_response():
    """A damped linear oscillator's response is one sinusoid: its peak, its first harmonic and its
    initial-value norm are one number, the exact amplitude F eps/|1 - Omega^2 + 2 i zeta eps
    Omega|, at every point of the true curve. The harmonic (trapezoid rule on a periodic orbit)
    and the initial values are exact to the shot's ~1e-13; the peak from 128 samples and a parabola
    to (pi/128)^4/... ~ 1e-7 (TRUE_CURVE_SAMPLES)."""
    problem = get_problem("forced-duffing").create(gamma=0.0)
    result = problem_response(problem, "Omega", np.linspace(0.9, 1.1, 3), true=400)
    (curve,) = result.true_curve.curves
    eps, zeta, force = (problem.values[k] for k in ("eps", "zeta", "F"))
    for p in curve.points:
        exact = eps * force / abs(1 - p.value**2 + 2j * zeta * eps * p.value)
        assert p.amplitude("x", "first-harmonic") == pytest.approx(exact, rel=1e-11)
        assert p.amplitude("x", "initial") == pytest.approx(exact, rel=1e-11)
        assert p.amplitude("x", "peak") == pytest.approx(exact, rel=1e-6)
    assert curve.success
    # order 1 (the default) is within 1 % of the linear response here: they never part
    assert result.true_curve.partings == ()
