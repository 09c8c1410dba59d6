"""Argument checks shared by the public constructors and methods (validation at the boundary).

Each helper either returns the value in the form the engine uses or raises the one-line error of
:func:`perturb.errors.bad_value`: the argument in backticks, the value received, the fix.
"""

from __future__ import annotations

import functools
import math
import numbers
from collections.abc import Mapping

import attrs
import numpy as np
import sympy as sp

from perturb.errors import InvalidParameterError, UnknownNameError, bad_value

__all__ = [
    "as_expression",
    "as_mapping",
    "as_real_array",
    "check_bool",
    "check_count",
    "check_positive_number",
    "known_keywords",
    "real_number",
]

#: Atoms that make an expression infinite or undefined.
NON_FINITE = (sp.nan, sp.oo, -sp.oo, sp.zoo)


def as_expression(argument: str, value, cls: type[ValueError] = InvalidParameterError) -> sp.Expr:
    """``value`` as a finite sympy expression (numbers, expressions, parseable strings)."""
    if value is None or isinstance(value, bool | Mapping | list | tuple | set):
        raise bad_value(argument, value, "give a number or a sympy expression", cls)
    try:
        expr = sp.sympify(value)
    except (sp.SympifyError, TypeError, ValueError, SyntaxError):
        raise bad_value(argument, value, "give a number or a sympy expression", cls) from None
    if not isinstance(expr, sp.Expr):
        raise bad_value(argument, value, "give a number or a sympy expression", cls)
    if expr.has(*NON_FINITE):
        raise bad_value(argument, value, "give a finite value (no NaN or infinity)", cls)
    return expr


def real_number(argument: str, value, cls: type[ValueError] = InvalidParameterError) -> sp.Expr:
    """A finite expression that is not a non-real number (symbols are allowed)."""
    expr = as_expression(argument, value, cls)
    if expr.has(sp.I) and (expr.is_number or expr.is_extended_real is False):
        if not (expr.is_number and sp.im(expr.evalf()) == 0):
            raise bad_value(argument, value, "give a real value, not a complex one", cls)
    return expr


def as_mapping(argument: str, value, cls: type[ValueError] = InvalidParameterError) -> dict:
    """``value`` (a mapping, or ``None`` for an empty one) as a new dict."""
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise bad_value(argument, value, "give a mapping {name: value} (a dict)", cls)
    return dict(value)


def as_real_array(argument: str, value, cls: type[ValueError] = InvalidParameterError):
    """``value`` as a float array of finite real numbers."""
    if value is None or isinstance(value, str | Mapping):
        raise bad_value(argument, value, "give a finite real number or an array of them", cls)
    try:
        array = np.asarray(value)
        if np.iscomplexobj(array) or array.dtype.kind == "b":  # a bool is no number here
            raise TypeError
        array = array.astype(float)
    except (TypeError, ValueError):
        raise bad_value(
            argument, value, "give a finite real number or an array of them", cls
        ) from None
    if not np.all(np.isfinite(array)):
        raise bad_value(argument, value, "give finite values (no NaN or infinity)", cls)
    return array


def check_positive_number(argument: str, value, cls: type[ValueError] = InvalidParameterError):
    """A finite real number > 0 (not a bool)."""
    ok = isinstance(value, numbers.Real) and not isinstance(value, bool)
    if not (ok and math.isfinite(value) and value > 0):
        raise bad_value(argument, value, "give a finite positive number", cls)


def check_count(argument: str, value, minimum: int = 1, cls=InvalidParameterError) -> None:
    """An integer (not a bool) >= ``minimum``."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < minimum:
        raise bad_value(argument, value, f"give an integer >= {minimum}", cls)


def check_bool(argument: str, value, cls: type[ValueError] = InvalidParameterError) -> None:
    if not isinstance(value, bool | np.bool_):
        raise bad_value(argument, value, "give True or False", cls)


def known_keywords(cls):
    """Class decorator for attrs classes: an unknown keyword argument of the constructor raises
    :class:`~perturb.errors.UnknownNameError` naming it and the known ones (not a ``TypeError``)."""
    init = cls.__init__
    known = tuple(a.alias for a in attrs.fields(cls) if a.init)

    @functools.wraps(init)
    def __init__(self, *args, **kwargs):
        for key in kwargs:
            if key not in known:
                raise bad_value(
                    key,
                    kwargs[key],
                    f"not an option of {cls.__name__}; use {list(known)}",
                    UnknownNameError,
                )
        init(self, *args, **kwargs)

    cls.__init__ = __init__
    return cls
