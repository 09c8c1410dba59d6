"""LaTeX for papers: the derived formulas of a solution, and tables of results.

Every function returns a fragment to ``\\input`` into a document (``amsmath`` for ``align*``,
``booktabs`` for the tables); nothing here computes: the formulas come from
:meth:`perturb.PeriodicSolution.latex`, derived by the method, never typed in.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

__all__ = ["latex_number", "latex_table", "solution_document"]


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


def latex_table(header: Sequence[str], rows: Iterable[Sequence], caption: str = "") -> str:
    """A ``booktabs`` tabular: text cells escaped, numbers in math mode."""

    def cell(value) -> str:
        if isinstance(value, str):
            return latex_text(value)
        return f"${latex_number(value)}$"

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
