"""The JSON dictionary and the text table of a :class:`perturb.validation.ValidationReport`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from perturb.oracle import OrbitStatus, TrajectoryStatus
from perturb.validation.report import Check, OrbitCheck, ValidationReport

__all__ = ["orbit_as_dict", "validation_as_dict", "validation_as_table"]


def _jsonable(value: Any) -> Any:
    """Plain Python containers and floats, for :func:`json.dumps`."""
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, TrajectoryStatus | OrbitStatus):
        return _status(value)
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, complex | np.complexfloating):
        return [float(value.real), float(value.imag)]
    if isinstance(value, float | np.floating):
        return float(value)
    return value


def _status(status: TrajectoryStatus | OrbitStatus | None) -> int | None:
    """A status for JSON: its integer code (0 success, negative failure), as the contract has it;
    None when nothing ran (a refused shooting seed)."""
    return None if status is None else status.code


def orbit_as_dict(orbit: OrbitCheck) -> dict:
    """The ``periodic_orbit`` block of the JSON contract."""
    return _jsonable(
        {
            "success": orbit.success,
            "resolved": orbit.resolved,
            "resolution": orbit.resolution if math.isfinite(orbit.resolution) else None,
            "period": orbit.period,
            "initial_state": dict(orbit.initial_state),
            "floquet": [[float(z.real), float(z.imag)] for z in orbit.floquet],
            "floquet_abs": [float(abs(z)) for z in orbit.floquet],
            "n_trivial": orbit.n_trivial,
            "trivial_multiplier_error": orbit.trivial_multiplier_error,
            "trivial_ok": orbit.trivial_ok,
            "period_error": orbit.period_error,
            "initial_state_error": orbit.initial_state_error,
            "orbit_error": orbit.orbit_error,
            "status": _status(orbit.status),
            "message": orbit.message,
            "integrator": orbit.integrator,
        }
    )


def _check_as_dict(check: Check) -> dict:
    return {
        "value": check.value,
        "tolerance": check.tolerance,
        "comparison": check.comparison,
        "passed": check.passed,
        "sentence": check.sentence,
    }


def validation_as_dict(report: ValidationReport) -> dict:
    """The JSON contract of ``perturb validate --format json`` (``docs/validation.md``)."""
    orbit = orbit_as_dict(report.periodic_orbit) if report.periodic_orbit is not None else None
    return _jsonable(
        {
            "problem": report.problem,
            "parameters": report.parameters,
            "order": report.order,
            "epsilon": report.epsilon,
            "valid": report.valid,
            "outcome": report.outcome.label,
            "accurate_order": report.accurate_order,
            "verdict": report.verdict,
            "tol": report.tol,
            "checks": {c.name: _check_as_dict(c) for c in report.checks},
            "completed": report.completed,
            "message": report.message,
            "status": _status(report.status),
            "t_reached": report.t_reached,
            "conditions": [c.as_dict() for c in report.conditions],
            "period": report.period,
            "periods": report.periods,
            "errors": report.errors,
            "slope": report.slope.as_dict() if report.slope is not None else None,
            "periodic_orbit": orbit,
            "invariants": {k: v.as_dict() for k, v in report.invariants.items()},
            "integrator": report.integrator,
            "stiffness": report.stiffness.as_dict() if report.stiffness is not None else None,
            "timings": report.timings,
        }
    )


def _mark(passed: bool | None) -> str:
    return {True: "ok", False: "FAIL", None: "----"}[passed]


def validation_as_table(report: ValidationReport) -> str:
    """A human-readable summary, one block per check."""
    lines = [
        f"# validate {report.problem}  order {report.order}  epsilon {report.epsilon:.6g}  "
        f"tol {report.tol:g}",
        "# " + "  ".join(f"{k}={v:g}" for k, v in report.parameters.items()),
        f"verdict: {report.outcome.name} - {report.verdict}",
    ]
    if not report.completed:
        lines.append(
            f"run failed: {report.message} (status {_status(report.status)}, t reached "
            f"{report.t_reached:g})"
        )
    elif report.status is not None and not report.status.success:
        lines.append(f"note: {report.message}")
    if report.checks:
        lines.append("checks:")
        for c in report.checks:
            lines.append(
                f"  [{_mark(c.passed)}] {c.name:>12s} = {c.value:.4g} ({c.comparison} "
                f"{c.tolerance:.4g}): {c.sentence}"
            )
    if report.conditions:
        lines.append("the problem's own estimates (information):")
        for c in report.conditions:
            lines.append(f"  [{'ok' if c.ok else 'WARN'}] {c.name} = {c.value:.6g}: {c.sentence}")
    lines.append(
        f"trajectory (information): {report.periods:g} periods of T = {report.period:.12g}, "
        f"integrator {report.integrator}"
    )
    comps = report.errors.get("components", {})
    if "note" in report.errors:
        lines.append(f"  {report.errors['note']}")
    if comps:
        lines.append(
            f"  {'component':>12s} {'max abs err':>13s} {'rel err':>11s} {'amplitude':>11s}"
        )
        for name, e in comps.items():
            lines.append(
                f"  {name:>12s} {e['abs']:13.4e} {e['relative']:11.3e} {e['amplitude']:11.4g}"
            )
    if report.invariants:
        lines.append("first integrals (drift along the numerical trajectory):")
        for name, d in report.invariants.items():
            lines.append(
                f"  {name:>12s} I(0) = {d.initial:.12g}  max drift {d.max_drift:.2e} "
                f"(relative {d.relative_drift:.2e})"
            )
    orbit = report.periodic_orbit
    if orbit is not None:
        lines.append(f"periodic orbit (shooting, {orbit.integrator}): {orbit.message}")
        if orbit.success:
            state = "  ".join(f"{k}={v:.10g}" for k, v in orbit.initial_state.items())
            lines.append(f"  period {orbit.period:.12g}   initial state {state}")
            mults = "  ".join(f"{z.real:+.6f}{z.imag:+.6f}j" for z in orbit.floquet)
            lines.append(f"  Floquet multipliers {mults}")
            lines.append(
                f"  trivial multipliers ({orbit.n_trivial}) within "
                f"{orbit.trivial_multiplier_error:.1e} of 1: {'ok' if orbit.trivial_ok else 'NO'}"
            )
            lines.append(
                f"  analytic vs true: period {orbit.period_error:.3e} (relative), initial state "
                f"{orbit.initial_state_error:.3e}, orbit {orbit.orbit_error:.3e}"
            )
    if report.slope is not None:
        s = report.slope
        pts = ", ".join(f"{e:.3g}:{r:.2e}" for e, r in zip(s.epsilons, s.errors, strict=True))
        lines.append(
            f"slope: {s.slope:.3f} (expected >= {s.expected:g} - {s.band:g}) [{pts}] {s.note}".rstrip()
        )
    if report.stiffness is not None:
        st = report.stiffness
        lines.append(
            f"stiffness: ratio {st.ratio:.3g} (max|Re| {st.max_real:.3g}, max|Im| "
            f"{st.max_imag:.3g}): {'stiff' if st.stiff else 'not stiff'}"
        )
    lines.append("timings [s]: " + "  ".join(f"{k} {v:.3f}" for k, v in report.timings.items()))
    return "\n".join(lines)
