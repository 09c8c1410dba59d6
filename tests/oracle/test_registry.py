"""`choose`, the one rule for "which integrator", and the status enums of the oracle's results."""

from __future__ import annotations

import pytest

from perturb.errors import InvalidParameterError, UnknownNameError
from perturb.oracle import (
    INTEGRATORS,
    RK4,
    Heyoka,
    OrbitStatus,
    Scipy,
    Trajectory,
    TrajectoryStatus,
    choose,
    heyoka_available,
)


def test_default_for_a_stiff_system_is_radau_at_a_reachable_tolerance():
    integrator = choose(rtol=1e-12, stiff=True)
    assert isinstance(integrator, Scipy) and integrator.method == "Radau"
    assert integrator.rtol == 1e-10  # Radau's Newton iterations stop converging below 1e-10
    assert choose(rtol=1e-8, stiff=True).rtol == 1e-8  # a looser request is kept


def test_a_step_budget_overrides_the_stiff_default():
    integrator = choose(stiff=True, max_steps=100, symbolic=False)
    assert isinstance(integrator, Scipy) and integrator.method == "DOP853"
    assert integrator.max_steps == 100


def test_default_for_a_symbolic_rhs_is_heyoka_when_installed():
    integrator = choose(rtol=1e-11)
    if heyoka_available():
        assert isinstance(integrator, Heyoka)
    else:
        assert isinstance(integrator, Scipy) and integrator.rtol == 1e-11


def test_default_for_a_numeric_rhs_is_dop853_at_the_requested_tolerance():
    integrator = choose(rtol=1e-9, symbolic=False)
    assert isinstance(integrator, Scipy) and integrator.method == "DOP853"
    assert integrator.rtol == 1e-9


@pytest.mark.parametrize("name", ["dop853", "RK45", "radau", "lsoda"])
def test_scipy_names_take_rtol_and_the_step_budget(name):
    integrator = choose(name, rtol=1e-7, max_steps=50)
    assert isinstance(integrator, Scipy) and integrator.method.lower() == name.lower()
    assert integrator.rtol == 1e-7 and integrator.max_steps == 50


def test_rk4_by_name_keeps_its_own_settings():
    assert choose("rk4", rtol=1e-3) == RK4()


def test_an_integrator_object_is_returned_unchanged():
    mine = Scipy("RK45", rtol=1e-5)
    assert choose(mine, rtol=1e-12, stiff=True) is mine


def test_heyoka_is_refused_without_symbolic_equations():
    with pytest.raises(InvalidParameterError, match="`integrator`.*dop853"):
        choose("heyoka", symbolic=False)


def test_unknown_name_lists_the_known_ones():
    with pytest.raises(UnknownNameError) as info:
        choose("euler")
    message = str(info.value)
    assert "'euler'" in message and all(name in message for name in INTEGRATORS)


def test_other_types_are_refused_naming_the_argument():
    with pytest.raises(InvalidParameterError, match="`integrator`"):
        choose(3.5)


@pytest.mark.parametrize("enum", [TrajectoryStatus, OrbitStatus])
def test_status_values_are_messages_and_only_the_first_member_succeeds(enum):
    members = list(enum)
    assert members[0].success and not any(m.success for m in members[1:])
    assert all(isinstance(m.value, str) and m.value.endswith(".") for m in members)
    assert len({m.value for m in members}) == len(members)


def test_trajectory_refuses_an_integer_status():
    with pytest.raises(TypeError):
        Trajectory(t=[0.0], y=[[0.0]], status=0)
