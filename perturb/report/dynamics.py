"""Where the motion goes, as text, CSV and JSON: basin maps, transients and ramps
(:mod:`perturb.dynamics`). Non-finite numbers are ``null`` in JSON."""

from __future__ import annotations

import math

import numpy as np
from attrs import frozen

__all__ = [
    "BasinsOutput",
    "basins_as_dict",
    "basins_as_table",
    "ramp_as_csv",
    "ramp_as_dict",
    "ramp_as_table",
    "transient_as_csv",
    "transient_as_dict",
    "transient_as_table",
]


@frozen
class BasinsOutput:
    """What ``perturb basins`` prints: the map and the store it was written to."""

    result: object
    store: str | None = None


def _num(value) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def _complex(z) -> list:
    return [_num(z.real), _num(z.imag)]


def _state(state, code: int | None = None) -> dict:
    out = {
        "name": state.name,
        "kind": state.kind.value,
        "points": [[_num(v) for v in p] for p in state.points],
        "multipliers": [_complex(z) for z in state.multipliers],
        "largest_multiplier": _num(state.largest_multiplier),
        "capture_radius": _num(state.radius),
    }
    if code is not None:
        out = {"code": code, **out}
    return out


# ---------------------------------------------------------------------------------- basins
def basins_as_dict(result, store=None) -> dict:
    """The JSON of ``perturb basins --format json``: ``{"problem", "status", "message", "mode",
    "axes", "phase", "periods_cap", "backend", "components", "attractors": [{code, name, kind,
    points, multipliers, largest_multiplier, capture_radius}], "saddles": [...], "outcomes":
    {code: meaning}, "fractions": [{code, name, count, fraction, error}], "points",
    "store", "seconds", "notes"}``."""
    chart = result.catalogue
    attrs = dict(getattr(result.dataset, "attrs", {}) or {})
    from perturb.dynamics.classify import outcome_meanings

    return {
        "problem": chart.problem,
        "parameters": {k: _num(v) for k, v in chart.values.items()},
        "status": result.status.name.lower(),
        "message": result.message,
        "mode": "samples" if result.sampled else "grid",
        "axes": list(result.axes),
        "phase": _num(chart.phase),
        "omega": _num(chart.omega),
        "periods_cap": attrs.get("periods_cap"),
        "backend": attrs.get("backend"),
        "components": list(chart.names),
        "attractors": [_state(s, k) for k, s in enumerate(chart.attractors)],
        "saddles": [_state(s) for s in chart.saddles],
        "outcomes": {str(k): v for k, v in outcome_meanings().items()},
        "fractions": [
            {
                "code": f.code,
                "name": f.name,
                "count": f.count,
                "fraction": _num(f.fraction),
                "error": _num(f.error),
            }
            for f in result.fractions
        ],  # fmt: skip
        "points": int(sum(f.count for f in result.fractions)),
        "points_computed": attrs.get("points_computed"),
        "store": None if store is None else str(store),
        "seconds": _num(attrs.get("seconds", math.nan)),
        "notes": list(chart.notes),
    }


