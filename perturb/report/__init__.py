"""Formatting of result objects (JSON dictionaries, text tables, LaTeX in :mod:`.latex`, plots in
:mod:`perturb.report.plots`, HTML in notebooks by :mod:`.notebook`): leaves that only the CLI, the
tests and a notebook (``%load_ext perturb.report``) import; the result objects themselves stay data."""

from perturb.report.notebook import load_ipython_extension
from perturb.report.response import (
    response_as_csv,
    response_as_dict,
    response_as_table,
    response_latex,
)
from perturb.report.validation import validation_as_dict, validation_as_table
from perturb.report.workprecision import (
    work_precision_as_csv,
    work_precision_as_dict,
    work_precision_as_table,
)

__all__ = [
    "load_ipython_extension",
    "response_as_csv",
    "response_as_dict",
    "response_as_table",
    "response_latex",
    "validation_as_dict",
    "validation_as_table",
    "work_precision_as_csv",
    "work_precision_as_dict",
    "work_precision_as_table",
]
