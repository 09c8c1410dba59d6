"""Nothing unbounded, nothing silent, nothing a user's code raises left unnamed: sizes checked
before anything is built, FIFOs and devices refused as inputs, values starting with '-' accepted,
two outputs naming one file refused, every BaseException of a user's hook one line, overflowing
inputs refused with the reason, every ``--format json`` strict JSON. In process, each refused
before any work (the corpus runs them in fresh processes: tests/cli/hostile_classes.py)."""

from __future__ import annotations

import json
import math
import os

import pytest

from perturb._defaults import AXIS_MAX_VALUES, MAX_ORDER, PARAMETER_MAX_MAGNITUDE
from perturb.axis import axis_size, parse_axis
from perturb.cli import main
from perturb.cost import census_seconds, response_cost, work_precision_cost
from perturb.errors import InvalidParameterError
from perturb.report.json_text import NON_FINITE_KEY, json_text
from tests.cli.hostile_files import GOOD_FILE, PROBLEM_FILES

GOOD = PROBLEM_FILES[GOOD_FILE][0]


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _one_error(code, out, err, *words):
    lines = [line for line in err.splitlines() if not line.startswith("perturb: warning")]
    assert code == 2 and len(lines) == 1 and lines[0].startswith("perturb: error:"), err
    assert "internal error" not in err and "Traceback" not in err
    for word in words:
        assert word in err, err


def _strict(text: str):
    def refuse(word):
        raise ValueError(f"{word} is not JSON")

    return json.loads(text, parse_constant=refuse)


# ---------------------------------------------------------------------------------- sizes
def test_an_axis_is_counted_before_any_value_is_made():
    assert axis_size("eps=0.01:0.2:1000000000000", most=10**13) == 10**12  # no 8 TB made
    with pytest.raises(InvalidParameterError, match="at most"):
        parse_axis("eps=0.01:0.2:1000000000")  # refused at once, nothing built
    with pytest.raises(InvalidParameterError, match="at most"):
        parse_axis("eps=0:1:" + "9" * 40)
    assert parse_axis(f"eps=0:1:{AXIS_MAX_VALUES}").size == AXIS_MAX_VALUES


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["solve", "duffing", "--times", "0:1e6:10000000"], ["--times", "1000000"]),
        (["solve", "duffing", "--times", "@/dev/zero"], ["device"]),
        (["solve", "duffing", "--times", "@."], ["folder"]),
        (["work-precision", "duffing", "--orders", "13"], ["--orders 13", f"{MAX_ORDER}"]),
        (["work-precision", "duffing", "--repeat", "1000"], ["--repeat 1000", "at most 100"]),
        (["work-precision", "duffing", "--periods", "1000", "--repeat", "50"], ["--yes"]),
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:1000000000"], ["at most"]),
        (["phase-diagram", "forced-duffing", "--set", "Omega=1", "--grid", "Omega=0.9:1.1:3",
          "--grid", "F=0.5:1:3"], ["also set with --set"]),
    ],
)  # fmt: skip
def test_sizes_and_silent_cuts_are_refused_first(capsys, tmp_path, monkeypatch, argv, words):
    monkeypatch.chdir(tmp_path)
    _one_error(*run(capsys, *argv), *words)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs are POSIX")
def test_a_fifo_with_no_writer_is_refused_not_waited_on(capsys, tmp_path, monkeypatch):
    os.mkfifo(tmp_path / "times")
    monkeypatch.chdir(tmp_path)
    _one_error(*run(capsys, "solve", "duffing", "--times", "@times"), "FIFO")


def test_the_cost_counts_modes_and_answers_at_once():
    one, four = response_cost(3, 3, 0, modes=1), response_cost(3, 3, 0, modes=4)
    assert four.seconds > 100 * one.seconds and "4 modes" in four.what
    assert census_seconds(3) > census_seconds(2) > census_seconds(1)
    assert math.isinf(census_seconds(10**6))  # past any estimate, no OverflowError
    huge = response_cost(10**18, 12, 50, 10_000, modes=10**6)
    assert huge.seconds > 3600
    assert work_precision_cost(10, 3, 100).seconds > work_precision_cost(10, 3, 1).seconds


# ---------------------------------------------------------------------------------- valid input
def test_values_starting_with_a_dash_are_values(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, "solve", "duffing", "--times", "-1,0,1", "--format", "json")
    assert code == 0, err
    assert _strict(out)["t"] == [-1.0, 0.0, 1.0]
    code, out, err = run(capsys, "solve", "duffing", "--output", "-o.json", "--format", "json")
    assert code == 0 and out == "", err
    assert _strict((tmp_path / "-o.json").read_text())["problem"] == "duffing"
    # a forgotten value stays an error: the next word is an option
    _one_error(*run(capsys, "solve", "duffing", "--set", "--order", "2"), "--set")


def test_a_tiny_parameter_swept_is_not_refused_with_a_value_never_given(capsys):
    code, out, err = run(capsys, "response", "forced-duffing", "--sweep", "eps=1e-6:2e-6:3",
                         "--order", "1")  # fmt: skip
    assert code == 0, err
    assert "invalid" not in err


# ---------------------------------------------------------------------------------- outputs
@pytest.mark.parametrize("plot", ["same.png", "./same.png", "data/../same.png", "link.png"])
def test_two_outputs_naming_one_file_are_refused(capsys, tmp_path, monkeypatch, plot):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "data").mkdir()
    (tmp_path / "same.png").write_bytes(b"")
    (tmp_path / "link.png").symlink_to("same.png")
    argv = ["work-precision", "duffing", "--plot", plot, "--output", "same.png"]
    _one_error(*run(capsys, *argv), "name the same file")
    assert (tmp_path / "same.png").read_bytes() == b""


