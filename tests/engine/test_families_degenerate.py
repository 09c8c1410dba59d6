"""Degenerate families resolved (issue 21.3): Hénon–Heiles's 8 families near the origin.

At order 2 the lines through the origin form a continuum in every direction; the conditions of
order 4 hold only for six of them. The engine restricts the continuum by those conditions and
reports what survives, each named; a direction no periodic orbit has (45°) is never reported.
Checked by routes that do not use the construction: the compatibility polynomial by exact
elimination done here, the orbits' existence, straightness and stability by shooting the
original equations (Newton on the variational equations, Floquet multipliers).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb import Status
from perturb.method.conditions import compatibility_conditions
from perturb.oracle import SymbolicRHS, find_periodic_orbit, heyoka_available
from tests.engine.henon_heiles import XDOT, YDOT, X, Y, henon_heiles_families

#: The 8 families: name -> direction of the generating line (degrees), None for the loops.
EXPECTED = {
    "y-line": 90, "line-30": 30, "line-150": 150,
    "bowed-0": 0, "bowed-60": 60, "bowed-120": 120,
    "circle-ccw": None, "circle-cw": None,
}  # fmt: skip
STRAIGHT = {"y-line", "line-30", "line-150"}
#: Shooting at eps = 0.1 and generating amplitude (norm) 1: small enough for the series, large
#: enough that the multipliers' distance from 1 (~1e-2) stands far above the shooting's 1e-8.
EPS_SHOOT, AMPLITUDE = 0.1, 1.0
#: |multiplier| - 1 below which a pair counts as on the unit circle (shooting accuracy ~1e-8).
UNIT_CIRCLE = 1e-6


@pytest.fixture(scope="module", params=[1, 2])
def families(request):
    return henon_heiles_families(request.param)


def test_all_eight_families_are_found_named_and_fixed(families):
    assert set(families.names) == set(EXPECTED)
    for family in families:
        assert family.status is Status.SUCCESS, (family.name, family.message)
        assert len(family.free) == 1  # one amplitude: the energy along the family


def _direction(family) -> float:
    amp = {k: sp.sympify(v) for k, v in family.amplitudes.items()}
    a_x = amp.get("a_x", 0).subs(sp.Symbol("a_x"), 1)
    a_y = amp.get("a_y", 0).subs({sp.Symbol("a_x"): 1, sp.Symbol("a_y"): 1})
    return math.degrees(math.atan2(float(a_y), float(a_x))) % 180


def test_the_lines_point_where_the_order_4_conditions_allow(families):
    for family in families:
        if EXPECTED[family.name] is not None:
            assert _direction(family) == pytest.approx(EXPECTED[family.name], abs=1e-9)


def test_compatibility_conditions_of_a_dependent_linear_system():
    """Three equations in two unknowns, the third the sum of the others: solvable iff
    r = p + q (the left null vector (1, 1, -1) of the matrix), whatever the parameters."""
    p, q, r, c = sp.symbols("p q r c")
    matrix = sp.Matrix([[1, 0], [0, c], [1, c]])
    (condition,) = compatibility_conditions(matrix, sp.Matrix([p, q, r]))
    assert sp.expand(condition - (p + q - r)) == 0 or sp.expand(condition + (p + q - r)) == 0
    assert compatibility_conditions(sp.eye(2), sp.Matrix([p, q])) == ()


def test_the_six_directions_are_the_zeros_of_sin_6_theta():
    """The order-4 condition the engine restricts the line by, a_y (a_x^2 - 3 a_y^2)(3 a_x^2 -
    a_y^2), is sin(6 theta) / (2 cos theta) on the unit circle: zero at multiples of 30 degrees."""
    a_x, a_y = sp.symbols("a_x a_y")
    poly = a_y * (a_x**2 - 3 * a_y**2) * (3 * a_x**2 - a_y**2)
    for theta in np.linspace(0.05, 3.0, 7):
        value = float(poly.subs({a_x: math.cos(theta), a_y: math.sin(theta)}))
        assert value == pytest.approx(math.sin(6 * theta) / (2 * math.cos(theta)), rel=1e-12)


def test_no_family_at_45_degrees(families):
    assert all(_direction(f) != pytest.approx(45.0) for f in families if EXPECTED[f.name])


def _rhs(eps):
    e = sp.Rational(eps).limit_denominator(1000)
    return SymbolicRHS((X, Y, XDOT, YDOT), (XDOT, YDOT, -X - 2 * e * X * Y, -Y - e * (X**2 - Y**2)))


def _energy(eps):
    e = sp.Rational(eps).limit_denominator(1000)
    return (XDOT**2 + YDOT**2 + X**2 + Y**2) / 2 + e * (X**2 * Y - Y**3 / 3)


def _shoot(family, eps=EPS_SHOOT):
    """The true orbit from the family's analytic start, its energy pinned (a Hamiltonian family)."""
    solution = family.solution
    name = family.free[0]
    norm = math.hypot(*(
        float(sp.sympify(family.amplitudes.get(k, 0)).subs(sp.Symbol(name), 1))
        for k in ("a_x", "a_y", "b_x", "b_y")
    ))  # fmt: skip
    values = {name: AMPLITUDE / norm}
    start = np.asarray(solution.initial_state(eps, values), dtype=float)
    period = float(solution.period_at(eps, values))
    section = 2 if family.phase_coordinate == "x" else 3
    orbit = find_periodic_orbit(
        _rhs(eps), start, period, section_index=section, integrals=[_energy(eps)],
        hamiltonian=True,
    )  # fmt: skip
    return start, period, orbit


