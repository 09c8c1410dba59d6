"""The members that left ``Problem``: asked through functions, and still answered for old scripts.

``original_rhs``, ``original_equations`` and ``with_epsilon`` are functions of
``perturb.validation`` that read a class's own hook (a user's file defining one is asked it, with
no warning), ``steady_state`` is ``perturb.response.steady_state_of`` and ``with_family`` the
``family`` keyword of ``create``. A script that still calls one of the old methods gets the same
answer with a ``DeprecationWarning`` naming the replacement.
"""

from __future__ import annotations

import importlib.util
import pickle
import sys
import textwrap
import warnings

import numpy as np
import pytest

from perturb.errors import InvalidSystemError
from perturb.response import steady_state_of
from perturb.validation import (
    Equations,
    original_equations,
    original_rhs,
    system_equations,
    with_epsilon,
)
from problems import get_problem
from problems.base import MOVED, Problem

#: A state where both routes evaluate the same compiled field: equal to the last bit on one
#: machine, so a relative 1e-15 only allows for nothing but the order of two sums.
SAME_FIELD = 1e-15


def _old(problem, name, *args):
    """``problem.name(*args)`` as a script of an earlier version calls it, with its warnings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        answer = getattr(problem, name)(*args)
    deprecations = [w for w in caught if issubclass(w.category, DeprecationWarning)]
    assert len(deprecations) == 1, [str(w.message) for w in caught]
    assert deprecations[0].filename == __file__  # the warning points at the caller's line
    return answer, str(deprecations[0].message)


def test_the_moved_names_are_not_members():
    public = {name for name in dir(Problem) if not name.startswith("_")}
    assert not public & set(MOVED)
    duffing = get_problem("duffing").create()
    with pytest.raises(AttributeError, match="no attribute 'not_a_member'"):
        duffing.not_a_member  # noqa: B018 - the attribute access is the test


@pytest.mark.parametrize("name", ["duffing", "van-der-pol"])
def test_original_rhs_and_equations_old_and_new_agree(name):
    problem = get_problem(name).create(eps=0.1)
    y = np.array([1.3, -0.4])
    field = original_rhs(problem)
    old, message = _old(problem, "original_rhs")
    assert "perturb.validation.original_rhs(problem)" in message
    np.testing.assert_allclose(old(0.0, y), field(0.0, y), rtol=SAME_FIELD)
    equations = original_equations(problem)
    assert equations.quasilinear
    np.testing.assert_allclose(equations.rhs(y), field(0.0, y), rtol=SAME_FIELD)
    old_equations, message = _old(problem, "original_equations", y)
    assert "original_equations(problem, y0)" in message
    np.testing.assert_allclose(old_equations.rhs(y), equations.rhs(y), rtol=SAME_FIELD)


def test_with_epsilon_old_and_new_agree_and_keep_the_family():
    pair = get_problem("resonant-pair").create(eps=0.05, family="anti-phase")
    moved = with_epsilon(pair, 0.025)
    assert moved.epsilon() == pytest.approx(0.025, rel=1e-12)
    assert moved.case().family == "anti-phase"
    old, message = _old(pair, "with_epsilon", 0.025)
    assert "with_epsilon(problem, eps)" in message
    assert old == moved


def test_steady_state_old_and_new_agree():
    duffing = get_problem("forced-duffing").create(Omega=1.05)
    state = steady_state_of(duffing, 1)
    assert state.names == ("lower", "middle", "upper")
    old, message = _old(duffing, "steady_state", 1)
    assert "perturb.response.steady_state_of" in message
    assert old.names == state.names
    assert [p.stable for p in old.points] == [p.stable for p in state.points]


def test_create_with_a_family_is_the_old_with_family():
    pair = get_problem("resonant-pair")
    chosen = pair.create(eps=0.05, family="anti-phase")
    old, message = _old(pair.create(eps=0.05), "with_family", "anti-phase")
    assert "family=NAME" in message
    assert old == chosen
    assert chosen.case().family == "anti-phase"
    assert chosen.solve(1) is pair.create(eps=0.05).solve(1, family="anti-phase")
    assert pickle.loads(pickle.dumps(chosen)) == chosen  # the fallback leaves pickling alone


USER_FILE = """
import numpy as np
import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.validation import Equations, system_equations
from problems.base import ParameterSpec, Problem

