"""The Model protocol (issue 8.1): problems, bare systems and user subclasses validate through it;
perturb never imports problems and validation never probes attributes."""

import ast
import pathlib

import pytest
import sympy as sp

import perturb
from perturb import EPS, QuasilinearSystem
from perturb.errors import InvalidParameterError
from perturb.validation import Model, ShootingSetup, SystemModel, Verdict, state_along, validate
from perturb.validation.model import parameter_value_of
from problems import get_problem
from problems.base import ParameterSpec, Problem, positive

ROOT = pathlib.Path(perturb.__file__).parent
X, XDOT, AMPLITUDE = sp.symbols("x xdot amplitude")


def _duffing_system():
    return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], parameter=EPS, name="bare-duffing")


def test_bare_system_validates_through_perturb_validate():
    """Issue 11.2: perturb.validate(system, values=..., order=...)."""
    report = perturb.validate(
        _duffing_system(),
        values={"epsilon": 0.05},
        options={"amplitudes": {"x": 1}},
        order=1,
        periods=1,
    )
    assert report.outcome is Verdict.VALID and report.problem == "bare-duffing"
    assert set(report.invariants) == {"energy"}  # the conservative energy is derived by default
    # the same numbers as the registered Duffing problem at the same parameters
    registered = validate(get_problem("duffing").create(eps=0.05), periods=1)
    assert report.check("orbit_error").value == pytest.approx(
        registered.check("orbit_error").value, rel=1e-6
    )


@pytest.mark.parametrize(
    "values", [None, {}, {"epsilon": 0.1, "kappa": 1.0}, {"epsilon": float("nan")}, "eps=0.1"]
)
def test_bare_system_needs_exactly_its_values(values):
    with pytest.raises(InvalidParameterError, match="`values`"):
        validate(_duffing_system(), values=values)


def test_something_else_is_refused_naming_the_argument():
    with pytest.raises(InvalidParameterError, match="`problem`"):
        validate("duffing")


def test_model_is_abstract_and_problems_are_models():
    with pytest.raises(TypeError):
        Model()
    assert isinstance(get_problem("duffing").create(), Model)
    assert isinstance(SystemModel(_duffing_system(), {"epsilon": 0.1}), Model)


class SofteningOscillator(Problem):
    """A user problem written against problems/base.py the way problems/duffing.py is (not
    registered): ẍ + x − ε x³ = 0 from rest at x(0) = amplitude."""

    name = "softening"
    summary = "softening oscillator"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "strength of the cubic term"),
        ParameterSpec("amplitude", 1.0, "x(0)", positive),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[EPS * X**3],
            parameter=EPS,
            parameters=[AMPLITUDE],
            name="softening",
        )

    def method_options(self):
        return {"amplitudes": {"x": AMPLITUDE}}


class WithOldHooks(SofteningOscillator):
    """The same, with the older duck-typed hooks a user subclass may define."""

    def validity_conditions(self):
        return [("amplitude modest", 2.0, False, "the amplitude estimate is pessimistic")]

    def shooting_setup(self):
        return {"section_index": 1, "fixed_indices": (0,), "n_trivial": 2}


def test_user_subclass_like_duffing_validates():
    report = validate(SofteningOscillator.create(), periods=1)
    assert report.outcome is Verdict.VALID, report.verdict
    assert report.problem == "softening" and report.parameters == {"eps": 0.05, "amplitude": 1.0}


def test_old_duck_typed_hooks_still_work_and_estimates_only_warn():
    report = validate(WithOldHooks.create(), periods=1)
    (condition,) = report.conditions
    assert condition.name == "amplitude modest" and not condition.ok
    assert "pessimistic" in report.verdict  # explained and warned ...
    assert report.outcome is Verdict.VALID  # ... but the verdict is measured
    assert report.periodic_orbit.n_trivial == 2


def test_shooting_setup_argument_accepts_the_typed_object():
    setup = ShootingSetup(section_index=1, fixed_indices=(0,), n_trivial=2)
    report = validate(SofteningOscillator.create(), periods=1, slope=False, shooting_setup=setup)
    assert report.periodic_orbit.success and report.check("existence").passed


class UserModel(Model):
    """A model written against the protocol table of docs/validation.md, not a problem: the
    required members (the value of the system's own parameter is derived from ε), the method
    options that fix its amplitude and ``with_epsilon`` for the order check."""

    def __init__(self, eps: float):
        self.eps = eps

    def state_names(self):
        return ("x", "xdot")

    def method_options(self):
        return {"amplitudes": {"x": 1}}

    def solve(self, order=1):
        return perturb.PoincareMethod(order=order, **self.method_options()).solve(_duffing_system())

    def state(self, solution, t):
        return state_along(solution, t, parameter_value_of(self), self.symbol_values())

    def period(self, solution):
        return float(solution.period_at(parameter_value_of(self), self.symbol_values()))

    def epsilon(self):
        return self.eps

    def system(self):
        return _duffing_system()

    def symbol_values(self):
        return {}

    def with_epsilon(self, eps):
        return type(self)(eps)


class EarlierUserModel(UserModel):
    """The same model as earlier versions of the protocol required it: its own
    ``parameter_value()`` (here deliberately the value the derived one gives)."""

    def parameter_value(self):
        return self.eps


@pytest.mark.parametrize("cls", [UserModel, EarlierUserModel])
def test_a_users_model_validates_through_the_protocol(cls):
    model = cls(0.05)
    assert parameter_value_of(model) == 0.05
    report = validate(model, periods=1)
    assert report.outcome is Verdict.VALID, report.verdict
    # the same figures as the bare system and the registered problem at the same numbers
    bare = perturb.validate(
        _duffing_system(), values={"epsilon": 0.05}, options={"amplitudes": {"x": 1}}, periods=1
    )
    assert report.check("orbit_error").value == pytest.approx(
        bare.check("orbit_error").value, rel=1e-9
    )
    assert report.parameters == {"epsilon": 0.05}  # its case's values: ε, the one it has


def test_a_models_own_parameter_value_is_the_one_its_solution_takes():
    """A model that computes its own parameter's value (a bare large-parameter system given
    mu) is read as it computes it, by every client (parameter_value_of)."""
    large = QuasilinearSystem([X], [XDOT], [1], [EPS * (1 - X**2) * XDOT]).as_large_parameter()
    model = SystemModel(large, {large.parameter.name: 7.0})
    assert parameter_value_of(model) == 7.0 and model.epsilon() == pytest.approx(1 / 7.0)


def _python_files(folder: pathlib.Path):
    return sorted(folder.rglob("*.py"))


# perturb never importing problems is tests/test_architecture.py's rule (every module, every import).


def test_validation_never_probes_attributes():
    offenders = []
    for path in _python_files(ROOT / "validation"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") in (
                "hasattr",
                "getattr",
            ):
                offenders.append(f"{path.name}:{node.lineno}")
    assert offenders == []
