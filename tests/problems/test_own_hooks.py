"""Hooks a problem defines, with no member on every problem: first integrals, the name reports
show, the parameter map; and the whole-set checks beside them.

``Problem`` has no ``integrals_of_motion``, ``label`` or ``parameter_map``: a class that defines
one is asked it (through :func:`perturb.validation.capabilities.integrals_of_motion` and
:func:`~perturb.validation.capabilities.label_of`, or when its map is read), and a class that
defines none gets the generic answer (the system's energy, its ``name``, each symbol its
parameter's). ``check_values`` stays a no-op on the base: a user's file calls
``super().check_values(values)`` (the shipped Duffing did). The problem files are written into
``tmp_path`` and loaded as a user's are (``file.py:Class``).
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

from perturb import validate
from perturb.cli import main
from perturb.errors import InvalidParameterError
from perturb.validation import with_epsilon
from perturb.validation.capabilities import integrals_of_motion, label_of
from problems import load_problem
from problems.base import Problem

#: The user's file: x'' + x = -eps x^3 from rest at x(0) = amplitude (Duffing's, conservative),
#: with one class per hook.
SOURCE = """
import numpy as np
import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.errors import InvalidParameterError
from perturb.validation import Integrals
from problems.base import ParameterSpec, Problem, positive

X, XDOT, A = sp.symbols("x xdot amplitude")
#: The calls of Own_rhs.original_rhs's function, to see that validation integrates it.
CALLS = []


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


class Checked(Plain):
    def check_values(self, values):
        if values["eps"] * values["amplitude"] ** 2 > 1:
            raise InvalidParameterError(
                f"`amplitude` = {values['amplitude']:g} is invalid: keep eps amplitude^2 <= 1"
            )


class Stricter(Checked):
    def check_values(self, values):
        super().check_values(values)  # the parent's checks, then its own
        if values["amplitude"] > 5:
            raise InvalidParameterError("`amplitude` is invalid: give amplitude <= 5")


class CallsTheBase(Plain):
    def check_values(self, values):
        super().check_values(values)  # Problem's, as the shipped Duffing wrote it
        if values["amplitude"] > 5:
            raise InvalidParameterError("`amplitude` is invalid: give amplitude <= 5")


class OwnIntegrals(Plain):
    def integrals_of_motion(self, y0=None):
        def twice_energy(y):
            y = np.asarray(y, dtype=float)
            return np.array([y[0] ** 2 + y[1] ** 2 + self.values["eps"] * y[0] ** 4 / 2])

        return Integrals(twice_energy, ("twice the energy",))


class OwnRhs(Plain):
    def original_rhs(self, solution=None):
        eps = self.values["eps"]

        def rhs(t, y):
            CALLS.append(t)
            return [y[1], -y[0] - eps * y[0] ** 3]

        return rhs


class OlderIntegrals(Plain):
    def first_integrals_function(self):
        eps = self.values["eps"]

        def energy(y):
            y = np.asarray(y, dtype=float)
            return np.array([(y[0] ** 2 + y[1] ** 2) / 2 + eps * y[0] ** 4 / 4])

        energy.names = ("H",)
        return energy


class Labelled(Plain):
    def label(self):
        return "my oscillator"


class Halved(Plain):
    parameter_map = {"epsilon": "eps / 2"}


class HalvedChild(Halved):
    pass
