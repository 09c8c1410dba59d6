"""Formatting of result objects (JSON dictionaries, text tables, plots in :mod:`perturb.report.plots`):
leaves that only the CLI and the tests import; the result objects themselves stay data."""

from perturb.report.validation import validation_as_dict, validation_as_table
from perturb.report.workprecision import (
    work_precision_as_csv,
    work_precision_as_dict,
    work_precision_as_table,
)

__all__ = [
    "validation_as_dict",
    "validation_as_table",
    "work_precision_as_csv",
    "work_precision_as_dict",
    "work_precision_as_table",
]
