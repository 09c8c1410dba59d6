"""One true-orbit value: every route returns a PeriodicOrbit, its multipliers under one name and
the route that found it; the older names read the same numbers."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.oracle import (
    OrbitRoute,
    OrbitStatus,
    PeriodicOrbit,
    SymbolicRHS,
    find_forced_orbit,
    find_periodic_orbit,
)
from perturb.validation import OrbitEstimate


def test_the_autonomous_and_the_driven_shooting_say_how_they_found_their_orbit():
    def vdp(y):
        return np.array([y[1], 0.1 * (1 - y[0] ** 2) * y[1] - y[0]])

    free = find_periodic_orbit(vdp, [2.0, 0.0], 2 * math.pi, section_index=1)
    x, v, th = sp.symbols("x v theta")
    rhs = SymbolicRHS((x, v, th), (v, -0.2 * v - x + sp.cos(th), 1))
    driven = find_forced_orbit(rhs, [0.0, 4.0], 2 * math.pi)
    assert free.success and driven.success
    assert (free.found_by, driven.found_by) == (OrbitRoute.SHOOTING, OrbitRoute.FORCED)
    for orbit in (free, driven):
        assert isinstance(orbit, PeriodicOrbit)
        assert orbit.floquet_multipliers is orbit.multipliers  # the older name, the same array
    # the driven orbit's multipliers against Liouville: det M = exp(-0.2 T), both of one modulus
    assert np.prod(driven.multipliers) == pytest.approx(math.exp(-0.2 * 2 * math.pi), rel=1e-10)


def test_every_status_has_its_code_and_back():
    codes = [status.code for status in OrbitStatus]
    assert len(set(codes)) == len(codes)
    assert all(OrbitStatus.of_code(status.code) is status for status in OrbitStatus)
    assert [s for s in OrbitStatus if s.success] == [OrbitStatus.CONVERGED]


def test_a_model_s_own_estimate_is_a_periodic_orbit():
    found = OrbitEstimate(True, 6.5, (1.0, 0.0), message="mine", floquet=(1.0, 0.5), n_trivial=1)
    failed = OrbitEstimate(False, math.nan, (), "no extended precision here")
    assert isinstance(found, PeriodicOrbit) and found.found_by is OrbitRoute.MODEL
    assert found.success and found.status is OrbitStatus.CONVERGED
    assert list(found.floquet) == list(found.multipliers) == [1.0, 0.5]
    assert found.n_trivial == found.n_trivial_expected == 1
    assert not failed.success and failed.status is OrbitStatus.FAILED
    assert failed.message == "no extended precision here" and failed.n_trivial is None
