"""Periodic orbits by shooting: van der Pol limit cycle, Duffing family at fixed amplitude, Floquet
multipliers, failures and error messages."""

from __future__ import annotations

import math

import numpy as np
import pytest

from perturb.errors import InvalidParameterError, PerturbError
from perturb.oracle import (
    OrbitStatus,
    PeriodicOrbit,
    Scipy,
    find_periodic_orbit,
    finite_difference_jacobian,
    heyoka_available,
)
from tests.oracle.systems import duffing, duffing_period, van_der_pol

EPS = 0.1  # van der Pol parameter of the brief

#: Van der Pol: T = 2 pi (1 + eps**2/16 - 5 eps**4/3072 + O(eps**6)) and amplitude
#: a = 2 + eps**2/96 + O(eps**4) (Lindstedt-Poincare, e.g. Nayfeh, Perturbation Methods, 4.2).
#: The eps**4 coefficients are ~2e-3; 1e-2 bounds them with margin.
VDP_EPS4_COEFFICIENT_BOUND = 1e-2


def vdp_numeric(y):
    return np.array([y[1], EPS * (1 - y[0] ** 2) * y[1] - y[0]])


def vdp_jacobian(y):
    return np.array([[0.0, 1.0], [-2 * EPS * y[0] * y[1] - 1.0, EPS * (1 - y[0] ** 2)]])


@pytest.fixture(scope="module")
def vdp_orbit() -> PeriodicOrbit:
    return find_periodic_orbit(
        van_der_pol(EPS), [2.0, 0.0], 2 * math.pi, section_index=1, direction=-1
    )


def test_van_der_pol_period_matches_poincare_lindstedt(vdp_orbit):
    assert vdp_orbit.success, vdp_orbit.message
    second_order = 2 * math.pi * (1 + EPS**2 / 16)
    assert abs(vdp_orbit.period - second_order) <= 2 * math.pi * VDP_EPS4_COEFFICIENT_BOUND * EPS**4
    assert abs(vdp_orbit.period - second_order) > 0  # the eps**4 correction is resolved


def test_van_der_pol_amplitude_is_two_plus_order_eps_squared(vdp_orbit):
    amplitude = vdp_orbit.initial_state[0]  # x at x' = 0 is the maximum of x
    assert abs(amplitude - 2.0) <= EPS**2
    assert abs(amplitude - (2 + EPS**2 / 96)) <= VDP_EPS4_COEFFICIENT_BOUND * EPS**4


def test_van_der_pol_floquet_multipliers(vdp_orbit):
    trivial, nontrivial = vdp_orbit.floquet_multipliers
    assert abs(trivial - 1) == pytest.approx(vdp_orbit.trivial_multiplier_error)
    assert vdp_orbit.trivial_multiplier_error < 1e-10
    # Liouville: det(monodromy) = exp(integral of div f = eps (1 - x**2)); to leading order the
    # cycle x = 2 cos t gives exp(eps * integral of (1 - 4 cos**2 t) over 2 pi) = exp(-2 pi eps),
    # with O(eps**3) corrections in the exponent
    assert abs(nontrivial.imag) < 1e-12
    assert nontrivial.real == pytest.approx(math.exp(-2 * math.pi * EPS), rel=EPS**2)
    assert abs(np.linalg.det(vdp_orbit.monodromy) - nontrivial.real) < 1e-12


@pytest.mark.parametrize(
    ("rhs", "jac"),
    [
        (vdp_numeric, vdp_jacobian),
        (vdp_numeric, None),  # finite-difference Jacobian
    ],
    ids=["numeric-with-jacobian", "numeric-finite-differences"],
)
def test_numeric_rhs_gives_the_same_limit_cycle(vdp_orbit, rhs, jac):
    orbit = find_periodic_orbit(
        rhs, [2.1, 0.0], 6.0, section_index=1, jac=jac, integrator=Scipy("DOP853", rtol=1e-12)
    )
    assert orbit.success, orbit.message
    assert "DOP853" in orbit.integrator
    assert orbit.period == pytest.approx(vdp_orbit.period, rel=1e-10)
    np.testing.assert_allclose(orbit.initial_state, vdp_orbit.initial_state, atol=1e-10)
    assert orbit.trivial_multiplier_error < 1e-8


@pytest.mark.parametrize("amplitude", [0.1, 0.5, 1.0, 2.0])
def test_duffing_period_at_fixed_amplitude_matches_elliptic_integral(amplitude):
    exact = duffing_period(amplitude)
    orbit = find_periodic_orbit(
        duffing(),
        [amplitude, 0.0],
        # harmonic balance, omega**2 = 1 + 3 A**2 / 4, as the guess: the linear period 2 pi is
        # close to *two* periods at A = 2, and Newton would find that doubled orbit
        2 * math.pi / math.sqrt(1 + 0.75 * amplitude**2),
        section_index=1,
        fixed_indices=0,  # the amplitude labels the conservative family: pin it
        n_trivial=2,  # autonomy + energy integral: a double multiplier 1 (Jordan block)
    )
    assert orbit.success, orbit.message
    assert orbit.period == pytest.approx(exact, rel=1e-12)
    assert orbit.initial_state[0] == amplitude
    # double multiplier: splits like sqrt(integration error), ~1e-7
    assert orbit.trivial_multiplier_error < 1e-5
    np.testing.assert_allclose(orbit.floquet_multipliers, [1.0, 1.0], atol=1e-5)


