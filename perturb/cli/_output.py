"""Printing a result in the format asked for: the one place the CLI meets the format registry
(:mod:`perturb.report.formats`)."""

from __future__ import annotations


def _emit(kind: str, fmt: str, result) -> None:
    """Print ``result`` (a result of ``kind``) in the format ``fmt``, exactly as written."""
    from perturb.report.formats import write

    print(write(kind, fmt, result), end="")
