"""One grammar for the values of a swept parameter, under ``perturb sweep --grid``,
``perturb response --sweep``, scenes and the phase diagrams: ``NAME=START:STOP:N`` (N evenly
spaced values, both ends included), ``NAME=START:STOP:N:log`` or ``NAME=V1,V2,...``.

Examples
--------
>>> parse_axis("Omega=0.9:1.1:3").values
(0.9, 1.0, 1.1)
>>> parse_axis("gamma=0.1,0.3").size
2
"""

from __future__ import annotations

import math

import numpy as np
from attrs import field, frozen

from perturb._defaults import AXIS_MAX_VALUES
from perturb.errors import InvalidParameterError

__all__ = ["Axis", "axis_size", "parse_axis"]

#: Spacings an axis may have: evenly spaced values, or evenly spaced logarithms.
SPACINGS = ("linear", "log")


def _fail(text: str, fix: str, argument: str = "grid axis") -> InvalidParameterError:
    return InvalidParameterError(f"{argument} {text!r}: {fix}")


def _number(text: str, item: str, argument: str = "grid axis") -> float:
    try:
        value = float(item)
    except ValueError:
        raise _fail(
            text, f"{item.strip()!r} is not a number; write NAME=START:STOP:N", argument
        ) from None
    if not math.isfinite(value):
        raise _fail(text, f"{item.strip()!r} is not finite; give finite values", argument)
    return value


def _floats(values) -> tuple:
    """``values`` as a tuple of Python floats (an array converted at C speed: 10⁷ values in a
    fraction of a second, where a loop over them took seconds)."""
    if isinstance(values, np.ndarray):
        return tuple(values.astype(float).ravel().tolist())
    return tuple(float(x) for x in values)


@frozen
class Axis:
    """One swept parameter: its name and its values (ascending or not, as given).

    Attributes
    ----------
    name : str
    values : tuple of float
    spec : str
        How it was written (``"r0=0.5:1:21"``), for messages and the store's attributes.
    """

    name: str
    values: tuple = field(converter=lambda v: _floats(v))
    spec: str = ""

    @property
    def size(self) -> int:
        return len(self.values)

    def as_dict(self) -> dict:
        return {"name": self.name, "values": list(self.values), "spec": self.spec}

    def array(self) -> np.ndarray:
        """The values as a read-only float array, made once per process (an axis of 10⁶ values
        converted for every chunk cost more than evaluating the chunk)."""
        entry = _ARRAYS.get(id(self))
        if entry is None or entry[0] is not self:
            if len(_ARRAYS) >= _ARRAYS_KEPT:
                _ARRAYS.clear()
            array = np.array(self.values, dtype=float)
            array.flags.writeable = False
            entry = _ARRAYS[id(self)] = (self, array)
        return entry[1]


#: Per process: each axis's values as an array, by the axis object's id (the axis kept beside it
#: so that the id is not reused); at most :data:`_ARRAYS_KEPT` axes.
_ARRAYS: dict[int, tuple] = {}
_ARRAYS_KEPT = 64


def _count(text: str, item: str, argument: str, most: int) -> int:
    """N of ``START:STOP:N``, checked against ``most`` before any value is made."""
    word = item.strip()
    if not word.lstrip("+-").isdigit() or len(word) > len(str(most)) + 1:
        if word.lstrip("+-").isdigit():  # a whole number of more digits than `most` has
            raise _fail(text, f"N = {word} points: give at most {most:,} per axis", argument)
        raise _fail(text, f"N = {word!r} must be a whole number >= 1", argument)
    count = int(word)
    if count < 1:
        raise _fail(text, f"N = {count} points: give N >= 1", argument)
    if count > most:
        raise _fail(text, f"N = {count:,} points: give at most {most:,} per axis", argument)
    return count


def axis_size(text: str, argument: str = "grid axis", most: int = AXIS_MAX_VALUES) -> int:
    """The number of values of the axis ``text`` (as :func:`parse_axis` reads it), counted
    without making them: N of ``NAME=START:STOP:N``, the items of ``NAME=V1,V2,...``.

    Raises
    ------
    perturb.errors.InvalidParameterError
        Malformed text, or N not a whole number from 1 to ``most``.

    Examples
    --------
    >>> axis_size("eps=0.01:0.2:1000")
    1000
    """
    if not isinstance(text, str):
        return parse_axis(text, argument).size  # the one-line refusal of a non-string
    name, sep, rest = text.partition("=")
    if ":" in rest:
        parts = rest.split(":")
        if len(parts) in (3, 4):
            return _count(text, parts[2], argument, most)
        return parse_axis(text, argument, most).size  # malformed: its one-line refusal
    return sum(1 for item in rest.split(",") if item.strip())


def parse_axis(text: str, argument: str = "grid axis", most: int = AXIS_MAX_VALUES) -> Axis:
    """An axis from ``NAME=START:STOP:N`` (N evenly spaced values, both ends included),
    ``NAME=START:STOP:N:log`` (evenly spaced logarithms; START and STOP of one sign) or
    ``NAME=V1,V2,...`` (the values as listed).

    ``most`` bounds N, checked before any value is made (default
    :data:`~perturb._defaults.AXIS_MAX_VALUES`).

    Raises
    ------
    perturb.errors.InvalidParameterError
        Malformed text, N < 1, past ``most`` or not a whole number, a value that is not a finite
        number, a log axis through zero, repeated values.
    """
    if not isinstance(text, str):
        raise InvalidParameterError(
            f"{argument} {text!r}: write NAME=START:STOP:N as a string, e.g. 'r0=0.5:1:21'"
        )
    name, sep, rest = text.partition("=")
    name = name.strip()
    if not sep or not name or not rest.strip():
        raise _fail(
            text,
            "write NAME=START:STOP:N (or NAME=V1,V2,...), e.g. "
            f"{argument if argument.startswith('-') else '--grid'} r0=0.5:1:21",
            argument,
        )
    if ":" in rest:
        parts = rest.split(":")
        if len(parts) not in (3, 4):
            raise _fail(text, "write NAME=START:STOP:N or NAME=START:STOP:N:log", argument)
        spacing = parts[3].strip() if len(parts) == 4 else "linear"
        if spacing not in SPACINGS:
            raise _fail(
                text, f"the spacing {spacing!r} is unknown: write :log or nothing", argument
            )
        start, stop = _number(text, parts[0], argument), _number(text, parts[1], argument)
        count = _count(text, parts[2], argument, most)
        if count > 1 and start == stop:
            raise _fail(
                text, f"START = STOP = {start:g} with N = {count}: give N = 1 or a range", argument
            )
        if spacing == "log":
            if start * stop <= 0:
                raise _fail(
                    text, "a log axis needs START and STOP of one sign, neither zero", argument
                )
            sign = math.copysign(1.0, start)
            values = sign * np.geomspace(abs(start), abs(stop), count)
        else:
            values = np.linspace(start, stop, count)
        if not np.all(np.isfinite(values)):
            raise _fail(text, "the values overflow; give a smaller range", argument)
    else:
        items = [item for item in rest.split(",") if item.strip()]
        if not items:
            raise _fail(text, "give at least one value", argument)
        if len(items) > most:
            raise _fail(text, f"{len(items):,} values: give at most {most:,} per axis", argument)
        values = np.array([_number(text, item, argument) for item in items])
    if np.unique(values).size != values.size:
        raise _fail(
            text,
            "the values repeat (a point would be computed twice); give distinct values",
            argument,
        )
    return Axis(name, values, text.strip())
