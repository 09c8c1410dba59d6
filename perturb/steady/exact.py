"""Numbers made exact: what the user typed, as the rational of its shortest decimal."""

from __future__ import annotations

import math

import sympy as sp

from perturb.errors import InvalidParameterError, bad_value

__all__ = ["exact_number"]


def exact_number(value) -> sp.Rational:
    """A number as the exact rational of its shortest decimal (what the user typed)."""
    if isinstance(value, sp.Basic) and value.is_Rational:
        return value
    value = float(value)
    if not math.isfinite(value):
        raise bad_value("value", value, "give a finite number", InvalidParameterError)
    return sp.Rational(repr(value))
