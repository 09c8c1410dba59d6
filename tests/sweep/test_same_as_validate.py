"""A validated sweep's numbers at a grid point are ``perturb validate``'s there, to the last digit
the JSON prints (both are read back from the JSON's repr of each float)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from perturb.cli import main
from perturb.sweep.derive import plan
from perturb.sweep.grid import parse_axis
from perturb.sweep.quantities import TIMINGS, check_names
from perturb.sweep.spec import SweepJob, check_spec
from perturb.sweep.status import member_of
from perturb.sweep.task import run_chunk
from perturb.validation import Verdict
from problems import get_problem


def validate_json(capsys, problem: str, values: dict, order: int) -> dict:
    argv = ["validate", problem, "--order", str(order), "--format", "json"]
    for name, value in values.items():
        argv += ["--set", f"{name}={value!r}"]
    main(argv)
    return json.loads(capsys.readouterr().out)


def same(a, b) -> bool:
    """Equal as the JSON prints them (NaN equal to NaN; None for a missing number)."""
    if a is None or b is None:
        return a is None and (b is None or (isinstance(b, float) and math.isnan(b)))
    return json.loads(json.dumps(float(a))) == json.loads(json.dumps(float(b))) or (
        math.isnan(a) and math.isnan(b)
    )


def check_point(out: dict, k: int, expected: dict) -> None:
    assert member_of(Verdict, out["verdict"][k]).label == expected["outcome"]
    assert out["verdict_reason"][k] == expected["verdict"]
    assert bool(out["completed"][k]) == expected["completed"]
    assert same(out["epsilon"][k], expected["epsilon"])
    assert same(out["period"][k], expected["period"])
    orbit = expected["periodic_orbit"]
    for key in ("orbit_error", "period_error", "initial_state_error"):
        assert same(out[key][k], orbit[key]), key
    assert same(out["true_period"][k], orbit["period"])
    assert out["orbit_status"][k] == orbit["status"]
    assert out["trajectory_status"][k] == expected["status"]
    floquet = [
        [out["floquet_real"][k][i], out["floquet_imag"][k][i]] for i in range(len(orbit["floquet"]))
    ]
    assert json.loads(json.dumps(floquet)) == orbit["floquet"]
    assert same(out["order_slope"][k], expected["slope"]["value"])
    for i, name in enumerate(check_names()):
        assert same(out["check_value"][k][i], expected["checks"][name]["value"]), name
        passed = {1: True, 0: False, -1: None}[int(out["check_passed"][k][i])]
        assert passed == expected["checks"][name]["passed"], name
    accurate = int(out["accurate_order"][k])
    assert (None if accurate < 0 else accurate) == expected["accurate_order"]


@pytest.mark.parametrize(
    ("problem", "fixed", "axes", "order"),
    [
        ("duffing", {}, ["eps=0.05,0.2", "amplitude=0.8,1.3"], 1),
        ("van-der-pol", {}, ["eps=0.1,0.4"], 2),
    ],
)
def test_a_validated_point_is_perturb_validate(capsys, problem, fixed, axes, order):
    model = get_problem(problem).create(**fixed)
    spec = check_spec(model, [parse_axis(a) for a in axes], order=order, validate=True)
    derivation, _ = plan(spec.model, spec.grid.axes, order)
    out = run_chunk(SweepJob(spec, derivation, "test"), np.arange(spec.grid.size))
    for k in range(spec.grid.size):
        values = {**fixed, **spec.grid.point(k)}
        check_point(out, k, validate_json(capsys, problem, values, order))


def test_the_fast_spin_disk_is_perturb_validate(capsys):
    fixed = {"R": 0.123299}
    model = get_problem("disk").create(r0=0.755155, gamma3_0=0.25, **fixed)
    spec = check_spec(
        model,
        [parse_axis("r0=0.755155,0.9"), parse_axis("gamma3_0=0.25,0.3")],
        order=1,
        validate=True,
    )
    derivation, _ = plan(spec.model, spec.grid.axes, 1)
    out = run_chunk(SweepJob(spec, derivation, "test"), [0, 3])
    for i, k in enumerate((0, 3)):
        values = {**fixed, **spec.grid.point(k)}
        expected = validate_json(capsys, "disk", values, 1)
        check_point(
            {name: value[[i]] for name, value in out.items() if name not in TIMINGS}, 0, expected
        )


@pytest.mark.slow
def test_the_disk_at_order_2_per_point_and_symbolic(capsys):
    """Per point: ``perturb validate``'s very numbers. Symbolic (derived once): the same exact
    series evaluated in another form, so the same verdicts and the numbers to rounding."""
    fixed = {"R": 0.123299}
    model = get_problem("disk").create(r0=0.755155, gamma3_0=0.25, **fixed)
    axes = [parse_axis("r0=0.755155,0.9"), parse_axis("gamma3_0=0.25,0.3")]
    runs = {}
    for derive in ("per-point", "auto"):
        spec = check_spec(model, axes, order=2, validate=True, derive=derive)
        derivation, _ = plan(spec.model, spec.grid.axes, 2, derive)
        runs[derivation.mode.name] = run_chunk(SweepJob(spec, derivation, "test"), np.arange(4))
    assert set(runs) == {"PER_POINT", "SYMBOLIC"}
    per_point, symbolic = runs["PER_POINT"], runs["SYMBOLIC"]
    for k in range(4):
        values = {**fixed, **spec.grid.point(k)}
        check_point(per_point, k, validate_json(capsys, "disk", values, 2))
    assert per_point["verdict"].tolist() == symbolic["verdict"].tolist()
    # the period is the same number (the frequency series is evaluated alike); the orbit errors
    # are distances from true orbits each known to `resolution` of the amplitude (the shooting
    # converges from seeds a few ulps apart), so they agree to within it
    for name in ("period", "true_period", "period_error"):
        np.testing.assert_array_equal(symbolic[name], per_point[name], err_msg=name)
    assert np.all(
        np.abs(symbolic["orbit_error"] - per_point["orbit_error"]) <= per_point["resolution"]
    )
    # the slope is fitted to one-period errors down to ~1e-9, whose last digits the rounding
    # moves: it agrees far inside the order check's band (SLOPE_TOLERANCE = 0.5)
    assert np.all(np.abs(symbolic["order_slope"] - per_point["order_slope"]) < 1e-4)
