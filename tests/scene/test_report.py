"""``perturb report SCENE --output DIR`` (issue 13 items 1-2): a scene computes only what its
[outputs] ask for (integrator calls counted, Euler angles and matplotlib watched) and the folder
holds exactly the files asked for; bad scenes and folders exit 2 with one line."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from perturb.cli import main
from perturb.oracle.base import IntegratorBase
from perturb.report.folder import MARKER
from perturb.scene import parse_scene, run_scene
from problems import get_problem

ROOT = Path(__file__).resolve().parents[2]

DUFFING = """
[problem]
name = "duffing"
[parameters]
eps = 0.05
[solve]
order = 2
periods = 2
samples = 40
"""


def _scene(tmp_path: Path, outputs: str, base: str = DUFFING, name: str = "scene.toml") -> Path:
    path = tmp_path / name
    path.write_text(base + "[outputs]\n" + textwrap.dedent(outputs), encoding="utf-8")
    return path


def _report(capsys, scene: Path, folder: Path) -> tuple[int, str, str]:
    code = main(["report", str(scene), "--output", str(folder), "--quiet"])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def integrations(monkeypatch):
    """Counts every call of the oracle's integrators (all of them go through IntegratorBase)."""
    calls = []
    original = IntegratorBase.integrate

    def counting(self, *args, **kwargs):
        calls.append(type(self).__name__)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(IntegratorBase, "integrate", counting)
    return calls


# ---------------------------------------------------------------------------------- laziness
def test_a_table_scene_integrates_nothing(integrations):
    scene = parse_scene(DUFFING + "[outputs]\ntable = true\nlatex = true\n")
    result = run_scene(scene, get_problem("duffing").create(eps=0.05))
    assert integrations == []
    assert result.computed == ("solve", "state")
    assert result.truth is None and result.validation is None and result.work_precision is None
    assert result.t.size == 2 * 40 + 1 and result.t[-1] == pytest.approx(2 * result.period)


def test_a_truth_plot_integrates_once_and_validation_more(integrations):
    problem = get_problem("duffing").create(eps=0.05)
    result = run_scene(parse_scene(DUFFING + "[outputs]\nplots = ['error']\n"), problem)
    assert len(integrations) == 1 and result.computed == ("solve", "state", "truth")
    assert set(result.truth) == {"x", "xdot"}
    # the true motion stays within the order-2 truncation error of the analytic one
    error = max(np.max(np.abs(result.truth[n] - result.state[n])) for n in result.truth)
    assert error < 10 * 0.05**3
    integrations.clear()
    result = run_scene(parse_scene(DUFFING + "[outputs]\nvalidation = true\n"), problem)
    assert result.computed == ("solve", "validation") and result.state is None
    assert len(integrations) >= 1 and result.validation.outcome.label == "valid"


def test_no_euler_angles_unless_asked(monkeypatch):
    from problems.rigid_body._body import FastSpinBody

    asked = []
    original = FastSpinBody.euler_angles
    monkeypatch.setattr(
        FastSpinBody, "euler_angles", lambda self, s, t: asked.append(1) or original(self, s, t)
    )
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    base = '[problem]\nname = "disk"\n[solve]\nperiods = 0.5\nsamples = 20\n'
    result = run_scene(parse_scene(base + "[outputs]\ntable = true\n"), disk)
    assert asked == [] and result.euler is None
    result = run_scene(parse_scene(base + "[outputs]\neuler = true\n"), disk)
    assert asked == [1] and set(result.euler) == {"theta", "psi", "phi"}
    assert result.state is None  # the angles alone do not write the state table


def test_euler_angles_of_a_problem_without_them_is_a_scene_error(capsys, tmp_path):
    scene = _scene(tmp_path, "euler = true\nplots = ['orientation']\n")
    code, out, err = _report(capsys, scene, tmp_path / "out")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "has no Euler angles" in err and "orientation" in err
    assert not (tmp_path / "out").exists()  # refused before anything was computed or written