@pytest.fixture(scope="module")
def order2():
    return henon_heiles_families(2)


@pytest.mark.skipif(not heyoka_available(), reason="shooting 8 orbits takes minutes without heyoka")
def test_each_family_is_a_true_orbit_and_its_stability_is_measured(order2):
    """Every family starts within O(eps^3 A^3) of a true periodic orbit with the series' period,
    and the Floquet multipliers say: the straight lines and the loops are elliptic (a pair on the
    unit circle), the bowed orbits hyperbolic (a real pair lambda, 1/lambda)."""
    for family in order2:
        start, period, orbit = _shoot(family)
        assert orbit.success, (family.name, orbit.message)
        moved = float(np.max(np.abs(orbit.initial_state - start)))
        assert moved < 10 * (EPS_SHOOT * AMPLITUDE) ** 3, (family.name, moved)
        assert abs(orbit.period - period) / period < 10 * (EPS_SHOOT * AMPLITUDE) ** 4
        pair = sorted(orbit.floquet_multipliers, key=lambda z: abs(z - 1))[2:]
        elliptic = all(abs(abs(z) - 1) < UNIT_CIRCLE and abs(z.imag) > 0 for z in pair)
        hyperbolic = all(abs(z.imag) < UNIT_CIRCLE and abs(abs(z) - 1) > UNIT_CIRCLE for z in pair)
        if family.name.startswith("bowed"):
            assert hyperbolic, (family.name, pair)
        else:
            assert elliptic, (family.name, pair)


@pytest.mark.skipif(not heyoka_available(), reason="shooting takes minutes without heyoka")
def test_straight_lines_stay_straight_and_bowed_ones_do_not(order2):
    """Along the true orbit from each line's analytic start, the distance from the generating
    line: round-off for a straight one, O(eps A^2) for a bowed one."""
    for family in order2:
        if EXPECTED[family.name] is None:
            continue
        _, _, orbit = _shoot(family)
        theta = math.radians(EXPECTED[family.name])
        from perturb.oracle import choose

        t = np.linspace(0.0, orbit.period, 64)
        traj = choose(None, rtol=1e-13, symbolic=True).integrate(
            _rhs(EPS_SHOOT), (0.0, orbit.period), orbit.initial_state, t_eval=t
        )
        off_line = np.max(np.abs(-math.sin(theta) * traj.y[0] + math.cos(theta) * traj.y[1]))
        if family.name in STRAIGHT:
            assert off_line < 1e-10, (family.name, off_line)
        else:
            assert off_line > 0.1 * EPS_SHOOT * AMPLITUDE**2, (family.name, off_line)


@pytest.mark.skipif(not heyoka_available(), reason="shooting takes minutes without heyoka")
def test_at_45_degrees_no_periodic_orbit_is_near():
    """The order-2 line at 45° (what order 1 used to report SUCCESS for): a shooting from its
    start, energy pinned, fails or moves far (the true families are 15° away)."""
    eps = EPS_SHOOT
    a = AMPLITUDE / math.sqrt(2)
    omega = 1 - 5 * (eps * AMPLITUDE) ** 2 / 12
    start = np.array([a, a, 0.0, 0.0])
    orbit = find_periodic_orbit(
        _rhs(eps), start, 2 * math.pi / omega, section_index=2, integrals=[_energy(eps)],
        hamiltonian=True, max_iter=15,
    )  # fmt: skip
    if orbit.success:
        moved = float(np.max(np.abs(orbit.initial_state - start)))
        assert moved > 0.05 * AMPLITUDE, moved
