"""Optional physics as declared capabilities (perturb/validation/capabilities.py): a model has one
when it defines the method; the older duck-typed hooks of a user's subclass declare them when the
class is made; and the table keyed by frame type does the free/driven work."""

from __future__ import annotations

import math

import pytest
import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.validation import OrbitEstimate, SystemModel, Verdict, has_euler_angles, validate
from perturb.validation.capabilities import (
    OwnShootingSetup,
    OwnTrueOrbit,
    ReportExtras,
    ValidityEstimates,
    own_shooting_setup,
    own_true_orbit,
    report_extras,
    validity_estimates,
)
from perturb.validation.frames import DrivenWork, FreeWork, work_of
from problems import get_problem
from problems.base import ParameterSpec, Problem

X, XDOT, A = sp.symbols("x xdot a")


class Plain(Problem):
    """x'' + x = eps x^3, x(0) = a: no optional physics."""

    name = "plain-softening"
    summary = "x'' + x = eps x^3"
    parameter_specs = (ParameterSpec("eps", 0.05, "strength"), ParameterSpec("a", 1.0, "x(0)"))

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [EPS * X**3], parameters=[A])

    def method_options(self):
        return {"amplitudes": {"x": A}}


class _Found:
    """What an older ``true_periodic_orbit`` returned: an object with the orbit's attributes."""

    success = True
    period = 6.5
    initial_state = (1.0, 0.0)
    message = "found by the user's own method"
    floquet = (1.0, 1.0)
    n_trivial = 2


class OlderHooks(Plain):
    """The older hooks a user's file may still define."""

    name = "older-hooks"

    def validity_conditions(self):
        return [("a modest", self.values["a"], self.values["a"] < 2, "a must stay below 2")]

    def true_periodic_orbit(self, solution=None):
        return _Found()


class OwnTyped(OlderHooks):
    """A subclass that defines the typed hook itself: its own, not the older one's reading."""

    name = "own-typed"

    def true_orbit(self, solution):
        return OrbitEstimate(False, math.nan, (), message="typed")


def test_a_plain_problem_declares_no_optional_physics():
    plain = Plain.create()
    for capability in (OwnTrueOrbit, OwnShootingSetup, ValidityEstimates, ReportExtras):
        assert not isinstance(plain, capability)
    assert not has_euler_angles(plain)
    solution = plain.solve(1)
    assert own_true_orbit(plain, solution) is None and own_shooting_setup(plain) is None
    assert validity_estimates(plain) == () and report_extras(plain) == {}
    assert "validity_conditions" not in dir(Problem) and "true_orbit" not in dir(Problem)


def test_the_older_hooks_declare_the_capabilities_they_stand_for():
    older = OlderHooks.create(a=3.0)
    assert isinstance(older, ValidityEstimates) and isinstance(older, OwnTrueOrbit)
    (condition,) = validity_estimates(older)
    assert condition.name == "a modest" and condition.value == 3.0 and not condition.ok
    orbit = own_true_orbit(older, older.solve(1))
    assert isinstance(orbit, OrbitEstimate)
    assert orbit.success and orbit.period == 6.5 and orbit.n_trivial == 2
    assert orbit.message == "found by the user's own method"


def test_a_typed_hook_is_not_replaced_by_an_older_one_below_it():
    own = OwnTyped.create()
    assert own_true_orbit(own, own.solve(1)).message == "typed"


def test_the_rigid_bodies_declare_theirs():
    disk = get_problem("disk").create()
    assert has_euler_angles(disk) and isinstance(disk, OwnTrueOrbit)
    assert sorted(report_extras(disk)) == ["mu", "regime"]
    assert validity_estimates(disk)[0].name == "ε = c/r0 small"


def test_a_validated_user_problem_reads_its_older_estimates():
    report = validate(OlderHooks.create(a=1.0), periods=1, slope=False)
    (condition,) = report.conditions
    assert condition.ok and report.outcome is not Verdict.INVALID


@pytest.mark.parametrize(("name", "work"), [("duffing", FreeWork), ("forced-duffing", DrivenWork)])
def test_the_frame_table_does_the_free_and_driven_work(name, work):
    problem = get_problem(name).create()
    entry = work_of(problem.system())
    assert isinstance(entry, work)
    # a free solution serves every point (no point in its key); a driven one is the point's own
    assert (entry.point_key(problem) == ()) is (work is FreeWork)
    assert problem.case().evaluates_directly is (work is FreeWork)
    assert entry.family_elsewhere("upper") is (work is DrivenWork)
    assert entry.family_elsewhere("no-such-branch") is False


def test_a_bare_driven_system_solves_its_branch_through_the_table():
    forced = get_problem("forced-duffing").create()
    values = {**forced.symbol_values(), "epsilon": forced.epsilon()}
    bare = SystemModel(forced.system(), values)
    assert not bare.case().evaluates_directly
    ours, theirs = bare.solve(1), forced.solve(1)
    assert ours.success and theirs.success
    assert ours.frequency_series() == theirs.frequency_series()
