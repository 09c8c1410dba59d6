"""Problems from anywhere (issue 11 item 1): ``PROBLEM`` as ``file.py:Class``, ``module:Class`` or an
installed entry point, for ``solve``, ``validate``, ``work-precision`` and ``list``.

The problem files are written into ``tmp_path`` at test time; none of them uses ``@register``.
"""

from __future__ import annotations

import importlib.metadata
import json
import math
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from perturb.cli import main
from perturb.validation import with_epsilon
from problems import ALL_PROBLEMS, get_problem, load_problem
from tests.engine.test_convergence import SLOPE_TOL, duffing_period_exact
from tests.helpers import REF_ATOL, REF_RTOL, fitted_slope, roundings

#: A decade of the small parameter, as in tests/engine/test_convergence.py.
EPS_DECADE = np.geomspace(0.01, 0.1, 4)
#: A period by two routes (a file and the registry, or the series and its exact value): the
#: frequency series of order <= 2 and 2 pi / Omega, about a dozen operations each.
PERIOD_ROUTES = roundings(12)
#: x(0) from the series: its terms at t = 0 (cos 0 = 1) summed to the amplitude, relative to it.
INITIAL_SUM = roundings(8)

_HEADER = """
import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem, positive

X, XDOT, A = sp.symbols("x xdot amplitude")
"""

#: x'' + x = eps * FORCE(x, xdot), started at rest from x(0) = amplitude.
_CONSERVATIVE = """

class {cls}(Problem):
    name = "{name}"
    summary = "{summary}"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter"),
        ParameterSpec("amplitude", 1.0, "x(0), velocity zero", positive),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [XDOT], [1], [EPS * ({force})], parameters=[A], name="{name}"
        )

    def method_options(self):
        return {{"amplitudes": {{"x": A}}}}
"""

_RAYLEIGH = """

class Rayleigh(Problem):
    name = "rayleigh"
    summary = "Rayleigh oscillator x'' + x = eps (x' - x'^3 / 3)"
    parameter_specs = (ParameterSpec("eps", 0.1, "small parameter"),)

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [EPS * (XDOT - XDOT**3 / 3)], name="rayleigh")
"""


def conservative(cls, name, force, summary="test oscillator"):
    return _HEADER + _CONSERVATIVE.format(cls=cls, name=name, force=force, summary=summary)


@pytest.fixture
def files(tmp_path):
    """The three problem files: a Duffing-like, a quadratic and a Rayleigh oscillator."""
    texts = {
        "cubic.py": conservative("MyDuffing", "my-duffing", "-X**3"),
        "quadratic.py": conservative("Quadratic", "quadratic", "-X**2"),
        "rayleigh.py": _HEADER + _RAYLEIGH,
    }
    for file, text in texts.items():
        (tmp_path / file).write_text(text)
    return tmp_path


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def solve_json(capsys, spec, *options):
    code, out, err = run(capsys, "solve", spec, *options, "--format", "json")
    assert code == 0, err
    return json.loads(out)


def resonant_frequency_shift(force):
    """Omega_1 for x'' + x = eps f(x, x') from x = A cos s: the cos-s Fourier coefficient of f
    must cancel the secular term 2 A Omega_1 cos s (derived here, not copied)."""
    s, a = sp.symbols("s amplitude")  # plain symbols, as the problem files declare them
    x, xdot = sp.symbols("x xdot")
    f = force.subs({x: a * sp.cos(s), xdot: -a * sp.sin(s)})
    return sp.simplify(-sp.integrate(f * sp.cos(s), (s, 0, 2 * sp.pi)) / (2 * sp.pi * a))


def quadratic_period_exact(eps, amplitude):
    """x'' + x + eps x^2 = 0 from (A, 0): twice the time to the other turning point (xdot = 0)."""

    def turn(t, y):
        return y[1]

    turn.direction = 1.0  # xdot comes back to 0 from below at the left turning point
    sol = solve_ivp(
        lambda t, y: [y[1], -y[0] - eps * y[0] ** 2],
        (0.0, 10.0),
        [amplitude, 0.0],
        method="DOP853",
        events=turn,
        rtol=REF_RTOL,
        atol=REF_ATOL,
    )
    return 2.0 * sol.t_events[0][0]


# ---------------------------------------------------------------------------------- solve
def test_duffing_file_frequency_is_the_textbook_one(files):
    cls = load_problem(f"{files / 'cubic.py'}:MyDuffing")
    x, a = sp.symbols("x amplitude")
    omega = cls.create().solve(1).frequency
    assert omega[0] == 1
    assert sp.simplify(omega[1] - resonant_frequency_shift(-(x**3))) == 0  # 3 A^2 / 8
    assert omega[1].free_symbols == {a}


