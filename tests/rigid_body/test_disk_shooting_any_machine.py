"""The disk's true orbit at the paper geometry is the same on any machine (issue 21).

The README's test command failed on a fresh AVX-512 machine: its conditioned shooting stalled at
residual 1.36e-12 > tol 1e-12 in the first pass, whose origin is ~1 % off the orbit (|u| ~ 1e4,
float64 spacing 1.8e-12: the fixed tol was below what the working precision can show there).
Here each thing another machine perturbs is perturbed — the integrator's tolerance, a noise floor
above the old tol, the last bits of the inputs, the seed, the last bit of the monodromy — and the
orbit is the two-route value of tests/rigid_body/test_disk_shooting.py to 1e-6.

The monodromy is integrated in extended precision and used in float64: a machine whose last bits
differ casts it one ulp away (and where long double is a double it is no better than that). With
one ulp on it, none on the state, the shooting used to return amplitudes up to 7e-6 off with a
claimed resolution of 8.5e-9 on one machine in six, and to stall on one in four (24 emulated):
the Newton matrix's singular value along a P-phase error offset by a time shift (3e-19) was far
below the monodromy's rounding (1e-16), and the residual did not see that direction at all.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from perturb.oracle import Heyoka, heyoka_available
from tests.oracle.noisy import NoisyIntegrator
from tests.rigid_body.test_disk_shooting import PAPER_EPS, TRUE_PAPER, disk, within_resolution

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="needs heyoka (extended precision)")

#: The issue's demand: the same orbit to 1e-6 (relative).
SAME_ORBIT = 1e-6
#: Machines emulated by float64 ulps on the monodromy: a few in the default suite, more (and four
#: ulps) in the slow one. Before the rank cut at the monodromy's rounding and the scaled section,
#: "m6" gave beta 7e-6 to 3e-5 off (from one run to the next) claiming 8.5e-9, and "m1" stalled.
FAST_MACHINES = ("m6", "m1")
SLOW_MACHINES = tuple(f"m{k}" for k in range(2, 6)) + tuple(f"m{k}" for k in range(7, 19))


def _orbit(problem, **kwargs):
    from problems.rigid_body.true_orbit import conditioned_true_orbit

    orbit = conditioned_true_orbit(problem, **kwargs)
    assert orbit.success, orbit.message
    assert orbit.resolution < SAME_ORBIT, orbit.message  # what it claims, it must hold to
    return orbit


def _same(orbit):
    assert (orbit.beta1, orbit.beta2, orbit.alpha) == pytest.approx(TRUE_PAPER, rel=SAME_ORBIT)


def _extended():
    from problems.rigid_body.true_orbit import extended_type

    return Heyoka(fp_type=extended_type())


@pytest.mark.parametrize("factor", [3.0, 30.0])
def test_integrator_tolerance_does_not_move_the_orbit(factor):
    orbit = _orbit(disk(PAPER_EPS), integrator=_extended().loosened(factor))
    _same(orbit)
    within_resolution(orbit)


@pytest.mark.parametrize("ulps", [1.0, 8.0])
def test_other_last_bits_give_the_same_orbit(ulps):
    """A machine whose last bits differ: each final state moved by up to ``ulps`` float64 spacings
    of each component. In the first pass |u| ~ 1.3e4, so one ulp is 1.8e-12, above the old fixed
    tol 1e-12 there (the failing machine stalled at 1.36e-12)."""
    orbit = _orbit(disk(PAPER_EPS), integrator=NoisyIntegrator(_extended(), ulps=ulps))
    _same(orbit)
    within_resolution(orbit)


def test_the_last_bits_of_the_inputs_do_not_move_the_orbit():
    reference = disk(PAPER_EPS)
    r0 = reference.values["r0"]
    nudged = type(reference).create(**{**reference.values, "r0": np.nextafter(r0, 2 * r0)})
    assert nudged.values["r0"] != r0
    _same(_orbit(nudged))


def _on_a_machine(machine: str, monodromy_ulps: float):
    from problems.rigid_body.true_orbit import conditioned_true_orbit

    noisy = NoisyIntegrator(_extended(), monodromy_ulps=monodromy_ulps, machine=machine)
    return conditioned_true_orbit(disk(PAPER_EPS), integrator=noisy)


@pytest.mark.parametrize("machine", FAST_MACHINES)
def test_one_ulp_on_the_monodromy_gives_the_orbit_within_its_resolution(machine):
    """Another machine's cast of the quadruple-precision monodromy (one float64 ulp, none on the
    state): the orbit is found, and is the two-route value within the resolution it claims."""
    orbit = _on_a_machine(machine, 1.0)
    assert orbit.success, orbit.message
    within_resolution(orbit)
    assert orbit.resolution < SAME_ORBIT


@pytest.mark.slow
@pytest.mark.parametrize("ulps", [1.0, 4.0])
def test_the_monodromy_last_bits_never_give_a_wrong_orbit(ulps):
    """Sixteen more machines, one and four ulps on the monodromy: each orbit is the two-route
    value within its claimed resolution, or a failure that says why (~1 min per ulps value)."""
    found = 0
    for machine in SLOW_MACHINES:
        orbit = _on_a_machine(machine, ulps)
        if orbit.success:
            within_resolution(orbit)
            found += 1
        else:
            assert math.isnan(orbit.beta1) and "conditioned" in orbit.message, orbit.message
    assert found > 0  # the check above ran
