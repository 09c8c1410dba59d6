"""The grid of a sweep: one axis per swept parameter, the points it spans, their limits."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from attrs import field, frozen

from perturb.errors import InvalidParameterError, bad_value

__all__ = ["CONFIRM_POINTS", "Grid", "GridAxis", "parse_axis"]

#: A sweep of more points than this must be confirmed (``--yes``, ``confirm=True``): at the
#: evaluation rate of 1e5 points/s it is minutes, validated it is days.
CONFIRM_POINTS = 10_000_000


def _values(value) -> tuple:
    array = np.asarray(value, dtype=float).ravel()
    return tuple(float(v) for v in array)


@frozen
class GridAxis:
    """One swept parameter and its values (finite, strictly increasing, at least one)."""

    name: str
    values: tuple = field(converter=_values)

    def __attrs_post_init__(self):
        values = np.asarray(self.values)
        if values.size < 1:
            raise bad_value(
                self.name, [], "give at least one value (N >= 1)", InvalidParameterError
            )
        if not np.all(np.isfinite(values)):
            raise bad_value(self.name, list(values), "give finite values", InvalidParameterError)
        if values.size > 1 and not np.all(np.diff(values) > 0):
            raise bad_value(
                self.name, f"{values[0]:g}..{values[-1]:g}",
                "give increasing values (START < STOP)", InvalidParameterError,
            )  # fmt: skip


def parse_axis(text: str) -> GridAxis:
    """``NAME=START:STOP:N`` (N >= 1 evenly spaced values, both ends; N = 1 is START alone)."""
    name, sep, spec = text.partition("=")
    parts = spec.split(":")
    if not sep or not name.strip() or len(parts) != 3:
        raise bad_value(
            "grid", text, "write NAME=START:STOP:N, e.g. r0=0.5:1.5:100", InvalidParameterError
        )
    try:
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise bad_value(
            "grid", text, "START and STOP must be numbers and N a whole number",
            InvalidParameterError,
        ) from None  # fmt: skip
    if count < 1:
        raise bad_value("grid", text, "N must be >= 1", InvalidParameterError)
    if count > 1 and not start < stop:
        raise bad_value("grid", text, "START must be below STOP (bounds reversed?)",
                        InvalidParameterError)  # fmt: skip
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise bad_value("grid", text, "START and STOP must be finite", InvalidParameterError)
    return GridAxis(name.strip(), np.linspace(start, stop, count))


@frozen
class Grid:
    """The axes of a sweep (their order is the dataset's dimensions')."""

    axes: tuple = field(converter=tuple)

    def __attrs_post_init__(self):
        names = [a.name for a in self.axes]
        if not names:
            raise bad_value("grid", [], "give at least one axis NAME=START:STOP:N",
                            InvalidParameterError)  # fmt: skip
        if len(set(names)) != len(names):
            raise bad_value(
                "grid", names, "each parameter may be swept once", InvalidParameterError
            )

    @classmethod
    def of(cls, axes: Mapping[str, Sequence[float]] | Sequence[GridAxis]) -> Grid:
        if isinstance(axes, Mapping):
            return cls(tuple(GridAxis(k, v) for k, v in axes.items()))
        return cls(tuple(axes))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    def point(self, flat: int) -> dict[str, float]:
        """The parameter values at a flat (C-order) index."""
        index = np.unravel_index(flat, self.shape)
        return {a.name: a.values[i] for a, i in zip(self.axes, index, strict=True)}

    def describe(self) -> list:
        """A JSON-able description (name, first, last, count) per axis."""
        return [[a.name, a.values[0], a.values[-1], len(a.values)] for a in self.axes]