def test_duffing_small_amplitude_with_per_component_tolerances():
    """States ~1e-3: the n-component y_scale is extended to the variational state."""
    amplitude = 1e-3
    integrator = Scipy("DOP853", rtol=1e-13, y_scale=[amplitude, amplitude])
    orbit = find_periodic_orbit(
        duffing(), [amplitude, 0.0], 6.0, section_index=1, fixed_indices=[0], integrator=integrator
    )
    assert orbit.success, orbit.message
    assert orbit.period == pytest.approx(duffing_period(amplitude), rel=1e-11)


def test_missing_pin_is_reported_but_still_converges():
    guess = duffing_period(1.0) * (1 + 1e-6)  # close: the Newton matrix is then nearly singular
    orbit = find_periodic_orbit(duffing(), [1.0, 0.0], guess, section_index=1, n_trivial=2)
    assert orbit.success
    assert "rank" in orbit.message and "fixed_indices" in orbit.message
    assert orbit.period == pytest.approx(duffing_period(orbit.initial_state[0]), rel=1e-11)


def test_collapse_onto_an_equilibrium_is_reported():
    """Without the amplitude pinned, Newton from a poor guess slides down the family to x = 0."""
    orbit = find_periodic_orbit(duffing(), [1.0, 0.0], 6.0, section_index=1, n_trivial=2)
    assert orbit.status is OrbitStatus.EQUILIBRIUM
    assert "equilibrium" in orbit.message and "fixed_indices" in orbit.message


def test_symbolic_rhs_with_explicit_jacobian_uses_a_numeric_integrator(vdp_orbit):
    orbit = find_periodic_orbit(
        van_der_pol(EPS), [2.0, 0.0], 6.3, section_index=1, jac=vdp_jacobian
    )
    assert orbit.success, orbit.message
    assert "DOP853" in orbit.integrator  # the augmented rhs is numeric: heyoka cannot take it
    assert orbit.period == pytest.approx(vdp_orbit.period, rel=1e-11)


def test_finite_difference_jacobian_is_accurate():
    y = np.array([1.3, -0.4])
    np.testing.assert_allclose(
        finite_difference_jacobian(vdp_numeric, y), vdp_jacobian(y), rtol=0, atol=1e-9
    )


# --------------------------------------------------------------------------------------------------
# failures are statuses, bad input raises
# --------------------------------------------------------------------------------------------------


def test_no_convergence_returns_status_and_message():
    orbit = find_periodic_orbit(van_der_pol(EPS), [3.0, 0.0], 5.0, section_index=1, max_iter=1)
    assert not orbit.success and orbit.status is OrbitStatus.MAX_ITER
    assert "max_iter = 1" in orbit.message and "residual" in orbit.message
    assert orbit.iterations == 1  # by construction: MAX_ITER is returned at the cap, on any machine
    with pytest.raises(PerturbError, match="max_iter"):
        orbit.raise_for_status()


def test_wrong_crossing_direction_is_reported():
    orbit = find_periodic_orbit(van_der_pol(EPS), [-2.0, 0.0], 6.3, section_index=1, direction=-1)
    assert orbit.status is OrbitStatus.WRONG_DIRECTION
    assert "direction" in orbit.message
    assert orbit.period == pytest.approx(2 * math.pi * (1 + EPS**2 / 16), rel=1e-5)


def test_integration_failure_returns_status():
    def blow_up(y):
        return np.array([y[1], y[0] ** 3])  # x'' = x**3: escapes to infinity in finite time

    orbit = find_periodic_orbit(
        blow_up, [10.0, 0.0], 50.0, section_index=1, integrator=Scipy("DOP853", max_steps=2000)
    )
    assert orbit.status is OrbitStatus.INTEGRATION_FAILED
    assert "integration" in orbit.message and "t =" in orbit.message


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"period_guess": 0.0}, "period_guess"),
        ({"period_guess": math.nan}, "period_guess"),
        ({"y0_guess": [math.nan, 0.0]}, "y0_guess"),
        ({"section_index": 2}, "section_index"),
        ({"fixed_indices": [5]}, "fixed_indices"),
        ({"direction": 2}, "direction"),
        ({"tol": 0.0}, "tol"),
        ({"max_iter": 0}, "max_iter"),
        ({"n_trivial": 3}, "n_trivial"),
        ({"y0_guess": [1.0, 0.0, 0.0]}, "y0_guess"),
    ],
)
def test_bad_shooting_input_names_the_argument(kwargs, argument):
    call = {"y0_guess": [2.0, 0.0], "period_guess": 6.3, "section_index": 1} | kwargs
    with pytest.raises(InvalidParameterError, match=f"`{argument}`.*invalid: "):
        find_periodic_orbit(
            van_der_pol(EPS), call.pop("y0_guess"), call.pop("period_guess"), **call
        )


@pytest.mark.slow
@pytest.mark.skipif(not heyoka_available(), reason="heyoka is not installed")
@pytest.mark.parametrize("eps", [0.05, 0.2, 0.5])
def test_van_der_pol_period_series_over_eps(eps):
    orbit = find_periodic_orbit(van_der_pol(eps), [2.0, 0.0], 2 * math.pi, section_index=1)
    fourth_order = 2 * math.pi * (1 + eps**2 / 16 - 5 * eps**4 / 3072)
    assert abs(orbit.period - fourth_order) <= 2 * math.pi * eps**6 * 1e-2 + 1e-12
