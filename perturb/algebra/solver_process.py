"""A budgeted solve where a fork is not safe: one warm helper interpreter per process.

A Dask worker is a daemonic process (it may not start ``multiprocessing`` children) and runs its
tasks in threads (a fork from one copies the locks other threads hold). There the solve is sent
to a helper interpreter started with ``python -P`` (nothing from the working folder on its path),
which imports sympy once and then answers request after request; when a budget is spent the
helper is killed, and the next solve starts a new one. Starting an interpreter per solve cost
0.5-1.2 s each; a phase diagram's line asks for dozens.

The messages are pickles framed by their length (8 bytes, little-endian): the request
``(solver, eqs, unknowns)``, the reply ``(kind, value)`` with ``kind`` ``"ok"`` or ``"error"``.
"""

from __future__ import annotations

import os
import pickle
import queue
import subprocess
import sys
import threading

from perturb._defaults import CHILD_START_SECONDS

__all__ = ["solve_in_helper"]

#: Bytes of a message's length prefix.
_HEAD = 8
#: The helper's first message, once its imports are done.
_READY = b"ready"

#: The helper's program: its replies go to a copy of the standard output, and whatever a solver
#: prints goes to the standard error (thrown away), so a print cannot break a message.
_PROGRAM = """\
import os, pickle, sys
import sympy
out = os.fdopen(os.dup(1), "wb")
os.dup2(2, 1)
def send(data):
    out.write(len(data).to_bytes(8, "little") + data)
    out.flush()
send(b"ready")
source = sys.stdin.buffer
while True:
    head = source.read(8)
    if len(head) < 8:
        break
    payload = source.read(int.from_bytes(head, "little"))
    try:
        solver, eqs, unknowns = pickle.loads(payload)
        reply = ("ok", solver(eqs, unknowns))
    except Exception as exc:
        reply = ("error", exc)
    try:
        data = pickle.dumps(reply)
    except Exception as exc:
        data = pickle.dumps(("error", NotImplementedError(repr(exc))))
    send(data)
"""


class _Helper:
    """One helper interpreter, and a thread that reads its messages into a queue."""

    def __init__(self) -> None:
        self.owner = os.getpid()
        self.process = subprocess.Popen(
            [sys.executable, "-P", "-c", _PROGRAM],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        self.replies: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, daemon=True, name="perturb-solver-reader").start()
        try:
            ready = self._next(CHILD_START_SECONDS)
        except TimeoutError:
            self.kill()
            raise NotImplementedError("the solver process did not start") from None
        if ready != _READY:
            self.kill()
            raise NotImplementedError("the solver process did not start")

    def _read(self) -> None:
        stream = self.process.stdout
        while True:
            head = stream.read(_HEAD)
            if len(head) < _HEAD:
                self.replies.put(None)
                return
            self.replies.put(stream.read(int.from_bytes(head, "little")))

    def _next(self, seconds: float):
        try:
            return self.replies.get(timeout=seconds)
        except queue.Empty:
            raise TimeoutError from None

    def alive(self) -> bool:
        return self.owner == os.getpid() and self.process.poll() is None

    def solve(self, payload: bytes, seconds: float) -> tuple[str, object]:
        try:
            self.process.stdin.write(len(payload).to_bytes(_HEAD, "little") + payload)
            self.process.stdin.flush()
        except OSError:
            raise NotImplementedError("the solver process died") from None
        data = self._next(seconds)
        if data is None:
            raise NotImplementedError("the solver process died")
        return pickle.loads(data)

    def kill(self) -> None:
        self.process.kill()
        self.process.wait()


_LOCK = threading.Lock()
_HELPER: list[_Helper] = []  # at most one, made on the first solve


def solve_in_helper(payload: bytes, seconds: float) -> tuple[str, object]:
    """The ``(kind, value)`` reply to the pickled request ``payload``, from this process's helper
    interpreter (started on first use, and again after a spent budget or a death).

    Raises
    ------
    TimeoutError
        When ``seconds`` pass without a reply (the helper is killed).
    NotImplementedError
        When the helper does not start or dies.
    """
    with _LOCK:
        if not (_HELPER and _HELPER[0].alive()):
            _HELPER[:] = [_Helper()]
        helper = _HELPER[0]
        try:
            return helper.solve(payload, seconds)
        except BaseException:
            helper.kill()
            _HELPER.clear()
            raise
