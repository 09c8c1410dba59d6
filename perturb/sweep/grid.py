"""The grid of a sweep: its axes (``NAME=START:STOP:N``), its points and its chunks.

A grid is the product of its axes, in the order given; a point is numbered in C order (the last
axis fastest). A chunk is a rectangular block of points — whole rows of the last axes and a run of
the first one not whole — so that it is one chunk of every array of the store, and a task's
results are written with one write per variable.

This module knows neither the problems nor Dask: it parses, checks and counts.

Examples
--------
>>> grid = Grid((parse_axis("r0=0.5:1:3"), parse_axis("gamma3_0=0.1,0.2")))
>>> grid.shape, grid.size
((3, 2), 6)
>>> grid.point(3)
{'r0': 0.75, 'gamma3_0': 0.2}
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable, Iterator, Sequence

import numpy as np
from attrs import field, frozen

from perturb._defaults import SCENE_SUGGESTION_CUTOFF, SWEEP_MAX_POINTS
from perturb.errors import InvalidParameterError, UnknownNameError

__all__ = ["Axis", "Chunking", "Grid", "check_names", "check_size", "parse_axis"]

#: Spacings an axis may have: evenly spaced values, or evenly spaced logarithms.
SPACINGS = ("linear", "log")


def _fail(text: str, fix: str) -> InvalidParameterError:
    return InvalidParameterError(f"grid axis {text!r}: {fix}")


def _number(text: str, item: str) -> float:
    try:
        value = float(item)
    except ValueError:
        raise _fail(text, f"{item.strip()!r} is not a number; write NAME=START:STOP:N") from None
    if not math.isfinite(value):
        raise _fail(text, f"{item.strip()!r} is not finite; give finite values")
    return value


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
    values: tuple = field(converter=lambda v: tuple(float(x) for x in v))
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


def parse_axis(text: str) -> Axis:
    """An axis from ``NAME=START:STOP:N`` (N evenly spaced values, both ends included),
    ``NAME=START:STOP:N:log`` (evenly spaced logarithms; START and STOP of one sign) or
    ``NAME=V1,V2,...`` (the values as listed).

    Raises
    ------
    perturb.errors.InvalidParameterError
        Malformed text, N < 1 or not a whole number, a value that is not a finite number, a log
        axis through zero, repeated values.
    """
    if not isinstance(text, str):
        raise InvalidParameterError(
            f"grid axis {text!r}: write NAME=START:STOP:N as a string, e.g. 'r0=0.5:1:21'"
        )
    name, sep, rest = text.partition("=")
    name = name.strip()
    if not sep or not name or not rest.strip():
        raise _fail(text, "write NAME=START:STOP:N (or NAME=V1,V2,...), e.g. --grid r0=0.5:1:21")
    if ":" in rest:
        parts = rest.split(":")
        if len(parts) not in (3, 4):
            raise _fail(text, "write NAME=START:STOP:N or NAME=START:STOP:N:log")
        spacing = parts[3].strip() if len(parts) == 4 else "linear"
        if spacing not in SPACINGS:
            raise _fail(text, f"the spacing {spacing!r} is unknown: write :log or nothing")
        start, stop = _number(text, parts[0]), _number(text, parts[1])
        try:
            count = int(parts[2])
        except ValueError:
            raise _fail(text, f"N = {parts[2].strip()!r} must be a whole number >= 1") from None
        if count < 1:
            raise _fail(text, f"N = {count} points: give N >= 1")
        if count > SWEEP_MAX_POINTS:
            raise _fail(text, f"N = {count} points: give at most {SWEEP_MAX_POINTS:.0e} per axis")
        if count > 1 and start == stop:
            raise _fail(text, f"START = STOP = {start:g} with N = {count}: give N = 1 or a range")
        if spacing == "log":
            if start * stop <= 0:
                raise _fail(text, "a log axis needs START and STOP of one sign, neither zero")
            sign = math.copysign(1.0, start)
            values = sign * np.geomspace(abs(start), abs(stop), count)
        else:
            values = np.linspace(start, stop, count)
        if not np.all(np.isfinite(values)):
            raise _fail(text, "the values overflow; give a smaller range")
    else:
        items = [item for item in rest.split(",") if item.strip()]
        if not items:
            raise _fail(text, "give at least one value")
        values = np.array([_number(text, item) for item in items])
    if len(set(values.tolist())) != len(values):
        raise _fail(
            text, "the values repeat (a point would be computed twice); give distinct values"
        )
    return Axis(name, values, text.strip())


def _closest(name: str, names: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(names), n=1, cutoff=SCENE_SUGGESTION_CUTOFF)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_names(axes: Sequence[Axis], known: Iterable[str], problem: str, fixed=()) -> None:
    """Raise unless every axis names a parameter of ``problem`` once, and none is also fixed.

    Raises
    ------
    perturb.errors.UnknownNameError
        An axis over an unknown parameter (the closest known name is suggested).
    perturb.errors.InvalidParameterError
        The same parameter on two axes, or both swept and fixed (``--set``).
    """
    known = list(known)
    seen: set[str] = set()
    for axis in axes:
        if axis.name not in known:
            raise UnknownNameError(
                f"grid axis {axis.spec or axis.name!r}: {axis.name!r} is not a parameter of "
                f"{problem}{_closest(axis.name, known)}; the parameters are {', '.join(known)}"
            )
        if axis.name in seen:
            raise InvalidParameterError(
                f"grid axis {axis.spec!r}: {axis.name!r} is swept twice; give one --grid per parameter"
            )
        if axis.name in fixed:
            raise InvalidParameterError(
                f"grid axis {axis.spec!r}: {axis.name!r} is also set with --set; sweep it or set it, "
                "not both"
            )
        seen.add(axis.name)


def check_size(size: int, yes: bool) -> None:
    """Raise for a grid past :data:`SWEEP_MAX_POINTS`, or past :data:`SWEEP_CONFIRM_POINTS`
    without confirmation (the message says how many points and how to confirm): the points
    part of :func:`perturb.cost.check_cost`, the one rule of expensive requests."""
    from perturb.cost import Cost, check_cost

    check_cost(Cost(f"{size:,} points", size, 0.0), yes)


@frozen
class Grid:
    """The product of its axes (C order: the last axis varies fastest).

    Raises
    ------
    perturb.errors.InvalidParameterError
        No axis.
    """

    axes: tuple = field(converter=tuple)

    def __attrs_post_init__(self):
        if not self.axes:
            raise InvalidParameterError(
                "`grid` = () is invalid: give at least one axis, e.g. --grid eps=0.01:0.1:10"
            )

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(axis.name for axis in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(axis.size for axis in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def point(self, index: int) -> dict[str, float]:
        """The parameter values of the point numbered ``index`` (C order)."""
        where = np.unravel_index(index, self.shape)
        return {axis.name: axis.values[int(i)] for axis, i in zip(self.axes, where, strict=True)}

    def columns(self, indices) -> dict[str, np.ndarray]:
        """The parameter values of the points numbered ``indices`` (C order), one array per axis."""
        where = np.unravel_index(np.asarray(indices, dtype=np.int64), self.shape)
        return {axis.name: axis.array()[w] for axis, w in zip(self.axes, where, strict=True)}

    def as_list(self) -> list[dict]:
        return [axis.as_dict() for axis in self.axes]


@frozen
class Chunking:
    """The grid cut into rectangular blocks of about ``points`` points (whole trailing rows).

    Attributes
    ----------
    shape : tuple of int
        The grid's shape.
    chunk : tuple of int
        The block's shape: 1 on the leading axes, a run ``c`` on one axis, whole on the rest.
    """

    shape: tuple = field(converter=lambda v: tuple(int(x) for x in v))
    chunk: tuple = field(converter=lambda v: tuple(int(x) for x in v))

    @classmethod
    def of(cls, shape: Sequence[int], points: int, first: Sequence[int] = ()) -> Chunking:
        """Blocks of at most ``max(points, 1)`` points (fewer only where the grid ends), filled
        along the axes ``first`` before the others (a per-point derivation keeps its entering
        axes fixed within a block), then from the last axis."""
        points = max(int(points), 1)
        chunk = [1] * len(shape)
        inner = 1
        order = [*first, *(a for a in range(len(shape) - 1, -1, -1) if a not in first)]
        for axis in order:
            if inner * shape[axis] <= points:
                chunk[axis] = shape[axis]
                inner *= shape[axis]
            else:
                chunk[axis] = max(points // inner, 1)
                break
        return cls(shape, chunk)

    @property
    def counts(self) -> tuple[int, ...]:
        """Blocks along each axis."""
        return tuple(-(-n // c) for n, c in zip(self.shape, self.chunk, strict=True))

    @property
    def n_chunks(self) -> int:
        return math.prod(self.counts)

    def region(self, number: int) -> tuple[slice, ...]:
        """The block numbered ``number`` (C order over :attr:`counts`) as slices of the grid."""
        where = np.unravel_index(number, self.counts)
        return tuple(
            slice(int(i) * c, min((int(i) + 1) * c, n))
            for i, c, n in zip(where, self.chunk, self.shape, strict=True)
        )

    def indices(self, number: int) -> np.ndarray:
        """The flat (C order) indices of the points of block ``number``, in C order of the block."""
        ranges = [np.arange(s.start, s.stop) for s in self.region(number)]
        mesh = np.meshgrid(*ranges, indexing="ij")
        return np.ravel_multi_index(tuple(m.ravel() for m in mesh), self.shape)

    def __iter__(self) -> Iterator[int]:
        return iter(range(self.n_chunks))
