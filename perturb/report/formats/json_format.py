"""``--format json``: one JSON document (the commands' JSON contracts)."""

from __future__ import annotations

import json

from perturb.report.formats.base import Format


def _problems(entries) -> str:
    problems = [
        {
            "name": name,
            "summary": summary,
            "parameters": [{"name": p.name, "default": p.default, "doc": p.doc} for p in specs],
        }
        for name, summary, specs in entries
    ]
    return json.dumps(problems, allow_nan=True) + "\n"


def _solution(output) -> str:
    from perturb.report.state import state_as_json

    return state_as_json(output)


def _validation(report) -> str:
    from perturb.report.validation import validation_as_dict

    return json.dumps(validation_as_dict(report), allow_nan=True) + "\n"


def _work_precision(result) -> str:
    from perturb.report.workprecision import work_precision_as_dict

    return json.dumps(work_precision_as_dict(result), allow_nan=True) + "\n"


def _response(result) -> str:
    from perturb.report.response import response_as_dict

    return json.dumps(response_as_dict(result), allow_nan=False) + "\n"


def _families(output) -> str:
    from perturb.report.families import as_dict

    return json.dumps(as_dict(output.families, output.problem, output.flags)) + "\n"


def _phase(output) -> str:
    from perturb.report.phase import phase_as_dict

    return json.dumps(phase_as_dict(output.dataset)) + "\n"


def _reproduction(done) -> str:
    return json.dumps(done.reproduction.as_dict(done.report), allow_nan=True) + "\n"


def _sweep(output) -> str:
    from perturb.report.sweep import sweep_as_dict

    return json.dumps(sweep_as_dict(output.dataset), allow_nan=True) + "\n"


def _failure(payload: dict) -> str:
    return json.dumps(payload, allow_nan=True) + "\n"


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
        "failure": _failure,
    },
    rank=3,
    keeps_warnings=True,
)
