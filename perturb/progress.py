"""Progress of long computations, reported to whoever listens (the CLI draws a bar on stderr).

Library code never prints: a long loop wraps its iterable in :func:`track`, which tells the current
listener (a context variable, so threads and nested runs keep their own) how far it has come. With no
listener, :func:`track` costs one context-variable lookup per loop.

Examples
--------
>>> seen = []
>>> with listening(lambda label, done, total: seen.append((label, done, total))):
...     for _ in track(range(2), label="work"):
...         pass
>>> seen
[('work', 0, 2), ('work', 1, 2), ('work', 2, 2)]

A step that is not a loop (a derivation) is a :func:`stage`, told as one item of one:

>>> seen.clear()
>>> with listening(lambda label, done, total: seen.append((label, done, total))):
...     with stage("deriving"):
...         pass
>>> seen
[('deriving', 0, 1), ('deriving', 1, 1)]
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Callable, Iterable, Iterator, Sized
from typing import TypeVar

__all__ = ["Listener", "listening", "notify", "stage", "track"]

T = TypeVar("T")

#: ``listener(label, done, total)``; ``total`` is ``None`` when the length is not known.
Listener = Callable[[str, int, "int | None"], None]

_LISTENER: contextvars.ContextVar[Listener | None] = contextvars.ContextVar(
    "perturb_progress", default=None
)


@contextlib.contextmanager
def listening(listener: Listener | None) -> Iterator[None]:
    """Send the progress of every :func:`track` inside the block to ``listener`` (None: nobody)."""
    token = _LISTENER.set(listener)
    try:
        yield
    finally:
        _LISTENER.reset(token)


def track(items: Iterable[T], *, label: str, total: int | None = None) -> Iterator[T]:
    """Yield ``items``, telling the listener before the first and after each one.

    Parameters
    ----------
    items : iterable
        The work items.
    label : str
        What is being done, shown beside the bar (e.g. ``"work-precision"``).
    total : int, optional
        Number of items, when ``items`` has no ``len``.
    """
    listener = _LISTENER.get()
    if listener is None:
        yield from items
        return
    if total is None and isinstance(items, Sized):
        total = len(items)
    listener(label, 0, total)
    for done, item in enumerate(items, start=1):
        yield item
        listener(label, done, total)


def notify(label: str, done: int, total: int | None) -> None:
    """Tell the current listener (if any) how far a computation has come, when the work is not a
    loop over an iterable (e.g. points of a sweep finishing in chunks, in any order)."""
    listener = _LISTENER.get()
    if listener is not None:
        listener(label, done, total)


@contextlib.contextmanager
def stage(label: str) -> Iterator[None]:
    """Tell the listener that the step ``label`` runs while the block does (a derivation, a
    cluster starting: work with no count to report), as one item of one.

    Parameters
    ----------
    label : str
        What is being done (``"deriving the order-2 solution of disk"``).
    """
    listener = _LISTENER.get()
    if listener is None:
        yield
        return
    listener(label, 0, 1)
    try:
        yield
    finally:
        listener(label, 1, 1)
