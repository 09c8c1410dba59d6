"""A sweep's points as CSV and as a JSON dictionary (``perturb sweep --format csv|json``).

Both read the :class:`xarray.Dataset` of :func:`perturb.sweep` through its arrays only (this leaf
does not import xarray). Coded variables (``status``, ``verdict``) are written as their labels
(``ok``, ``valid``...), read from the variable's own attributes.
"""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
from attrs import frozen

__all__ = ["SweepOutput", "sweep_as_csv", "sweep_as_dict", "sweep_summary"]


@frozen
class SweepOutput:
    """What ``perturb sweep`` prints: the dataset, the problem's label, the store (or None)."""

    dataset: object
    label: str = ""
    store: str | None = None


#: Variables written as the label of their code.
_CODED = ("status", "verdict")


def _grid(ds) -> list[tuple[str, np.ndarray]]:
    return [(axis["name"], np.asarray(axis["values"])) for axis in json.loads(ds.attrs["grid"])]


def _labels(var) -> dict[int, str]:
    return {int(k): v for k, v in json.loads(var.attrs["labels"]).items()}


def _plain(value):
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return value
    return value if not isinstance(value, np.str_) else str(value)


def _columns(ds, swept: list[str]):
    """(column name, variable, extra-index) for every column of the CSV, in order."""
    out = []
    for name, var in ds.data_vars.items():
        extra = [d for d in var.dims if d not in swept]
        if not extra:
            out.append((name, name, ()))
            continue
        labels = [
            [f"t={float(x)!r}" if d == "time" else str(_plain(x)) for x in ds[d].values]
            for d in extra
        ]
        for index in np.ndindex(*(len(lab) for lab in labels)):
            text = ",".join(lab[i] for lab, i in zip(labels, index, strict=True))
            out.append((f"{name}[{text}]", name, index))
    return out


def sweep_as_csv(ds) -> str:
    """One row per point (C order of the grid): the swept parameters, then every quantity."""
    grid = _grid(ds)
    swept = [name for name, _ in grid]
    columns = _columns(ds, swept)
    arrays = {name: np.asarray(ds[name].values) for name in ds.data_vars}
    coded = {name: _labels(ds[name]) for name in _CODED if name in ds}
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([*swept, *(c for c, _, _ in columns)])
    for where in np.ndindex(*(len(v) for _, v in grid)):
        row = [repr(float(values[i])) for (_, values), i in zip(grid, where, strict=True)]
        for _, name, index in columns:
            value = _plain(arrays[name][where + index])
            if name in coded:
                value = coded[name].get(int(value), str(value))
            elif isinstance(value, float):
                value = repr(value)
            row.append(value)
        writer.writerow(row)
    return buffer.getvalue().rstrip("\n")


def sweep_as_dict(ds) -> dict:
    """``{"problem", "order", "fixed_parameters", "grid", "settings", "derivation", "points"}``;
    each point ``{"parameters", "status", "reason", ..., "amplitude": {name: value}, "state":
    {name: [value at each time]}}`` and, validated, ``"verdict"``, ``"floquet"`` ([re, im] pairs)
    and ``"checks"`` ({name: {"value", "passed"}})."""
    grid = _grid(ds)
    components = [str(c) for c in ds["component"].values]
    checks = [str(c) for c in ds["check"].values] if "check" in ds.coords else []
    arrays = {name: np.asarray(ds[name].values) for name in ds.data_vars}
    coded = {name: _labels(ds[name]) for name in _CODED if name in ds}
    names = {name.removeprefix("sweep_"): name for name in ds.data_vars}
    points = []
    for where in np.ndindex(*(len(v) for _, v in grid)):
        point: dict = {
            "parameters": {n: float(v[i]) for (n, v), i in zip(grid, where, strict=True)}
        }
        for key, name in names.items():
            value = arrays[name][where]
            if key in coded:
                point[key] = coded[key].get(int(value), str(value))
            elif key == "amplitude":
                point[key] = dict(zip(components, map(float, value), strict=True))
            elif key == "state":
                point[key] = {c: [float(v) for v in value[:, j]] for j, c in enumerate(components)}
            elif key in ("floquet_real", "floquet_imag", "check_value", "check_passed"):
                continue
            else:
                point[key] = _plain(value)
        if "floquet_real" in names:
            re = arrays[names["floquet_real"]][where]
            im = arrays[names["floquet_imag"]][where]
            point["floquet"] = [
                [float(a), float(b)] for a, b in zip(re, im, strict=True) if not math.isnan(a)
            ]
            passed = arrays[names["check_passed"]][where]
            values = arrays[names["check_value"]][where]
            point["checks"] = {
                c: {"value": float(values[i]), "passed": {1: True, 0: False}.get(int(passed[i]))}
                for i, c in enumerate(checks)
            }
        points.append(point)
    return {
        "problem": ds.attrs.get("problem"),
        "order": int(ds.attrs.get("order", 0)),
        "fixed_parameters": json.loads(ds.attrs.get("fixed_parameters", "{}")),
        "grid": [{"name": n, "values": [float(x) for x in v]} for n, v in grid],
        "settings": json.loads(ds.attrs.get("settings", "{}")),
        "derivation": ds.attrs.get("derivation"),
        "complete": bool(ds.attrs.get("complete", False)),
        "points": points,
    }


def sweep_summary(output: SweepOutput) -> str:
    """A sweep in a few lines: its points by status, its verdicts, where it is written."""
    from perturb.sweep.status import PointStatus, member_of
    from perturb.sweep.store import code_counts
    from perturb.validation import Verdict

    ds = output.dataset
    size = int(ds["session"].size)
    statuses = code_counts(ds["status"])
    parts = [
        f"{member_of(PointStatus, code).name.lower().replace('_', ' ')} {n}"
        for code, n in sorted(statuses.items())
        if code >= 0
    ]
    dims = [(axis["name"], len(axis["values"])) for axis in json.loads(ds.attrs["grid"])]
    order = f" order {ds.attrs['order']}" if "order" in ds.attrs else ""
    lines = [
        f"sweep {output.label}{order}: {size} points ({' x '.join(f'{n} {d}' for d, n in dims)}), "
        f"{ds.attrs.get('seconds', 0.0):.1f} s; points: {', '.join(parts)}"
    ]
    if "verdict" in ds:
        verdicts = code_counts(ds["verdict"])
        counts = [
            f"{member_of(Verdict, code).label} {n}"
            for code, n in sorted(verdicts.items())
            if code >= 0
        ]
        lines.append(f"verdicts: {', '.join(counts) or 'none'}")
    if output.store is not None:
        lines.append(f"written to {output.store} (open it with xarray.open_zarr)")
    return "\n".join(lines)