def test_a_plot_free_scene_never_imports_matplotlib(tmp_path):
    scene = _scene(tmp_path, "table = true\nvalidation = true\n")
    code = (
        "import sys\n"
        "from perturb.cli import main\n"
        f"rc = main(['report', {str(scene)!r}, '--output', {str(tmp_path / 'out')!r}])\n"
        "assert rc == 0, rc\n"
        "print('matplotlib' in sys.modules)\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert run.stdout.strip().splitlines()[-1] == "False"
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(
        [MARKER, "scene.toml", "summary.md", "solution.csv", "solution.json", "validation.json"]
    )


# ---------------------------------------------------------------------------------- the folder
@pytest.mark.parametrize(
    "outputs, files",
    [
        ("", []),
        ("table = true", ["solution.csv", "solution.json"]),
        ("latex = true", ["solution.tex"]),
        ("validation = true", ["validation.json"]),
        ("plots = ['phase']\nformats = ['png', 'svg']", ["phase.png", "phase.svg"]),
        ("table = true\nplots = ['time_series', 'error']", [
            "solution.csv", "solution.json", "time_series.png", "error.png"]),
    ],
)  # fmt: skip
def test_the_folder_holds_exactly_what_was_asked(capsys, tmp_path, outputs, files):
    scene = _scene(tmp_path, outputs + "\n")
    folder = tmp_path / "out"
    code, out, err = _report(capsys, scene, folder)
    assert code == 0, err
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        [MARKER, "scene.toml", "summary.md", *files]
    )
    assert (folder / "scene.toml").read_text(encoding="utf-8") == scene.read_text(encoding="utf-8")
    summary = (folder / "summary.md").read_text(encoding="utf-8")
    assert out == summary and "# duffing: order 2" in summary
    for name in files:
        assert f"- {name}" in summary and (folder / name).stat().st_size > 0


def test_a_second_report_removes_the_files_no_longer_asked(capsys, tmp_path):
    folder = tmp_path / "out"
    (tmp_path / "keep").mkdir()
    _report(capsys, _scene(tmp_path, "table = true\nlatex = true\n"), folder)
    (folder / "notes.txt").write_text("mine")
    code, _, _ = _report(capsys, _scene(tmp_path, "latex = true\n"), folder)
    assert code == 0
    assert sorted(p.name for p in folder.iterdir()) == [
        MARKER, "notes.txt", "scene.toml", "solution.tex", "summary.md"]  # fmt: skip


def test_duffing_scene_end_to_end(capsys, tmp_path):
    scene = _scene(tmp_path, "table = true\nvalidation = true\nlatex = true\nplots = ['phase']\n")
    folder = tmp_path / "out"
    code, out, _ = _report(capsys, scene, folder)
    assert code == 0 and "verdict: VALID" in out
    table = np.genfromtxt(folder / "solution.csv", delimiter=",", names=True)
    assert table.dtype.names == ("t", "x", "xdot") and table.size == 2 * 40 + 1
    data = json.loads((folder / "solution.json").read_text())
    assert set(data) >= {"problem", "parameters", "epsilon", "order", "period", "t", "state"}
    np.testing.assert_array_equal(np.asarray(data["state"]["x"]), table["x"])
    assert json.loads((folder / "validation.json").read_text())["outcome"] == "valid"
    tex = (folder / "solution.tex").read_text()
    assert "\\begin{align*}" in tex and "x &= " in tex and "T &= " in tex


def test_a_scene_naming_a_problem_file(capsys, tmp_path):
    (tmp_path / "quadratic.py").write_text(
        textwrap.dedent("""
        import sympy as sp

        from perturb import EPS, QuasilinearSystem
        from problems.base import ParameterSpec, Problem, positive

        X, XDOT, A = sp.symbols("x xdot amplitude")


        class Quadratic(Problem):
            name = "quadratic"
            summary = "x'' + x = -eps x^2 started at rest from x(0) = amplitude"
            parameter_specs = (
                ParameterSpec("eps", 0.1, "strength of the quadratic term"),
                ParameterSpec("amplitude", 1.0, "initial displacement", positive),
            )

            @classmethod
            def build_system(cls):
                return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**2], parameters=[A])

            def method_options(self):
                return {"amplitudes": {"x": A}}
        """),
        encoding="utf-8",
    )
    base = f'[problem]\nname = "{tmp_path / "quadratic.py"}:Quadratic"\n[parameters]\neps = 0.05\n'
    scene = _scene(tmp_path, "table = true\nvalidation = true\n", base=base)
    code, out, err = _report(capsys, scene, tmp_path / "out")
    assert code == 0, err
    assert "# quadratic: order 1" in out and "verdict: VALID" in out
    assert (tmp_path / "out" / "solution.csv").read_text().startswith("t,x,xdot\n")


