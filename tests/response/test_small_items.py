"""The issue's small items and the bad input of the continued response (issue 29).

* ``perturb solve --family upper`` where no upper orbit exists: a failed run with the reason
  (exit 1), never a silent first-order leftover;
* a parametric problem written at ratio 1 (cos 2θ): x(t) and its half-period shift −x(t) are one
  branch, not two;
* a user's own driven problem refuses a detuning that makes Ω <= 0 (one line, exit 2);
* ``--plot`` to a folder that does not exist or in an unknown format fails before any computing,
  ``--validate`` above its budget, ``--tol`` that is not a positive number: one line, exit 2.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from perturb.cli import main

PARAMETRIC_AT_RATIO_1 = """
import sympy as sp
from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, V, TH = sp.symbols("x xdot theta")
Z, G, H, S = sp.symbols("zeta gamma h sigma")


class Parametric(Problem):
    name = "parametric-at-ratio-1"
    summary = "x'' + 2 zeta eps x' + (1 + 2 h eps cos 2 theta) x + gamma eps x^3 = 0, theta = Omega t"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small"),
        ParameterSpec("zeta", 0.1, "damping"),
        ParameterSpec("h", 1.0, "depth"),
        ParameterSpec("gamma", 1.0, "cubic"),
        ParameterSpec("sigma", 0.5, "detuning"),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [V], [1], [EPS * (-2 * Z * V - 2 * H * X * sp.cos(2 * TH) - G * X**3)],
            parameters=[Z, H, G, S], excitation=Excitation(TH, 1, S),
        )
"""


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_a_family_that_does_not_exist_here_fails_with_the_reason(capsys):
    code, out, err = run(capsys, "solve", "forced-duffing", "--set", "Omega=1.3", "--family",
                         "upper", "--order", "3")  # fmt: skip
    assert code == 1
    assert "no branch 'upper'" in out + err and "['response']" in out + err
    code, out, err = run(capsys, "solve", "forced-duffing", "--set", "Omega=1.3", "--family",
                         "uper")  # fmt: skip
    assert code == 2 and "choose from" in err  # a name no branch has anywhere: bad input


def test_a_parametric_problem_at_ratio_1_lists_each_orbit_once(capsys, tmp_path):
    path = tmp_path / "parametric.py"
    path.write_text(PARAMETRIC_AT_RATIO_1)
    code, out, err = run(capsys, "families", f"{path}:Parametric", "--format", "json")
    assert code == 0, err
    families = json.loads(out)["families"]
    amplitudes = [np.array(list(f["amplitudes"].values())) for f in families]
    for i, a in enumerate(amplitudes):  # no branch is another's half-period shift (a, b) -> -(a, b)
        for b in amplitudes[i + 1 :]:
            assert np.max(np.abs(a + b)) > 1e-6 or np.max(np.abs(a)) == 0
    names = [f["name"] for f in families]
    assert names == ["trivial", "lower", "upper"]  # the same count as parametric-duffing's


def test_a_users_driven_problem_refuses_a_nonpositive_frequency(capsys, tmp_path):
    path = tmp_path / "parametric.py"
    path.write_text(PARAMETRIC_AT_RATIO_1)
    code, _, err = run(capsys, "solve", f"{path}:Parametric", "--set", "sigma=-25")
    assert code == 2 and "Omega" in err and "<= 0" in err and len(err.strip().splitlines()) == 1
    code, _, err = run(capsys, "response", f"{path}:Parametric", "--sweep", "sigma=-30:0:4")
    assert code == 2 and "<= 0" in err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--plot", "no/such/folder/response.png"], "does not exist"),
        (["--plot", "response.unknown"], "is unknown: give a file name ending in"),
        (["--validate", "51"], "at most 50"),
        (["--tol", "0"], "--tol"),
        (["--tol", "abc"], "--tol"),
        (["--measure", "rms"], "--measure"),
    ],
)
def test_bad_response_options_fail_before_any_computing(capsys, monkeypatch, argv, words):
    if argv[0] == "--plot":
        pytest.importorskip("matplotlib")
    import perturb.response.model as model

    def refuse(*args, **kwargs):  # the check must come before any computing
        raise AssertionError("computed before the bad option was refused")

    monkeypatch.setattr(model, "problem_response", refuse)
    code, out, err = run(capsys, "response", "forced-duffing", "--sweep", "Omega=1:1.1:3", *argv)
    assert code == 2 and out == "" and words in err and len(err.strip().splitlines()) == 1


def test_a_tongue_edge_is_listed_once():
    """A branch point is met on both curves through it: the trivial one crosses it transversally
    (its secant converges), the nontrivial one turns there (located in λ to the square root of
    the tolerance only); the edge is listed once, at the trivial curve's location."""
    import numpy as np

    from perturb.response.model import problem_response
    from problems import get_problem

    result = problem_response(get_problem("parametric-duffing").create(), "Omega",
                              np.linspace(1.9, 2.1, 41))  # fmt: skip
    edges = [s for s in result.response.special if s.kind == "branch-point"]
    assert len(edges) == 2
    assert all(max(s.peak.values()) == 0.0 for s in edges)  # on x = 0 itself
