"""A phase diagram (:func:`perturb.sweep.phase.phase_diagram`) as text and as JSON."""

from __future__ import annotations

import json

import numpy as np
from attrs import frozen

__all__ = ["PhaseOutput", "phase_as_dict", "phase_as_table"]


@frozen
class PhaseOutput:
    """What ``perturb phase-diagram`` prints: the dataset and the store it was written to."""

    dataset: object
    store: str | None = None


def _axes(dataset):
    y_name, x_name = dataset["n_stable"].dims
    return x_name, y_name


def _special(dataset, first_order: bool | None = None) -> list[dict]:
    """The special points (only the first-order ones, or only the order-N ones, when asked)."""
    kinds = {int(k): v for k, v in json.loads(dataset["special_kind"].attrs["meanings"]).items()}
    x_name, y_name = _axes(dataset)
    points = [
        {x_name: float(px), y_name: float(py), "kind": kinds[int(k)], "along": int(line),
         "first_order": int(o) == 0}
        for px, py, k, line, o in zip(
            dataset["special_x"].values, dataset["special_y"].values,
            dataset["special_kind"].values, dataset["special_line"].values,
            dataset["special_order"].values, strict=True,
        )
    ]  # fmt: skip
    return [p for p in points if first_order is None or p["first_order"] is first_order]


def phase_as_dict(dataset) -> dict:
    """The JSON of ``perturb phase-diagram --format json``: ``{"problem", "order", "parameters",
    "x": {"name", "values"}, "y": {"name", "values"}, "maps": {name: [[count per x] per y]},
    "special": [{x, y, "kind", "along"}], "failures": [str], "seconds"}``; -1 where not counted.
    """
    x_name, y_name = _axes(dataset)
    maps = [n for n in dataset.data_vars if n.startswith("n_")]
    return {
        "problem": dataset.attrs["problem"],
        "order": int(dataset.attrs["order"]),
        "parameters": json.loads(dataset.attrs["parameters"]),
        "x": {"name": x_name, "values": [float(v) for v in dataset[x_name].values]},
        "y": {"name": y_name, "values": [float(v) for v in dataset[y_name].values]},
        "maps": {n: np.asarray(dataset[n].values).astype(int).tolist() for n in maps},
        "special": _special(dataset),
        "failures": json.loads(dataset.attrs["failures"]),
        "seconds": float(dataset.attrs.get("seconds", 0.0)),
    }


def _grid(dataset, name: str) -> list[str]:
    x_name, y_name = _axes(dataset)
    xs, ys = dataset[x_name].values, dataset[y_name].values
    values = np.asarray(dataset[name].values)
    width = max([4, *(len(f"{v:.5g}") for v in xs)])
    corner = f"{y_name} | {x_name}"
    lines = [f"{corner:>14s} " + " ".join(f"{v:>{width}.5g}" for v in xs)]
    for i in range(len(ys) - 1, -1, -1):
        cells = ("?" if v < 0 else str(int(v)) for v in values[i])
        lines.append(f"{ys[i]:>14.6g} " + " ".join(c.rjust(width) for c in cells))
    return lines


def phase_as_table(dataset) -> str:
    """The maps of stable and of all steady states as text grids (y decreasing down the page),
    the special points by kind, the checks between the routes, what could not be counted."""
    x_name, y_name = _axes(dataset)
    stable = np.asarray(dataset["n_stable"].values)
    states = np.asarray(dataset["n_states"].values)
    lines = [
        f"# phase diagram {dataset.attrs['problem']}  {x_name} x {y_name}  order "
        f"{dataset.attrs['order']}  ({dataset.attrs.get('seconds', 0.0):.1f} s)",
        "stable steady states:",
        *_grid(dataset, "n_stable"),
        "steady states:",
        *_grid(dataset, "n_states"),
    ]
    proved = np.asarray(dataset["n_first_order"].values)
    if np.any(proved >= 0):
        lines += ["stable steady states of the first-order equations (slow flow):",
                  *_grid(dataset, "n_stable_first_order"),
                  "steady states of the first-order equations (certified):",
                  *_grid(dataset, "n_first_order")]  # fmt: skip
    both = (proved >= 0) & (states >= 0)
    if np.any(both):
        fewer, more = int(np.sum(both & (states < proved))), int(np.sum(both & (states > proved)))
        stable_first = np.asarray(dataset["n_stable_first_order"].values)
        agree = int(np.sum(both & (stable == stable_first)))
        lines.append(
            f"order {dataset.attrs['order']} against the certified first order: the stable "
            f"counts agree at {agree} of {int(np.sum(both))} points; the steady states at "
            f"{int(np.sum(both)) - fewer - more}"
            + (f", fewer at {fewer} (a branch the continuation did not follow, or a fold the "
               "higher orders move past the point: within O(eps) of it)" if fewer else "")
            + (f", more at {more} (a fold the higher orders move past the point: the first "
               "order's is within O(eps) of it)" if more else "")
        )  # fmt: skip
    if "n_states_columns" in dataset:
        columns = np.asarray(dataset["n_states_columns"].values)
        both = (columns >= 0) & (states >= 0)
        differ = int(np.sum(both & (columns != states)))
        lines.append(
            f"continued along {y_name} too: the counts agree at {int(np.sum(both)) - differ} of "
            f"{int(np.sum(both))} points" + (f" (differ at {differ})" if differ else "")
        )
    for first, what in ((False, "order-N curves"), (True, "first-order equations, exact")):
        kinds: dict[str, int] = {}
        for point in _special(dataset, first):
            kinds[point["kind"]] = kinds.get(point["kind"], 0) + 1
        if kinds:
            lines.append(f"boundaries crossed by the lines ({what}): " + ", ".join(
                f"{n} {kind.replace('-', ' ')}{'s' if n > 1 else ''}"
                for kind, n in kinds.items()))  # fmt: skip
    missing = int(np.sum(stable < 0))
    if missing:
        lines.append(f"not counted: {missing} points")
    lines += [f"failed: {f}" for f in json.loads(dataset.attrs["failures"])]
    return "\n".join(lines)
