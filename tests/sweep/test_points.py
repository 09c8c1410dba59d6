"""The work of a task, in this process (no Dask): each point's numbers, statuses and reasons."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.domain import series_domain
from perturb.sweep.derive import DeriveMode, plan
from perturb.sweep.grid import parse_axis
from perturb.sweep.spec import SweepJob, check_spec
from perturb.sweep.status import PointStatus, code_of
from perturb.sweep.task import run_chunk
from perturb.validation import SystemModel
from perturb.validation.model import parameter_value_of
from problems import get_problem
from tests.helpers import roundings

#: The vectorised route and the scalar one evaluate the frequency series of order <= 2 (about ten
#: operations: powers of the amplitude, coefficients, eps, the sums) and 2 pi / Omega each.
PERIOD_ROUTES = roundings(12)
#: ... and the state series: about 8 terms of up to 3 operations (a cosine or sine of j Omega t, a
#: coefficient, the sum), relative to the amplitude, the terms' size.
STATE_ROUTES = roundings(24)


def job_of(model, axes, **settings) -> SweepJob:
    spec = check_spec(model, [parse_axis(a) for a in axes], **settings)
    derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
    return SweepJob(spec, derivation, "test")


def run_all(job):
    return run_chunk(job, np.arange(job.spec.grid.size))


def test_duffing_points_are_the_problems_own_numbers():
    model = get_problem("duffing").create()
    times = [0.0, 0.7, 3.1]
    job = job_of(model, ["eps=0.02:0.2:4", "amplitude=0.5,1.5"], order=2, times=times)
    assert job.derivation.mode is DeriveMode.OWN
    out = run_all(job)
    assert np.all(out["status"] == code_of(PointStatus.OK)) and np.all(out["session"] == 1)
    for k in range(job.spec.grid.size):
        point = model.with_parameters(**job.spec.grid.point(k))
        solution = point.solve(2)
        assert out["epsilon"][k] == point.epsilon()
        # period and state: the vectorised route gives the scalar route's numbers to rounding
        assert out["period"][k] == pytest.approx(point.period(solution), rel=PERIOD_ROUTES)
        frequency = 2 * math.pi / point.period(solution)
        assert out["frequency"][k] == pytest.approx(frequency, rel=PERIOD_ROUTES)
        state = point.state(solution, np.array(times))
        scale = point.values["amplitude"]  # the terms' size: x and xdot cross zero
        for j, name in enumerate(("x", "xdot")):
            np.testing.assert_allclose(
                out["state"][k][:, j], state[name], rtol=0, atol=STATE_ROUTES * scale
            )
        # x(0) = amplitude and the orbit is odd in s -> pi: half its range is the amplitude
        assert out["amplitude"][k][0] == pytest.approx(scale, rel=STATE_ROUTES)


def _extreme(f, t0, dt, sign):
    """sign * max of sign * f near t0 (scipy's bounded Brent search, to its tolerance 1e-13)."""
    from scipy.optimize import minimize_scalar

    found = minimize_scalar(
        lambda t: -sign * f(t),
        bounds=(t0 - dt, t0 + dt),
        method="bounded",
        options={"xatol": 1e-13},
    )
    return sign * -found.fun


def test_amplitudes_are_half_the_range_over_a_period():
    model = get_problem("van-der-pol").create()
    job = job_of(model, ["eps=0.05,0.3"], order=3)
    out = run_all(job)
    for k, eps in enumerate((0.05, 0.3)):
        point = model.with_parameters(eps=eps)
        solution = point.solve(3)
        t = np.linspace(0, point.period(solution), 20_001)
        dt = t[1] - t[0]
        for j, name in enumerate(("x", "xdot")):

            def f(time, name=name, point=point, solution=solution):
                return float(point.state(solution, np.array([time]))[name][0])

            values = point.state(solution, t)[name]
            top = _extreme(f, t[np.argmax(values)], dt, 1.0)
            bottom = _extreme(f, t[np.argmin(values)], dt, -1.0)
            # an extreme found to 1e-13 in t is exact to ~(1e-13)^2 in value
            assert out["amplitude"][k][j] == pytest.approx((top - bottom) / 2, rel=1e-13)
    # the limit cycle: amplitude 2 + O(eps^2)
    assert abs(out["amplitude"][0][0] - 2) < 0.05**2


def test_the_sampled_route_refines_its_extremes():
    from perturb.sweep.evaluate import half_range

    s = 2 * np.pi * np.arange(256) / 256
    x = 1.3 * np.cos(s - 0.0123) + 0.2 * np.sin(3 * s + 0.4)
    dense = np.linspace(0, 2 * np.pi, 2_000_001)
    reference = np.ptp(1.3 * np.cos(dense - 0.0123) + 0.2 * np.sin(3 * dense + 0.4)) / 2
    plain = np.ptp(x) / 2
    # the samples alone miss the extremes by ~1e-4; the quartic through five samples at most by
    # its interpolation error max|x^(5)| step^5 max|prod (u - k)| / 5! at each extreme
    step = 2 * np.pi / 256
    bound = (1.3 + 0.2 * 3**5) * step**5 * (2.5 * 1.5 * 0.5 * 0.5 * 1.5) / 120
    assert abs(plain - reference) > 1e-5
    assert abs(half_range(x) - reference) <= bound


def test_a_point_the_problem_refuses_is_recorded_and_the_rest_computed():
    model = get_problem("duffing").create()
    job = job_of(model, ["amplitude=-1,1"])
    out = run_all(job)
    assert out["status"].tolist() == [
        code_of(PointStatus.INVALID_PARAMETERS),
        code_of(PointStatus.OK),
    ]
    assert "`amplitude` = -1 is invalid: give a value > 0" in out["reason"][0]
    assert math.isnan(out["period"][0]) and math.isfinite(out["period"][1])


def test_outside_the_domain_is_series_domains_verdict_and_reason():
    model = get_problem("van-der-pol").create()
    eps = [0.1, 1.0, 5.0]
    job = job_of(model, [f"eps={','.join(map(str, eps))}"], order=2)
    out = run_all(job)
    for k, value in enumerate(eps):
        point = model.with_parameters(eps=value)
        domain = series_domain(point.solve(2), parameter_value_of(point), point.symbol_values())
        expected = PointStatus.OK if domain.ok else PointStatus.OUTSIDE_DOMAIN
        assert out["status"][k] == code_of(expected)
        if not domain.ok:
            assert out["reason"][k] == "the series is outside its domain: " + "; ".join(
                domain.reasons
            )
    assert out["status"][2] == code_of(PointStatus.OUTSIDE_DOMAIN)  # negative period at eps = 5


def _singular_system():
    """x'' + x = eps x^3 / (a - 1): the coefficients blow up at a = 1."""
    x, v, a = sp.symbols("x v a")
    return QuasilinearSystem([x], [v], [1], [EPS * x**3 / (a - 1)], parameters=[a])


def test_a_bare_system_is_swept_and_a_singular_point_is_not_finite():
    model = SystemModel(_singular_system(), {"a": 3.0, "epsilon": 0.1}, {"amplitudes": {"x": 1}})
    job = job_of(model, ["a=0,1,3"])
    out = run_all(job)
    ok, bad = code_of(PointStatus.OK), code_of(PointStatus.NOT_FINITE)
    assert out["status"].tolist() == [ok, bad, ok]
    assert "not finite" in out["reason"][1]
    # the points around it are the model's own numbers
    for k in (0, 2):
        point = model.with_parameters(a=[0.0, 1.0, 3.0][k])
        assert out["period"][k] == pytest.approx(point.period(point.solve(1)), rel=PERIOD_ROUTES)


def test_a_failing_point_does_not_stop_the_chunk(tmp_path):
    source = tmp_path / "flaky.py"
    source.write_text(
        "from problems.duffing import Duffing\n"
        "class Flaky(Duffing):\n"
        "    name = 'flaky'\n"
        "    def period(self, solution):\n"
        "        if self.values['amplitude'] > 1.2:\n"
        "            raise ZeroDivisionError('no period here')\n"
        "        return super().period(solution)\n"
    )
    from problems.loading import load_problem

    model = load_problem(f"{source}:Flaky").create()
    assert not model.case().evaluates_directly  # it maps the period itself
    job = job_of(model, ["amplitude=1.0,1.5"])
    out = run_all(job)
    assert out["status"].tolist() == [code_of(PointStatus.OK), code_of(PointStatus.FAILED)]
    assert "ZeroDivisionError: no period here" in out["reason"][1]


def test_derive_once_picks_the_symbolic_derivation_where_it_is_needed():
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    # r0 does not enter the derivation (only eps changes): the problem's own solution serves
    own, _ = plan(disk, [parse_axis("r0=0.6:0.9:3")], 2)
    assert own.mode is DeriveMode.OWN
    # order 1 is symbolic in the body's parameters already
    first, _ = plan(disk, [parse_axis("gamma3_0=0.2:0.3:3")], 1)
    assert first.mode is DeriveMode.OWN
    asked, solution = plan(disk, [parse_axis("gamma3_0=0.2:0.3:3")], 2, "per-point")
    assert asked.mode is DeriveMode.PER_POINT and solution is None
    # each of 3 derivations would serve 20 points: made once each, chunks along r0
    axes = [parse_axis("r0=0.6:0.9:20"), parse_axis("gamma3_0=0.2:0.3:3")]
    cheaper, _ = plan(disk, axes, 2)
    assert cheaper.mode is DeriveMode.PER_POINT and cheaper.entering == ("gamma3_0",)
    spec = check_spec(disk, axes, order=2)
    assert SweepJob(spec, cheaper, "k").fill_first() == (0,)


@pytest.mark.parametrize(
    ("name", "order", "parameter", "low", "high"),
    [
        ("van-der-pol", 3, "eps", -6.0, 6.0),
        ("duffing", 3, "eps", -3.0, 3.0),
        ("resonant-pair", 2, None, None, None),
    ],
)
def test_the_domain_screen_is_series_domain(name, order, parameter, low, high):
    """Where the screen clears a point, series_domain does too; elsewhere it is series_domain."""
    from perturb.sweep.evaluate import DomainScreen, group_arrays

    problem = get_problem(name).create()
    solution = problem.solve(order)
    specs = [s for s in type(problem).parameter_specs]
    rng = np.random.default_rng(21)
    models = []
    for _ in range(200):
        values = {}
        for spec in specs:
            scale = abs(spec.default) or 1.0
            lo, hi = (low, high) if spec.name == parameter else (-4 * scale, 4 * scale)
            values[spec.name] = float(rng.uniform(lo, hi))
        try:
            models.append(problem.with_parameters(**values))
        except ValueError:
            continue
    pv, arrays = group_arrays(models)
    omega = np.array([float(np.asarray(solution.coefficients(parameter_value_of(m), m.symbol_values())[0]))
                      if np.isfinite(parameter_value_of(m)) else np.nan for m in models])  # fmt: skip
    checks = DomainScreen(solution).check(pv, arrays, omega)
    cleared = 0
    for model, check in zip(models, checks, strict=True):
        exact = series_domain(solution, parameter_value_of(model), model.symbol_values())
        assert check.ok == exact.ok and tuple(check.reasons) == tuple(exact.reasons)
        cleared += check.ok
    assert 0 < cleared < len(models) or name == "resonant-pair"


def test_a_component_that_does_not_return_has_no_amplitude():
    from perturb.sweep.evaluate import half_range

    s = 2 * np.pi * np.arange(256) / 256
    phase, wave = 1.7 * s, np.cos(s)
    amplitudes = half_range(np.array([phase, wave]))
    assert np.isnan(amplitudes[0]) and amplitudes[1] == pytest.approx(1.0, rel=1e-9)
