"""`perturb response --true` (issue 29, item 4): the JSON's true_curve entry, the table, the plot,
and bad input with one line and exit 2."""

from __future__ import annotations

import json
import math

import pytest

from perturb.cli import main
from perturb.oracle import heyoka_available

#: The undamped linear Mathieu oscillator: only x = 0 analytically, one true curve with two
#: branch points (the first tongue's edges), in a few seconds.
MATHIEU = ("parametric-duffing", "--set", "zeta=0", "--set", "gamma=0", "--sweep",
           "Omega=1.9:2.1:5")  # fmt: skip

slow_without_heyoka = pytest.mark.skipif(
    not heyoka_available(), reason="the true curves take minutes without heyoka"
)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@slow_without_heyoka
def test_true_curve_json_table_and_plot(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "response.png"
    code, out, err = run(capsys, "response", *MATHIEU, "--true", "60", "--format", "json",
                         "--plot", str(plot))  # fmt: skip
    assert code == 0, err
    entry = json.loads(out)["true_curve"]
    assert set(entry) == {
        "budget", "tolerance", "measure", "integrator", "curves", "bifurcations", "partings",
        "failures",
    }  # fmt: skip
    assert entry["budget"] == 60 and entry["failures"] == []
    assert entry["tolerance"] == 0.1 and entry["measure"] == "peak"  # --tol's and --measure's
    (curve,) = entry["curves"]
    assert curve["branches"] == ["trivial"] and curve["success"]
    assert 2 <= len(curve["points"]) <= 60
    point = curve["points"][0]
    assert set(point) == {"value", "state", "norms", "peaks", "harmonics", "multipliers", "stable"}
    kinds = [b["kind"] for b in entry["bifurcations"]]
    assert kinds == ["branch-point", "branch-point"]
    assert 1.94 < entry["bifurcations"][0]["value"] < 1.96 < entry["bifurcations"][1]["value"]
    assert plot.stat().st_size > 0

    code, out, err = run(capsys, "response", *MATHIEU, "--true", "--tol", "0.05")
    assert code == 0, err
    assert "true curves (shooting with the period fixed" in out
    assert out.count("branch-point Omega = 1.9") == 1 and "branch-point Omega = 2.04" in out


@slow_without_heyoka
def test_a_spent_budget_keeps_the_curve_and_says_so(capsys):
    code, out, err = run(capsys, "response", *MATHIEU, "--true", "6", "--format", "json")
    assert code == 0, err
    (curve,) = json.loads(out)["true_curve"]["curves"]
    assert curve["status"] == "MAX_POINTS" and not curve["success"]
    assert "budget of points was spent" in curve["message"]
    assert 2 <= len(curve["points"]) <= 6
    assert all(math.isfinite(p["value"]) for p in curve["points"])


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--true", "0"], "from 2 to 10000"),
        (["--true", "20000"], "the budget's maximum"),
        (["--true", "many"], "a whole number from 2 to 10000"),
        (["--true", "--tol", "nan"], "a finite number > 0"),
        (["--true", "--tol", "-1"], "a finite number > 0"),
    ],
)
def test_bad_true_input_is_one_line_and_exit_2(capsys, argv, words):
    code, out, err = run(capsys, "response", *MATHIEU, *argv)
    assert code == 2 and out == ""
    assert words in err and len(err.strip().splitlines()) == 1
