"""What a long run is doing, told on stderr while it runs: a bar redrawn in place on a terminal,
periodic lines on a file or a pipe (``perturb sweep ... 2> log``), nothing with ``--quiet``.

The library tells a listener (:mod:`perturb.progress`) of loops (``track``, ``notify``) and of
steps with no count (``stage``: a derivation, a cluster starting). :class:`Reporter` is that
listener for the CLI: it keeps the steps under way as a stack (a derivation inside a report's
item), shows the innermost one, and a heartbeat thread keeps showing it while the library is busy
and says nothing (a derivation of twenty seconds is one event at its start and one at its end).

On a terminal a step is drawn at once and its elapsed time ticks; a loop is drawn by the CLI's bar
(``perturb: sweep disk 85.3/s ETA 1m43s [###....] 1200/10000``). Elsewhere a step gets a line
once it has lasted :data:`~perturb._defaults.PROGRESS_FIRST_SECONDS` and another every
:data:`~perturb._defaults.PROGRESS_LINE_SECONDS` while it lasts, with the count, the rate and the
time left for a loop, and a closing line when it ends; a quick command prints none.

Progress never holds a run up: a pipe that nobody drains (a caller reading only stdout) fills,
and a line that would wait for room in it is dropped rather than written (the computation that
told it, and the heartbeat, go on).
"""

from __future__ import annotations

import select
import threading
import time
from collections.abc import Callable

from perturb._defaults import (
    PROGRESS_FIRST_SECONDS,
    PROGRESS_LINE_SECONDS,
    PROGRESS_REDRAW_SECONDS,
    PROGRESS_TICK_SECONDS,
)

#: The words a progress line starts with (a log reader can tell them from warnings and errors).
PREFIX = "perturb: "


def duration(seconds: float) -> str:
    """``42s``, ``3m07s``, ``2h05m``."""
    seconds = int(round(max(seconds, 0.0)))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"


def _has_room(stream) -> bool:
    """Whether a write to ``stream`` returns at once: False only for a file descriptor the system
    says is full (a pipe nobody reads); a stream without one, or one the system cannot be asked
    about, is written to."""
    try:
        _, ready, _ = select.select([], [stream.fileno()], [], 0)
    except (AttributeError, OSError, ValueError):
        return True
    return bool(ready)


class _Line:
    """The stream, with the width of what stands on its current line (to wipe it).

    A text the stream has no room for is dropped (see the module's notes); ``dropped`` counts
    them.
    """

    def __init__(self, stream):
        self.stream = stream
        self.width = 0
        self.dropped = 0

    def write(self, text: str) -> None:
        if not _has_room(self.stream):
            self.dropped += 1
            return
        self.stream.write(text)
        tail = max(text.rfind("\r"), text.rfind("\n"))
        self.width = len(text) - tail - 1 if tail >= 0 else self.width + len(text)

    def flush(self) -> None:
        if _has_room(self.stream):
            self.stream.flush()

    def wipe(self) -> None:
        """Blank the current line and return to its start."""
        if self.width:
            self.write("\r" + " " * self.width + "\r")
            self.width = 0


class _Entry:
    """One step under way: a loop (``done`` of ``total``) or a stage (0 of 1)."""

    def __init__(self, label: str, done: int, total: int | None, now: float):
        self.label = label
        self.first = done  # work done before this run (a resumed sweep) is not timed
        self.done = done
        self.total = total
        self.started = now
        self.shown: float | None = None  # when it was last drawn or printed
        self.bar = None  # the terminal's bar of a loop

    @property
    def is_stage(self) -> bool:
        return self.total == 1 and self.done == 0

    def rate(self, now: float) -> float | None:
        count, seconds = self.done - self.first, now - self.started
        return count / seconds if count > 0 and seconds > 0 else None

    def line(self, now: float) -> str:
        """The step in one line, for a log: what, how far, how fast, how long still."""
        elapsed = duration(now - self.started)
        if self.is_stage:
            return f"{PREFIX}{self.label} ... {elapsed} so far"
        if not self.total:
            return f"{PREFIX}{self.label}: {self.done} done, {elapsed} so far"
        parts = [f"{self.done}/{self.total} ({100 * self.done // self.total}%)"]
        rate = self.rate(now)
        if rate is not None:
            parts.append(f"{rate:.3g}/s, about {duration((self.total - self.done) / rate)} left")
        else:
            parts.append("estimating the time left")
        return f"{PREFIX}{self.label}: {', '.join(parts)}, {elapsed} so far"


