"""The grid of a sweep: its axes (``NAME=START:STOP:N``), its points and its chunks.

A grid is the product of its axes, in the order given; a point is numbered in C order (the last
axis fastest). A chunk is a rectangular block of points — whole rows of the last axes and a run of
the first one not whole — so that it is one chunk of every array of the store, and a task's
results are written with one write per variable.

This module knows neither the problems nor Dask: it checks and counts. An axis and its one
grammar are :mod:`perturb.axis` (shared with ``perturb response --sweep``).

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

from perturb._defaults import SCENE_SUGGESTION_CUTOFF
from perturb.axis import Axis, parse_axis
from perturb.errors import InvalidParameterError, UnknownNameError

__all__ = ["Axis", "Chunking", "Grid", "check_names", "check_size", "parse_axis"]


def _closest(name: str, names: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(names), n=1, cutoff=SCENE_SUGGESTION_CUTOFF)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_names(
    axes: Sequence[Axis], known: Iterable[str], problem: str, fixed=(), advice=None
) -> None:
    """Raise unless every axis names a parameter of ``problem`` once, and none is also fixed.

    ``advice(name)``, if given, says what to sweep instead of a name that is not a parameter
    (:meth:`perturb.case.ParameterMap.set_by`: a system symbol the parameter map sets), in place
    of the closest name.

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
            told = advice(axis.name) if advice is not None else ""
            raise UnknownNameError(
                f"grid axis {axis.spec or axis.name!r}: {axis.name!r} is not a parameter of "
                + (f"{problem}: {told}" if told else f"{problem}{_closest(axis.name, known)}")
                + f"; the parameters are {', '.join(known)}"
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