X, XDOT, A = sp.symbols("x xdot amplitude")


class Own(Problem):
    name = "own-hooks"
    summary = "a Duffing oscillator with every moved hook of its own"
    parameter_specs = (ParameterSpec("eps", 0.1, "strength"), ParameterSpec("amplitude", 1.0, "x(0)"))
    calls = []

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], parameters=[A])

    def method_options(self):
        return {"amplitudes": {"x": A}}

    def original_equations(self, y0=None):
        type(self).calls.append("original_equations")
        return system_equations(self, y0)  # what super().original_equations(y0) gave

    def with_epsilon(self, eps):
        type(self).calls.append("with_epsilon")
        return type(self).create(eps=eps, amplitude=self.values["amplitude"])


class OwnRHS(Own):
    name = "own-rhs"

    def original_rhs(self):
        eps = self.epsilon()
        return lambda t, y: np.array([y[1], -y[0] - eps * y[0] ** 3])


class Family(Own):
    name = "with-a-family"
    parameter_specs = (*Own.parameter_specs, ParameterSpec("family", 1.0, "a clash"))
"""


@pytest.fixture(scope="module")
def user_module(tmp_path_factory):
    path = tmp_path_factory.mktemp("user") / "own_hooks_file.py"
    path.write_text(textwrap.dedent(USER_FILE))
    spec = importlib.util.spec_from_file_location("own_hooks_file", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


def test_a_users_own_hooks_are_asked_without_a_warning(user_module):
    own = user_module.Own.create(eps=0.1)
    user_module.Own.calls.clear()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a class's own hook is no moved member: no warning
        equations = original_equations(own, None)
        moved = with_epsilon(own, 0.05)
        own.original_equations()
        own.with_epsilon(0.02)
    assert isinstance(equations, Equations)
    assert moved.epsilon() == pytest.approx(0.05, rel=1e-12)
    assert user_module.Own.calls == ["original_equations", "with_epsilon"] * 2
    y = np.array([0.7, 0.2])
    np.testing.assert_allclose(equations.rhs(y), system_equations(own).rhs(y), rtol=SAME_FIELD)


def test_an_own_rhs_becomes_the_equations(user_module):
    own = user_module.OwnRHS.create(eps=0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        field = original_rhs(own)
    y = np.array([0.7, 0.2])
    assert field(0.0, y)[1] == pytest.approx(-0.7 - 0.1 * 0.7**3, rel=SAME_FIELD)


def test_a_parameter_named_family_is_refused_in_one_line(user_module):
    with pytest.raises(InvalidSystemError, match="parameter named `family`.*rename it"):
        user_module.Family.create()


def test_a_hook_returning_something_else_is_refused_in_one_line(user_module):
    class Wrong(user_module.Own):
        name = "wrong-equations"

        def original_equations(self, y0=None):
            return lambda y: y

    with pytest.raises(InvalidSystemError, match="return perturb.validation.Equations"):
        original_equations(Wrong.create())


def test_a_number_given_as_family_is_a_parameter_the_problem_does_not_have(capsys):
    """A family is a name: ``--set family=1`` or a grid over ``family`` is told, as before the
    keyword existed, that the problem has no such parameter."""
    from perturb.cli import main
    from perturb.errors import UnknownNameError

    assert main(["solve", "duffing", "--set", "family=1"]) == 2
    err = capsys.readouterr().err
    assert "`family` is not a parameter of duffing" in err and "Traceback" not in err
    with pytest.raises(UnknownNameError, match="`family` is not a parameter of duffing"):
        get_problem("duffing").create().with_parameters(family=2.0)
