"""Every wait shown: what a long run is doing reaches stderr while it runs — a bar on a terminal,
periodic lines on a file or a pipe (``perturb sweep ... 2> log``) — and ``--quiet`` silences it.

The subprocess tests read stderr while the command still runs: the first line must arrive before
the process ends (a line printed at the end is no news of a wait). The reporter's own rules (when
a line is due, what it says) are checked with a clock of the test's own, so no assertion hangs on
a machine's speed.
"""

from __future__ import annotations

import io
import os
import pty
import select
import subprocess
import sys
import textwrap
import threading

import pytest

from perturb.cli import _ProgressBar
from perturb.cli._progress import Reporter, duration, reporter_for
from perturb.progress import listening, notify, stage, track

#: A problem whose loading waits inside a step: the CLI's plumbing (pipe, heartbeat, --quiet)
#: checked without depending on how fast a derivation is on this machine. The wait is several
#: times the first notice (PROGRESS_FIRST_SECONDS = 0.5 s).
_WAITING = """
import time

import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.progress import stage
from problems.base import ParameterSpec, Problem, positive

X, XDOT, A = sp.symbols("x xdot amplitude")


class Waiting(Problem):
    name = "waiting"
    summary = "x'' + x = -eps x^3, built slowly"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter"),
        ParameterSpec("amplitude", 1.0, "x(0), velocity zero", positive),
    )

    @classmethod
    def build_system(cls):
        with stage("waiting for the test"):
            time.sleep(2.5)
        return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], parameters=[A], name="waiting")

    def method_options(self):
        return {"amplitudes": {"x": A}}
"""


class Clock:
    def __init__(self):
        self.now = 1000.0

    def __call__(self):
        return self.now


def _lines(stream: io.StringIO) -> list[str]:
    return stream.getvalue().splitlines()


# ------------------------------------------------------------------ the reporter, on its own clock
def test_a_step_in_a_log_is_told_once_due_then_periodically_then_ended():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter), stage("deriving the order-2 solution of disk"):
        reporter.tick()
        assert out.getvalue() == ""  # a quick step says nothing
        clock.now += 0.6
        reporter.tick()
        assert _lines(out) == ["perturb: deriving the order-2 solution of disk ... 1s so far"]
        clock.now += 5
        reporter.tick()
        assert len(_lines(out)) == 1  # not yet due again
        clock.now += 5
        reporter.tick()
        assert _lines(out)[-1].endswith("... 11s so far")
    assert _lines(out)[-1] == "perturb: deriving the order-2 solution of disk: done in 11s"


def test_a_quick_step_leaves_no_line_in_a_log():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter):
        with stage("quick"):
            clock.now += 0.1
            reporter.tick()
        for _ in track(range(3), label="quick loop"):
            clock.now += 0.1
    assert out.getvalue() == ""


def test_a_loop_in_a_log_gives_its_count_rate_and_time_left():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter):
        notify("sweep disk", 0, 400)
        clock.now += 10
        notify("sweep disk", 100, 400)
        line = _lines(out)[-1]
        assert line.startswith("perturb: sweep disk: 100/400 (25%), 10/s")
        assert "about 30s left" in line and "10s so far" in line
        clock.now += 30
        notify("sweep disk", 400, 400)
    assert _lines(out)[-1] == "perturb: sweep disk: 400/400 done in 40s"


def test_a_resumed_loop_times_only_this_run():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter):
        notify("sweep", 300, 400)  # 300 points written by an earlier run
        clock.now += 10
        notify("sweep", 350, 400)
    assert "5/s, about 10s left" in _lines(out)[-1]


def test_the_innermost_step_is_shown_and_its_parent_again_after_it():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter), stage("sweep disk: deriving"):
        clock.now += 1
        reporter.tick()
        with stage("reducing the disk equations"):
            clock.now += 1
            reporter.tick()
        clock.now += 10
        reporter.tick()
    assert [line.split(" ...")[0].split(":")[1] for line in _lines(out)] == [
        " sweep disk",
        " reducing the disk equations",
        " reducing the disk equations",
        " sweep disk",
        " sweep disk",
    ]


def test_a_log_tells_the_outer_step_before_the_inner_one():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=False, clock=clock)
    with listening(reporter), stage("response duffing: the true curves"):
        with stage("branches followed"):
            clock.now += 0.6
            reporter.tick()
    assert [line.split(" ...")[0] for line in _lines(out)[:2]] == [
        "perturb: response duffing: the true curves",
        "perturb: branches followed",
    ]


def test_a_step_on_a_terminal_is_drawn_at_once_ticks_and_is_wiped():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=True, bar=_ProgressBar, clock=clock)
    with listening(reporter), stage("deriving the order-2 solution of disk"):
        assert out.getvalue() == "\rperturb: deriving the order-2 solution of disk ... 0s so far"
        clock.now += 3
        reporter.tick()
        assert out.getvalue().endswith("disk ... 3s so far")
    text = out.getvalue()
    assert text.endswith("\r") and text.split("\r")[-2].strip() == ""  # the line blanked