def basins_as_table(result, store=None) -> str:
    """The text of ``perturb basins``: the attractors with their points and multipliers, the
    saddles, the basin fractions with their sampling error."""
    chart = result.catalogue
    lines = [f"basins of {chart.problem} ("
             + ", ".join(f"{k}={v:g}" for k, v in chart.values.items()) + ")"]  # fmt: skip
    if result.dataset is None:
        lines.append(f"failed: {result.message}")
        return "\n".join(lines)
    attrs = result.dataset.attrs
    where = "random states" if result.sampled else "grid"
    lines.append(
        f"section at drive phase {chart.phase:g} rad (Omega = {chart.omega:.6g}); {where} over "
        f"{', '.join(result.axes)}; cap {attrs.get('periods_cap')} drive periods; "
        f"{attrs.get('backend')}"
    )
    names = ", ".join(chart.names)
    width = max([14, *(len(s.name) for s in chart.states)])
    lines.append("")
    lines.append(f"{'code':>4s}  {'state':<{width}s} {'kind':<44s} point ({names})  "
                 "max|multiplier|")  # fmt: skip
    for k, s in enumerate(chart.attractors):
        point = ", ".join(f"{v:.6g}" for v in s.points[0])
        more = f" (+{s.period - 1} points)" if s.period > 1 else ""
        lines.append(f"{k:>4d}  {s.name:<{width}s} {s.kind.value:<44s} ({point}){more}  "
                     f"{s.largest_multiplier:.6g}")  # fmt: skip
    for s in chart.saddles:
        point = ", ".join(f"{v:.6g}" for v in s.points[0])
        lines.append(f"{'-':>4s}  {s.name:<{width}s} {s.kind.value:<44s} ({point})  "
                     f"{s.largest_multiplier:.6g}")  # fmt: skip
    lines.append("")
    width = max([40, *(len(f.name) for f in result.fractions)])
    lines.append(f"{'code':>4s}  {'where the motion goes':<{width}s} {'states':>9s} "
                 f"{'fraction':>9s}  {'sampling error':>14s}")  # fmt: skip
    for f in result.fractions:
        lines.append(f"{f.code:>4d}  {f.name:<{width}s} {f.count:>9d} {f.fraction:>9.4f}  "
                     f"{f.error:>14.2g}")  # fmt: skip
    for note in chart.notes:
        lines.append(f"note: {note}")
    if not result.status.success:
        lines.append(f"failed: {result.message}")
    if store is not None:
        lines.append(f"written to {store} (open it with xarray.open_zarr)")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------- transients
def transient_as_dict(result, every: int = 1) -> dict:
    """The JSON of ``perturb transient --format json``: the settling, and the samples (every
    ``every``-th): ``times``, the state by name, per resonant coordinate the envelope and phase
    of the true motion and of the slow flow."""
    t = result.times[::every]
    env, slow_env = result.envelope()[::every], result.envelope(slow=True)[::every]
    ph, slow_ph = result.phase_of()[::every], result.phase_of(slow=True)[::every]
    return {
        "problem": result.problem,
        "start": {k: _num(v) for k, v in result.start.items()},
        "phase": _num(result.phase),
        "slow_flow_order": result.order,
        "settled": result.settled,
        "settle_time": _num(result.settle_time),
        "slow_flow_settles": result.slow_settled,
        "times": [_num(v) for v in t],
        "state": {
            n: [_num(v) for v in result.state[::every, i]] for i, n in enumerate(result.names)
        },
        "envelope": {c: [_num(v) for v in env[:, i]] for i, c in enumerate(result.coordinates)},
        "phase_angle": {c: [_num(v) for v in ph[:, i]] for i, c in enumerate(result.coordinates)},
        "slow_envelope": {
            c: [_num(v) for v in slow_env[:, i]] for i, c in enumerate(result.coordinates)
        },  # fmt: skip
        "slow_phase_angle": {
            c: [_num(v) for v in slow_ph[:, i]] for i, c in enumerate(result.coordinates)
        },  # fmt: skip
    }


def transient_as_csv(result) -> str:
    """Every sample: ``t``, the state, then per resonant coordinate the true and slow envelope
    and phase."""
    env, slow_env = result.envelope(), result.envelope(slow=True)
    ph, slow_ph = result.phase_of(), result.phase_of(slow=True)
    head = ["t", *result.names]
    for c in result.coordinates:
        head += [f"envelope_{c}", f"phase_{c}", f"slow_envelope_{c}", f"slow_phase_{c}"]
    rows = [",".join(head)]
    for k, t in enumerate(result.times):
        row = [t, *result.state[k]]
        for i in range(len(result.coordinates)):
            row += [env[k, i], ph[k, i], slow_env[k, i], slow_ph[k, i]]
        rows.append(",".join(f"{v:.10g}" for v in row))
    return "\n".join(rows)


