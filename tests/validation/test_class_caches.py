"""The per-class caches of the validation room hold classes weakly: a class a user makes and drops
(a problem file loaded again, a class made in a loop or a test) is not kept alive by them."""

from __future__ import annotations

import gc
import weakref

import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.validation import original_equations, with_epsilon
from perturb.validation.capabilities import label_of
from perturb.validation.model import parameter_value_of

X, XDOT = sp.symbols("x xdot")
SYSTEM = QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3])


def _made_and_asked() -> weakref.ref:
    class Made:  # a model as a user's script makes one: every hook asked through a cache by class
        def label(self):
            return "made"

        def epsilon(self):
            return 0.1

        def system(self):
            return SYSTEM

        def symbol_values(self):
            return {}

        def with_epsilon(self, eps):
            return self

    model = Made()
    assert label_of(model) == "made"
    assert parameter_value_of(model) == 0.1
    assert with_epsilon(model, 0.2) is model
    assert original_equations(model).quasilinear
    return weakref.ref(Made)


def test_a_dropped_class_is_not_kept_alive():
    made = _made_and_asked()
    gc.collect()
    assert made() is None