# ---------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "base, outputs, fragment",
    [
        (DUFFING.replace('"duffing"', '"dufing"'), "", "did you mean 'duffing'"),
        (DUFFING.replace('"duffing"', '"nowhere.py:X"'), "", "nowhere.py"),
        (DUFFING.replace("eps = 0.05", "epss = 0.05"), "", "did you mean 'eps'"),
        (DUFFING.replace("eps = 0.05", "amplitude = -1"), "", "amplitude"),
        (DUFFING + "integrator = 'rk5'\n", "validation = true", "rk5"),
        (DUFFING, "plots = ['eror']", "did you mean 'error'"),
        (DUFFING, "tabel = true", "did you mean 'table'"),
        ("[problem\n", "", "line 1"),
    ],
)
def test_bad_scenes_exit_2_with_one_line(capsys, tmp_path, base, outputs, fragment):
    scene = _scene(tmp_path, outputs + "\n", base=base)
    code, out, err = _report(capsys, scene, tmp_path / "out")
    assert code == 2 and out == ""
    assert err.startswith("perturb: error: ") and err.count("\n") == 1, err
    assert fragment in err and "Traceback" not in err


def test_an_unwritable_folder_exits_2(capsys, tmp_path):
    scene = _scene(tmp_path, "table = true\n")
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    code, out, err = _report(capsys, scene, blocker / "out")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--output" in err and "cannot write" in err


def test_the_example_scene_parses():
    from perturb.scene import read_scene

    scene = read_scene(ROOT / "examples" / "scenes" / "disk-fast-spin.toml")
    assert scene.problem == "disk" and scene.outputs.work_precision
    assert scene.parameters == {"r0": 0.755155, "R": 0.123299, "gamma3_0": 0.25}


# ---------------------------------------------------------------------------------- the disk
#: Methods whose error must fall as their setting tightens (the work-precision acceptance, issue 13).
SWEPT = ("rk4", "scipy DOP853", "scipy RK45", "scipy Radau", "scipy LSODA")


@pytest.mark.slow  # the disk's work-precision runs (Radau at rtol 1e-12 alone takes seconds): ~50 s
def test_disk_fast_spin_scene_end_to_end(capsys, tmp_path):
    scene = ROOT / "examples" / "scenes" / "disk-fast-spin.toml"
    folder = tmp_path / "disk"
    code, out, err = _report(capsys, scene, folder)
    assert code == 0, err
    assert "verdict: VALID" in out
    plots = ["time_series", "error", "phase", "convergence", "work_precision", "euler",
             "orientation"]  # fmt: skip
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        [MARKER, "scene.toml", "summary.md", "solution.csv", "solution.json", "euler.csv",
         "validation.json", "work_precision.csv", "solution.tex", *[f"{p}.png" for p in plots]]
    )  # fmt: skip
    euler = np.genfromtxt(folder / "euler.csv", delimiter=",", names=True)
    assert euler.dtype.names == ("t", "theta", "psi", "phi")
    rows = np.genfromtxt(
        folder / "work_precision.csv", delimiter=",", names=True, dtype=None, encoding="utf-8"
    )
    assert rows.dtype.names == ("method", "setting", "error", "seconds")
    methods = set(rows["method"])
    assert {"analytic", "rk4"} <= methods and len(methods & set(SWEPT[1:])) >= 2
    analytic = rows["error"][rows["method"] == "analytic"]
    eps = 0.004  # c/r0 of the scene: the order-1 solution's error is O(eps^2)
    assert analytic.size >= 1 and np.all(analytic < 10 * eps**2)
    for method in methods & set(SWEPT):
        errors = rows["error"][rows["method"] == method]  # loosest setting first
        assert np.all(np.isfinite(errors)) and errors[-1] < errors[0] / 100, (method, errors)
