"""A bare system's numbers: every parameter and its own ε (or μ), checked once."""

from __future__ import annotations

import math
from collections.abc import Mapping

from perturb.errors import InvalidParameterError, bad_value
from perturb.system import QuasilinearSystem

__all__ = ["check_system_values"]


def check_system_values(system: QuasilinearSystem, values) -> dict[str, float]:
    """``values`` as floats by name: exactly the system's parameters and its own parameter.

    Raises
    ------
    perturb.errors.InvalidParameterError
        A value missing, unknown, not a real number or not finite (one line, with the fix).
    """
    if not isinstance(values, Mapping):
        raise bad_value("values", values, "pass a mapping {name: number}")
    names = [p.name for p in system.parameters] + [system.parameter.name]
    unknown = sorted(set(map(str, values)) - set(names))
    missing = [n for n in names if n not in values]
    if unknown or missing:
        raise InvalidParameterError(
            f"`values` = {dict(values)!r} is invalid: give exactly the system's parameters "
            f"{names} (missing {missing}, unknown {unknown})"
        )
    out = {}
    for name in names:
        try:
            number = float(values[name])
        except (TypeError, ValueError):
            raise bad_value("values", dict(values), f"{name} must be a real number") from None
        if not math.isfinite(number):
            raise bad_value("values", dict(values), f"{name} must be finite")
        out[name] = number
    return out
