"""The CLI contract of issue 2: commands, JSON keys, exit codes, one-line errors."""

import json
import subprocess
import sys

import numpy as np
import pytest

from perturb.cli import main
from problems import get_problem


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_list_names_every_problem(capsys):
    code, out, _ = run(capsys, "list")
    assert code == 0
    for name in ("duffing", "van-der-pol", "linear-pair", "resonant-pair"):
        assert name in out


def test_solve_json_contract(capsys):
    code, out, _ = run(
        capsys, "solve", "duffing", "--set", "eps=0.05", "--order", "2", "--format", "json"
    )
    assert code == 0
    data = json.loads(out)
    for key in ("problem", "parameters", "epsilon", "order", "period", "t", "state"):
        assert key in data
    assert data["parameters"] == {"eps": 0.05, "amplitude": 1.0}
    assert set(data["state"]) == {"x", "xdot"}
    # default times: one period, 101 samples from t = 0
    t = np.array(data["t"])
    assert t.size == 101 and t[0] == 0 and t[-1] == pytest.approx(data["period"])
    # the printed state is the solution's
    problem = get_problem("duffing").create(eps=0.05)
    expected = problem.state(problem.solve(2), t)
    np.testing.assert_allclose(data["state"]["x"], expected["x"], rtol=1e-12)


def test_solve_times_and_csv(capsys):
    code, out, _ = run(capsys, "solve", "van-der-pol", "--times", "0,1.5", "--format", "csv")
    lines = out.strip().splitlines()
    assert code == 0 and lines[0] == "t,x,xdot" and len(lines) == 3
    assert float(lines[1].split(",")[1]) == pytest.approx(2.0)  # limit cycle amplitude at t = 0


def test_table_format_has_header_and_rows(capsys):
    code, out, _ = run(capsys, "solve", "linear-pair", "--times", "0,1")
    assert code == 0 and "period" in out and len(out.strip().splitlines()) == 5


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["solve", "nope"], "choose from"),
        (["solve", "duffing", "--set", "foo=1"], "`foo` is not a parameter"),
        (["solve", "duffing", "--set", "eps"], "NAME=VALUE"),
        (["solve", "duffing", "--set", "eps=abc"], "not a number"),
        (["solve", "duffing", "--order", "0"], "--order 0"),
        (["solve", "duffing", "--order", "1.5"], "not an integer"),
        (["solve", "duffing", "--times", "a,b"], "--times"),
        (["solve", "duffing", "--set", "amplitude=-1"], "`amplitude`"),
        (["solve", "duffing", "--set", "eps=nan"], "not finite"),
        (["solve", "duffing", "--euler"], "--euler"),
        (["frobnicate"], "invalid choice"),
        (["validate", "duffing", "--periods", "0"], "--periods"),
        (["validate", "duffing", "--integrator", "euler"], "use one of"),
        (["work-precision", "duffing", "--orders", "x"], "--orders"),
        (["work-precision", "duffing", "--repeat", "-2"], "--repeat"),
        (["reproduce", "nope"], "choose from ['paper']"),
    ],
)
def test_bad_input_is_one_line_exit_2(capsys, argv, fragment):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert fragment in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_failed_construction_exits_1(capsys, monkeypatch):
    from perturb import Status

    problem_cls = get_problem("duffing")
    original = problem_cls.solve

    def failing(self, order=1):
        return __import__("attrs").evolve(
            original(self, order), status=Status.NO_ROOT, message="forced"
        )

    monkeypatch.setattr(problem_cls, "solve", failing)
    code, _, err = run(capsys, "solve", "duffing")
    assert code == 1 and "forced" in err


@pytest.mark.parametrize("command", [[sys.executable, "-m", "perturb"], ["perturb"]])
def test_module_and_console_script(command):
    ok = subprocess.run(
        [*command, "solve", "duffing", "--times", "0"], capture_output=True, text=True
    )
    assert ok.returncode == 0 and "duffing" in ok.stdout
    bad = subprocess.run(
        [*command, "solve", "duffing", "--order", "x"], capture_output=True, text=True
    )
    assert (
        bad.returncode == 2
        and "Traceback" not in bad.stderr
        and len(bad.stderr.strip().splitlines()) == 1
    )


def test_latex_and_steps_only_when_asked(capsys):
    code, out, _ = run(capsys, "solve", "duffing", "--times", "0", "--format", "json")
    plain = json.loads(out)
    assert code == 0 and "latex" not in plain and "steps" not in plain
    code, out, _ = run(
        capsys, "solve", "duffing", "--times", "0", "--latex", "--steps", "--format", "json"
    )
    data = json.loads(out)
    assert "\\cos" in data["latex"] and data["latex"].count("\\\\") == 1  # x line and T line
    assert data["steps"][0].startswith("generating solution") and "Omega1" in data["steps"][1]


@pytest.mark.parametrize(
    "argv",
    [
        ["solve", "van-der-pol", "--set", "eps=5", "--order", "2"],
        ["solve", "resonant-pair", "--set", "eps=10"],
    ],
)
def test_series_outside_its_domain_fails_with_exit_1(capsys, argv):
    """Issue 9.4: formerly negative periods in a normal table with exit 0 (the disk's defaults:
    tests/rigid_body/test_disk.py)."""
    code, out, err = run(capsys, *argv)
    assert code == 1 and out == ""
    assert "outside its domain" in err and "not a positive number" in err
    code, out, _ = run(capsys, *argv, "--format", "json")
    data = json.loads(out)
    assert code == 1 and data["status"] == "failed" and "outside its domain" in data["reason"]
    assert isinstance(data["warnings"], list)


def test_solve_json_carries_warnings(capsys):
    code, out, _ = run(capsys, "solve", "duffing", "--times", "0", "--format", "json")
    assert code == 0 and json.loads(out)["warnings"] == []
