"""``--format csv``: one row per time, per point or per run."""

from __future__ import annotations

from perturb.report.formats.base import Format


def _solution(output) -> str:
    from perturb.report.state import state_as_csv

    return state_as_csv(output)


def _work_precision(result) -> str:
    from perturb.report.workprecision import work_precision_as_csv

    return work_precision_as_csv(result) + "\n"


def _response(result) -> str:
    from perturb.report.response import response_as_csv

    return response_as_csv(result) + "\n"


def _sweep(output) -> str:
    from perturb.report.sweep import sweep_as_csv

    return sweep_as_csv(output.dataset) + "\n"


def _transient(result) -> str:
    from perturb.report.dynamics import transient_as_csv

    return transient_as_csv(result) + "\n"


def _ramp(result) -> str:
    from perturb.report.dynamics import ramp_as_csv

    return ramp_as_csv(result) + "\n"


FORMAT = Format(
    "csv",
    {
        "solution": _solution,
        "work-precision": _work_precision,
        "response": _response,
        "sweep": _sweep,
        "transient": _transient,
        "ramp": _ramp,
    },
    rank=2,
)
