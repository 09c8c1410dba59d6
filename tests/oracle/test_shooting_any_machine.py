"""The shooting's answer does not depend on the machine (issue 21): its stopping rule is scaled to
what the working precision can show, so what another machine perturbs — the integrator's
tolerance, the seed, the last bits of the inputs, a higher noise floor — moves the orbit by no
more than its own resolution, and a floor above the requested ``tol`` is reached, not stalled at.
"""

from __future__ import annotations

import numpy as np
import pytest

from perturb._defaults import FLOOR_SAFETY, SHOOTING_TOL
from perturb.oracle import Scipy, SymbolicRHS, find_periodic_orbit
from perturb.oracle.orbit import OrbitStatus
from tests.oracle.noisy import NoisyIntegrator
from tests.oracle.systems import duffing, duffing_period, v, van_der_pol, x

#: The issue's demand: the same orbit to 1e-6 (relative) whatever the machine perturbs.
SAME_ORBIT = 1e-6
#: A noise floor well above the default tol (1e-12), as the failing machine had (1.36e-12 there):
#: with 3e-11 of noise no draw brings the residual under 1e-12.
NOISE = 3e-11
EPS_VDP = 0.5
#: The shooting's default tolerance (the relative residual it stops at without noise).
TOL = SHOOTING_TOL


def _integrator(rtol: float = 1e-13) -> Scipy:
    return Scipy("DOP853", rtol=rtol)


def _vdp(integrator, guess=(2.0, 0.0), eps=EPS_VDP):
    return find_periodic_orbit(
        van_der_pol(eps), list(guess), 2 * np.pi, section_index=1, integrator=integrator
    )


@pytest.fixture(scope="module")
def vdp_reference():
    orbit = _vdp(_integrator())
    assert orbit.success and orbit.residual <= 1e-12, orbit.message
    return orbit


def _same(orbit, reference, rel=SAME_ORBIT):
    assert orbit.success, orbit.message
    assert orbit.period == pytest.approx(reference.period, rel=rel)
    assert np.allclose(orbit.initial_state, reference.initial_state, rtol=0, atol=rel * 2)


@pytest.mark.parametrize("factor", [0.3, 3.0])
def test_integrator_tolerance_does_not_move_the_orbit(vdp_reference, factor):
    _same(_vdp(_integrator(1e-13 * factor)), vdp_reference)


@pytest.mark.parametrize("guess", [(1.8, 0.0), (2.3, 0.0)])
def test_seed_does_not_move_the_orbit(vdp_reference, guess):
    _same(_vdp(_integrator(), guess), vdp_reference)


def test_last_bits_of_the_input_do_not_move_the_orbit(vdp_reference):
    eps = np.nextafter(np.nextafter(EPS_VDP, 1.0), 1.0)  # two ulps up
    _same(_vdp(_integrator(), eps=eps), vdp_reference)


def _decided_by_the_floor(orbit):
    """Success on a machine with NOISE in its integrations: the residual is within the tol or,
    above it, within FLOOR_SAFETY of the floor measured there, which the message names; that floor
    is no larger than the noise (it measures NOISE |u| / scale per component, |u| <= 1, scale >= 1
    here). Which of the two holds depends on the draw, i.e. on the machine's last bits: with 3e-11
    of noise nearly every draw stops above 1e-12, but a lucky one can land below it."""
    assert orbit.success, orbit.message
    assert orbit.precision_floor <= NOISE
    if orbit.residual > TOL:
        assert "precision floor" in orbit.message
        assert orbit.residual <= FLOOR_SAFETY * orbit.precision_floor


def test_a_noise_floor_above_tol_is_reached_not_stalled_at(vdp_reference):
    """A machine whose integrations carry 3e-11 of noise can hardly show a residual below 1e-12:
    the fixed tol = 1e-12 stalled there; the measured floor accepts it and says so."""
    orbit = _vdp(NoisyIntegrator(_integrator(), NOISE))
    _decided_by_the_floor(orbit)
    _same(orbit, vdp_reference)


def test_a_stall_far_above_the_floor_still_fails():
    """The floor is measured, not granted: an integrator whose noise is far below the residual at
    which Newton cannot gain (here a max_iter of 1 from a poor guess) is a failure, not a pass."""
    orbit = find_periodic_orbit(
        van_der_pol(EPS_VDP),
        [1.0, 0.0],
        2 * np.pi,
        section_index=1,
        max_iter=1,
        integrator=_integrator(),
    )
    assert not orbit.success and orbit.status is OrbitStatus.MAX_ITER


def test_a_family_pinned_by_its_energy_is_the_same_orbit_on_a_noisy_machine():
    """Duffing's conservative family, the member pinned by its energy integral (no fixed index)."""
    amplitude = 1.2
    energy = v**2 / 2 + x**2 / 2 + x**4 / 4
    rhs = duffing()
    kwargs = dict(section_index=1, integrals=[energy])
    guess = 1.02 * duffing_period(amplitude)
    clean = find_periodic_orbit(rhs, [amplitude, 0.0], guess, integrator=_integrator(), **kwargs)
    noisy = find_periodic_orbit(
        rhs, [amplitude, 0.0], guess, integrator=NoisyIntegrator(_integrator(), NOISE), **kwargs
    )
    assert clean.success and noisy.success, noisy.message
    exact = duffing_period(amplitude)
    assert clean.period == pytest.approx(exact, rel=1e-10)
    _decided_by_the_floor(noisy)
    assert noisy.period == pytest.approx(exact, rel=SAME_ORBIT)


def test_without_noise_the_floor_is_round_off_and_stays_silent(vdp_reference):
    assert vdp_reference.precision_floor < 1e-14
    assert "precision floor" not in vdp_reference.message
    assert isinstance(van_der_pol(EPS_VDP), SymbolicRHS)
