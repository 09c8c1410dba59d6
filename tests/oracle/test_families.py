"""Families of periodic orbits (issue 9): pinning the member by a first integral, and the count of
trivial Floquet multipliers derived from the integrals (autonomy + 1 per integral; 2 per integral
in involution for a Hamiltonian system)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.special import ellipk

from perturb._defaults import SHOOTING_TOL
from perturb.errors import InvalidParameterError
from perturb.oracle import (
    OrbitStatus,
    SymbolicRHS,
    expected_trivial_multipliers,
    find_periodic_orbit,
)

#: Agreement of a converged orbit with a closed form: the shooting tolerance (1e-12 relative
#: residual) divided by the conditioning of the period along the family (O(1) here), times 10.
ORBIT_AGREEMENT = 1e-11


@pytest.mark.parametrize(
    ("n_integrals", "hamiltonian", "expected"),
    [(0, False, 1), (1, False, 2), (2, False, 3), (0, True, 2), (1, True, 2), (2, True, 4)],
)
def test_expected_trivial_multipliers(n_integrals, hamiltonian, expected):
    assert expected_trivial_multipliers(n_integrals, hamiltonian) == expected


@pytest.mark.parametrize("bad", [-1, 1.5, True, "2"])
def test_expected_trivial_multipliers_refuses_bad_counts(bad):
    with pytest.raises(InvalidParameterError, match="`n_integrals`"):
        expected_trivial_multipliers(bad)


# --------------------------------------------------------------------------------------------------
# pendulum x'' + sin x = 0, i.e. the quasilinear x'' + x = x - sin x: a family by energy
# --------------------------------------------------------------------------------------------------

x, v = sp.symbols("x v")
PENDULUM = SymbolicRHS((x, v), (v, -x + (x - sp.sin(x))))
PENDULUM_ENERGY = v**2 / 2 - sp.cos(x)
AMPLITUDE = 1.2


def pendulum_period(amplitude: float) -> float:
    """T = 4 K(m), m = sin(amplitude / 2)**2 (complete elliptic integral, parameter convention)."""
    return 4 * ellipk(math.sin(amplitude / 2) ** 2)


def test_shooting_without_a_pin_drifts_along_the_family():
    """The defect of issue 9: nothing fixes the member, Newton slides off the seed's amplitude."""
    orbit = find_periodic_orbit(PENDULUM, [AMPLITUDE, 0.0], 6.0, section_index=1)
    drifted = abs(orbit.initial_state[0] - AMPLITUDE) > 0.1
    assert drifted or orbit.status is OrbitStatus.EQUILIBRIUM


@pytest.mark.parametrize(
    "energy",
    [PENDULUM_ENERGY, lambda y: y[1] ** 2 / 2 - np.cos(y[0])],
    ids=["sympy", "callable"],
)
@pytest.mark.parametrize("period_guess", [6.0, 7.5])
def test_an_energy_integral_pins_the_family_member(energy, period_guess):
    orbit = find_periodic_orbit(
        PENDULUM,
        [AMPLITUDE, 0.0],
        period_guess,
        section_index=1,
        integrals=[energy],
        hamiltonian=True,
    )
    assert orbit.success, orbit.message
    assert orbit.initial_state[0] == pytest.approx(AMPLITUDE, abs=ORBIT_AGREEMENT)
    assert orbit.period == pytest.approx(pendulum_period(AMPLITUDE), rel=ORBIT_AGREEMENT)
    # 1-DOF Hamiltonian: the energy brings a Jordan block at 1, two trivial multipliers
    assert orbit.n_trivial_expected == 2 and orbit.n_trivial_found == 2


# --------------------------------------------------------------------------------------------------
# the count of trivial multipliers, checked on monodromies computed by the shooting
# --------------------------------------------------------------------------------------------------

q1, q2, p1, p2 = sp.symbols("q1 q2 p1 p2")


def hamiltonian_rhs(energy: sp.Expr, coordinates, momenta) -> SymbolicRHS:
    """Hamilton's equations q' = dH/dp, p' = -dH/dq, derived from H."""
    expressions = [sp.diff(energy, p) for p in momenta] + [-sp.diff(energy, q) for q in coordinates]
    return SymbolicRHS(tuple(coordinates) + tuple(momenta), expressions)


#: Frequency of the second oscillator of the linear pair: irrational, so no resonance with 1.
OMEGA2 = math.sqrt(2.0)


