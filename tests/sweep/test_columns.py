"""The columns route of a chunk (no model per point, the case's points) gives the per-point
route's very results.

Every variable, status, reason and warning of ``run_chunk(job, indices)`` is compared with
``run_chunk(job, indices, columns=False)``, which makes each point's model with
``with_parameters``; and the route is offered only where that equality is a promise.
"""

from __future__ import annotations

import warnings

import hypothesis.strategies as st
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given

from perturb import EPS, QuasilinearSystem, Regime
from perturb.sweep.derive import plan
from perturb.sweep.grid import parse_axis
from perturb.sweep.spec import SweepJob, check_spec
from perturb.sweep.status import PointStatus, code_of
from perturb.sweep.task import run_chunk
from problems import ParameterSpec, Problem, get_problem
from problems.base import positive

x, xdot, a, c, mu = sp.symbols("x xdot a c mu")


def job_of(model, axes, **settings) -> SweepJob:
    spec = check_spec(model, [parse_axis(axis) for axis in axes], **settings)
    derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
    return SweepJob(spec, derivation, "test")


def both_routes(job):
    indices = np.arange(job.spec.grid.size)
    return run_chunk(job, indices), run_chunk(job, indices, columns=False)


def assert_same(fast: dict, slow: dict) -> None:
    assert fast.keys() == slow.keys()
    for name in fast:
        if name in ("seconds", "cpu"):
            continue
        one, other = np.asarray(fast[name]), np.asarray(slow[name])
        if one.dtype == object:
            assert one.tolist() == other.tolist(), name
        else:
            np.testing.assert_array_equal(one, other, err_msg=name)


def offered(job) -> bool:
    grid = job.spec.grid
    columns = {axis.name: np.asarray(axis.values, dtype=float) for axis in grid.axes}
    size = min(axis.size for axis in grid.axes)
    columns = {name: values[:size] for name, values in columns.items()}
    return job.spec.model.case().points(columns) is not None


class Pinned(Problem):
    """Duffing's oscillator with a whole-set check that warns near its edge and refuses past it."""

    name = "pinned"
    summary = "x'' + x = -eps c x^3, x(0) = a, with a c <= 2"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter"),
        ParameterSpec("a", 1.0, "x(0)", positive),
        ParameterSpec("c", 1.0, "cubic coefficient"),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([x], [xdot], [1], [-EPS * c * x**3], parameters=[a, c])

    def method_options(self):
        return {"amplitudes": {"x": a}}

    def check_values(self, values):
        product = values["a"] * values["c"]
        if product > 2:
            raise ValueError(f"a * c = {product:g} exceeds 2: give a smaller a or c")
        if product > 1.5:
            warnings.warn(f"a * c = {product:g} is near its limit 2", stacklevel=2)


class ReadsAmplitude(Pinned):
    """The same oscillator whose amplitude enters the method options as a number."""

    name = "reads-amplitude"

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([x], [xdot], [1], [-EPS * c * x**3], parameters=[c])

    def method_options(self):
        return {"amplitudes": {"x": sp.Float(self.values["a"])}}


class ComparesMode(Pinned):
    """Options that compare a parameter with a number (with the parameter a plain sympy symbol,
    ``mode == 1`` would be a silent False: the case must read it as read)."""

    name = "compares-mode"
    parameter_specs = (*Pinned.parameter_specs, ParameterSpec("mode", 1.0, "which amplitude"))

    def method_options(self):
        return {"amplitudes": {"x": a if self.values["mode"] == 1 else 2 * a}}


class OwnSymbols(Pinned):
    """The same oscillator whose symbols' values are its own (c doubled)."""

    name = "own-symbols"

    def symbol_values(self):
        return {"a": self.values["a"], "c": 2 * self.values["c"]}


class OwnParameterValue(Pinned):
    """The same oscillator whose solution's own parameter is computed by the class."""

    name = "own-parameter-value"

    def parameter_value(self):
        return self.values["eps"]


class Large(Problem):
    """Van der Pol's oscillator written in the large parameter mu = 1/eps."""

    name = "large-vdp"
    summary = "x'' + x = (1 - x^2) x' / mu"
    parameter_specs = (ParameterSpec("eps", 0.1, "1/mu"),)

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [x], [xdot], [1], [(1 - x**2) * xdot / mu], parameter=mu, regime=Regime.LARGE
        )


def test_duffing_every_status_the_same_through_both_routes():
    model = get_problem("duffing").create()
    job = job_of(model, ["eps=-0.3:0.6:19", "amplitude=-0.5:3.5:21"], order=2, times=[0, 1.5])
    assert offered(job)
    fast, slow = both_routes(job)
    assert_same(fast, slow)
    statuses = set(fast["status"].tolist())
    expected = {PointStatus.OK, PointStatus.INVALID_PARAMETERS, PointStatus.OUTSIDE_DOMAIN}
    assert statuses == {code_of(s) for s in expected}


