"""A work–precision table (:class:`perturb.workprecision.WorkPrecision`) as CSV, JSON or text."""

from __future__ import annotations

from perturb.workprecision import WorkPrecision

__all__ = ["work_precision_as_csv", "work_precision_as_dict", "work_precision_as_table"]

#: The CSV header: a promise to users' scripts (issue 13: ``method,setting,error,seconds``).
CSV_HEADER = "method,setting,error,seconds"


def work_precision_as_csv(result: WorkPrecision) -> str:
    """``method,setting,error,seconds`` lines, with the header."""
    lines = [CSV_HEADER]
    lines += [f"{p.method},{p.setting},{p.error:.6e},{p.seconds:.6e}" for p in result.points]
    return "\n".join(lines)


def work_precision_as_table(result: WorkPrecision) -> str:
    """An aligned text table headed by the problem, the horizon and the reference integrator."""
    lines = [
        f"# work-precision {result.problem}: {result.periods:g} periods "
        f"(t = {result.horizon:.6g}), reference {result.reference}",
        f"{'method':<22s} {'setting':<16s} {'error':>11s} {'seconds':>11s}",
    ]
    for p in result.points:
        lines.append(f"{p.method:<22s} {p.setting:<16s} {p.error:11.3e} {p.seconds:11.4g}")
    return "\n".join(lines)


def work_precision_as_dict(result: WorkPrecision) -> dict:
    """The JSON form: ``{"problem", "periods", "horizon", "reference", "points": [...]}``."""
    return {
        "problem": result.problem,
        "periods": result.periods,
        "horizon": result.horizon,
        "reference": result.reference,
        "points": [
            {"method": p.method, "setting": p.setting, "error": p.error, "seconds": p.seconds}
            for p in result.points
        ],
    }
