"""A user's problem file with its hooks in odd but legal shapes, or wrong ones: each gives the
right answer or one line naming where the class defines the hook, the value and the fix (from
Python a ValueError subclass, from the CLI exit 2 and no traceback), never an internal error or
a silently ignored answer.

The shapes: ``label`` a string attribute or a property instead of a method, ``label()``
returning a non-string; ``parameter_map`` None, a list of pairs, a string; ``integrals_of_motion``
without the ``y0`` argument, returning a bare function (the older hook's form) or a number,
values of the wrong shape, more names than integrals; ``check_values`` returning its refusal (a fix, as a
``ParameterSpec`` check does, or False) instead of raising it, or returning other values. The
files are written into ``tmp_path`` and loaded as a user's are (``file.py:Class``).
"""

from __future__ import annotations

import json
import sys

import pytest

from perturb import validate
from perturb.cli import main
from perturb.errors import InvalidParameterError, InvalidSystemError, ProblemLoadError
from perturb.validation.capabilities import integrals_of_motion, label_of
from problems import load_problem

SOURCE = """
import numpy as np
import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.validation import Integrals
from problems.base import ParameterSpec, Problem, positive

X, XDOT, A = sp.symbols("x xdot amplitude")


def energy_of(eps):
    def energy(y):
        y = np.asarray(y, dtype=float)
        return np.array([(y[0] ** 2 + y[1] ** 2) / 2 + eps * y[0] ** 4 / 4])

    return energy


class Plain(Problem):
    name = "plain"
    summary = "x'' + x = -eps x^3"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter"),
        ParameterSpec("amplitude", 1.0, "x(0), at rest", positive),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], parameters=[A], name="plain")

    def method_options(self):
        return {"amplitudes": {"x": A}}


class LabelAttribute(Plain):
    label = "my oscillator"


class LabelProperty(Plain):
    @property
    def label(self):
        return "my property"


class LabelNumber(Plain):
    def label(self):
        return 42


class LabelWithArgument(Plain):
    def label(self, style):
        return f"{style} oscillator"


class CheckWithoutValues(Plain):
    def check_values(self):
        return None


class MapNone(Plain):
    parameter_map = None


class MapPairs(Plain):
    parameter_map = [("epsilon", "eps / 2")]


class MapString(Plain):
    parameter_map = "eps / 2"


class Doubled(Plain):
    parameter_map = {"epsilon": "eps / 2", "amplitude": "2 * amplitude"}


class Replaced(Doubled):
    parameter_map = {"epsilon": "eps / 4"}  # the whole map: amplitude is its parameter again


class Extended(Doubled):
    parameter_map = {**Doubled.parameter_map, "epsilon": "eps / 4"}


class IntegralsNoState(Plain):
    def integrals_of_motion(self):
        return Integrals(energy_of(self.values["eps"]), ("E",))


class IntegralsBareFunction(Plain):
    def integrals_of_motion(self, y0=None):
        function = energy_of(self.values["eps"])
        function.names = ("H",)
        return function


class IntegralsNotAFunction(Plain):
    def integrals_of_motion(self, y0=None):
        return 0.5


class IntegralsWrongShape(Plain):
    def integrals_of_motion(self, y0=None):
        return Integrals(lambda y: np.ones((3, 3)), ("E",))


class IntegralsTooManyNames(Plain):
    def integrals_of_motion(self, y0=None):
        return Integrals(energy_of(self.values["eps"]), ("E", "F"))


class Both(Plain):
    def integrals_of_motion(self, y0=None):
        return Integrals(energy_of(self.values["eps"]), ("typed",))

    def first_integrals_function(self):
        return energy_of(self.values["eps"])


class OlderInChildOfTyped(Both):
    def first_integrals_function(self):
        return energy_of(self.values["eps"])


class ReturnsFix(Plain):
    def check_values(self, values):
        if values["amplitude"] > 5:
            return "give amplitude <= 5"


class ReturnsFalse(Plain):
    def check_values(self, values):
        return values["amplitude"] <= 5


class ReturnsItsValues(Plain):
    def check_values(self, values):
        return values


class ReturnsOtherValues(Plain):
    def check_values(self, values):
        return {**values, "amplitude": min(values["amplitude"], 1.0)}  # meant to clip it
"""


@pytest.fixture
def user_file(tmp_path):
    path = tmp_path / "odd_oscillators.py"
    path.write_text(SOURCE)
    return path


def loaded(path, cls):
    return load_problem(f"{path}:{cls}")


def run(capsys, *argv):
    capsys.readouterr()
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(code, err):
    assert code == 2, err
    assert "Traceback" not in err and "internal error" not in err
    assert len(err.strip().splitlines()) == 1, err


