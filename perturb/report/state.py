"""A solution's state along time, as ``perturb solve`` prints it (table, CSV, JSON, LaTeX)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from attrs import field, frozen

__all__ = ["StateOutput", "state_as_csv", "state_as_json", "state_as_latex", "state_as_table"]


@frozen
class StateOutput:
    """What ``perturb solve`` prints.

    Attributes
    ----------
    payload : dict
        ``problem``, ``parameters``, ``epsilon``, ``order``, ``period``, ``t``, ``state`` (and
        ``euler``, ``warnings``, ``steps``, ``latex`` when asked): the JSON contract.
    blocks : sequence of (str, dict)
        The columns after ``t``, block by block (``state``, ``euler``).
    solution : PeriodicSolution, optional
        The solution itself: ``--format latex`` prints its formulas before the state.
    """

    payload: dict
    blocks: Sequence = field(converter=tuple)
    solution: object = None


def _columns(output: StateOutput) -> dict[str, np.ndarray]:
    columns = {"t": np.asarray(output.payload["t"])}
    for _, block in output.blocks:
        columns.update({k: np.asarray(v, dtype=float) for k, v in block.items()})
    return columns


def state_as_json(output: StateOutput) -> str:
    from perturb.report.json_text import json_text

    return json_text(output.payload) + "\n"


def state_as_latex(output: StateOutput) -> str:
    from perturb.report.latex import solution_document, state_latex

    formulas = (
        ""
        if output.solution is None
        else solution_document(output.solution, output.payload["problem"])
    )
    return formulas + state_latex(output.payload, list(output.blocks))


def state_as_csv(output: StateOutput) -> str:
    columns = _columns(output)
    lines = [",".join(columns)]
    lines += [",".join(repr(float(v)) for v in row) for row in zip(*columns.values(), strict=True)]
    return "\n".join(lines) + "\n"


def state_as_table(output: StateOutput) -> str:
    payload = output.payload
    columns = _columns(output)
    head = (
        f"# {payload['problem']}  order {payload['order']}  epsilon {payload['epsilon']:.6g}  "
        f"period {payload['period']:.12g}"
    )
    params = "  ".join(f"{k}={v:g}" for k, v in payload["parameters"].items())
    lines = [head, f"# {params}", "".join(f"{n:>20s}" for n in columns)]
    lines += [
        "".join(f"{float(v):20.12g}" for v in row) for row in zip(*columns.values(), strict=True)
    ]
    for key in ("steps", "latex"):
        if key in payload:
            text = payload[key] if isinstance(payload[key], str) else "\n".join(payload[key])
            lines.append(f"\n# {key}\n{text}")
    return "\n".join(lines) + "\n"
