"""The fast paths of the rigid-body reduction give the same results as the direct ones.

* the ring -> sympy conversion equals ``expand(as_expr())`` with 1/a, 1/b put back,
* a reduction with the parameters put in first equals the symbolic one with them put in after
  (system, maps and amplitude constraint: identical expressions, hence identical solutions),
* the numeric inverse map equals the symbolic series evaluated in floating point,
* a reduction read back from the disk cache equals the computed one.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from perturb.errors import InvalidParameterError
from perturb.system import EPS
from problems.rigid_body import _elimination
from problems.rigid_body._body import geometric_constraint
from problems.rigid_body._series_ring import INV_A, INV_B
from problems.rigid_body.equations import NONDIMENSIONAL_STATE, a, b
from problems.rigid_body.reduction import (
    INITIAL_VALUES,
    REDUCED_STATE,
    _reduce,
    disk_reduction,
    general_body_reduction,
    specialised_disk_reduction,
    specialised_general_body_reduction,
)

#: An exact body (the paper's moments, a strong field, x0', y0' as rationals of norm ~1).
DISK_VALUES = {
    "a": sp.Rational(9, 20),
    "b": sp.Rational(11, 20),
    "k": sp.Rational(1, 2),
    "x0p": sp.Rational(1643989873053573, 10**16),
    "y0p": sp.Rational(9863939238321437, 10**16),
    "gamma3_0": sp.Rational(3, 10),
}
GENERAL_VALUES = {**DISK_VALUES, "b": sp.Rational(11, 15), "a": sp.Rational(9, 15)}
GENERAL_VALUES["z0p"] = sp.Rational(1, 3)
#: The inverse map's coefficients are rounded once (exact evaluation) where the symbolic series
#: evaluated in floats rounds at every operation: on states of size ~1 with a few hundred terms
#: both stay within a few hundred ulps of the exact value.
FLOAT_AGREEMENT = 1e-12


def _by_symbol(reduction, values):
    return {p: values[p.name] for p in reduction.parameters}


@pytest.mark.parametrize("order", [2, 3])
def test_ring_to_expr_equals_the_expanded_expression(order):
    reduction = disk_reduction(order)
    ring = reduction._ring
    for poly in reduction._series.values():
        direct = sp.expand(poly.as_expr().subs({INV_A: 1 / a, INV_B: 1 / b}))
        assert ring.to_expr(poly) == direct


@pytest.mark.parametrize("order", [3, 4])
def test_specialised_disk_reduction_is_the_symbolic_one_evaluated(order):
    symbolic = disk_reduction(order)
    values = _by_symbol(symbolic, DISK_VALUES)
    special = specialised_disk_reduction(order, DISK_VALUES)
    after = symbolic.system.with_values(values)
    assert special.system == after
    assert sp.srepr(special.system.rhs) == sp.srepr(after.rhs)
    assert sp.srepr(special.system.first_integrals) == sp.srepr(after.first_integrals)
    for name in ("full_state", "initial_full_state"):
        assert getattr(special, name) == tuple(e.xreplace(values) for e in getattr(symbolic, name))
    amplitude = geometric_constraint(symbolic).xreplace(values)
    assert sp.srepr(geometric_constraint(special)) == sp.srepr(amplitude)


def test_specialised_general_body_reduction_is_the_symbolic_one_evaluated():
    symbolic = general_body_reduction(2)
    values = _by_symbol(symbolic, GENERAL_VALUES)
    special = specialised_general_body_reduction(2, GENERAL_VALUES)
    after = symbolic.system.with_values(values)
    assert special.system == after
    assert sp.srepr(special.system.frequencies) == sp.srepr(after.frequencies)


def _float_values(values):
    return {name: float(v) for name, v in values.items()}


@pytest.mark.parametrize(
    ("reduction", "values"),
    [
        (lambda: disk_reduction(3), DISK_VALUES),
        (lambda: specialised_disk_reduction(3, DISK_VALUES), DISK_VALUES),
        (lambda: general_body_reduction(2), GENERAL_VALUES),
    ],
    ids=["disk", "disk-specialised", "general"],
)
def test_inverse_map_equals_the_series_evaluated(reduction, values):
    reduction = reduction()
    eps = 0.01
    floats = _float_values(values)
    numeric = reduction.inverse_function(floats, eps)
    fixed = {p: floats[p.name] for p in reduction.parameters}
    symbolic = sp.lambdify(
        (REDUCED_STATE, INITIAL_VALUES),
        [e.xreplace({**fixed, EPS: eps}) for e in reduction.full_state],
        "numpy",
    )
    rng = np.random.default_rng(7)
    z = rng.uniform(-0.3, 0.3, size=(4, 50))
    z0 = (0.05, 0.9, -0.02, 0.0)
    expected = np.array(np.broadcast_arrays(*symbolic(tuple(z), z0)))
    got = numeric(z, z0)
    assert got.shape == (6, 50)
    assert np.abs(got - expected).max() <= FLOAT_AGREEMENT
    # one point at a time, and initial values given per point, agree with the vectorised call
    assert np.abs(numeric(z[:, 3], z0) - got[:, 3]).max() <= FLOAT_AGREEMENT
    per_point = numeric(z, tuple(np.full(50, v) for v in z0))
    assert np.abs(per_point - got).max() <= FLOAT_AGREEMENT


def test_specialised_inverse_map_refuses_other_values():
    special = specialised_disk_reduction(3, DISK_VALUES)
    wrong = {**_float_values(DISK_VALUES), "k": 0.25}
    with pytest.raises(InvalidParameterError, match="`k` = 0.25"):
        special.inverse_function(wrong, 0.01)


def test_specialised_reduction_needs_exact_values():
    with pytest.raises(InvalidParameterError, match="`k` = 0.5"):
        specialised_disk_reduction(3, {**DISK_VALUES, "k": 0.5})
    with pytest.raises(InvalidParameterError, match="give values for"):
        specialised_disk_reduction(3, {"a": sp.Rational(1, 2)})


def test_reduction_is_read_back_from_the_disk_cache(monkeypatch, tmp_path):
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    first = _reduce("disk", 2, ())
    assert any(path.name.startswith("reduction-") for path in tmp_path.iterdir())

    def no_derivation(self):
        raise AssertionError("the reduction was derived again instead of read from disk")

    monkeypatch.setattr(_elimination.Builder, "run", no_derivation)
    second = _reduce("disk", 2, ())
    assert second._series == first._series
    assert second.F == first.F and second.full_state == first.full_state
    assert {s.name for s in NONDIMENSIONAL_STATE} <= {
        name.split(":")[1] for name in second._series if ":" in name
    }
