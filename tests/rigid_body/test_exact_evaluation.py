"""The inverse map's coefficients: the fast integer evaluation is the exact one rounded once."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

from perturb.system import EPS
from problems import get_problem
from problems.rigid_body.reduction import NONDIMENSIONAL_STATE


@pytest.mark.parametrize("symbolic", [True, False])
def test_integer_evaluation_is_the_fractions_rounded_once(symbolic):
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    solution = disk.solve(1, symbolic=symbolic)
    reduction = disk._reduction_of(solution)
    ring = reduction._ring
    rng = random.Random(19)
    for _ in range(4):
        values = {s: Fraction(rng.uniform(0.05, 0.95)) for s in reduction.parameters}
        values[EPS] = Fraction(rng.uniform(1e-4, 0.1))
        keep = ring.free_generators(values)
        for symbol in NONDIMENSIONAL_STATE:
            poly = reduction._series[f"state:{symbol.name}"]
            exact = ring.evaluate(poly, values, keep)
            fast = ring.evaluate_float(poly, values, keep)
            assert fast == {monom: float(c) for monom, c in exact.items()}
            assert all(isinstance(v, float) for v in fast.values())
