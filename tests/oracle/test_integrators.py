"""Integrators behind the oracle protocol: accuracy against exact solutions, RK4 order, failures,
error messages."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.errors import IntegrationError, InvalidParameterError, UnknownNameError
from perturb.oracle import (
    INTEGRATORS,
    RK4,
    Heyoka,
    Integrator,
    Scipy,
    SymbolicRHS,
    Trajectory,
    TrajectoryStatus,
    default_integrator,
    get_integrator,
    heyoka_available,
    scaled_atol,
    to_heyoka,
)
from tests.helpers import fitted_slope
from tests.oracle.systems import HARMONIC, duffing, duffing_exact, duffing_period, harmonic_exact

needs_heyoka = pytest.mark.skipif(not heyoka_available(), reason="heyoka is not installed")

#: Adaptive local-error control gives a global error growing about linearly in time, roughly
#: tol per unit time on these unit-frequency oscillators (measured: 0.2-1.6 tol per unit time);
#: the factor 5 leaves margin for platform differences.
GLOBAL_ERROR_PER_UNIT_TIME = 5.0

#: (registry name, options, tolerance) of every integrator; the tolerance is what the options promise.
ADAPTIVE_CASES = [
    ("dop853", {"rtol": 1e-10}, 1e-10),
    ("rk45", {"rtol": 1e-8}, 1e-8),
    ("radau", {"rtol": 1e-7}, 1e-7),  # implicit: slow at tight tolerances, loose one suffices here
    ("lsoda", {"rtol": 1e-10}, 1e-10),
    pytest.param("heyoka", {"tol": 1e-12}, 1e-12, marks=needs_heyoka),
]

#: RK4 steps per unit time in the accuracy tests.
RK4_STEPS = 100


def rk4_harmonic_bound(t_end: float, h: float, amplitude: float) -> float:
    """Leading global error of RK4 on x'' + x = 0: the phase error per step is h**5/120."""
    return amplitude * t_end * h**4 / 120


# --------------------------------------------------------------------------------------------------
# accuracy
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "options", "tol"), ADAPTIVE_CASES)
def test_adaptive_integrators_match_harmonic_exact_solution(name, options, tol):
    y0, t_end = [1.0, 0.5], 20.0
    t = np.linspace(0.0, t_end, 41)
    trajectory = get_integrator(name, **options).integrate(HARMONIC, (0.0, t_end), y0, t_eval=t)
    assert trajectory.success, trajectory.message
    np.testing.assert_array_equal(trajectory.t, t)
    error = np.max(np.abs(trajectory.y.astype(float) - harmonic_exact(y0, t)))
    assert error <= GLOBAL_ERROR_PER_UNIT_TIME * tol * t_end


def test_rk4_matches_harmonic_exact_solution_to_its_error_bound():
    y0, t_end = [1.0, 0.5], 20.0
    t = np.linspace(0.0, t_end, 41)
    trajectory = RK4(steps_per_unit=RK4_STEPS).integrate(HARMONIC, (0.0, t_end), y0, t_eval=t)
    error = np.max(np.abs(trajectory.y - harmonic_exact(y0, t)))
    assert error <= 1.5 * rk4_harmonic_bound(t_end, 1.0 / RK4_STEPS, math.hypot(*y0))
    assert trajectory.nfev == 4 * RK4_STEPS * t_end


@pytest.fixture(scope="module")
def duffing_reference():
    """Duffing x'' + x + x**3 = 0 from x = 1.5 over 10 periods: exact (cn) and high-accuracy runs."""
    amplitude = 1.5
    t_end = 10 * duffing_period(amplitude)
    t = np.linspace(0.0, t_end, 51)
    if heyoka_available():
        reference = Heyoka(high_precision=True).integrate(
            duffing(), (0.0, t_end), [amplitude, 0.0], t_eval=t
        )
    else:
        reference = Scipy("DOP853", rtol=1e-14).integrate(
            duffing(), (0.0, t_end), [amplitude, 0.0], t_eval=t
        )
    assert reference.success, reference.message
    return amplitude, t, reference


def test_high_accuracy_reference_matches_elliptic_function_solution(duffing_reference):
    amplitude, t, reference = duffing_reference
    # ellipj is accurate to a few 1e-15 per unit argument; 1e-12 covers the 10-period run of the
    # extended-precision heyoka reference. Without heyoka the reference is DOP853 at scipy's rtol
    # floor (2.2e-14), whose global error grows to ~1e-12 over the run: allow 5e-12 there.
    tolerance = 1e-12 if heyoka_available() else 5e-12
    assert np.max(np.abs(reference.y.astype(float) - duffing_exact(amplitude, t))) < tolerance


@pytest.mark.parametrize(("name", "options", "tol"), ADAPTIVE_CASES)
def test_adaptive_integrators_match_duffing_reference(duffing_reference, name, options, tol):
    amplitude, t, reference = duffing_reference
    trajectory = get_integrator(name, **options).integrate(
        duffing(), (0.0, t[-1]), [amplitude, 0.0], t_eval=t
    )
    assert trajectory.success, trajectory.message
    error = np.max(np.abs(trajectory.y.astype(float) - reference.y.astype(float)))
    assert error <= GLOBAL_ERROR_PER_UNIT_TIME * tol * t[-1]


def test_rk4_matches_duffing_reference(duffing_reference):
    amplitude, t, reference = duffing_reference
    trajectory = RK4(steps_per_unit=RK4_STEPS).integrate(
        duffing(), (0.0, t[-1]), [amplitude, 0.0], t_eval=t
    )
    error = np.max(np.abs(trajectory.y - reference.y.astype(float)))
    # measured 4.5e-7 with h = 0.01 over 10 periods (the nonlinearity raises the error constant
    # ~5x above the harmonic bound); the order itself is checked by the slope test below
    assert error <= 1e-6


def test_rk4_global_error_falls_as_h_to_the_fourth():
    t_end, y0 = 10.0, [1.2, 0.0]
    exact = duffing_exact(1.2, [t_end])[:, -1]
    steps = np.array([50, 100, 200, 400])
    errors = [
        np.max(np.abs(RK4(n_steps=int(n)).integrate(duffing(), (0.0, t_end), y0).y_final - exact))
        for n in steps
    ]
    assert abs(fitted_slope(t_end / steps, errors) - 4.0) < 0.3


def test_rk4_hits_every_output_time_exactly():
    t = np.array([0.3, 0.35, 1.0, 2.0])
    trajectory = RK4(steps_per_unit=50).integrate(HARMONIC, (0.0, 2.0), [1.0, 0.0], t_eval=t)
    np.testing.assert_array_equal(trajectory.t, t)
    np.testing.assert_allclose(trajectory.y, harmonic_exact([1.0, 0.0], t), atol=1e-9)


@needs_heyoka
@pytest.mark.parametrize("fp_type", ["long double", "real128"])
def test_heyoka_extended_precision_beats_double(fp_type):
    trajectory = Heyoka(fp_type=fp_type).integrate(HARMONIC, (0.0, 10.0), [1.0, 0.0])
    # cos(10) in long double, accurate to ~1e-19
    exact = np.cos(np.longdouble(10))
    assert abs(np.longdouble(str(trajectory.y_final[0])) - exact) < 1e-17
    assert fp_type in trajectory.integrator


def test_scaled_atol_keeps_small_states_accurate():
    """A scalar atol of 1e-6 ignores a 1e-3 state; per-component tolerances scale with it."""
    amplitude = 1e-3
    t_end = 5 * duffing_period(amplitude)
    exact = duffing_exact(amplitude, [t_end])[:, -1]

    def relative_error(integrator):
        y_end = integrator.integrate(duffing(), (0.0, t_end), [amplitude, 0.0]).y_final
        return np.max(np.abs(y_end - exact)) / amplitude

    assert relative_error(Scipy("RK45", rtol=1e-10, atol=1e-6)) > 1e-6
    assert relative_error(Scipy("RK45", rtol=1e-10)) < 1e-8  # default: atol scaled to y0
    assert relative_error(Scipy("RK45", rtol=1e-10, y_scale=[amplitude, amplitude])) < 1e-8


def test_scaled_atol_values():
    np.testing.assert_allclose(scaled_atol([1e-3, 0.0, -2e-3], rtol=1e-10), [1e-13, 2e-16, 2e-13])
    with pytest.raises(InvalidParameterError, match="y_scale"):
        scaled_atol([0.0, 0.0])
    with pytest.raises(InvalidParameterError, match="rtol"):
        scaled_atol([1.0], rtol=-1.0)


def test_plain_callable_and_symbolic_rhs_give_the_same_trajectory():
    def numeric(y):
        return np.array([y[1], -y[0]])

    integrator = Scipy("DOP853", rtol=1e-10)
    a = integrator.integrate(numeric, (0.0, 3.0), [1.0, 0.0])
    b = integrator.integrate(HARMONIC, (0.0, 3.0), [1.0, 0.0])
    np.testing.assert_allclose(a.y, b.y, rtol=0, atol=1e-15)


# --------------------------------------------------------------------------------------------------
# registry and result object
# --------------------------------------------------------------------------------------------------


def test_registry_names_and_protocol():
    assert set(INTEGRATORS) == {"rk4", "dop853", "rk45", "radau", "lsoda", "heyoka"}
    for name in INTEGRATORS:
        integrator = get_integrator(name.upper())
        assert isinstance(integrator, Integrator)
        assert integrator.name


def test_unknown_integrator_lists_the_known_names():
    with pytest.raises(UnknownNameError, match=r"'euler'.*dop853.*heyoka.*rk4"):
        get_integrator("euler")


def test_default_integrator_and_trajectory_say_which_ran():
    expected = "heyoka" if heyoka_available() else "DOP853"
    integrator = default_integrator()
    assert expected in integrator.name
    assert expected in integrator.integrate(HARMONIC, (0.0, 1.0), [1.0, 0.0]).integrator
    # heyoka cannot integrate a plain numeric callable: the default falls back to DOP853
    assert "DOP853" in default_integrator(lambda y: -y).name


def test_trajectory_is_a_frozen_value_object():
    a = RK4(n_steps=10).integrate(HARMONIC, (0.0, 1.0), [1.0, 0.0])
    b = RK4(n_steps=10).integrate(HARMONIC, (0.0, 1.0), [1.0, 0.0])
    assert a == b and a.success and a.status is TrajectoryStatus.SUCCESS
    assert a.y.shape == (2, 2) and a.t_reached == 1.0
    with pytest.raises(ValueError):
        a.y[0, 0] = 5.0  # read-only arrays
    assert a.raise_for_status() is a
    assert isinstance(a, Trajectory)


# --------------------------------------------------------------------------------------------------
# failures return a trajectory; bad input raises
# --------------------------------------------------------------------------------------------------

BLOW_UP = SymbolicRHS((sp.Symbol("y"),), (sp.Symbol("y") ** 2,))  # y = 1/(1 - t): singular at t = 1


@pytest.mark.parametrize(
    "integrator",
    [
        RK4(steps_per_unit=100),
        Scipy("DOP853"),
        Scipy("LSODA"),
        pytest.param(Heyoka(), marks=needs_heyoka),
    ],
    ids=lambda i: i.name,
)
@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")
def test_blow_up_returns_failed_trajectory_with_message_and_time(integrator):
    trajectory = integrator.integrate(BLOW_UP, (0.0, 2.0), [1.0], t_eval=[0.0, 0.5, 1.5, 2.0])
    assert not trajectory.success and not trajectory.status.success
    assert trajectory.message and trajectory.message != "failed"
    assert 0.99 < trajectory.t_reached < 1.1
    np.testing.assert_allclose(trajectory.y[0, :2], [1.0, 2.0], rtol=1e-6)  # points before t = 1
    with pytest.raises(IntegrationError) as info:
        trajectory.raise_for_status()
    assert info.value.t_reached == trajectory.t_reached


@pytest.mark.parametrize(
    "integrator",
    [Scipy("DOP853", max_steps=3), pytest.param(Heyoka(max_steps=3), marks=needs_heyoka)],
    ids=lambda i: i.name,
)
def test_step_budget_exhaustion_is_reported(integrator):
    trajectory = integrator.integrate(HARMONIC, (0.0, 100.0), [1.0, 0.0])
    assert trajectory.status is TrajectoryStatus.MAX_STEPS
    assert "max_steps" in trajectory.message
    assert 0.0 < trajectory.t_reached < 100.0


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"t_span": (1.0, 1.0)}, "t_span"),
        ({"t_span": (1.0, 0.0)}, "t_span"),
        ({"t_span": (0.0, math.inf)}, "t_span"),
        ({"y0": [math.nan, 0.0]}, "y0"),
        ({"y0": [[1.0, 0.0]]}, "y0"),
        ({"t_eval": [0.0, 2.0]}, "t_eval"),
        ({"t_eval": [0.5, 0.2]}, "t_eval"),
    ],
)
@pytest.mark.parametrize("name", sorted(INTEGRATORS))
def test_bad_integration_input_names_the_argument(name, kwargs, argument):
    if name == "heyoka" and not heyoka_available():
        pytest.skip("heyoka is not installed")
    call = {"t_span": (0.0, 1.0), "y0": [1.0, 0.0], "t_eval": None} | kwargs
    with pytest.raises(InvalidParameterError, match=f"`{argument}`.*invalid: "):
        get_integrator(name).integrate(HARMONIC, call["t_span"], call["y0"], t_eval=call["t_eval"])


@pytest.mark.parametrize(
    ("factory", "argument"),
    [
        (lambda: Scipy(rtol=0.0), "rtol"),
        (lambda: Scipy(rtol=-1e-8), "rtol"),
        (lambda: Scipy(atol=[1e-8, -1.0]), "atol"),
        (lambda: RK4(steps_per_unit=0), "steps_per_unit"),
        (lambda: RK4(n_steps=0), "n_steps"),
        (lambda: RK4(n_steps=10, steps_per_unit=10), "n_steps"),
        (lambda: Heyoka(tol=0.0), "tol"),
        (lambda: Heyoka(fp_type="float16"), "fp_type"),
    ],
)
def test_bad_integrator_options_name_the_argument_value_and_fix(factory, argument):
    with pytest.raises(InvalidParameterError, match=f"`{argument}` = .* is invalid: .+"):
        factory()


def test_atol_of_the_wrong_length_is_rejected():
    with pytest.raises(InvalidParameterError, match="`atol`.*one per component"):
        Scipy(atol=[1e-9, 1e-9, 1e-9]).integrate(HARMONIC, (0.0, 1.0), [1.0, 0.0])


@needs_heyoka
def test_heyoka_with_numeric_rhs_asks_for_a_symbolic_rhs():
    with pytest.raises(InvalidParameterError, match="heyoka needs a symbolic rhs.*SymbolicRHS"):
        Heyoka().integrate(lambda y: -y, (0.0, 1.0), [1.0])


# --------------------------------------------------------------------------------------------------
# symbolic rhs
# --------------------------------------------------------------------------------------------------


def test_symbolic_rhs_rejects_stray_symbols_and_wrong_lengths():
    x, v, k = sp.symbols("x v k")
    with pytest.raises(InvalidParameterError, match="`expressions` = 'k'.*substitute"):
        SymbolicRHS((x, v), (v, -k * x))
    with pytest.raises(InvalidParameterError, match="one expression per state symbol"):
        SymbolicRHS((x, v), (v,))


def test_symbolic_rhs_jacobian_and_variational_system():
    rhs = duffing(beta=2.0)
    np.testing.assert_allclose(rhs.jacobian([1.0, 0.0]), [[0.0, 1.0], [-7.0, 0.0]])
    variational = rhs.variational
    assert variational.n == 6
    z = np.concatenate(([1.0, 0.0], np.eye(2).ravel()))
    np.testing.assert_allclose(variational(z)[2:], [0.0, 1.0, -7.0, 0.0])


@needs_heyoka
def test_to_heyoka_rounds_rationals_in_the_target_precision():
    x = sp.Symbol("x")
    import heyoka as hy

    (var,) = [hy.make_vars("x")]
    third = to_heyoka(sp.Rational(1, 3) * x, {x: var}, np.longdouble)
    assert "0.333333333333333333" in str(third)  # 18+ digits: long double, not double
    with pytest.raises(InvalidParameterError, match="heyoka implements only"):
        to_heyoka(sp.besselj(0, x), {x: var})


def test_scipy_integrate_is_imported_only_when_a_scipy_integrator_runs():
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    code = (
        "import sys, numpy as np; import perturb.oracle, perturb.validation; "
        "print('scipy.integrate' in sys.modules); "
        "perturb.oracle.Scipy().integrate(lambda y: -y, (0.0, 1.0), np.ones(1)); "
        "print('scipy.integrate' in sys.modules)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=root,
        env={"PYTHONPATH": str(root), "PATH": "", "PERTURB_CACHE_DIR": "off"},
    ).stdout.split()  # fmt: skip
    assert out == ["False", "True"]
