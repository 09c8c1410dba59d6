"""``--format table`` (the default): text for a terminal."""

from __future__ import annotations

from perturb.report.formats.base import Format


def _problems(entries) -> str:
    lines = []
    for name, summary, specs in entries:
        lines.append(f"{name:16s} {summary}")
        lines += [f"    {s.name:10s} default {s.default:<12g} {s.doc}" for s in specs]
    return "".join(line + "\n" for line in lines)


def _solution(output) -> str:
    from perturb.report.state import state_as_table

    return state_as_table(output)


def _validation(report) -> str:
    from perturb.report.validation import validation_as_table

    return validation_as_table(report) + "\n"


def _work_precision(result) -> str:
    from perturb.report.workprecision import work_precision_as_table

    return work_precision_as_table(result) + "\n"


def _response(result) -> str:
    from perturb.report.response import response_as_table

    return response_as_table(result) + "\n"


def _families(output) -> str:
    from perturb.report.families import as_table

    return as_table(output.families, output.problem, output.flags, output.values) + "\n"


def _phase(output) -> str:
    from perturb.report.phase import phase_as_table

    text = phase_as_table(output.dataset) + "\n"
    if output.store is not None:
        text += f"written to {output.store} (open it with xarray.open_zarr)\n"
    return text


def _reproduction(done) -> str:
    text = done.reproduction.summary(done.report) + "\n"
    if done.full:
        text += "\n" + done.reproduction.full(done.report) + "\n"
    return text


def _basins(output) -> str:
    from perturb.report.dynamics import basins_as_table

    return basins_as_table(output.result, output.store) + "\n"


def _transient(result) -> str:
    from perturb.report.dynamics import transient_as_table

    return transient_as_table(result) + "\n"


def _ramp(result) -> str:
    from perturb.report.dynamics import ramp_as_table

    return ramp_as_table(result) + "\n"


FORMAT = Format(
    "table",
    {
        "problems": _problems,
        "solution": _solution,
        "validation": _validation,
        "work-precision": _work_precision,
        "response": _response,
        "families": _families,
        "phase": _phase,
        "reproduction": _reproduction,
        "basins": _basins,
        "transient": _transient,
        "ramp": _ramp,
    },
    rank=0,
)
