"""The driven engine against routes that do not use it (issue 18).

Forced Duffing: the first-order response equation by averaging done here with sympy integrals;
its backbone against the free engine; the parametric tongue against the Floquet multipliers of
the linear Mathieu equation integrated by scipy; the autoparametric absorber's saturation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from perturb import EPS, PoincareMethod, QuasilinearSystem, amplitude_equations
from perturb.response import branches_at, real_roots, steady_state_of
from problems import get_problem

s_, a_, b_ = sp.symbols("s a b", real=True)


def _averaged(force, sigma, m=1):
    """First-harmonic averages of eps*f over one period for x = a cos s + b sin s, with the
    strained-time term 2 sigma x'' moved to the right: the slow-flow right-hand sides."""
    x = a_ * sp.cos(m * s_) + b_ * sp.sin(m * s_)
    v = sp.diff(x, s_)
    f = force(x, v) + 2 * sigma * x * m**2  # nu^2 x'' = (1 + 2 eps sigma) x'' -> eps(...)
    fc = sp.integrate(sp.expand(f * sp.cos(m * s_)), (s_, 0, 2 * sp.pi)) / sp.pi
    fs = sp.integrate(sp.expand(f * sp.sin(m * s_)), (s_, 0, 2 * sp.pi)) / sp.pi
    return sp.expand(fc), sp.expand(fs)


def test_forced_duffing_first_order_response_by_averaging():
    duffing = get_problem("forced-duffing")
    eqs = amplitude_equations(duffing.system(), 0)
    zeta, gamma, force, sigma = sp.symbols("zeta gamma F sigma")
    fc, fs = _averaged(lambda x, v: -2 * zeta * v - gamma * x**3 + force * sp.cos(s_), sigma)
    a_x, b_x = eqs.amplitudes
    rows = [r.subs({a_x: a_, b_x: b_}) for r in eqs.displacement(0)]
    # the engine's rows are (g(2pi), dg(2pi)) = pi (-fs, fc) (the quadrature of zero initial data)
    assert sp.simplify(rows[0] + sp.pi * fs) == 0
    assert sp.simplify(rows[1] - sp.pi * fc) == 0
    # and its roots satisfy the textbook [(sigma - 3 gamma r^2/8)^2 + zeta^2] r^2 = (F/2)^2
    values = {zeta: sp.Rational(1, 10), gamma: 1, force: 1, sigma: sp.Rational(3, 2)}
    found = real_roots([r.xreplace(values) for r in eqs.displacement(0)], [a_x, b_x])
    assert len(found.roots) == 3
    for root in found.roots:
        r2 = float(root[a_x]) ** 2 + float(root[b_x]) ** 2
        assert ((1.5 - 3 * r2 / 8) ** 2 + 0.01) * r2 == pytest.approx(0.25, rel=1e-10)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_without_forcing_and_damping_the_response_is_the_free_engines_backbone(order):
    """F = zeta = 0: the nontrivial responses sit on the free Duffing frequency Omega(A) to the
    order computed: sigma(A) from the response equations against (Omega_free(A) - 1)/eps."""
    duffing = get_problem("forced-duffing")
    eqs = amplitude_equations(duffing.system(), order)
    x, v = sp.symbols("x xdot")
    amplitude = sp.Symbol("A", positive=True)
    free = QuasilinearSystem([x], [v], [1], [-EPS * x**3], parameters=[amplitude])
    omega = PoincareMethod(order=order + 1, amplitudes={"x": amplitude}).solve(free)
    eps, a = 0.01, 0.8
    omega_free = float(omega.frequency_expr.subs({EPS: eps, amplitude: a}))
    zeta, gamma, force, sigma = sp.symbols("zeta gamma F sigma")
    a_x, b_x = eqs.amplitudes
    rows = [
        r.subs(
            {zeta: 0, force: 0, gamma: 1, EPS: sp.Rational(1, 100), a_x: sp.Rational(4, 5), b_x: 0}
        )
        for r in eqs.displacement(order)
    ]
    # the truncated series is polynomial in sigma: its root on the branch is the one near the
    # first-order 3 A^2/8 (the others are far, O(1/eps), artefacts of the truncation)
    roots = [complex(r) for r in sp.Poly(rows[1], sigma).nroots()]
    real = [r.real for r in roots if abs(r.imag) < 1e-9]
    sigma_value = min(real, key=lambda r: abs(r - 3 * a**2 / 8))
    assert sp.simplify(rows[0]) == 0  # b = 0 is a solution of the first condition
    assert sigma_value == pytest.approx((omega_free - 1) / eps, abs=10 * eps ** (order + 1))


def _mathieu_multiplier(eps, h, zeta, omega):
    """Largest |Floquet multiplier| of x'' + 2 eps zeta x' + (1 + 2 eps h cos(Omega t)) x = 0."""
    period = 2 * math.pi / omega * 2  # the response has two forcing periods

    def rhs(t, y):
        x, v = y[:2], y[2:]
        return np.concatenate(
            (v, -2 * eps * zeta * v - (1 + 2 * eps * h * math.cos(omega * t)) * x)
        )

    sol = solve_ivp(rhs, (0, period), [1, 0, 0, 1], rtol=1e-11, atol=1e-12, method="DOP853")
    monodromy = sol.y[:, -1].reshape(2, 2).T
    return max(abs(np.linalg.eigvals(monodromy)))


@pytest.mark.parametrize("sigma", [-3.0, -1.0, 0.0, 1.0, 3.0])
def test_parametric_tongue_the_trivial_response_is_unstable_exactly_where_floquet_says(sigma):
    problem = get_problem("parametric-duffing").create(
        eps=0.02, zeta=0.2, h=1.0, gamma=1.0, Omega=2.0 + 0.02 * sigma
    )
    points = steady_state_of(problem, 1).points
    trivial = [p for p in points if p.trivial]
    assert len(trivial) == 1
    largest = _mathieu_multiplier(0.02, 1.0, 0.2, 2.0 + 0.02 * sigma)
    assert trivial[0].stable == (largest < 1)
    # the slow flow's multiplier is Floquet's to O(eps^2)
    predicted = max(abs(z) for z in trivial[0].multipliers)
    assert predicted == pytest.approx(largest, abs=0.02**2 * 10)


def test_autoparametric_absorber_saturates():
    """Above the threshold the forced mode's amplitude on the coupled branch does not depend on F:
    the x-equation alone fixes it (its conditions are linear in x with y's amplitude inside)."""
    cls = get_problem("autoparametric-absorber")
    saturated = []
    for force in (1.0, 2.0, 4.0):
        points = steady_state_of(cls.create(F=force, Omega=2.0), 0).points
        coupled = [p for p in points if p.norms["x"] > 1e-9]
        assert coupled, force
        saturated.append(coupled[0].norms["y"])
    assert saturated[1] == pytest.approx(saturated[0], rel=1e-10)
    assert saturated[2] == pytest.approx(saturated[0], rel=1e-10)
    single = [p for p in steady_state_of(cls.create(F=4.0), 0).points if p.norms["x"] <= 1e-9]
    assert single[0].norms["y"] > 3 * saturated[0]  # without the absorber y would grow with F


def test_branches_at_counts_every_root_and_names_them():
    problem = get_problem("forced-duffing").create(Omega=1.075)
    points, why = branches_at(
        amplitude_equations(problem.system(), 1), problem.symbol_values(), problem.epsilon(), 1
    )
    assert why == "" and len(points) == 3
    assert [p.stable for p in points] == [True, False, True]
    assert [f.name for f in problem.families(1)] == ["lower", "middle", "upper"]