# ---------------------------------------------------------------------------------- user code
HOOKS = {
    "exit0.py": "raise SystemExit(0)",
    "keyboard.py": "raise KeyboardInterrupt",
    "generator.py": "raise GeneratorExit",
    "bare.py": "raise BaseException('bare')",
}


@pytest.mark.parametrize("name", sorted(HOOKS))
@pytest.mark.parametrize("command", ["solve", "validate", "families"])
def test_a_hook_raising_a_base_exception_is_one_line_naming_it(
    capsys, tmp_path, monkeypatch, name, command
):
    (tmp_path / name).write_text(GOOD.replace('return {"amplitudes": {"x": A}}', HOOKS[name]))
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, command, name)
    _one_error(code, out, err, f"{name}:")
    assert str(tmp_path / name) in err


# ---------------------------------------------------------------------------------- overflow, JSON
@pytest.mark.parametrize(
    "argv",
    [
        ["solve", "disk", "--set", "r0=1e308", "--format", "json"],
        ["families", "resonant-pair", "--set", "kappa=1e308"],
        ["solve", "linear-pair", "--set", "kappa=1e308"],
        ["response", "forced-duffing", "--sweep", "F=1e150:1e151:3"],
    ],
)
def test_inputs_that_overflow_fail_with_that_reason(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 1 and out == "" and err.startswith("perturb: failed:"), err
    assert "past the floats" in err and "internal error" not in err


def test_a_duffing_started_past_its_separatrix_is_refused(capsys):
    _one_error(*run(capsys, "solve", "duffing", "--set", "eps=-1"), "separatrix")


def test_the_parameter_bound_is_the_documented_one():
    from perturb.errors import ParameterOverflowError
    from problems import get_problem

    edge = get_problem("linear-pair").create(kappa=PARAMETER_MAX_MAGNITUDE)
    assert edge.values["kappa"] == PARAMETER_MAX_MAGNITUDE
    with pytest.raises(ParameterOverflowError, match="past the floats"):
        get_problem("linear-pair").create(kappa=PARAMETER_MAX_MAGNITUDE * 10)


def test_a_response_with_no_steady_state_anywhere_is_a_failed_run(capsys):
    code, out, err = run(capsys, "response", "forced-duffing", "--sweep", "F=1e10:1e11:3",
                         "--order", "1")  # fmt: skip
    assert code == 1 and "no steady state" in err, err


def test_json_text_is_strict_and_says_where_it_wrote_null():
    text = json_text({"period": float("inf"), "points": [1.0, float("nan")], "n": 2})
    data = _strict(text)
    assert data["period"] is None and data["points"] == [1.0, None]
    assert data[NON_FINITE_KEY] == ["period", "points[1]"]
    assert _strict(json_text({"a": 1.0})) == {"a": 1.0}  # nothing added when all is finite


def test_a_sweeps_json_with_points_that_failed_is_strict(capsys):
    pytest.importorskip("distributed")
    code, out, err = run(capsys, "sweep", "duffing", "--grid", "eps=-1.5,0.1", "--format",
                         "json", "--workers", "1", "--quiet")  # fmt: skip
    assert code == 0, err
    data = _strict(out)
    assert NON_FINITE_KEY in data  # the point past the separatrix has no period: null, said


# ---------------------------------------------------------------------------------- internal errors
def test_a_step_in_a_parameter_map_has_a_rate(tmp_path):
    from perturb.case import ParameterMap
    from problems import load_problem

    driven = PROBLEM_FILES["driven.py"][0]
    text = driven.replace('ParameterSpec("sigma", 0.0, "detuning"),',
                          'ParameterSpec("Omega", 1.0, "frequency"),')  # fmt: skip
    text += '\n    parameter_map = {"sigma": "Heaviside(Omega - 1)*(Omega - 1)/eps"}\n'
    (tmp_path / "step.py").write_text(text)
    problem = load_problem(f"{tmp_path / 'step.py'}:Driven").create(Omega=1.05)
    rates, _ = problem.case().rate("Omega")
    assert rates["sigma"] == pytest.approx(1 / 0.05)  # off the jump: the derivative of the ramp
    assert isinstance(problem.case().map, ParameterMap)


def test_a_problem_that_cannot_be_pickled_is_one_line(capsys, tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    text = GOOD.replace(
        '    name = "good"', '    name = "good"\n    guard = __import__("threading").Lock()'
    )
    (tmp_path / "lock.py").write_text(text)
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, "sweep", "lock.py", "--grid", "eps=0.05,0.1", "--format", "csv",
                         "--workers", "1", "--quiet")  # fmt: skip
    _one_error(code, out, err, "lock.py", "cannot be sent to the Dask workers", "pickl")


def test_an_output_file_saved_by_the_user_during_the_run_is_kept(capsys, tmp_path, monkeypatch):
    """--output is checked before the work and looked at again before it is written: a file the
    user saved there meanwhile is theirs (one line, exit 2, the file kept)."""
    import perturb.cli._main as entry

    real = entry._COMMANDS["solve"]

    def slow(args):
        code = real(args)
        (tmp_path / "out.json").write_text("saved meanwhile\n")
        return code

    monkeypatch.setitem(entry._COMMANDS, "solve", slow)
    monkeypatch.chdir(tmp_path)
    _one_error(*run(capsys, "solve", "duffing", "--output", "out.json"), "out.json")
    assert (tmp_path / "out.json").read_text() == "saved meanwhile\n"