# ------------------------------------------------------------------ label
@pytest.mark.parametrize(
    ("cls", "label"), [("LabelAttribute", "my oscillator"), ("LabelProperty", "my property")]
)
def test_a_label_declared_as_a_string_is_the_label(user_file, capsys, cls, label):
    problem = loaded(user_file, cls).create(eps=0.05)
    assert label_of(problem) == label
    assert validate(problem, periods=2, slope=False, shoot=False).problem == label
    code, out, _ = run(capsys, "validate", f"{user_file}:{cls}", "--periods", 2, "--format", "json")
    assert code == 0
    assert json.loads(out)["problem"] == label


def test_a_label_that_is_not_a_string_is_refused_in_one_line(user_file, capsys):
    problem = loaded(user_file, "LabelNumber").create()
    with pytest.raises(InvalidSystemError, match=r"odd_oscillators\.py:\d+.*label.*42.*str"):
        label_of(problem)
    code, _, err = run(capsys, "validate", f"{user_file}:LabelNumber", "--periods", 2)
    one_line_error(code, err)
    assert "odd_oscillators.py:" in err and "42" in err


def test_hooks_that_cannot_be_called_so_are_one_line(user_file, capsys):
    with pytest.raises(InvalidSystemError, match=r"odd_oscillators\.py:\d+.*label\(self\)"):
        label_of(loaded(user_file, "LabelWithArgument").create())
    code, _, err = run(capsys, "validate", f"{user_file}:LabelWithArgument", "--periods", 2)
    one_line_error(code, err)
    assert "label(style)" in err
    with pytest.raises(
        ProblemLoadError, match=r"odd_oscillators\.py:\d+.*check_values\(self, values\)"
    ):
        loaded(user_file, "CheckWithoutValues")


# ------------------------------------------------------------------ parameter_map
def test_a_map_of_none_is_no_map_and_pairs_are_a_map(user_file):
    assert loaded(user_file, "MapNone").create(eps=0.1).epsilon() == 0.1
    halved = loaded(user_file, "MapPairs").create(eps=0.1)
    assert halved.epsilon() == pytest.approx(0.05, rel=1e-15)


def test_a_map_that_is_not_a_mapping_is_refused_in_one_line(user_file, capsys):
    with pytest.raises(ProblemLoadError, match=r"parameter_map.*'eps / 2'.*dict"):
        loaded(user_file, "MapString")
    code, _, err = run(capsys, "solve", f"{user_file}:MapString")
    one_line_error(code, err)
    assert "odd_oscillators.py" in err and "parameter_map" in err


@pytest.mark.parametrize(("cls", "amplitude"), [("Doubled", 6.0), ("Replaced", 3.0),
                                                ("Extended", 6.0)])  # fmt: skip
def test_a_subclass_map_replaces_its_parents_whole_as_documented(user_file, cls, amplitude):
    problem = loaded(user_file, cls).create(eps=0.2, amplitude=3.0)
    expected = 0.1 if cls == "Doubled" else 0.05
    assert problem.epsilon() == pytest.approx(expected, rel=1e-15)
    assert problem.symbol_values()["amplitude"] == pytest.approx(amplitude, rel=1e-15)


# ------------------------------------------------------------------ integrals_of_motion
def test_integrals_without_the_state_argument_are_refused_in_one_line(user_file, capsys):
    problem = loaded(user_file, "IntegralsNoState").create()
    with pytest.raises(InvalidSystemError, match=r"odd_oscillators\.py:\d+.*y0=None"):
        integrals_of_motion(problem)
    code, _, err = run(capsys, "validate", f"{user_file}:IntegralsNoState", "--periods", 2)
    one_line_error(code, err)
    assert "integrals_of_motion" in err


@pytest.mark.parametrize(
    ("cls", "what"),
    [
        ("IntegralsNotAFunction", r"0\.5.*Integrals\(function, names\)"),
        ("IntegralsBareFunction", r"function energy.*Integrals\(function, names\)"),
        ("IntegralsWrongShape", r"shape \(3, 3\)"),
        ("IntegralsTooManyNames", r"2 names.*1 integral"),
    ],
)
def test_integrals_of_the_wrong_kind_are_refused_in_one_line(user_file, capsys, cls, what):
    problem = loaded(user_file, cls).create(eps=0.05)
    with pytest.raises(InvalidSystemError, match=what):
        validate(problem, periods=2, slope=False, shoot=False)
    code, _, err = run(capsys, "validate", f"{user_file}:{cls}", "--periods", 2)
    one_line_error(code, err)
    assert "integrals_of_motion" in err and "odd_oscillators.py:" in err


@pytest.mark.parametrize("cls", ["Both", "OlderInChildOfTyped"])
def test_the_typed_integrals_win_over_the_older_hook_as_documented(user_file, cls):
    problem = loaded(user_file, cls).create(eps=0.05)
    assert integrals_of_motion(problem).names == ("typed",)


