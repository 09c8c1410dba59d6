"""``--format zarr`` (a sweep's default): the points are in the Zarr store; a summary is printed."""

from __future__ import annotations

from perturb.report.formats.base import Format


def _sweep(output) -> str:
    from perturb.report.sweep import sweep_summary

    return sweep_summary(output) + "\n"


FORMAT = Format("zarr", {"sweep": _sweep}, rank=1)
