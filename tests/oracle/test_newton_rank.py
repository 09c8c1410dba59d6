"""The Newton step's rank cut at the rounding of the monodromy (perturb/oracle/newton.py).

A shooting whose Newton matrix is small (a monodromy near the identity: a near-resonant orbit in
conditioned coordinates) has singular values far below its monodromy's entries, so the rounding of
those entries — one float64 ulp, 1e-16 — is far above a cut relative to the matrix (1e-9 of 1e-12).
Two unknowns that move the defect alike (the conditioned disk's period and its period component
w) then get a singular value from the rounding alone, and the step follows it: the whole time
correction goes to one unknown, chosen by a last bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from perturb._defaults import ROUNDING_ULPS
from perturb.oracle.newton import newton_step, rounding_norm

#: Two defect components moved by time, and a constant component (the period component w).
VELOCITY = np.array([1e-12, 3e-12, 0.0])
#: The period moves the state as w does, six times less per unit (the conditioned disk's ratio).
PERIOD_RATIO = 6.0
#: Agreement of the step with the cut and the step of the exact matrix: the ulp d = 2.2e-16 left
#: out tilts the kept singular direction by (d / sigma)**2 = 5e-9 (sigma = 3.2e-12); 20 times that.
SAME_STEP = 1e-7


def _system(phi_ww: float):
    """The Newton matrix [(Phi - I)[:, w], f(y(T))] and target of the time correction."""
    phi = np.eye(3)
    phi[:, 2] += VELOCITY
    phi[2, 2] = phi_ww
    matrix = np.column_stack(((phi - np.eye(3))[:, 2], VELOCITY / PERIOD_RATIO))
    return phi, matrix, -0.5 * VELOCITY


def test_one_ulp_on_a_constant_component_does_not_choose_the_step():
    phi, exact, target = _system(1.0)
    noisy_phi, noisy, _ = _system(np.nextafter(1.0, 2.0))
    assert noisy[2, 0] > 0  # one ulp: a singular value ~2e-16, 1e5 above the relative cut
    reference, rank = newton_step(exact, target)
    assert rank == 1  # the two columns are parallel: the minimum-norm step shares the correction
    step, rank = newton_step(noisy, target, matrix_noise=rounding_norm(noisy_phi[:, 2]))
    assert rank == 1
    assert step == pytest.approx(reference, rel=SAME_STEP)
    # the share of each unknown is the columns' (the period takes 1/37 of the time correction)
    assert step[1] / step[0] == pytest.approx(1 / PERIOD_RATIO, rel=SAME_STEP)


def test_without_the_cut_the_last_bit_puts_the_correction_on_one_unknown():
    """What the cut prevents: the noisy row 'w does not change' is believed."""
    _, noisy, target = _system(np.nextafter(1.0, 2.0))
    step, rank = newton_step(noisy, target)
    assert rank == 2
    assert abs(step[0]) < 1e-3 * abs(step[1])  # w left alone, the period moved by all of it


def test_the_rounding_norm_is_a_few_spacings_of_the_entries():
    entries = np.array([[1.0, 1e-12], [0.5, 2.0]])
    spacings = np.spacing(np.abs(entries))
    assert rounding_norm(entries) == pytest.approx(ROUNDING_ULPS * np.linalg.norm(spacings))
    assert rounding_norm(entries) < 1e-14  # far below any singular value of an O(1) matrix
