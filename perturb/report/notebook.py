"""Rich display in Jupyter: validation reports and work–precision results as HTML tables.

The result objects hold data only and never import this leaf, so their HTML is registered with
IPython's display formatter instead of written as ``_repr_html_`` methods on them. Load it once a
session::

    %load_ext perturb.report

(:func:`load_ipython_extension`; or call :func:`register` from code.) A
:class:`perturb.PeriodicSolution` needs no extension: it renders its derived formulas by its own
``_repr_latex_``, as sympy objects do, since its LaTeX is part of the result.
"""

from __future__ import annotations

import html
import math

from perturb.validation.report import ValidationReport
from perturb.workprecision import WorkPrecision

__all__ = ["load_ipython_extension", "register", "validation_html", "work_precision_html"]

#: Colours of the verdict (green, red, amber): readable on light and dark notebook themes.
VERDICT_COLOURS = {
    "VALID": "#1a7f37",
    "INVALID": "#cf222e",
    "UNDECIDED": "#9a6700",
    "LOWER_ORDER": "#0969da",
}


def _number(value) -> str:
    if isinstance(value, float) and not math.isfinite(value):
        return "&ndash;"
    return f"{value:.4g}" if isinstance(value, float) else html.escape(str(value))


def _table(header, rows) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{cell}</td>" for cell in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def validation_html(report: ValidationReport) -> str:
    """The verdict, its checks and the parameters as HTML."""
    colour = VERDICT_COLOURS.get(report.outcome.name, "inherit")
    marks = {True: "&#10003;", False: "&#10007;", None: "?"}
    rows = [
        (
            html.escape(c.name),
            _number(c.value),
            html.escape(c.comparison),
            _number(c.tolerance),
            marks[c.passed],
            html.escape(c.sentence),
        )
        for c in report.checks
    ]
    params = ", ".join(f"{html.escape(k)} = {v:g}" for k, v in report.parameters.items())
    return (
        f"<div><p><b>{html.escape(report.problem)}</b>, order {report.order}, "
        f"&epsilon; = {report.epsilon:.6g}: <b style='color:{colour}'>{report.outcome.name}</b>"
        f"</p><p>{html.escape(report.verdict)}</p>"
        + _table(["check", "value", "", "tolerance", "passed", "measured"], rows)
        + f"<p><small>{params}</small></p></div>"
    )


def work_precision_html(result: WorkPrecision) -> str:
    """The work–precision points as an HTML table headed by the horizon and the reference."""
    rows = [
        (html.escape(p.method), html.escape(p.setting), _number(p.error), _number(p.seconds))
        for p in result.points
    ]
    return (
        f"<div><p><b>{html.escape(result.problem)}</b>: {result.periods:g} periods "
        f"(t = {result.horizon:.6g}), reference {html.escape(result.reference)}</p>"
        + _table(["method", "setting", "error", "seconds"], rows)
        + "</div>"
    )


def register(ipython=None) -> None:
    """Register the HTML of :class:`ValidationReport` and :class:`WorkPrecision` with IPython
    (``ipython``: the shell, default the running one; nothing happens outside IPython)."""
    if ipython is None:
        try:
            from IPython import get_ipython
        except ImportError:
            return
        ipython = get_ipython()
        if ipython is None:
            return
    formatter = ipython.display_formatter.formatters["text/html"]
    formatter.for_type(ValidationReport, validation_html)
    formatter.for_type(WorkPrecision, work_precision_html)


def load_ipython_extension(ipython) -> None:
    """``%load_ext perturb.report``: register the HTML display of perturb's results."""
    register(ipython)
