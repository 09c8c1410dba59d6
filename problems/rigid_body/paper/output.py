"""FORMATTING of a :class:`~problems.rigid_body.paper.report.ReproductionReport`: no computation.

Everything that turns the report into text or files lives here:

* :func:`report_dict` -- the JSON-serialisable dict (``--format json``; its keys are a contract for
  users' scripts and must not change),
* :func:`summary_text` -- the one-screen summary ``perturb reproduce paper`` prints first,
* :func:`full_text` -- the full tables (``--full``; also :meth:`ReproductionReport.as_table`),
* :func:`prepare_output` and :func:`write_outputs` -- the report files of ``--output DIR``.

Each function takes the report (a ``ReproductionReport``) and reads its fields; this module does
not import the report's class, so the report's own ``as_dict``/``as_table`` call here without
the two modules importing each other.
"""

from __future__ import annotations

import csv
import io
import json
import tempfile
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from perturb.errors import InvalidParameterError
from problems.rigid_body.paper.data import PAPER_CITATION, PRINTED_CONSTANTS, TABLE1_COLUMNS
from problems.rigid_body.paper.errata import ERRATA_STATUSES
from problems.rigid_body.paper.geometry_orbit import ROUTE_QUAD

__all__ = [
    "OUTPUT_FILES",
    "SUMMARY_MAX_LINES",
    "SUMMARY_MAX_WIDTH",
    "full_text",
    "prepare_output",
    "report_dict",
    "summary_text",
    "write_outputs",
]

#: Files written by ``--output DIR``.
OUTPUT_FILES = ("paper-report.json", "constants.csv", "table1.csv", "table2.csv", "errata.csv")

#: The summary must fit one terminal screen (a 100x35 window keeps the prompt visible): the verdict,
#: the figures, and the lines that say which paper it is and how to read it without the paper open.
SUMMARY_MAX_LINES = 34

#: ... and one line of it fits the project's line length (a wide terminal shows it unwrapped).
SUMMARY_MAX_WIDTH = 100

#: Where the errata are argued in full.
ERRATA_DOC = PAPER_CITATION["errata"]


