"""Checks of the plain inputs the plotting functions take (times, name → array mappings).

Bad input raises :class:`perturb.errors.InvalidParameterError` naming the argument, the value and
the fix, before any figure is made.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from perturb.errors import bad_value

__all__ = ["as_series", "as_times", "pick_names", "units_for"]


def _short(value: object) -> object:
    """The value as shown in a message: arrays by shape, not by content."""
    if isinstance(value, np.ndarray):
        return f"<array of shape {value.shape}>"
    if isinstance(value, Mapping):
        return f"<mapping with keys {sorted(map(str, value))}>"
    return value


def as_times(t, argument: str = "t") -> np.ndarray:
    """``t`` as a 1-D float array of at least two finite, increasing times."""
    try:
        times = np.asarray(t, dtype=float)
    except (TypeError, ValueError):
        raise bad_value(argument, t, "pass a 1-D sequence of times") from None
    if times.ndim != 1 or times.size < 2:
        raise bad_value(argument, _short(times), "pass a 1-D sequence of at least two times")
    if not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
        raise bad_value(argument, _short(times), "times must be finite and increasing")
    return times


def as_series(
    values, n: int, argument: str, names: Sequence[str] | None = None
) -> dict[str, np.ndarray]:
    """A mapping name → 1-D float array of length ``n`` (``names``: the keys that must be there)."""
    if not isinstance(values, Mapping) or not values:
        raise bad_value(argument, _short(values), "pass a non-empty mapping name -> array")
    wanted = list(values) if names is None else list(names)
    missing = [name for name in wanted if name not in values]
    if missing:
        raise bad_value(
            argument,
            _short(values),
            f"it has no {', '.join(map(repr, missing))}; give every name plotted",
        )
    series = {}
    for name in wanted:
        try:
            array = np.asarray(values[name], dtype=float)
        except (TypeError, ValueError):
            raise bad_value(f"{argument}[{name!r}]", values[name], "pass numbers") from None
        if array.shape != (n,):
            raise bad_value(
                f"{argument}[{name!r}]",
                _short(array),
                f"pass one value per time ({n} values, 1-D)",
            )
        series[name] = array
    return series


def pick_names(names, analytic: Mapping, argument: str = "names") -> list[str]:
    """The names to plot: ``names`` if given (non-empty, strings), else every key of ``analytic``."""
    if names is None:
        return [str(name) for name in analytic] if isinstance(analytic, Mapping) else []
    if isinstance(names, str) or not all(isinstance(name, str) for name in names) or not names:
        raise bad_value(argument, names, "pass a non-empty list of state names")
    return list(names)


def units_for(units, names: Sequence[str]) -> dict[str, str]:
    """The unit of each name: ``units`` maps name → unit; an absent name is dimensionless (``""``)."""
    if units is None:
        return dict.fromkeys(names, "")
    if not isinstance(units, Mapping) or not all(isinstance(u, str) for u in units.values()):
        raise bad_value("units", units, "pass a mapping name -> unit string, e.g. {'x': 'm'}")
    return {name: units.get(name, "") for name in names}
