"""A phase diagram's boundaries are where the problem's own map puts them, whatever the map.

The forced Duffing oscillator written with Omega^2 = 1 + 2 eps sigma (a map that is not affine in
Omega): its first-order folds, found in sigma, are carried back to Omega by the map's exact
inverse, not by a straight line through two samples. The folds are checked against a second,
independent route: the discriminant of the first-order response cubic in a^2,
[(sigma - 3 gamma a^2/8)^2 + zeta^2] a^2 = (F/2)^2, whose real roots in sigma are the folds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.sweep.phase import FIRST_ORDER, phase_line
from problems.forced_duffing import ForcedDuffing

#: Two exact routes (a 30-digit inverse of the map, numpy's roots of the discriminant): a
#: fold agrees to the rounding of a few dozen operations on numbers of size 1.
SAME_FOLD = 1e-10


class SquaredDuffing(ForcedDuffing):
    """The forced Duffing oscillator whose detuning is read off Omega^2."""

    name = "squared-duffing"
    parameter_map = {"sigma": "(Omega**2 - 1)/(2*eps)"}


def _folds_by_discriminant(eps: float, zeta: float, gamma: float, force: float) -> list[float]:
    """Omega at the first-order folds: sigma where the response cubic in A = a^2 has a double
    positive root (its discriminant's real roots), then Omega = sqrt(1 + 2 eps sigma)."""
    a, s = sp.symbols("A s")
    k, z, f = (sp.nsimplify(3 * gamma / 8), sp.nsimplify(zeta), sp.nsimplify(force))
    cubic = k**2 * a**3 - 2 * s * k * a**2 + (s**2 + z**2) * a - f**2 / 4
    discriminant = sp.Poly(sp.discriminant(cubic, a), s)
    roots = np.roots([float(c) for c in discriminant.all_coeffs()])
    sigmas = [r.real for r in roots if abs(r.imag) < 1e-9 and 1 + 2 * eps * r.real > 0]
    return sorted(math.sqrt(1 + 2 * eps * sigma) for sigma in sigmas)


def test_the_first_order_folds_of_a_map_quadratic_in_omega():
    problem = SquaredDuffing.create(F=0.5)
    eps, zeta, gamma = (problem.values[k] for k in ("eps", "zeta", "gamma"))
    omegas = np.linspace(1.0, 1.13, 6)
    line = phase_line(problem, "Omega", omegas, "F", 0.5, 1, True)
    folds = sorted(
        v for kind, v, order in line["special"] if kind == "fold" and order == FIRST_ORDER
    )
    expected = _folds_by_discriminant(eps, zeta, gamma, 0.5)
    assert len(expected) == 2 and omegas[0] < expected[0] < expected[1] < omegas[-1]
    assert folds == pytest.approx(expected, rel=SAME_FOLD, abs=0)
    # the certified count changes exactly across the folds: 1 outside, 3 between
    between = [bool(expected[0] < w < expected[1]) for w in omegas]
    assert line["first_order"] == [3 if b else 1 for b in between]