def test_duffing_file_period_converges_to_the_elliptic_one(capsys, files):
    order, amplitude, errors = 2, 1.2, []
    for eps in EPS_DECADE:
        data = solve_json(
            capsys,
            f"{files / 'cubic.py'}:MyDuffing",
            "--set",
            f"eps={eps}",
            "--set",
            f"amplitude={amplitude}",
            "--order",
            order,
            "--times",
            0,
        )
        assert data["problem"].endswith("cubic.py:MyDuffing")
        assert data["state"]["x"] == [pytest.approx(amplitude, rel=INITIAL_SUM)]  # x(0) = A
        errors.append(abs(data["period"] - duffing_period_exact(eps, amplitude)))
    assert abs(fitted_slope(EPS_DECADE, errors) - (order + 1)) < SLOPE_TOL


def test_duffing_file_matches_the_builtin(capsys, files):
    """Same equations, two routes (file and registry): the same numbers."""
    argv = ("--set", "eps=0.07", "--order", "2", "--times", "0,0.5,1.3")
    mine = solve_json(capsys, f"{files / 'cubic.py'}:MyDuffing", *argv)
    builtin = solve_json(capsys, "duffing", *argv)
    assert mine["period"] == pytest.approx(builtin["period"], rel=PERIOD_ROUTES)
    np.testing.assert_allclose(mine["state"]["x"], builtin["state"]["x"], rtol=1e-13)


def test_quadratic_file_series_against_the_exact_period(capsys, files, monkeypatch):
    """x'' + x = -eps x^2: no first-order frequency shift, and the period error falls as eps^3."""
    monkeypatch.chdir(files)  # a relative path, as a user types it
    cls = load_problem("quadratic.py:Quadratic")
    x = sp.Symbol("x")
    assert cls.create().solve(2).frequency[1] == resonant_frequency_shift(-(x**2)) == 0
    errors = []
    for eps in EPS_DECADE:
        data = solve_json(capsys, "quadratic.py:Quadratic", "--set", f"eps={eps}", "--order", 2)
        errors.append(abs(data["period"] - quadratic_period_exact(eps, 1.0)))
    assert abs(fitted_slope(EPS_DECADE, errors) - 3) < SLOPE_TOL


def test_rayleigh_file_without_class_name(capsys, files):
    """A file defining one problem may be named alone; Rayleigh's limit cycle has amplitude 2 and,
    since x' of Rayleigh obeys van der Pol's equation, van der Pol's frequency series."""
    data = solve_json(capsys, files / "rayleigh.py", "--times", "0")
    eps, a = sp.symbols("epsilon a", positive=True)
    s = sp.Symbol("s")
    averaged = sp.integrate(
        (-a * sp.sin(s) + (a * sp.sin(s)) ** 3 / 3) * sp.sin(s), (s, 0, 2 * sp.pi)
    )
    (cycle,) = sp.solve(averaged, a)
    assert data["state"]["x"] == [pytest.approx(float(cycle), abs=1e-12)]  # order 1: x(0) = 2
    rayleigh = load_problem(str(files / "rayleigh.py")).create().solve(2).frequency
    assert rayleigh == get_problem("van-der-pol").create().solve(2).frequency


def test_module_spec(capsys, files, monkeypatch):
    monkeypatch.syspath_prepend(str(files))
    data = solve_json(capsys, "quadratic:Quadratic", "--times", "0")
    assert data["problem"] == "quadratic:Quadratic" and set(data["state"]) == {"x", "xdot"}
    builtin = solve_json(capsys, "problems.duffing:Duffing", "--times", "0,1")
    assert builtin["state"] == solve_json(capsys, "duffing", "--times", "0,1")["state"]


def test_file_may_import_a_sibling(capsys, tmp_path):
    (tmp_path / "forces.py").write_text("def force(x):\n    return -x**3\n")
    text = conservative("Sibling", "sibling", "force(X)").replace(
        "import sympy as sp", "import sympy as sp\nfrom forces import force"
    )
    (tmp_path / "sibling.py").write_text(text)
    data = solve_json(capsys, f"{tmp_path / 'sibling.py'}:Sibling", "--times", "0")
    assert data["period"] == solve_json(capsys, "duffing", "--times", "0")["period"]
    assert str(tmp_path) not in sys.path  # the folder is on sys.path only during the import


# ---------------------------------------------------------------------------------- validate
def test_validate_file(capsys, files):
    spec = f"{files / 'cubic.py'}:MyDuffing"
    code, out, err = run(capsys, "validate", spec, "--set", "eps=0.05", "--format", "json")
    report = json.loads(out)
    assert code == 0, err
    assert report["completed"] and report["valid"], report["verdict"]


