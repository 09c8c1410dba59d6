"""Homogeneous systems typed without a fixed amplitude (issue 30, deliverable 2): every family a
continuum in its amplitude, the same families as with the amplitude fixed, exact modes found and
named, travelling waves named, against the true motion."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from perturb import EPS, QuasilinearSystem, find_families
from perturb.algebra import msolve_binary
from perturb.algebra.msolve import install_advice
from perturb.method.components import components_or_failed
from perturb.method.conditions import OrderFailed
from perturb.method.projective import exact_on, quasi_weights, scaling_degree
from perturb.steps import GeneratingSolution
from problems.resonant_chain import chain_of, chain_system

A = sp.Symbol("a_x1")
#: C of a family's distance to the true motion over a period, C eps^(N+1) A^(1+(N+1)(d-1)) (the
#: continuum scales as A with eps A^(d-1), d = 3): the free chain's shape-p0n measures 0.08 at
#: N = 2; a lost order would measure eps^N A^(...), about 80 on this scale.
TRUE_MOTION_CONSTANT = 1.0


def _springs(n: int, ring: bool) -> QuasilinearSystem:
    """n unit oscillators joined by cubic springs only: a free-ended chain or a ring."""
    x = sp.symbols(f"x1:{n + 1}")
    v = sp.symbols(f"v1:{n + 1}")
    pairs = [(i, i + 1) for i in range(n - 1)] + ([(n - 1, 0)] if ring else [])
    potential = sum((x[i] - x[j]) ** 4 / 4 for i, j in pairs)
    rhs = [-EPS * sp.diff(potential, xi) for xi in x]
    return QuasilinearSystem(list(x), list(v), [1] * n, rhs, name="springs")


def test_weights_and_degree_of_a_chain_of_cubic_springs():
    system = chain_system(3)
    assert scaling_degree(system) == 3
    w, a, b = sp.symbols("Omega1 a b")
    assert quasi_weights([w * a - a**3, w * b - a * b**2], [w, a, b], [a, b])[w] == 2
    linear = QuasilinearSystem([sp.Symbol("x")], [sp.Symbol("v")], [1], [-EPS * sp.Symbol("x")])
    assert scaling_degree(linear) is None  # a linear term at order eps moves the frequency


@pytest.mark.parametrize("order", [1, 2])
def test_a_chain_typed_without_an_amplitude_has_the_families_of_one_typed_with_it(order):
    """The shipped chain of 3 (x1(0) = amplitude fixed) against its system with nothing fixed:
    the same five families, each now a continuum in a_x1, equal at a_x1 = 1 in every amplitude
    and in the frequency series."""
    free = find_families(chain_system(3), order)
    fixed = chain_of(3).create(amplitude=1.0).families(order)
    assert free.names == fixed.names and len(free) == 5
    for name in fixed.names:
        scaled, given = free.get(name), fixed.get(name)
        assert scaled.kind == "continuum" and scaled.free == ("a_x1",)
        assert scaled.status.ok and given.status.ok
        for key, value in given.amplitudes.items():
            assert sp.simplify(sp.sympify(scaled.amplitudes[key]).subs(A, 1) - value) == 0
        series = scaled.solution.frequency_series()
        assert sp.expand(series.subs(A, 1) - given.solution.frequency_series()) == 0
        # the continuum scales: a_x1 = 2 is the member at amplitude 1 with eps -> 4 eps
        assert sp.expand(series.subs(A, 2) - series.subs(A, 1).subs(EPS, 4 * EPS)) == 0


def _trajectory_error(system, solution, amplitude: float, eps: float) -> float:
    """Largest distance over one period between the solution at a_x1 = amplitude and the true
    motion from its initial state (DOP853 at rtol 1e-12)."""
    values = {A.name: amplitude}
    period = float(solution.period_at(eps, values))
    t = np.linspace(0.0, period, 41)
    state = solution.evaluate(t, eps, values)
    rhs = sp.lambdify([system.state_symbols], [f.subs(EPS, eps) for f in system.rhs], "numpy")
    n = system.n

    def field(_, y):
        return np.concatenate((y[n:], np.asarray(rhs(y), dtype=float) - y[:n]))

    true = solve_ivp(field, (0.0, period), state[:, 0], t_eval=t, rtol=1e-12, atol=1e-14,
                     method="DOP853")  # fmt: skip
    return float(np.max(np.abs(true.y - state)))


@pytest.mark.slow
def test_the_free_chain_of_three_has_its_exact_linear_mode():
    """The issue's example: cubic springs, free ends, nothing fixed. Three synchronous families,
    among them the in-phase mode on which no spring stretches: exact at every order, Omega = 1 at
    every amplitude, and the true motion from its state is it (to the integrator's accuracy);
    the others against the true motion to O(eps^2)."""
    system = _springs(3, ring=False)
    families = find_families(system, 2)
    assert sorted(families.names) == ["anti-phase", "in-phase-exact", "shape-p0n"]
    exact = families.get("in-phase-exact")
    assert exact.status.ok and exact.solution.frequency_series() == 1
    assert exact_on(system, GeneratingSolution(("x1", "x2", "x3"), (1, 1, 1), (1, 1, 1),
                                               (0, 0, 0), "x1", 1))  # fmt: skip
    eps = 0.02
    assert _trajectory_error(system, exact.solution, 0.8, eps) < 1e-9
    line = families.get("shape-p0n")
    assert line.status.ok
    error = _trajectory_error(system, line.solution, 0.8, eps)
    assert error < TRUE_MOTION_CONSTANT * eps**3 * 0.8**7


@pytest.mark.slow
def test_the_ring_of_three_travels_both_ways():
    """On a ring the travelling waves x_j = A cos(s -+ j 2 pi/3) are families, named by where
    they go; the in-phase mode is exact; the plane of zero mean is a continuum of two
    amplitudes. By hand: each spring's difference has modulus A sqrt(3), so each mass feels
    -(3/4)(3 A^2)(2 z_j - z_(j-1) - z_(j+1)) = -(27 A^2/4) z_j: Omega = 1 + 27 A^2 eps/8."""
    system = _springs(3, ring=True)
    families = find_families(system, 1)
    names = set(families.names)
    assert {"travelling-left", "travelling-right", "in-phase-exact"} <= names
    right = families.get("travelling-right")
    assert right.free == ("a_x1",)
    series = sp.expand(right.solution.frequency_series())
    assert series.coeff(EPS, 0) == 1 and sp.expand(series.coeff(EPS, 1) - 27 * A**2 / 8) == 0
    error = _trajectory_error(system, right.solution, 0.5, 0.02)
    assert error < TRUE_MOTION_CONSTANT * 0.02**2 * 0.5**5
    planes = [f for f in families if len(f.free) == 2]
    assert planes and planes[0].status.ok


def test_an_install_is_advised_only_when_msolve_is_missing():
    x, y, z = sp.symbols("x y z")
    hard = [x**7 - 3 * y**5 + z - 1, y**7 + x * z**3 - 2, z**7 - x * y - 5]
    with pytest.raises(OrderFailed) as failed:
        components_or_failed(1, hard, [x, y, z], [x], 1e-3)
    assert ("install" in failed.value.message) is (msolve_binary() is None)
    assert (install_advice() == "") is (msolve_binary() is not None)
