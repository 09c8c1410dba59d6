"""``--format json``: one JSON document (the commands' JSON contracts), always valid JSON
(:func:`perturb.report.json_text.json_text`: a non-finite number is ``null``, and named)."""

from __future__ import annotations

from perturb.report.formats.base import Format
from perturb.report.json_text import json_text


def _problems(entries) -> str:
    problems = [
        {
            "name": name,
            "summary": summary,
            "parameters": [{"name": p.name, "default": p.default, "doc": p.doc} for p in specs],
        }
        for name, summary, specs in entries
    ]
    return json_text(problems) + "\n"


def _solution(output) -> str:
    from perturb.report.state import state_as_json

    return state_as_json(output)


def _validation(report) -> str:
    from perturb.report.validation import validation_as_dict

    return json_text(validation_as_dict(report)) + "\n"


def _work_precision(result) -> str:
    from perturb.report.workprecision import work_precision_as_dict

    return json_text(work_precision_as_dict(result)) + "\n"


def _response(result) -> str:
    from perturb.report.response import response_as_dict

    return json_text(response_as_dict(result)) + "\n"


def _families(output) -> str:
    from perturb.report.families import as_dict

    return json_text(as_dict(output.families, output.problem, output.flags, output.values)) + "\n"


def _phase(output) -> str:
    from perturb.report.phase import phase_as_dict

    return json_text(phase_as_dict(output.dataset)) + "\n"


def _reproduction(done) -> str:
    return json_text(done.reproduction.as_dict(done.report)) + "\n"


def _sweep(output) -> str:
    from perturb.report.sweep import sweep_as_dict

    return json_text(sweep_as_dict(output.dataset)) + "\n"


def _failure(payload: dict) -> str:
    return json_text(payload) + "\n"


def _basins(output) -> str:
    from perturb.report.dynamics import basins_as_dict

    return json_text(basins_as_dict(output.result, output.store)) + "\n"


def _transient(result) -> str:
    from perturb.report.dynamics import transient_as_dict

    return json_text(transient_as_dict(result)) + "\n"


def _ramp(result) -> str:
    from perturb.report.dynamics import ramp_as_dict

    return json_text(ramp_as_dict(result)) + "\n"


FORMAT = Format(
    "json",
    {
        "problems": _problems,
        "solution": _solution,
        "validation": _validation,
        "work-precision": _work_precision,
        "response": _response,
        "families": _families,
        "phase": _phase,
        "reproduction": _reproduction,
        "sweep": _sweep,
        "basins": _basins,
        "transient": _transient,
        "ramp": _ramp,
        "failure": _failure,
    },
    rank=3,
    keeps_warnings=True,
)