def test_whole_set_checks_and_their_warnings_are_the_points_own():
    job = job_of(Pinned.create(), ["a=0.5:3:6", "c=0.2:1.4:5"], order=2)
    assert offered(job)
    fast, slow = both_routes(job)
    assert_same(fast, slow)
    assert any("exceeds 2" in r for r in fast["reason"].tolist())
    assert any("near its limit" in w for w in fast["warnings"].tolist())


def test_options_that_read_a_changing_parameter_make_the_points_one_by_one():
    varying = job_of(ReadsAmplitude.create(), ["a=0.5:1.5:3", "c=0.2:1:3"], order=2)
    assert not offered(varying)
    assert_same(*both_routes(varying))
    fixed_a = job_of(ReadsAmplitude.create(a=0.8), ["c=0.2:1:5"], order=2)
    assert offered(fixed_a)
    assert_same(*both_routes(fixed_a))


def test_options_that_compare_a_parameter_with_a_number_read_it():
    varying = job_of(ComparesMode.create(), ["mode=1,2", "c=0.2:1:3"], order=2)
    assert not offered(varying)
    fast, slow = both_routes(varying)
    assert_same(fast, slow)
    amplitudes = fast["amplitude"].reshape(2, 3, -1)[:, 0, 0]
    assert amplitudes[1] == pytest.approx(2 * amplitudes[0], rel=0.05)  # each mode its own
    fixed = job_of(ComparesMode.create(mode=2.0), ["c=0.2:1:3"], order=2)
    assert offered(fixed)
    assert_same(*both_routes(fixed))


def test_a_class_with_its_own_symbol_values_is_not_offered():
    job = job_of(OwnSymbols.create(), ["c=0.2:0.6:3"], order=1)
    assert not offered(job)
    assert_same(*both_routes(job))


def test_a_class_with_its_own_parameter_value_is_not_offered():
    job = job_of(OwnParameterValue.create(), ["c=0.2:0.6:3"], order=1)
    assert not offered(job)
    assert_same(*both_routes(job))


def test_the_large_parameter_regime():
    job = job_of(Large.create(), ["eps=0.05:0.4:7"], order=2, times=[0, 2])
    assert offered(job)
    fast, slow = both_routes(job)
    assert_same(fast, slow)
    assert np.all(fast["status"] == code_of(PointStatus.OK))


def test_a_validated_sweep_makes_its_points_one_by_one():
    job = job_of(get_problem("duffing").create(), ["eps=0.05,0.1"], order=1, validate=True)
    fast = run_chunk(job, np.arange(2))
    assert np.all(fast["verdict"] >= 0)  # validated: the per-point route ran


@given(
    eps=st.tuples(st.floats(-0.5, 0.8), st.floats(-0.5, 0.8)),
    amplitude=st.tuples(st.floats(-1, 4), st.floats(-1, 4)),
    order=st.integers(1, 3),
)
def test_any_duffing_grid_the_same_through_both_routes(eps, amplitude, order):
    axes = [f"eps={eps[0]!r}:{eps[1]!r}:4", f"amplitude={amplitude[0]!r}:{amplitude[1]!r}:3"]
    assume(eps[0] != eps[1] and amplitude[0] != amplitude[1])  # a grid has distinct values
    job = job_of(get_problem("duffing").create(), axes, order=order, times=[0.3])
    assert_same(*both_routes(job))


def test_a_bare_system_and_its_singular_point_the_same_through_both_routes():
    from perturb.validation import SystemModel

    system = QuasilinearSystem([x], [xdot], [1], [EPS * x**3 / (c - 1)], parameters=[c])
    model = SystemModel(system, {"c": 3.0, "epsilon": 0.1}, {"amplitudes": {"x": 1}})
    statuses = []
    for axes in (["c=0,1,3", "epsilon=0.05,0.1"], ["c=0,2,3"]):
        job = job_of(model, axes, order=2, times=[0, 1])
        assert offered(job)
        fast, slow = both_routes(job)
        assert_same(fast, slow)
        statuses.append(set(fast["status"].tolist()))
    assert statuses == [
        {code_of(s) for s in (PointStatus.OK, PointStatus.NOT_FINITE)},
        {code_of(PointStatus.OK)},
    ]


def test_a_bare_system_in_the_large_parameter():
    from perturb.validation import SystemModel

    system = QuasilinearSystem(
        [x], [xdot], [1], [(1 - x**2) * xdot / mu], parameter=mu, regime=Regime.LARGE
    )
    job = job_of(SystemModel(system, {"mu": 10.0}), ["mu=2:40:9"], order=2, times=[0.5])
    assert offered(job)
    assert_same(*both_routes(job))
