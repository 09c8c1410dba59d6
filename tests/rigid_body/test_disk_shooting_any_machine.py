"""The disk's true orbit at the paper geometry is the same on any machine (issue 21).

The README's test command failed on a fresh AVX-512 machine: its conditioned shooting stalled at
residual 1.36e-12 > tol 1e-12 in the first pass, whose origin is ~1 % off the orbit (|u| ~ 1e4,
float64 spacing 1.8e-12: the fixed tol was below what the working precision can show there).
Here each thing another machine perturbs is perturbed — the integrator's tolerance, a noise floor
above the old tol, the last bits of the inputs, the seed — and the orbit is the two-route value
of tests/rigid_body/test_disk_shooting.py to 1e-6.
"""

from __future__ import annotations

import numpy as np
import pytest

from perturb.oracle import Heyoka, heyoka_available
from tests.oracle.noisy import NoisyIntegrator
from tests.rigid_body.test_disk_shooting import PAPER_EPS, TRUE_PAPER, disk

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="needs heyoka (extended precision)")

#: The issue's demand: the same orbit to 1e-6 (relative).
SAME_ORBIT = 1e-6


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
    _same(_orbit(disk(PAPER_EPS), integrator=_extended().loosened(factor)))


@pytest.mark.parametrize("ulps", [1.0, 8.0])
def test_other_last_bits_give_the_same_orbit(ulps):
    """A machine whose last bits differ: each final state moved by up to ``ulps`` float64 spacings
    of each component. In the first pass |u| ~ 1.3e4, so one ulp is 1.8e-12, above the old fixed
    tol 1e-12 there (the failing machine stalled at 1.36e-12)."""
    orbit = _orbit(disk(PAPER_EPS), integrator=NoisyIntegrator(_extended(), ulps=ulps))
    _same(orbit)


def test_the_last_bits_of_the_inputs_do_not_move_the_orbit():
    reference = disk(PAPER_EPS)
    r0 = reference.values["r0"]
    nudged = type(reference).create(**{**reference.values, "r0": np.nextafter(r0, 2 * r0)})
    assert nudged.values["r0"] != r0
    _same(_orbit(nudged))
