"""Hénon–Heiles near the origin, and its families found once per session for the tests that use
them (tests/engine/test_families.py, tests/engine/test_families_degenerate.py): the order-2 search
is a minute's work, and its result is a frozen value."""

from __future__ import annotations

import functools

import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.method.families import find_families

X, Y, XDOT, YDOT = sp.symbols("x y xdot ydot")

#: V = (x² + y²)/2 + ε(x²y − y³/3), a 1:1 resonance in both coordinates.
HENON_HEILES = QuasilinearSystem(
    [X, Y], [XDOT, YDOT], [1, 1], [-2 * EPS * X * Y, -EPS * (X**2 - Y**2)], name="henon-heiles"
)


@functools.cache
def henon_heiles_families(order: int):
    """``find_families(HENON_HEILES, order)``, computed once."""
    return find_families(HENON_HEILES, order)