# ---------------------------------------------------------------------------- JSON
def _jsonable(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return [_jsonable(v) for v in value.tolist()]
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    return value


def report_dict(report) -> dict:
    """A JSON-serialisable dict (NaN/inf kept as floats; ``json.dumps(..., allow_nan=True)``)."""
    return _jsonable(
        {
            "paper": report.paper,
            "citation": PAPER_CITATION,
            "constants": report.constants,
            "closed_form": report.closed_form,
            "table1": report.table1,
            "table1_printed": report.table1_printed,
            "table1_check": report.table1_check,
            "table2": report.table2,
            "experiment": report.experiment,
            "verdict": report.verdict,
            "errata": report.errata,
            "notes": list(report.notes),
            "elapsed_seconds": report.elapsed,
            "euler_angles": report.euler_angles,
            "true_orbit": report.true_orbit,
        }
    )


# ---------------------------------------------------------------------------- full text
def full_text(report) -> str:
    """A plain-text report: constants, Table 1 check, our Table 2, experiment, verdict, errata."""
    out = io.StringIO()
    w = out.write
    w(
        f"# Reproduction of {report.paper!r} (seed paper: disk in a Newtonian field, 'slow spin')\n\n"
    )
    w("## Derived constants (32): computed from (31) vs printed\n")
    w(f"{'name':<10}{'computed':>20}{'printed':>16}  ok   note\n")
    for name, row in report.constants.items():
        printed = "-" if row["printed"] is None else f"{row['printed']:.7g}"
        ok = {True: "yes", False: "NO", None: "-"}[row["matches"]]
        w(f"{name:<10}{row['computed']:>20.10g}{printed:>16}  {ok:<4} {row['note']}\n")
    w("\n## Table 1 from the closed form (30), h = T t/300\n")
    w(f"{'t':>5}" + "".join(f"{c:>14}{'printed':>12}" for c in TABLE1_COLUMNS) + "\n")
    for i, t in enumerate(report.table1["t"]):
        w(f"{t:>5g}")
        for c in TABLE1_COLUMNS:
            w(f"{report.table1[c][i]:>14.7g}{report.table1_printed[c][i]:>12.7g}")
        w("\n")
    for c in TABLE1_COLUMNS:
        chk = report.table1_check[c]
        w(
            f"  {c:<8} max|dev| {chk['max_deviation']:.2e}  max dev/tol {chk['max_ratio']:.2f}"
            f"  rows outside tolerance: {chk['rows_outside']}\n"
        )
    w("\n## Our Table 2: corrected solution and true motion at the table's t (seconds)\n")
    for key in ("corrected", "true_motion"):
        block = report.table2[key]
        w(f"### {key}: {block['description']}\n")
        if block.get("p2a") is None:
            w("  (not available)\n")
            continue
        w(f"{'t':>5}" + "".join(f"{c:>16}" for c in TABLE1_COLUMNS) + "\n")
        for i, t in enumerate(block["t"]):
            w(f"{t:>5g}" + "".join(f"{block[c][i]:>16.7g}" for c in TABLE1_COLUMNS) + "\n")
        w(
            "  max|this - Table 1|: "
            + ", ".join(f"{c} {v:.3g}" for c, v in block["max_diff_vs_table1"].items())
            + "\n"
        )
    w("\n## The paper's numerical experiment (33) redone (RK4)\n")
    for name, run in report.experiment["runs"].items():
        w(f"  {name}: {run['description']}\n    {run['outcome']}\n")
    w("\n## Verdict\n")
    w(f"  {report.verdict['summary']}\n")
    for key, value in report.verdict["numbers"].items():
        w(f"    {key}: {value:.6g}\n")
    if report.euler_angles:
        w("\n## Euler angles (28)-(29) vs the true motion (fast spin, 3 periods)\n")
        w("  max |difference| per eps; slope = d log / d log eps\n")
        for case, block in report.euler_angles.items():
            w(f"### {case}: k = {block['k']:g}, gamma0'' = {block['gamma3_0']:g}\n")
            w(f"    eps: {', '.join(f'{e:.3g}' for e in block['eps'])}\n")
            rows = {"size (true)": block["size"], **block["max_diff"]}
            slopes = {"size (true)": block["slope"]["size"], **block["slope"]}
            for name, per_angle in rows.items():
                for angle, values in per_angle.items():
                    w(
                        f"    {name:<36}{angle:<6}"
                        + "".join(f"{v:>10.2e}" for v in values)
                        + f"   slope {slopes[name][angle]:5.2f}\n"
                    )
    w("\n## Errata (details: docs/paper-errata.md)\n")
    for status in ERRATA_STATUSES:
        w(f"### {status}\n")
        for eid, item in report.errata.items():
            if item["status"] == status:
                w(f"  {eid} {item['where']}: {item['claim']}\n")
    w("\n## Readings used\n")
    for note in report.notes:
        w(f"  - {note}\n")
    w(f"\n(elapsed {report.elapsed:.1f} s)\n")
    return out.getvalue()


# ---------------------------------------------------------------------------- summary
#: Short names of the RK4 experiment's runs, in the summary.
_RUN_LABELS = {
    "printed_mu_squared": "mu^2 (33 as printed)",
    "mu_minus_2": "mu^-2 (as in (1))",
    "eps_squared": "eps^2 (consistent)",
}


def _per_column(values: dict, fmt: str) -> str:
    return ", ".join(f"{c} {values[c]:{fmt}}" for c in TABLE1_COLUMNS if c in values)


def _summary_constants(report) -> list[str]:
    rows = {name: report.constants[name] for name in PRINTED_CONSTANTS}
    missed = [name for name, row in rows.items() if not row["matches"]]
    line = (
        f"constants (32)      {len(rows) - len(missed)}/{len(rows)} printed values reproduced "
        "from (31) to their last digit"
    )
    return [line + (f"; not: {', '.join(missed)}" if missed else "")]


def _summary_table1(report) -> list[str]:
    check = report.table1_check
    n_rows = len(report.table1["t"])
    total = n_rows * len(TABLE1_COLUMNS)
    outside = sum(len(check[c]["rows_outside"]) for c in TABLE1_COLUMNS)
    worst = max(check[c]["max_ratio"] for c in TABLE1_COLUMNS)
    deviations = {c: check[c]["max_deviation"] for c in TABLE1_COLUMNS}
    return [
        f"Table 1 vs (30)     {total - outside}/{total} entries within printed precision "
        f"(h = T t/300; max dev/tol {worst:.2f})",
        f"                    max |dev|: {_per_column(deviations, '.2e')}",
    ]


def _summary_motion(report) -> list[str]:
    truth = report.table2["true_motion"]
    drift = max(truth["relative_integral_drift"].values())
    lines = [
        f"true motion         max |true - Table 1|: {_per_column(truth['max_diff_vs_table1'], '.3g')}",
        f"                    (full Euler-Poisson from (26), 0-300 s; integrals drift {drift:.1e})",
    ]
    corrected = report.table2["corrected"]
    if corrected.get("p2a") is None:
        lines.append(f"corrected solution  not available: {corrected.get('unavailable', '')}")
    else:
        diff = _per_column(corrected["max_diff_vs_true_motion"], ".3g")
        lines.append(f"corrected solution  max |ours - true|: {diff}")
    return lines


def _summary_experiment(report) -> list[str]:
    lines = ["RK4 experiment (33) redone from Table 1's first row:"]
    for name, run in report.experiment["runs"].items():
        label = _RUN_LABELS.get(name, name)
        if "h_reached" in run:
            outcome = f"blows up at h = {run['h_reached']:.3g} (t = {run['t_reached']:.3g} s)"
        else:
            vs_table = max(run["max_diff_vs_table1"].values())
            vs_true = max(run["max_diff_vs_true_motion"].values())
            outcome = (
                f"completes: max |RK4 - Table 1| {vs_table:.2g}, max |RK4 - true| {vs_true:.3g}"
            )
        lines.append(f"  {label:<22}{outcome}")
    return lines


def _summary_euler(report) -> list[str]:
    e12 = report.errata.get("E12")
    if not report.euler_angles or e12 is None:
        return []
    w = e12["witness"]
    case = w["case"]

    def row(label: str, sizes: dict, slopes: dict) -> str:
        cells = "  ".join(f"{a} {sizes[a]:.2e}" for a in sizes)
        return f"  {label:<14}{cells}   slopes in eps " + " ".join(
            f"{slopes[a]:.2f}" for a in sizes
        )

    return [
        f"Euler angles (28)-(29), fast spin k = {case['k']:g}, gamma0'' = {case['gamma3_0']:g}, "
        f"max over 3 periods at eps = {case['eps']:g}:",
        row("true size", w["true_size"], w["slopes"]["size"]),
        row("paper - true", w["true_vs_paper"], w["slopes"]["true_vs_paper"]),
        row("ours - true", w["true_vs_ours"], w["slopes"]["true_vs_ours"]),
    ]


def _summary_true_orbit(report) -> list[str]:
    orbit = report.true_orbit
    if not orbit:
        return []
    if not orbit["success"]:
        return [
            f"true orbit at eps = {orbit['eps']:g} (paper geometry): not found: {orbit['message']}"
        ]
    b1, b2 = orbit["beta1_over_eps"], orbit["beta2_over_eps"]
    f1, f2 = orbit["first_order"][:2]
    return [
        f"true orbit at eps = {orbit['eps']:g} (paper geometry; {orbit.get('route', ROUTE_QUAD)}):",
        f"  beta/eps = {b1:.7f}, {b2:.7f} (+-{orbit['resolution']:.0e}); first order "
        f"{f1:.6f}, {f2:.6f}: {100 * (1 - f1 / b1):.2f} % low",
    ]


def _summary_errata(report) -> list[str]:
    by_status = {
        status: [eid for eid, item in report.errata.items() if item["status"] == status]
        for status in ERRATA_STATUSES
    }
    counts = ", ".join(f"{len(ids)} {status}" for status, ids in by_status.items())
    lines = [f"errata              {counts} (argued in {ERRATA_DOC})"]
    lines += [f"  {status:<18}{' '.join(ids)}" for status, ids in by_status.items() if ids]
    return lines


def _summary_citation() -> list[str]:
    """Which paper, and how to read the screen without it open."""
    legend = (
        f'paper: "{PAPER_CITATION["title"]}" (authors and year: {PAPER_CITATION["authors"]}). '
        "How to read: (NN) = the paper's equation NN; eps = c/r0 the small parameter (c = "
        "sqrt(M g l/C)), mu = 1/eps the paper's large one; p2a gamma2a xa ya = Table 1's columns; "
        "E#/C#/U# = errata wrong/confirmed/unverifiable, each argued under its ID in "
        f"{ERRATA_DOC}"
    )
    return textwrap.wrap(legend, SUMMARY_MAX_WIDTH - 2, initial_indent="  ", subsequent_indent="  ")


def summary_text(report) -> str:
    """The one-screen summary (:data:`SUMMARY_MAX_LINES` x :data:`SUMMARY_MAX_WIDTH` at most).

    Parameters
    ----------
    report : ReproductionReport
        The reproduction.

    Returns
    -------
    str
        The verdict on the paper, the constants matched, the Table 1 deviations, the true-motion
        discrepancy, the RK4 experiment's outcome, the Euler-angle finding and the errata count
        by status, ending with where the details are.
    """
    numbers = report.verdict["numbers"]
    valid = report.verdict["valid"]
    lines = [
        f"Reproduction of {report.paper!r}: a disk about a fixed point in a Newtonian field and "
        "gravity",
        *_summary_citation(),
        "",
        f"VERDICT  the paper's solution {'holds' if valid else 'does NOT hold'} for its own data: "
        f"eps = c/r0 = {numbers['eps_c_over_r0']:.4g} ({'small' if valid else 'not small'})",
        f"         true motion: r/r0 goes from 1 to {numbers['r_over_r0_min_0_300s']:.4g} by "
        f"t = {numbers['t_of_r_min']:.4g} s (the paper: r1 = 1 + O(mu^-2))",
        "",
        *_summary_constants(report),
        *_summary_table1(report),
        *_summary_motion(report),
        *_summary_experiment(report),
        *_summary_euler(report),
        *_summary_true_orbit(report),
        *_summary_errata(report),
        "",
        f"Full tables: --full; report files: --output DIR; every number: --format json "
        f"(elapsed {report.elapsed:.1f} s)",
    ]
    return "\n".join(lines)


# ---------------------------------------------------------------------------- files
def prepare_output(output) -> Path:
    """Create ``output`` if needed and check that it is writable, before any work is done.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``output`` cannot be created or written (the message names ``--output``).
    """
    fix = "give a directory you can write to, e.g. --output ./reproduction"
    if not str(output).strip():  # Path("") is the current folder: never write there by accident
        raise InvalidParameterError(f"`output` = {str(output)!r} is invalid: {fix}")
    path = Path(output)
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise InvalidParameterError(
            f"`--output` = {str(output)!r} is not a writable directory ({reason}): {fix}"
        ) from None
    return path


def _write_csv(path: Path, header: list[str], rows) -> None:
    with path.open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(header)
        writer.writerows(rows)


def write_outputs(report, path: Path) -> None:
    """Write :data:`OUTPUT_FILES` into the directory ``path`` (see :func:`prepare_output`)."""
    data = report_dict(report)
    (path / "paper-report.json").write_text(json.dumps(data, indent=1, allow_nan=True))
    _write_csv(
        path / "constants.csv",
        ["name", "computed", "printed", "matches", "note"],
        [
            [n, r["computed"], r["printed"], r["matches"], r["note"]]
            for n, r in data["constants"].items()
        ],
    )
    t1, pr = data["table1"], data["table1_printed"]
    _write_csv(
        path / "table1.csv",
        ["t", *(h for c in TABLE1_COLUMNS for h in (c, c + "_printed"))],
        [
            [t, *(v for c in TABLE1_COLUMNS for v in (t1[c][i], pr[c][i]))]
            for i, t in enumerate(t1["t"])
        ],
    )
    rows = []
    blocks = {k: v for k, v in data["table2"].items() if v.get("p2a") is not None}
    for i, t in enumerate(t1["t"]):
        rows.append([t, *(blk[c][i] for blk in blocks.values() for c in TABLE1_COLUMNS)])
    _write_csv(
        path / "table2.csv",
        ["t", *(f"{c}_{k}" for k in blocks for c in TABLE1_COLUMNS)],
        rows,
    )
    _write_csv(
        path / "errata.csv",
        ["id", "status", "where", "claim"],
        [[k, e["status"], e["where"], e["claim"]] for k, e in data["errata"].items()],
    )