class Reporter:
    """The CLI's progress listener (``listener(label, done, total)``), with its heartbeat.

    Parameters
    ----------
    stream : file
        Where it writes (stderr).
    terminal : bool
        Draw in place (a terminal) rather than print lines (a file or a pipe).
    bar : callable, optional
        ``bar(stream)``: a new bar drawing a loop on a terminal (the CLI's ``_ProgressBar``).
    clock : callable
        Seconds, monotonic (tests pass their own).
    """

    def __init__(
        self,
        stream,
        *,
        terminal: bool,
        bar: Callable | None = None,
        clock: Callable[[], float] = time.monotonic,
    ):
        self.out = _Line(stream)
        self.terminal = terminal
        self.make_bar = bar
        self.clock = clock
        self.entries: list[_Entry] = []
        self.drawn: _Entry | None = None  # the entry standing on the terminal's line
        self.lock = threading.Lock()
        self.stopped = threading.Event()
        self.thread: threading.Thread | None = None

    # ------------------------------------------------------------------ the listener
    def __call__(self, label: str, done: int, total: int | None) -> None:
        with self.lock:
            now = self.clock()
            entry = self._entry(label, done, total, now)
            entry.done, entry.total = done, total
            if total is not None and done >= total:
                self._finish(entry, now)
            else:
                self._show(entry, now, event=True)

    def _entry(self, label: str, done: int, total: int | None, now: float) -> _Entry:
        for depth in range(len(self.entries) - 1, -1, -1):
            entry = self.entries[depth]
            if entry.label == label and done >= entry.done:
                # steps above it ended without saying so (a loop left early): gone
                for stale in self.entries[depth + 1 :]:
                    self._forget(stale)
                del self.entries[depth + 1 :]
                return entry
        entry = _Entry(label, done, total, now)
        self.entries.append(entry)
        return entry

    def _forget(self, entry: _Entry) -> None:
        if self.terminal and self.drawn is entry:
            self.out.wipe()
            self.drawn = None

    # ------------------------------------------------------------------ showing
    def _show(self, entry: _Entry, now: float, *, event: bool) -> None:
        if self.terminal:
            due = event or entry.shown is None or now - entry.shown >= PROGRESS_REDRAW_SECONDS
            if due:
                self._draw(entry, now)
            return
        if entry.shown is None:
            due = now - entry.started >= PROGRESS_FIRST_SECONDS
        else:
            due = now - entry.shown >= PROGRESS_LINE_SECONDS
        if due:
            # the steps it runs inside, not yet told, first: a log reads outside in
            told = [e for e in self.entries[: self.entries.index(entry)] if e.shown is None]
            for step in [*told, entry]:
                self.out.write(step.line(now) + "\n")
                step.shown = now
            self.out.flush()

    def _draw(self, entry: _Entry, now: float) -> None:
        if self.drawn is not entry:
            self.out.wipe()
        if entry.is_stage or self.make_bar is None:
            text = entry.line(now)
            pad = max(self.out.width - len(text) - 1, 0)
            self.out.write(f"\r{text}{' ' * pad}")
            self.out.flush()
        else:
            if entry.bar is None:
                entry.bar = self.make_bar(self.out)
                entry.bar(entry.label, entry.first, entry.total)  # the rate counts from here
            entry.bar(entry.label, entry.done, entry.total)
        self.drawn = entry
        entry.shown = now

    def _finish(self, entry: _Entry, now: float) -> None:
        depth = self.entries.index(entry)
        for stale in self.entries[depth + 1 :]:
            self._forget(stale)
        del self.entries[depth:]
        if self.terminal:
            if entry.bar is not None and not entry.is_stage:
                if self.drawn is not entry:
                    self.out.wipe()
                entry.bar(entry.label, entry.done, entry.total)  # the full bar, a new line
                self.out.width = 0
                self.drawn = None
            elif self.drawn is entry:
                self.out.wipe()  # a step done: its line makes way for what follows
                self.drawn = None
            if self.entries and self.drawn is None:
                self._draw(self.entries[-1], now)
        elif entry.shown is not None:
            total = f"{entry.done}/{entry.total} " if entry.total and entry.total > 1 else ""
            self.out.write(f"{PREFIX}{entry.label}: {total}done in "
                           f"{duration(now - entry.started)}\n")  # fmt: skip
            self.out.flush()

    # ------------------------------------------------------------------ the heartbeat
    def tick(self) -> None:
        """Show the innermost step if it is due (its elapsed time, its next line)."""
        with self.lock:
            if self.entries:
                self._show(self.entries[-1], self.clock(), event=False)

    def start(self) -> Reporter:
        """Start the heartbeat (a daemon thread); returns the reporter."""

        def beat() -> None:
            while not self.stopped.wait(PROGRESS_TICK_SECONDS):
                self.tick()

        self.thread = threading.Thread(target=beat, name="perturb-progress", daemon=True)
        self.thread.start()
        return self

    def close(self) -> None:
        """Stop the heartbeat; leave the terminal's line clean (the run is over)."""
        self.stopped.set()
        if self.thread is not None:
            self.thread.join()
        with self.lock:
            if self.terminal and self.drawn is not None:
                self.out.wipe()
            self.entries.clear()
            self.drawn = None


def reporter_for(stream, bar: Callable | None = None) -> Reporter | None:
    """The reporter of ``stream`` (started), or None where progress is not shown: a stream that
    is neither a terminal nor a file or pipe of this process (a caller's buffer)."""
    try:
        terminal = stream.isatty()
        if not terminal:
            stream.fileno()  # a file or a pipe: the lines go to it (a log)
    except (AttributeError, OSError, ValueError):
        return None
    return Reporter(stream, terminal=terminal, bar=bar).start()
