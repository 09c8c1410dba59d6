"""Honest labels: a response point whose labels the series cannot vouch for is marked wherever it
is shown (table, CSV, JSON, plot), so that no label the truth contradicts goes unmarked.

The case is a forced Helmholtz–Duffing (quadratic and cubic stiffness) written as docs/forced.md
says: at order 3 its middle branch near the upper fold is "stable" by the order-N multipliers
(max|λ| 0.975) while the true orbit, shot by ``perturb validate``, is unstable (|λ| 1.13).
"""

from __future__ import annotations

import csv
import io
import json
import math
import textwrap
from types import SimpleNamespace

import pytest

from perturb.cli import main
from perturb.report.marks import PointMark, point_mark

HELMHOLTZ_DUFFING = """
import sympy as sp
from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, V, TH = sp.symbols("x xdot theta")
ZETA, ALPHA, GAMMA, F, SIGMA = sp.symbols("zeta alpha gamma F sigma")


class HelmholtzDuffing(Problem):
    name = "helmholtz-duffing"
    summary = "x'' + x = eps [-2 zeta x' - alpha x^2 - gamma x^3 + F cos(Omega t)]"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter"),
        ParameterSpec("zeta", 0.1, "damping"),
        ParameterSpec("alpha", 0.5, "quadratic stiffness"),
        ParameterSpec("gamma", 1.0, "cubic stiffness"),
        ParameterSpec("F", 1.0, "forcing"),
        ParameterSpec("Omega", 1.0, "excitation frequency"),
    )
    parameter_map = {"sigma": "(Omega - 1)/eps"}

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [V], [1],
            [EPS * (-2 * ZETA * V - ALPHA * X**2 - GAMMA * X**3 + F * sp.cos(TH))],
            parameters=[ZETA, ALPHA, GAMMA, F, SIGMA],
            excitation=Excitation(TH, ratio=1, detuning=SIGMA),
        )
"""


def _point(*, ok=True, error=1e-4, peak=1.0, largest=0.97):
    return SimpleNamespace(
        series_ok=ok, error={"x": error}, peak={"x": peak}, multipliers=(complex(largest, 0),)
    )


@pytest.mark.parametrize(
    ("point", "mark"),
    [
        (_point(), PointMark.NONE),
        (_point(ok=False), PointMark.OUTSIDE),
        (_point(error=0.5, peak=2.0), PointMark.BEYOND),  # a quarter of the amplitude
        (_point(error=0.05, largest=0.975), PointMark.UNCERTAIN),  # 0.025 from 1, error 0.05
        (_point(error=0.01, largest=0.975), PointMark.NONE),  # error below the distance
        (_point(error=math.nan, largest=0.999), PointMark.NONE),  # no estimate: not judged
    ],
)
def test_the_checks_of_one_point(point, mark):
    assert point_mark(point) is mark


@pytest.fixture(scope="module")
def problem_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("marks") / "hd.py"
    path.write_text(textwrap.dedent(HELMHOLTZ_DUFFING))
    return f"{path}:HelmholtzDuffing"


def _run(capsys, *argv):
    code = main([*argv, "--quiet"])
    out, err = capsys.readouterr()
    assert code == 0, err
    return out


def test_every_label_the_truth_contradicts_is_marked(capsys, problem_file):
    sweep = ["response", problem_file, "--sweep", "Omega=1.23:1.25:3"]
    points = json.loads(_run(capsys, *sweep, "--format", "json"))["points"]
    middle = [p for p in points if p["branch"] == "middle"]
    assert len(middle) == 3 and all(p["stable"] for p in middle)  # what the series says
    for p in middle:  # the second route: the true orbit, shot by `perturb validate`
        report = json.loads(_run(capsys, "validate", problem_file, "--set",
                                 f"Omega={p['value']:.12g}", "--family", "middle",
                                 "--format", "json"))  # fmt: skip
        assert report["checks"]["stability"]["value"] > 1  # truly unstable
        assert p["mark"] in ("outside", "beyond", "uncertain"), p
    rows = list(csv.DictReader(io.StringIO(_run(capsys, *sweep, "--format", "csv"))))
    assert [r["mark"] for r in rows] == [p["mark"] for p in points]
    table = _run(capsys, *sweep)
    for p in middle:
        (row,) = [line for line in table.splitlines()
                  if line.split()[:2] == [f"{p['value']:g}", "middle"]]  # fmt: skip
        assert f"[{PointMark[p['mark'].upper()].value}]" in row


def test_the_plot_draws_the_marked_points_with_a_legend_entry(capsys, problem_file, tmp_path):
    pytest.importorskip("matplotlib")
    import numpy as np

    from perturb.report.plots import plot_frequency_response
    from perturb.response.model import problem_response
    from problems import load_problem

    problem = load_problem(problem_file).create()
    result = problem_response(problem, "Omega", np.linspace(1.23, 1.25, 3), order=3)
    marked = [p for p in result.response.points if point_mark(p) is not PointMark.NONE]
    figure = plot_frequency_response(result)
    (ax,) = figure.axes
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "label not vouched for by the series" in labels
    (line,) = [
        ln for ln in ax.get_lines() if ln.get_label() == "label not vouched for by the series"
    ]
    assert line.get_markerfacecolor() == "none" and len(line.get_xdata()) == len(marked) > 0