def transient_as_table(result, rows: int = 21) -> str:
    """The text of ``perturb transient``: where it settles and when, and the envelope beside the
    slow flow's at ``rows`` times."""
    lines = [
        f"transient of {result.problem} from "
        + ", ".join(f"{k} = {v:g}" for k, v in result.start.items())
        + f" at drive phase {result.phase:g}",
        f"true motion settles on: {result.settled}"
        + (f" after t = {result.settle_time:.6g}" if math.isfinite(result.settle_time) else ""),
        f"slow flow (order {result.order}) settles near: {result.slow_settled}",
        "",
    ]
    env, slow_env = result.envelope(), result.envelope(slow=True)
    ph, slow_ph = result.phase_of(), result.phase_of(slow=True)
    head = f"{'t':>10s}"
    for c in result.coordinates:
        head += (
            f"  {'envelope ' + c:>14s} {'slow flow':>10s} {'phase ' + c:>10s} {'slow flow':>10s}"
        )
    lines.append(head)
    for k in np.unique(np.linspace(0, result.times.size - 1, rows).round().astype(int)):
        line = f"{result.times[k]:>10.4g}"
        for i in range(len(result.coordinates)):
            line += (f"  {env[k, i]:>14.6g} {slow_env[k, i]:>10.6g} {ph[k, i]:>10.4f} "
                     f"{slow_ph[k, i]:>10.4f}")  # fmt: skip
        lines.append(line)
    return "\n".join(lines)


# ---------------------------------------------------------------------------------- ramps
def ramp_as_dict(result, envelopes: bool = False) -> dict:
    """The JSON of ``perturb ramp --format json``: the folds and, per run, its direction, rate,
    jump, the fold it left and the delay (the envelopes too, with ``envelopes``)."""
    runs = []
    for run in result.runs:
        entry = {
            "direction": run.direction, "rate": _num(run.rate), "jump": _num(run.jump),
            "jump_size": _num(run.jump_size), "fold": _num(run.fold), "delay": _num(run.delay),
        }  # fmt: skip
        if envelopes:
            entry["values"] = [_num(v) for v in run.values]
            entry["envelope"] = [_num(v) for v in run.envelope]
        runs.append(entry)
    return {
        "problem": result.problem,
        "parameter": result.parameter,
        "start": _num(result.start),
        "stop": _num(result.stop),
        "order": result.order,
        "coordinate": result.coordinate,
        "folds": [_num(f) for f in result.folds],
        "runs": runs,
    }


def ramp_as_csv(result) -> str:
    """One row per run: direction, rate, jump, jump size, fold, delay."""
    rows = ["direction,rate,jump,jump_size,fold,delay"]
    for run in result.runs:
        values = [run.rate, run.jump, run.jump_size, run.fold, run.delay]
        rows.append(run.direction + "," + ",".join(f"{v:.10g}" for v in values))
    return "\n".join(rows)


def ramp_as_table(result) -> str:
    """The text of ``perturb ramp``: each run's jump beside the fold it left, the delay."""
    p = result.parameter
    lines = [
        f"ramp of {result.problem}: {p} from {result.start:g} to {result.stop:g}",
        f"folds of the order-{result.order} response curve: "
        + (", ".join(f"{f:.8g}" for f in result.folds) or "none between the ends"),
        "",
        f"{'direction':>9s} {'rate':>10s} {'jump at':>12s} {'envelope change':>16s} "
        f"{'fold':>12s} {'delay':>11s}",
    ]
    for run in result.runs:
        fold = f"{run.fold:>12.8g}" if math.isfinite(run.fold) else f"{'-':>12s}"
        delay = f"{run.delay:>11.3g}" if math.isfinite(run.delay) else f"{'-':>11s}"
        lines.append(f"{run.direction:>9s} {run.rate:>10.3g} {run.jump:>12.8g} "
                     f"{run.jump_size:>16.4g} {fold} {delay}")  # fmt: skip
    return "\n".join(lines)