def test_linear_pair_with_energy_only_has_two_trivial_multipliers():
    """Mode 1 of q1'' + q1 = 0, q2'' + OMEGA2**2 q2 = 0: multipliers 1, 1, exp(+-2 pi i OMEGA2)."""
    energy = (p1**2 + q1**2) / 2 + (p2**2 + OMEGA2**2 * q2**2) / 2
    rhs = hamiltonian_rhs(energy, (q1, q2), (p1, p2))
    orbit = find_periodic_orbit(
        rhs, [1.0, 0.0, 0.0, 0.0], 6.0, section_index=2, integrals=[energy], hamiltonian=True
    )
    assert orbit.success, orbit.message
    assert orbit.period == pytest.approx(2 * math.pi, rel=ORBIT_AGREEMENT)
    assert orbit.n_trivial_expected == 2 and orbit.n_trivial_found == 2
    rotation = np.exp(2j * math.pi * OMEGA2 * np.array([1, -1]))
    np.testing.assert_allclose(
        np.sort_complex(orbit.floquet_multipliers[2:]), np.sort_complex(rotation), atol=1e-9
    )


def test_henon_heiles_orbit_has_two_trivial_multipliers_and_a_reciprocal_pair():
    """H = (px**2 + py**2 + x**2 + y**2)/2 + x**2 y - y**3/3, energy only (not integrable)."""
    energy = (p1**2 + p2**2 + q1**2 + q2**2) / 2 + q1**2 * q2 - q2**3 / 3
    rhs = hamiltonian_rhs(energy, (q1, q2), (p1, p2))
    guess = [0.2, 0.1, 0.0, 0.25]  # section p1 = 0; energy ~0.06, below the escape energy 1/6
    orbit = find_periodic_orbit(
        rhs, guess, 2 * math.pi, section_index=2, integrals=[energy], hamiltonian=True
    )
    assert orbit.success, orbit.message
    assert orbit.n_trivial_expected == 2 and orbit.n_trivial_found == 2
    energy_at = sp.lambdify((q1, q2, p1, p2), energy)
    # held to the shooting's tol relative to the integral's size, max(|E|, |grad E| max|y|) =
    # 0.25 * 0.25 at the guess (|E| = 0.06): the defect of the integral is part of the residual
    held = SHOOTING_TOL * 0.25 * 0.25
    assert energy_at(*orbit.initial_state) == pytest.approx(energy_at(*guess), abs=held)
    nontrivial = orbit.floquet_multipliers[2:]
    assert abs(nontrivial[0] * nontrivial[1] - 1) < 1e-9  # symplectic: lambda and 1/lambda
    assert np.min(np.abs(nontrivial - 1)) > 1e-2  # an isolated orbit at this energy


def test_euler_rigid_body_has_one_plus_two_trivial_multipliers():
    """Free rigid body (not canonical; energy and |L|**2): 1 + 2 = 3 multipliers at 1."""
    w1, w2, w3 = sp.symbols("w1 w2 w3")
    inertia = (1, 2, 3)
    rhs = SymbolicRHS(
        (w1, w2, w3),
        (
            sp.Rational(inertia[1] - inertia[2], inertia[0]) * w2 * w3,
            sp.Rational(inertia[2] - inertia[0], inertia[1]) * w3 * w1,
            sp.Rational(inertia[0] - inertia[1], inertia[2]) * w1 * w2,
        ),
    )
    energy = sum(i * w**2 for i, w in zip(inertia, (w1, w2, w3), strict=True))
    momentum = sum(i**2 * w**2 for i, w in zip(inertia, (w1, w2, w3), strict=True))
    # wobble about the axis of least inertia, frequency w1 sqrt((I2 - I1)(I3 - I1) / (I2 I3))
    guess_period = 2 * math.pi / math.sqrt((2 - 1) * (3 - 1) / (2 * 3))
    orbit = find_periodic_orbit(
        rhs, [1.0, 0.1, 0.0], guess_period, section_index=2, integrals=[energy, momentum]
    )
    assert orbit.success, orbit.message
    assert orbit.n_trivial_expected == 3 and orbit.n_trivial_found == 3


def test_integrals_are_checked():
    with pytest.raises(InvalidParameterError, match="`integrals`.*callables"):
        find_periodic_orbit(PENDULUM, [1.0, 0.0], 6.0, section_index=1, integrals=[3.0])
    with pytest.raises(InvalidParameterError, match="`integrals`.*SymbolicRHS"):
        find_periodic_orbit(
            lambda y: np.array([y[1], -np.sin(y[0])]),
            [1.0, 0.0],
            6.0,
            section_index=1,
            integrals=[PENDULUM_ENERGY],
        )
    with pytest.raises(InvalidParameterError, match="`integrals`.*stationary"):
        find_periodic_orbit(  # v**2 has zero gradient on the section v = 0, x = 0
            PENDULUM, [0.0, 0.0], 6.0, section_index=1, integrals=[x**2 + v**2]
        )
    with pytest.raises(InvalidParameterError, match="`integrals`.*trivial multipliers"):
        find_periodic_orbit(
            PENDULUM,
            [1.0, 0.0],
            6.0,
            section_index=1,
            integrals=[PENDULUM_ENERGY, 2 * PENDULUM_ENERGY],
            hamiltonian=True,
        )
    with pytest.raises(InvalidParameterError, match="`hamiltonian`"):
        find_periodic_orbit(PENDULUM, [1.0, 0.0], 6.0, section_index=1, hamiltonian="yes")