@pytest.mark.parametrize(
    "integrator",
    [
        "dop853",
        None,  # the default (heyoka): integer powers are exact products since the oracle fix
    ],
)
def test_validate_rayleigh_file(capsys, files, integrator):
    if integrator is None:
        pytest.importorskip("heyoka")  # the default integrator when installed
    spec = f"{files / 'rayleigh.py'}:Rayleigh"
    options = ["--integrator", integrator] if integrator else []
    code, out, err = run(
        capsys, "validate", spec, "--set", "eps=0.05", *options, "--format", "json"
    )
    report = json.loads(out)
    assert code == 0, err
    assert report["valid"], report["verdict"]


#: A pendulum written as its user thinks of it: theta = a x, so x'' + x = eps x^3/6 - eps^2 x^5/120
#: + ... with eps = a^2 (sin's series to its second term), eps a function of the amplitude.
#: ``{epsilon}`` is the body of ``epsilon()``: code sympy can read (the map's inverse gives the
#: amplitude at another eps), or code it cannot, with eps declared in ``parameter_map`` instead.
_PENDULUM = """
import math

class Pendulum(Problem):
    name = "pendulum"
    summary = "theta'' = -sin theta, theta = a x"
    parameter_specs = (ParameterSpec("amplitude", 0.3, "theta(0), radians", positive),)
    parameter_map = {declared}

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [XDOT], [1], [EPS * X**3 / 6 - EPS**2 * X**5 / 120], name="pendulum"
        )

    def epsilon(self):
        return {epsilon}

    def method_options(self):
        return {{"amplitudes": {{"x": 1}}}}
"""


@pytest.mark.parametrize(
    ("epsilon", "declared"),
    [
        ('self.values["amplitude"] ** 2', "{}"),  # read off the method
        ('math.pow(self.values["amplitude"], 2)', '{"epsilon": "amplitude**2"}'),  # declared
    ],
)
@pytest.mark.parametrize("order", [1, 2])
def test_a_problem_whose_eps_is_a_function_of_its_parameters_validates(
    capsys, tmp_path, epsilon, declared, order
):
    """eps = a^2 written in the problem's own epsilon(): the order scan re-creates the pendulum at
    eps/8 .. eps (the amplitude sqrt(eps), not -sqrt(eps): the root the move continues from) and
    the error falls like eps^(order+1), so the verdict is VALID, as the subclass contract says."""
    path = tmp_path / "pendulum.py"
    path.write_text(_HEADER + _PENDULUM.format(epsilon=epsilon, declared=declared))
    spec = f"{path}:Pendulum"
    code, out, err = run(capsys, "validate", spec, "--order", order, "--format", "json")
    report = json.loads(out)
    assert code == 0, err
    assert report["outcome"] == "valid", report["verdict"]
    slope = report["slope"]
    assert slope["consistent"] and abs(slope["value"] - (order + 1)) < SLOPE_TOL
    assert slope["epsilons"][-1] == 0.3**2
    pendulum = load_problem(spec).create()
    for eps in slope["epsilons"]:  # each point of the scan, re-created by the amplitude alone
        moved = with_epsilon(pendulum, eps)
        assert moved.values["amplitude"] == pytest.approx(math.sqrt(eps), rel=REF_RTOL)
        assert moved.epsilon() == pytest.approx(eps, rel=REF_RTOL)


