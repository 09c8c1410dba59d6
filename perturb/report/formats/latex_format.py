"""``--format latex``: a LaTeX fragment (:mod:`perturb.report.latex`)."""

from __future__ import annotations

from perturb.report.formats.base import Format


def _problems(entries) -> str:
    from perturb.report.latex import problems_latex

    return problems_latex(entries)


def _solution(output) -> str:
    from perturb.report.state import state_as_latex

    return state_as_latex(output)


def _validation(report) -> str:
    from perturb.report.latex import validation_latex

    return validation_latex(report)


def _work_precision(result) -> str:
    from perturb.report.latex import work_precision_latex

    return work_precision_latex(result)


def _response(result) -> str:
    from perturb.report.response import response_latex

    return response_latex(result)


def _families(output) -> str:
    from perturb.report.latex import families_latex

    return families_latex(output.families, output.problem)


FORMAT = Format(
    "latex",
    {
        "problems": _problems,
        "solution": _solution,
        "validation": _validation,
        "work-precision": _work_precision,
        "response": _response,
        "families": _families,
    },
    rank=4,
)
