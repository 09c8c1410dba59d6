"""The CLI's promises (issue 10): exit 2 only for the user's input, exit 1 for a failed run, never a
traceback, no abbreviated options, every way of giving times, progress only when asked for."""

from __future__ import annotations

import io
import subprocess
import sys

import numpy as np
import pytest

from perturb import cli
from perturb.errors import InvalidParameterError
from perturb.progress import listening, track


def run(capsys, *argv):
    code = cli.main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def csv_times(out: str) -> np.ndarray:
    rows = out.strip().splitlines()[1:]
    return np.array([float(row.split(",")[0]) for row in rows])


def test_options_are_never_abbreviated(capsys):
    code, out, err = run(capsys, "work-precision", "duffing", "--order", "2")
    assert code == 2 and out == ""
    assert "--order" in err and len(err.strip().splitlines()) == 1


def test_times_as_start_stop_count(capsys):
    code, out, _ = run(capsys, "solve", "duffing", "--times", "0:2:5", "--format", "csv")
    assert code == 0
    np.testing.assert_array_equal(csv_times(out), np.linspace(0, 2, 5))


def test_times_from_a_file_one_per_line_or_csv(tmp_path, capsys):
    path = tmp_path / "times.txt"
    path.write_text("# my sampling\n0\n0.25, 0.5\n\n1.0  # last\n")
    code, out, _ = run(capsys, "solve", "duffing", "--times", f"@{path}", "--format", "csv")
    assert code == 0
    np.testing.assert_array_equal(csv_times(out), [0, 0.25, 0.5, 1.0])


def test_ten_thousand_times_from_a_file(tmp_path, capsys):
    wanted = np.linspace(0.0, 50.0, 10_000)
    path = tmp_path / "many.csv"
    path.write_text("\n".join(repr(float(t)) for t in wanted))
    code, out, _ = run(capsys, "solve", "duffing", "--times", f"@{path}", "--format", "csv")
    assert code == 0
    np.testing.assert_array_equal(csv_times(out), wanted)


@pytest.mark.parametrize(
    "times",
    [
        "@",
        "@/no/such/file",
        "0:1",
        "0:1:x",
        "0:1:0",
        "0:inf:3",
        "a,b",
        "nan",
        ",",
        "1e308:-1e308:3",
    ],
)
def test_bad_times_name_the_option(capsys, times):
    code, out, err = run(capsys, "solve", "duffing", "--times", times)
    assert code == 2 and out == ""
    assert err.startswith("perturb: error: --times") and len(err.strip().splitlines()) == 1


def test_an_internal_failure_is_exit_1_not_bad_input(capsys, monkeypatch):
    def broken(args):
        raise ValueError("operands could not be broadcast together")

    monkeypatch.setitem(cli._COMMANDS, "solve", broken)
    code, out, err = run(capsys, "solve", "duffing")
    assert code == 1 and out == ""
    assert "internal error" in err and "Traceback" not in err


def test_an_input_error_from_the_library_is_exit_2(capsys, monkeypatch):
    def refuses(args):
        raise InvalidParameterError("`r0` = -1.0 is invalid: pass a positive distance")

    monkeypatch.setitem(cli._COMMANDS, "solve", refuses)
    code, _, err = run(capsys, "solve", "duffing")
    assert code == 2 and "`r0` = -1.0" in err


def test_overflow_is_a_failed_run_with_a_reason(capsys, monkeypatch):
    def overflows(args):
        raise OverflowError("(34, 'Numerical result out of range')")

    monkeypatch.setitem(cli._COMMANDS, "validate", overflows)
    code, _, err = run(capsys, "validate", "duffing")
    assert code == 1 and "overflowed" in err and "Traceback" not in err


def test_non_finite_results_are_never_printed(capsys, monkeypatch):
    from problems.duffing import Duffing

    monkeypatch.setattr(Duffing, "period", lambda self, solution: float("nan"))
    code, out, err = run(capsys, "solve", "duffing", "--times", "0,1")
    assert code == 1 and out == ""
    assert "not finite" in err


def test_a_closed_pipe_ends_quietly():
    command = [sys.executable, "-m", "perturb", "solve", "duffing", "--times", "0:100:200000"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.readline()
    proc.stdout.close()  # what `| head -1` does
    err = proc.stderr.read().decode()
    proc.wait(timeout=120)
    assert "Traceback" not in err and "BrokenPipe" not in err


def test_progress_reaches_the_listener_and_nothing_without_one():
    seen = []
    with listening(lambda *event: seen.append(event)):
        assert list(track(iter("ab"), label="steps", total=2)) == ["a", "b"]
    assert seen == [("steps", 0, 2), ("steps", 1, 2), ("steps", 2, 2)]
    assert list(track([1, 2], label="quiet")) == [1, 2]  # no listener: just the items


def test_the_bar_draws_on_one_line_and_ends_it():
    stream = io.StringIO()
    bar = cli._ProgressBar(stream)
    for done in range(4):
        bar("work", done, 3)
    text = stream.getvalue()
    assert text.count("\r") == 4 and text.endswith("3/3\n")


def test_no_bar_when_stderr_is_not_a_terminal(capsys):
    code, _, err = run(capsys, "solve", "duffing", "--times", "0")
    assert code == 0 and "\r" not in err


def test_the_bar_shows_the_rate_and_the_time_left():
    stream = io.StringIO()
    now = [100.0]
    bar = cli._ProgressBar(stream, clock=lambda: now[0])
    bar("sweep", 200, 1000)  # resumed: 200 points were done before; the rate counts from here
    now[0] += 4.0
    bar("sweep", 600, 1000)
    line = stream.getvalue().split("\r")[-1]
    assert "100/s" in line and "ETA     4s" in line and line.endswith("600/1000")
    now[0] += 4.0
    bar("sweep", 1000, 1000)
    assert stream.getvalue().endswith("1000/1000\n")


@pytest.mark.parametrize("command", ["solve", "validate", "families"])
def test_a_driven_problem_past_the_floats_fails_with_its_reason(capsys, command):
    """eps = 1e308 puts the amplitude equations' coefficients past the floats: exit 1 saying so
    (it was an internal error, ``name 'inf' is not defined``, then a false "no real root
    (proved)")."""
    code, _, err = run(capsys, command, "forced-duffing", "--set", "eps=1e308")
    assert code == 1 and "past the floats" in err and "internal error" not in err
    assert "proved" not in err


def test_no_family_says_why_on_stderr(capsys):
    code, out, err = run(capsys, "families", "superharmonic-duffing", "--set", "eps=10")
    assert code == 1 and "no family" in out
    assert err.startswith("perturb: superharmonic-duffing: no family of periodic solutions: ")