"""


@pytest.fixture
def user_file(tmp_path):
    path = tmp_path / "user_oscillators.py"
    path.write_text(SOURCE)
    return path


def loaded(path, cls):
    return load_problem(f"{path}:{cls}")


def test_the_base_class_has_none_of_the_hooks():
    public = {n for n in dir(Problem) if not n.startswith("_")}
    assert not public & {"integrals_of_motion", "label", "parameter_map"}


def test_a_problem_defining_none_gets_the_generic_answers(user_file):
    plain = loaded(user_file, "Plain").create(eps=0.1, amplitude=10.0)  # no whole-set check
    integrals = integrals_of_motion(plain)
    assert integrals.names == ("energy",)
    # x^2/2 + eps x^4/4 at (1, 0), eps = 0.1: the potential of -eps x^3 plus the kinetic energy
    assert integrals.function(np.array([1.0, 0.0]))[0] == pytest.approx(0.525, rel=1e-14)
    assert label_of(plain) == "plain"
    report = validate(loaded(user_file, "Plain").create(eps=0.05), periods=2, slope=False)
    assert set(report.invariants) == {"energy"}
    assert report.problem == "plain"


def test_own_whole_set_checks_run_from_python_and_the_cli(user_file, capsys):
    checked = loaded(user_file, "Checked")
    assert checked.create(eps=0.1, amplitude=3.0).values["amplitude"] == 3.0
    with pytest.raises(InvalidParameterError, match="keep eps amplitude"):
        checked.create(eps=0.1, amplitude=4.0)
    stricter = loaded(user_file, "Stricter")
    with pytest.raises(InvalidParameterError, match="keep eps amplitude"):  # the parent's
        stricter.create(eps=0.1, amplitude=4.0)
    with pytest.raises(InvalidParameterError, match="amplitude <= 5"):  # its own
        stricter.create(eps=0.01, amplitude=6.0)
    with pytest.raises(InvalidParameterError, match="amplitude <= 5"):
        loaded(user_file, "CallsTheBase").create(amplitude=6.0)
    capsys.readouterr()
    code = main(["validate", f"{user_file}:Checked", "--set", "amplitude=4"])
    err = capsys.readouterr().err
    assert code == 2
    assert "keep eps amplitude^2 <= 1" in err
    assert "Traceback" not in err


def test_own_integrals_are_the_ones_checked(user_file, capsys):
    problem = loaded(user_file, "OwnIntegrals").create(eps=0.05)
    assert integrals_of_motion(problem).names == ("twice the energy",)
    capsys.readouterr()
    code = main(["validate", f"{user_file}:OwnIntegrals", "--set", "eps=0.05", "--format", "json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert set(out["invariants"]) == {"twice the energy"}
    drift = out["invariants"]["twice the energy"]
    # 2 x (x(0)^2/2 + eps x(0)^4/4) at x(0) = 1, eps = 0.05
    assert drift["initial"] == pytest.approx(1.025, rel=1e-12)


def test_own_equations_are_integrated_and_carry_no_system_integrals(user_file):
    cls = loaded(user_file, "OwnRhs")
    problem = cls.create(eps=0.05)
    assert integrals_of_motion(problem) is None  # numeric equations of its own: none known
    calls = sys.modules[cls.__module__].CALLS
    calls.clear()
    report = validate(problem, periods=2, slope=False, shoot=False)
    assert calls, "validation did not integrate the problem's own original_rhs"
    assert report.invariants == {}


def test_older_integrals_and_own_label(user_file):
    older = loaded(user_file, "OlderIntegrals").create(eps=0.05)
    assert integrals_of_motion(older).names == ("H",)
    report = validate(older, periods=2, slope=False)
    assert set(report.invariants) == {"H"}
    labelled = loaded(user_file, "Labelled").create(eps=0.05)
    assert label_of(labelled) == "my oscillator"
    assert validate(labelled, periods=2, slope=False, shoot=False).problem == "my oscillator"


def test_a_declared_map_is_read_and_inherited(user_file):
    assert loaded(user_file, "Plain").create(eps=0.1).epsilon() == 0.1  # none: eps is ε
    for name in ("Halved", "HalvedChild"):
        problem = loaded(user_file, name).create(eps=0.1)
        assert problem.epsilon() == pytest.approx(0.05, rel=1e-15)
        assert with_epsilon(problem, 0.02).values["eps"] == pytest.approx(0.04, rel=1e-12)
