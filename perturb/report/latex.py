"""LaTeX for papers: the derived formulas of a solution, and tables of results.

Every function returns a fragment to ``\\input`` into a document (``amsmath`` for ``align*``,
``booktabs`` for the tables); nothing here computes: the formulas come from
:meth:`perturb.PeriodicSolution.latex`, derived by the method, never typed in.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

__all__ = [
    "families_latex",
    "latex_number",
    "latex_table",
    "latex_text",
    "Raw",
    "problems_latex",
    "solution_document",
    "state_latex",
    "validation_latex",
    "work_precision_latex",
]


def latex_number(value) -> str:
    """A number for a table cell: ``1.23\\times10^{-4}``, ``--`` for NaN, ``\\infty``."""
    if isinstance(value, bool) or value is None:
        return "--" if value is None else str(value).lower()
    if isinstance(value, int):
        return str(value)
    try:
        number = float(value)
    except (TypeError, ValueError):
        return latex_text(str(value))
    if math.isnan(number):
        return "--"
    if math.isinf(number):
        return "\\infty" if number > 0 else "-\\infty"
    mantissa, _, exponent = f"{number:.4g}".partition("e")
    return f"{mantissa}\\times10^{{{int(exponent)}}}" if exponent else mantissa


_SPECIAL = {
    "\\": "\\textbackslash{}",
    "&": "\\&",
    "%": "\\%",
    "$": "\\$",
    "#": "\\#",
    "_": "\\_",
    "{": "\\{",
    "}": "\\}",
    "~": "\\textasciitilde{}",
    "^": "\\textasciicircum{}",
}


def latex_text(text: str) -> str:
    """``text`` with LaTeX's special characters escaped."""
    return "".join(_SPECIAL.get(ch, ch) for ch in str(text))


class Raw(str):
    """A table cell already written in LaTeX (not escaped)."""


def latex_table(header: Sequence[str], rows: Iterable[Sequence], caption: str = "") -> str:
    """A ``booktabs`` tabular: text cells escaped (but :class:`Raw` ones), numbers in math mode."""

    def cell(value) -> str:
        if isinstance(value, Raw):
            return str(value)
        if isinstance(value, str):
            return latex_text(value)
        number = latex_number(value)
        return number if number == "--" else f"${number}$"  # an en dash in text, not math

    lines = []
    if caption:
        lines.append(f"% {caption}")
    lines += [
        f"\\begin{{tabular}}{{{'l' * len(header)}}}",
        "\\toprule",
        " & ".join(latex_text(h) for h in header) + " \\\\",
        "\\midrule",
    ]
    lines += [" & ".join(cell(v) for v in row) + " \\\\" for row in rows]
    lines += ["\\bottomrule", "\\end{tabular}"]
    return "\n".join(lines) + "\n"


def solution_document(solution, label: str = "") -> str:
    """The solution's coordinates and period as an ``align*`` block, ready for a paper.

    Parameters
    ----------
    solution : perturb.PeriodicSolution
    label : str, optional
        The problem's name, for the comment line.
    """
    name = label or solution.system.name
    rows = solution.latex().split(" \\\\\n")
    aligned = [row.replace(" = ", " &= ", 1) for row in rows]
    head = (
        f"% {latex_comment(name)}: periodic solution to order {solution.order} by Poincare's "
        "method (perturb); needs amsmath"
    )
    return "\n".join([head, "\\begin{align*}", " \\\\\n".join(aligned), "\\end{align*}"]) + "\n"


def latex_comment(text: str) -> str:
    """``text`` on one comment line."""
    return " ".join(str(text).split())


def state_latex(payload: dict, blocks: Sequence[tuple[str, dict]]) -> str:
    """The state table of ``perturb solve`` (its JSON payload) as a ``booktabs`` tabular."""
    columns = {"t": payload["t"]}
    for _, block in blocks:
        columns.update(block)
    header = [f"${n}$" if len(n) == 1 else n for n in columns]
    rows = zip(*(list(map(float, v)) for v in columns.values()), strict=True)
    caption = (
        f"{payload['problem']}: order {payload['order']}, epsilon = {payload['epsilon']:.6g}, "
        f"period {payload['period']:.12g}"
    )
    return _raw_header(latex_table(columns, rows, caption), header)


def _raw_header(table: str, header: Sequence[str]) -> str:
    """``table`` with its header row replaced by ``header`` (cells already LaTeX)."""
    lines = table.split("\n")
    start = lines.index("\\toprule") + 1
    lines[start] = " & ".join(header) + " \\\\"
    return "\n".join(lines)


#: The comparisons of a check, in math mode (``<`` in text mode is another glyph in OT1 fonts).
_RELATION = {"<=": Raw("$\\le$"), ">=": Raw("$\\ge$")}
_PASSED = {True: "yes", False: "no", None: "--"}


def validation_latex(report) -> str:
    """A :class:`perturb.validation.ValidationReport`: its checks and the verdict."""
    caption = (
        f"validation of {report.problem}, order {report.order}, epsilon = {report.epsilon:.6g}: "
        f"{report.outcome.name}"
    )
    rows = [
        (c.name, c.value, _RELATION.get(c.comparison, c.comparison), c.tolerance, _PASSED[c.passed])
        for c in report.checks
    ]
    table = latex_table(["check", "value", "", "tolerance", "passed"], rows, caption)
    return table + f"% verdict: {latex_comment(report.verdict)}\n"


def work_precision_latex(result) -> str:
    """A :class:`perturb.workprecision.WorkPrecision` table (``method, setting, error, seconds``)."""
    caption = (
        f"work-precision of {result.problem}: {result.periods:g} periods, reference "
        f"{result.reference}"
    )
    rows = [(p.method, p.setting, p.error, p.seconds) for p in result.points]
    return latex_table(["method", "setting", "error", "seconds"], rows, caption)


def families_latex(families, problem: str) -> str:
    """A :class:`perturb.FamilyList`: one row per family, amplitudes and frequency in math mode."""
    import sympy as sp

    def math(expr) -> str:
        return f"${sp.latex(sp.sympify(expr))}$"

    header = ["family", "kind", "amplitudes", "$\\Omega$", "status"]
    rows = []
    for f in families:
        amplitudes = ", ".join(
            f"${sp.latex(sp.Symbol(k))} = {sp.latex(sp.sympify(v))}$"
            for k, v in f.amplitudes.items()
        )
        omega = sum(sp.Symbol("epsilon") ** k * sp.sympify(w) for k, w in enumerate(f.frequency))
        rows.append(
            [
                latex_text(f.name),
                latex_text(f.kind),
                amplitudes,
                math(omega),
                latex_text(f.status.name),
            ]
        )
    caption = f"{problem}: families of periodic solutions to order {families.order}"
    lines = [f"% {caption}", f"\\begin{{tabular}}{{{'l' * len(header)}}}", "\\toprule"]
    lines += [" & ".join(header) + " \\\\", "\\midrule"]
    lines += [" & ".join(row) + " \\\\" for row in rows]
    lines += ["\\bottomrule", "\\end{tabular}"]
    return "\n".join(lines) + "\n"


def problems_latex(entries: Sequence[tuple[str, str, Sequence]]) -> str:
    """``perturb list``: (name, summary, parameter specs) as one table, a row per parameter."""
    rows = []
    for name, summary, specs in entries:
        rows.append((name, summary, "", ""))
        rows += [("", spec.name, spec.default, spec.doc) for spec in specs]
    return latex_table(["problem", "parameter", "default", "meaning"], rows, "perturb problems")