# ------------------------------------------------------------------ check_values
@pytest.mark.parametrize(("cls", "what"), [("ReturnsFix", "give amplitude <= 5"),
                                           ("ReturnsFalse", "check_values")])  # fmt: skip
def test_a_refusal_returned_by_check_values_refuses(user_file, capsys, cls, what):
    checked = loaded(user_file, cls)
    assert checked.create(amplitude=4.0).values["amplitude"] == 4.0
    with pytest.raises(InvalidParameterError, match=what):
        checked.create(amplitude=6.0)
    code, _, err = run(capsys, "validate", f"{user_file}:{cls}", "--set", "amplitude=6")
    one_line_error(code, err)
    assert what in err and "amplitude" in err
    pytest.importorskip("distributed")
    code, out, err = run(capsys, "sweep", f"{user_file}:{cls}", "--grid", "amplitude=4,6",
                         "--format", "json", "--workers", 1, "--quiet")  # fmt: skip
    assert code == 0, err
    assert what in out  # the refused point says why


def test_check_values_returning_its_values_passes_and_other_values_are_refused(user_file):
    assert loaded(user_file, "ReturnsItsValues").create(amplitude=2.0).values["amplitude"] == 2.0
    with pytest.raises(InvalidSystemError, match=r"odd_oscillators\.py:\d+.*check_values"):
        loaded(user_file, "ReturnsOtherValues").create(amplitude=2.0)


# ------------------------------------------------------------------ one name, two classes
REDEFINED = """
import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, XDOT = sp.symbols("x xdot")


def oscillator(power):
    class Osc(Problem):
        name = "osc"
        summary = f"x'' + x = -eps x^{power}"
        parameter_specs = (ParameterSpec("eps", 0.1, "small parameter"),)

        @classmethod
        def build_system(cls):
            return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**power], name="osc")

        def method_options(self):
            return {"amplitudes": {"x": 1}}

    return Osc
"""


def test_a_class_redefined_under_its_name_is_not_answered_from_the_first(tmp_path, capsys):
    """The second ``Osc`` of a file (the first solved while the file was imported) is solved
    for its own system, as a file defining it alone: the per-class caches do not take two
    classes of one name in one module for one."""
    (tmp_path / "twice.py").write_text(
        REDEFINED + "Osc = oscillator(3)\nCUBIC = Osc.create().solve(1)\nOsc = oscillator(5)\n"
    )
    (tmp_path / "once.py").write_text(REDEFINED + "Osc = oscillator(5)\n")
    twice = loaded(tmp_path / "twice.py", "Osc").create()
    once = loaded(tmp_path / "once.py", "Osc").create()
    assert twice.system().rhs == once.system().rhs
    period = once.period(once.solve(1))
    assert twice.period(twice.solve(1)) == pytest.approx(period, rel=1e-12)
    cubic = sys.modules[type(twice).__module__].CUBIC  # the first class's answer is another
    assert twice.period(cubic) != pytest.approx(period, rel=1e-6)
    code, out, _ = run(capsys, "solve", f"{tmp_path / 'twice.py'}:Osc", "--format", "json")
    assert code == 0
    assert json.loads(out)["period"] == pytest.approx(period, rel=1e-12)


# ------------------------------------------------------------------ a sibling module
def test_a_file_importing_a_sibling_module_sweeps_on_the_workers(tmp_path, capsys):
    """A problem file may import a module beside it at its top (problems.loading); the sweep's
    workers, which cannot import it, get it with the file's class."""
    pytest.importorskip("distributed")
    (tmp_path / "oscillators_base.py").write_text(SOURCE)
    (tmp_path / "derived.py").write_text(
        "from oscillators_base import Plain\n\n\nclass Derived(Plain):\n    name = 'derived'\n"
    )
    code, out, err = run(capsys, "sweep", f"{tmp_path / 'derived.py'}:Derived", "--grid",
                         "eps=0.04,0.08", "--format", "json", "--workers", 1, "--quiet")  # fmt: skip
    assert code == 0, err
    points = json.loads(out)["points"]
    assert [p["status"] for p in points] == ["ok", "ok"]
    # x'' + x = -eps x^3 from rest at x(0) = 1: frequency 1 + 3 eps / 8 at order 1
    assert [p["frequency"] for p in points] == pytest.approx([1.015, 1.03], rel=1e-12)


def test_integrals_set_to_none_on_the_class_are_none():
    """``integrals_of_motion = None`` declares that a model has none (as ``__hash__ = None``),
    where leaving it out gives the system's energy."""
    from perturb.validation.capabilities import integrals_of_motion
    from problems import get_problem

    duffing = get_problem("duffing")
    assert integrals_of_motion(duffing.create()).names == ("energy",)

    class Without(duffing):
        name = "duffing-without-integrals"
        integrals_of_motion = None

    assert integrals_of_motion(Without.create()) is None
