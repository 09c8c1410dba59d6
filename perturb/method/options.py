"""The options of :class:`~perturb.method.poincare.PoincareMethod`, checked at the boundary.

Each check raises the one-line :class:`~perturb.errors.InvalidSystemError` of
:func:`~perturb.errors.bad_value` (the option, the value, the fix).
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp

from perturb._checks import as_mapping, check_bool, check_positive_number, real_number
from perturb._defaults import MAX_ORDER
from perturb.errors import InvalidSystemError, bad_value
from perturb.system import QuasilinearSystem

__all__ = [
    "check_branch",
    "check_cache",
    "check_order",
    "check_phase",
    "check_seconds",
    "check_system",
    "one_of",
    "to_amplitudes",
]


def check_system(system) -> None:
    """Refuse anything but a :class:`QuasilinearSystem` (the engine's input)."""
    if not isinstance(system, QuasilinearSystem):
        raise bad_value("system", system, "give a perturb.QuasilinearSystem", InvalidSystemError)


def check_order(instance, attribute, value):
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise bad_value("order", value, "pass an integer >= 1", InvalidSystemError)
    if value > MAX_ORDER:
        raise bad_value("order", value, f"pass an integer <= {MAX_ORDER}", InvalidSystemError)


def to_amplitudes(value) -> dict:
    out = {}
    for name, amplitude in as_mapping("amplitudes", value, InvalidSystemError).items():
        if not isinstance(name, str):
            raise bad_value(
                "amplitudes",
                {name: amplitude},
                "key it by the coordinate's name (a str)",
                InvalidSystemError,
            )
        real_number(f"amplitudes[{name!r}]", amplitude, InvalidSystemError)
        out[name] = amplitude
    return out


def check_branch(instance, attribute, value):
    if value is None:
        return
    if isinstance(value, int) and not isinstance(value, bool):
        if value < 0:
            raise bad_value("branch", value, "give an index >= 0", InvalidSystemError)
        return
    if not isinstance(value, Mapping):
        raise bad_value(
            "branch",
            value,
            "give None, an index >= 0 or a mapping {symbol name: value}",
            InvalidSystemError,
        )
    for key, v in value.items():
        if not isinstance(key, str | sp.Symbol):
            raise bad_value(
                "branch", {key: v}, "key it by a symbol name such as 'a_x0'", InvalidSystemError
            )
        real_number(f"branch[{str(key)!r}]", v, InvalidSystemError)


def one_of(*choices: str):
    def check(instance, attribute, value):
        if value not in choices:
            raise bad_value(
                attribute.name, value, f"use one of {list(choices)}", InvalidSystemError
            )

    return check


def check_phase(instance, attribute, value):
    if value is not None and not isinstance(value, str):
        raise bad_value(
            "phase_coordinate",
            value,
            "give a coordinate's name (a str) or None",
            InvalidSystemError,
        )


def check_seconds(instance, attribute, value):
    check_positive_number("solve_seconds", value, InvalidSystemError)


def check_cache(instance, attribute, value):
    check_bool("cache", value, InvalidSystemError)
