"""`perturb response` (issue 18): the JSON contract, the plot, bad input with one line and exit 2."""

from __future__ import annotations

import json

import pytest

from perturb.cli import main

POINT_KEYS = {
    "value",
    "branch",
    "amplitudes",
    "norms",
    "stable",
    "eigenvalues",
    "multipliers",
    "note",
}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_response_json_contract(capsys):
    code, out, err = run(
        capsys, "response", "forced-duffing", "--sweep", "Omega=1.0:1.1:5", "--format", "json"
    )
    assert code == 0, err
    data = json.loads(out)
    assert set(data) == {
        "problem", "parameter", "order", "epsilon", "parameters", "points", "folds", "backbone",
        "true", "failures",
    }  # fmt: skip
    assert data["parameter"] == "Omega" and data["order"] == 1
    assert all(set(p) == POINT_KEYS for p in data["points"])
    at_105 = [p for p in data["points"] if p["value"] == pytest.approx(1.05)]
    assert [p["branch"] for p in at_105] == ["lower", "middle", "upper"]
    assert [p["stable"] for p in at_105] == [True, False, True]
    (fold,) = data["folds"]
    assert 1.0 < fold["value"] < 1.05
    assert data["backbone"]["values"][0] == pytest.approx(1.0)  # the free frequency at rest


def test_response_csv_and_plot(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "response.png"
    code, out, err = run(
        capsys, "response", "parametric-duffing", "--sweep", "Omega=1.9:2.1:5", "--format", "csv",
        "--plot", str(plot),
    )  # fmt: skip
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0] == "Omega,branch,x_amplitude,stable"
    assert any(",trivial,0," in line for line in lines)
    assert plot.stat().st_size > 0


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--sweep", "Omega=1.2:1.0:5"], "START must be below STOP"),
        (["--sweep", "Omega=1.0:1.2:1"], "between 2 and"),
        (["--sweep", "Omga=1.0:1.2:5"], "did you mean 'Omega'"),
        (["--sweep", "Omega=-1:1:5"], "Omega > 0"),
        (["--sweep", "Omega=1.0:1.2"], "NAME=START:STOP:N"),
        (
            ["--sweep", "Omega=1.0:1.2:5", "--set", "zeta=0", "--set", "gamma=0"],
            "no bounded response",
        ),
        (["--sweep", "Omega=1.0:1.2:5", "--validate", "-1"], "whole number >= 0"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv, words):
    code, out, err = run(capsys, "response", "forced-duffing", *argv)
    assert code == 2 and out == ""
    assert words in err and len(err.strip().splitlines()) == 1


def test_a_free_problem_has_no_frequency_response(capsys):
    code, _, err = run(capsys, "response", "duffing", "--sweep", "eps=0.1:0.2:3")
    assert code == 2 and "not driven" in err