def test_work_precision_file(capsys, files):
    spec = f"{files / 'cubic.py'}:MyDuffing"
    code, out, err = run(
        capsys, "work-precision", spec, "--periods", "1", "--orders", "1", "--repeat", "1",
        "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    assert json.loads(out)


def test_through_a_subprocess(files):
    spec = f"{files / 'cubic.py'}:MyDuffing"
    argv = ["solve", spec, "--set", "eps=0.05", "--times", "0", "--format", "json"]
    ok = subprocess.run([sys.executable, "-m", "perturb", *argv], capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    eps = 0.05
    omega = 1 + sp.Rational(3, 8) * eps  # 1 + 3 A^2 eps / 8 at A = 1, order 1
    assert json.loads(ok.stdout)["period"] == pytest.approx(
        float(2 * sp.pi / omega), rel=PERIOD_ROUTES
    )
    bad = subprocess.run(
        [sys.executable, "-m", "perturb", "solve", f"{files / 'cubic.py'}:Nope"],
        capture_output=True,
        text=True,
    )
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1 and "MyDuffing" in bad.stderr


# ---------------------------------------------------------------------------------- bad input
_BAD_FILES = {
    "syntax": ("def broken(:\n", ["syntax error", "bad.py:1"]),
    "import": ("import surely_not_installed_xyz\n", ["surely_not_installed_xyz", "bad.py:1"]),
    "raises": ("x = 1\nraise RuntimeError('boom')\n", ["bad.py:2", "RuntimeError", "boom"]),
    "not-a-problem": ("class Thing:\n    pass\n", ["not a subclass of problems.base.Problem"]),
    "abstract": (
        _HEADER + "\nclass Thing(Problem):\n    name = 'x'\n    summary = 's'\n"
        "    parameter_specs = (ParameterSpec('eps', 0.1, 'e'),)\n",
        ["incomplete", "build_system"],
    ),
    "no-summary": (
        _HEADER
        + _RAYLEIGH.replace("Rayleigh(Problem)", "Thing(Problem)").replace(
            "    summary = \"Rayleigh oscillator x'' + x = eps (x' - x'^3 / 3)\"\n", ""
        ),
        ["incomplete", "summary"],
    ),
    "no-specs": (
        _HEADER
        + _RAYLEIGH.replace("Rayleigh(Problem)", "Thing(Problem)").replace(
            '    parameter_specs = (ParameterSpec("eps", 0.1, "small parameter"),)\n', ""
        ),
        ["incomplete", "parameter_specs"],
    ),
    "not-a-class": ("Thing = 3\n", ["not a class"]),
}


@pytest.mark.parametrize("case", sorted(_BAD_FILES))
@pytest.mark.parametrize("command", ["solve", "validate", "work-precision"])
def test_bad_file_is_one_line_exit_2(capsys, tmp_path, case, command):
    text, fragments = _BAD_FILES[case]
    (tmp_path / "bad.py").write_text(textwrap.dedent(text))
    code, out, err = run(capsys, command, f"{tmp_path / 'bad.py'}:Thing")
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    for fragment in fragments:
        assert fragment in err


@pytest.mark.parametrize(
    ("spec", "fragments"),
    [
        ("{d}/missing.py:Thing", ["missing.py", "does not exist"]),
        ("{d}:Thing", ["is a folder"]),
        ("{d}/cubic.py:MyDufing", ["no class 'MyDufing'", "did you mean 'MyDuffing'", "choose"]),
        ("{d}/cubic.py:", ["ClassName"]),
        ("{d}/cubic.py:1x", ["identifier"]),
        ("surely_not_a_package_xyz.mod:Thing", ["no module named 'surely_not_a_package_xyz'"]),
        ("problems.duffing:Dufing", ["did you mean 'Duffing'"]),
        ("problems.duffing:Y", ["choose from the Problem subclasses it defines, ['Duffing']"]),
        ("problems.duffing:X", ["is a Symbol, not a class", "['Duffing']"]),
        ("dufing", ["did you mean 'duffing'", "choose from", "file.py:ClassName"]),
        ("zzzzzz", ["choose from"]),
    ],
)
def test_bad_spec_is_one_line_exit_2(capsys, files, spec, fragments):
    code, _, err = run(capsys, "solve", spec.format(d=files))
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    for fragment in fragments:
        assert fragment in err
    if spec == "zzzzzz":
        assert "did you mean" not in err


def test_module_that_fails_to_import_is_named_with_its_line(capsys, tmp_path, monkeypatch):
    (tmp_path / "failing_osc.py").write_text("import math\n\nmath.sqrt(-1)\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    code, _, err = run(capsys, "solve", "failing_osc:Thing")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert f"{tmp_path / 'failing_osc.py'}:3" in err and "ValueError: math domain error" in err


def test_two_problems_in_a_file_need_a_class_name(capsys, tmp_path):
    text = conservative("One", "one", "-X**3") + _CONSERVATIVE.format(
        cls="Two", name="two", force="-X**2", summary="s"
    )
    (tmp_path / "two.py").write_text(text)
    code, _, err = run(capsys, "solve", tmp_path / "two.py")
    assert code == 2 and "['One', 'Two']" in err and "ClassName" in err
    assert run(capsys, "solve", f"{tmp_path / 'two.py'}:Two", "--times", "0")[0] == 0


# ---------------------------------------------------------------------------------- entry points
@pytest.fixture
def installed(tmp_path, monkeypatch):
    """A fake distribution declaring problems in the entry-point group ``perturb.problems``."""
    (tmp_path / "fake_oscillators.py").write_text(conservative("Quadratic", "quad", "-X**2"))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(ALL_PROBLEMS, "_loaded", dict(ALL_PROBLEMS._loaded))  # undo what loads
    points = [
        importlib.metadata.EntryPoint("quad-osc", "fake_oscillators:Quadratic", "perturb.problems"),
        importlib.metadata.EntryPoint("broken-osc", "fake_oscillators:Nope", "perturb.problems"),
        importlib.metadata.EntryPoint("duffing", "fake_oscillators:Quadratic", "perturb.problems"),
        importlib.metadata.EntryPoint("other", "fake_oscillators:Quadratic", "other.group"),
    ]
    real = importlib.metadata.entry_points

    def entry_points(**select):
        if not select:  # every group of every distribution: not what perturb asks for
            return real()
        return importlib.metadata.EntryPoints(points).select(**select)

    monkeypatch.setattr(importlib.metadata, "entry_points", entry_points)
    return points


def test_entry_point_problem_is_listed_and_solved(capsys, installed):
    names = list(ALL_PROBLEMS)
    assert "quad-osc" in names and "other" not in names
    data = solve_json(capsys, "quad-osc", "--times", "0")
    assert data["problem"] == "quad-osc"
    assert data["state"]["x"] == [pytest.approx(1.0, rel=INITIAL_SUM)]  # x(0) = amplitude
    assert get_problem("quad-osc").summary == "test oscillator"


def test_list_shows_entry_points(capsys, installed):
    del installed[1]  # the broken one: see the next test
    code, out, err = run(capsys, "list")
    assert code == 0 and err == ""
    assert "quad-osc" in out and "test oscillator" in out and "duffing" in out


def test_list_warns_about_a_broken_entry_point_and_lists_the_rest(capsys, installed):
    assert "broken-osc" in list(ALL_PROBLEMS)  # listing names imports nothing
    code, out, err = run(capsys, "list")
    assert code == 0 and "quad-osc" in out and "duffing" in out and "broken-osc" not in out
    assert len(err.strip().splitlines()) == 1 and err.startswith("perturb: warning: ")
    assert "entry point 'broken-osc'" in err and "uninstall" in err


def test_builtin_wins_over_an_entry_point(installed):
    assert get_problem("duffing").__module__ == "problems.duffing"


def test_broken_entry_point_is_one_line_exit_2(capsys, installed):
    code, _, err = run(capsys, "solve", "broken-osc")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert "entry point 'broken-osc'" in err and "fake_oscillators:Nope" in err


# ---------------------------------------------------------------------------------- the README
def test_readme_example(capsys, files, tmp_path_factory):
    """The README's "Your own problem" file runs as shown and is the quadratic oscillator above."""
    readme = (Path(__file__).parents[2] / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("## Your own problem") :].split("\n## ", 1)[0]
    (code,) = re.findall(r"```python\n(.*?)```", section, re.S)
    (commands,) = re.findall(r"```bash\n(.*?)```", section, re.S)
    folder = tmp_path_factory.mktemp("readme")
    (folder / "quadratic.py").write_text(code)
    argv = ("--set", "eps=0.05", "--order", "2", "--times", "0,1")
    readme_run = solve_json(capsys, f"{folder / 'quadratic.py'}:Quadratic", *argv)
    tested = solve_json(capsys, f"{files / 'quadratic.py'}:Quadratic", *argv)
    assert readme_run["period"] == pytest.approx(tested["period"], rel=PERIOD_ROUTES)
    assert readme_run["state"] == tested["state"]
    for line in commands.strip().splitlines():
        program, *args = line.split()
        assert program == "perturb"
        args = [str(folder / a) if a.startswith("quadratic.py") else a for a in args]
        assert main(args) == 0, capsys.readouterr().err


def test_entry_points_of_an_installed_distribution(capsys, tmp_path, monkeypatch):
    """No monkeypatched lookup: a real ``.dist-info`` folder on sys.path declares the problems."""
    (tmp_path / "fakeosc_problems.py").write_text(conservative("Quadratic", "quad", "-X**2"))
    info = tmp_path / "fakeosc-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fakeosc\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(
        "[perturb.problems]\n"
        "fake-quadratic = fakeosc_problems:Quadratic\n"
        "fake-broken = fakeosc_problems:Missing\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(ALL_PROBLEMS, "_loaded", dict(ALL_PROBLEMS._loaded))
    assert {"fake-quadratic", "fake-broken"} <= set(ALL_PROBLEMS)
    data = solve_json(capsys, "fake-quadratic", "--times", "0")
    assert data["state"]["x"] == [pytest.approx(1.0, rel=INITIAL_SUM)]
    code, _, err = run(capsys, "solve", "fake-broken")
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "fakeosc_problems:Missing" in err and "uninstall fakeosc" in err
