"""Formatting of result objects (JSON dictionaries, text tables, LaTeX in :mod:`.latex`, plots in
:mod:`perturb.report.plots`, HTML in notebooks by :mod:`.notebook`): leaves that only the CLI, the
tests and a notebook (``%load_ext perturb.report``) import; the result objects themselves stay data."""

import importlib

#: Where each public name lives: imported on first use, so that a command needing one formatter
#: does not import them all (the notebook's pulls in the whole validation room).
_WHERE = {
    "load_ipython_extension": "perturb.report.notebook",
    "response_as_csv": "perturb.report.response",
    "response_as_dict": "perturb.report.response",
    "response_as_table": "perturb.report.response",
    "response_latex": "perturb.report.response",
    "validation_as_dict": "perturb.report.validation",
    "validation_as_table": "perturb.report.validation",
    "work_precision_as_csv": "perturb.report.workprecision",
    "work_precision_as_dict": "perturb.report.workprecision",
    "work_precision_as_table": "perturb.report.workprecision",
}


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(_WHERE[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'perturb.report' has no attribute {name!r}")


def __dir__():
    return sorted({*globals(), *_WHERE})


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
