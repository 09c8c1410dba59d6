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
#: What issue 29 added to a point (the contract is extended, never renamed).
POINT_EXTENSIONS = {"peak", "first_harmonic", "error_estimate", "series_ok", "liouville", "curve"}
#: ... and the honest labels: whether the series vouches for the point (perturb.report.marks).
POINT_EXTENSIONS |= {"mark"}


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
        "true", "failures", "measure", "special", "curves", "true_curve",
    }  # fmt: skip
    assert data["true_curve"] is None  # only with --true
    assert data["parameter"] == "Omega" and data["order"] == 3  # the response's default order
    assert data["measure"]["name"] == "peak"  # the plotted default, and the JSON says which
    assert all(set(p) == POINT_KEYS | POINT_EXTENSIONS for p in data["points"])
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
    assert lines[0].startswith("Omega,branch,x_amplitude,stable,")  # extended, never renamed
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


USER_FILE = '''
import sympy as sp
from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, V, TH = sp.symbols("x xdot theta")
MU, K, SIGMA = sp.symbols("mu k sigma")


class ForcedVanDerPol(Problem):
    """A user's own: x'' + x = eps [mu (1 - x^2) x' + k cos(Omega t)], Omega = 1 + eps sigma."""

    name = "forced-vdp"
    summary = "forced van der Pol (a user's file)"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter"),
        ParameterSpec("mu", 1.0, "negative damping"),
        ParameterSpec("k", 1.0, "forcing"),
        ParameterSpec("sigma", 0.0, "detuning"),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [V], [1], [EPS * (MU * (1 - X**2) * V + K * sp.cos(TH))],
            parameters=[MU, K, SIGMA], excitation=Excitation(TH, 1, SIGMA),
        )
'''


def test_a_users_own_forced_oscillator_from_one_file(capsys, tmp_path):
    """Issue 18's 'done when': a forced oscillator of one's own, in one file, its response with
    stable and unstable branches, and `perturb validate` at a chosen point."""
    path = tmp_path / "forced_vdp.py"
    path.write_text(USER_FILE)
    code, out, err = run(
        capsys, "response", f"{path}:ForcedVanDerPol", "--sweep", "sigma=-1:1:9", "--format",
        "json",
    )  # fmt: skip
    assert code == 0, err
    points = json.loads(out)["points"]
    assert {p["stable"] for p in points} >= {True, False}  # frequency entrainment and its loss
    code, out, err = run(
        capsys, "validate", f"{path}:ForcedVanDerPol", "--set", "sigma=0", "--format", "json"
    )
    assert code == 0, err
    report = json.loads(out)
    assert report["outcome"] == "valid", report["verdict"]
    assert report["checks"]["stability"]["passed"] is True