def test_a_loop_on_a_terminal_is_the_bar_and_stays_when_done():
    clock, out = Clock(), io.StringIO()
    reporter = Reporter(out, terminal=True, bar=_ProgressBar, clock=clock)
    with listening(reporter):
        with stage("deriving"):
            clock.now += 1
        for _ in track(range(4), label="sweep duffing"):
            clock.now += 1
    assert out.getvalue().endswith("[" + "#" * _ProgressBar.WIDTH + "] 4/4\n")


def test_the_heartbeat_thread_shows_a_silent_step():
    out = io.StringIO()
    reporter = Reporter(out, terminal=True).start()
    try:
        with listening(reporter), stage("a silent step"):
            for _ in range(100):  # the heartbeat redraws once a second: wait for it, 5 s at most
                if "1s so far" in out.getvalue():
                    break
                select.select([], [], [], 0.05)
    finally:
        reporter.close()
    assert "a silent step ... 1s so far" in out.getvalue()
    assert reporter.thread is not None and not reporter.thread.is_alive()


def test_no_reporter_for_a_callers_buffer():
    assert reporter_for(io.StringIO()) is None  # main() called with stderr captured: quiet


@pytest.mark.parametrize(
    ("seconds", "text"), [(0.4, "0s"), (42, "42s"), (187, "3m07s"), (7500, "2h05m")]
)
def test_durations(seconds, text):
    assert duration(seconds) == text


# ------------------------------------------------------------------ the command, as a process
def _started(tmp_path, *options, stderr=subprocess.PIPE):
    (tmp_path / "waiting.py").write_text(textwrap.dedent(_WAITING))
    argv = ["solve", str(tmp_path / "waiting.py"), "--times", "0", *options]
    return subprocess.Popen(
        [sys.executable, "-m", "perturb", *argv],
        stdout=subprocess.PIPE, stderr=stderr, text=True, cwd=tmp_path,
    )  # fmt: skip


def test_a_wait_is_told_on_a_pipe_while_it_lasts(tmp_path):
    proc = _started(tmp_path)
    first = proc.stderr.readline()  # blocks until the first line: it must come before the end
    running = proc.poll() is None
    out, rest = proc.communicate(timeout=300)
    assert first.startswith("perturb: waiting for the test ... ") and running, first + rest
    assert "perturb: waiting for the test: done in" in rest
    assert proc.returncode == 0 and "waiting" in out


def test_quiet_silences_it(tmp_path):
    proc = _started(tmp_path, "--quiet")
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0 and err == "" and "waiting" in out


def test_a_wait_is_drawn_on_a_terminal(tmp_path):
    leader, follower = pty.openpty()
    try:
        proc = _started(tmp_path, stderr=follower)
        os.close(follower)
        seen = b""
        while True:
            ready, _, _ = select.select([leader], [], [], 300)
            if not ready:
                break
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # the terminal closed: the process is done
                break
            if not chunk:
                break
            seen += chunk
        proc.communicate(timeout=300)
    finally:
        os.close(leader)
    text = seen.decode()
    assert proc.returncode == 0
    assert "\rperturb: waiting for the test ... 1s so far" in text
    segments = text.split("\r")
    assert segments[-1] == "" and segments[-2].strip() == ""  # the line was wiped at the end


def _full_pipe() -> tuple[int, int]:
    """A pipe whose buffer is full (nobody reads it): a blocking write to it would wait forever."""
    read, write = os.pipe()
    os.set_blocking(write, False)
    try:
        while True:
            os.write(write, b"x" * 65536)
    except BlockingIOError:
        pass
    os.set_blocking(write, True)
    return read, write


def test_a_full_pipe_never_holds_the_reporter_up():
    """The listener is called from the computation's own thread: a line that waited for room in
    a pipe nobody drains would stop the run. It is dropped instead, and counted."""
    read, write = _full_pipe()
    stream = os.fdopen(write, "w")
    clock = Clock()
    reporter = Reporter(stream, terminal=False, clock=clock)
    finished = []

    def run():
        with listening(reporter):
            for _ in track(range(5), label="work"):
                clock.now += 30  # every step due for a line
        finished.append(True)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(timeout=60)  # a generous bound: the loop itself takes microseconds
    blocked = thread.is_alive()
    os.close(read)  # a writer still waiting (the failure) now meets a broken pipe and ends
    thread.join(timeout=60)
    assert not blocked and finished, "the reporter waited on a full pipe"
    assert reporter.out.dropped >= 5


def test_a_command_whose_stderr_nobody_drains_still_ends(tmp_path):
    """End to end: the command's progress meets a full pipe (a caller reading only stdout) and
    the command ends with its answer all the same."""
    read, write = _full_pipe()
    try:
        proc = _started(tmp_path, stderr=write)
        os.close(write)
        out, _ = proc.communicate(timeout=300)
    finally:
        os.close(read)
    assert proc.returncode == 0 and "waiting" in out
