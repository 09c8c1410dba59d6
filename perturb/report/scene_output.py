"""Writing a scene's report folder (``perturb report SCENE.toml --output DIR``).

:func:`write_report` turns a :class:`perturb.scene.run.SceneResult` into exactly the files its
scene asked for, plus ``scene.toml`` (the scene as written) and ``summary.md`` (the verdict):

==========================  ==================================================
file                        written when ``[outputs]`` has
==========================  ==================================================
``solution.csv``, ``.json`` ``table = true``
``euler.csv``               ``euler = true``
``validation.json``         ``validation = true``
``work_precision.csv``      ``work_precision = true`` (``method,setting,error,seconds``)
``solution.tex``            ``latex = true``
``sweep.zarr``, ``.csv``    ``sweep = true`` (the ``[sweep]``'s points: a Zarr store, a table)
``response.csv``, ``.json`` ``response = true`` (the ``[response]``: as ``perturb response``)
``NAME.png`` (``.pdf``...)  ``plots = ["NAME", ...]`` (``formats``: png, pdf, svg)
==========================  ==================================================

matplotlib is imported only when a plot is asked for. The folder also holds the marker
``.perturb-report.json`` (:mod:`perturb.report.folder`): the scene reported and the files perturb
wrote. Files of an earlier report of the scene that are not asked for this time are removed when
perturb wrote them and they are unchanged, so that the folder holds what the scene asks for; a
file perturb did not write is never removed or overwritten (a clash is refused before any work).
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
from pathlib import Path

import numpy as np

from perturb.errors import OutputError
from perturb.report.folder import STORE_TOKEN, ReportFolder, claim_folder
from perturb.report.json_text import json_text
from perturb.report.latex import solution_document
from perturb.report.response import response_as_csv, response_as_dict
from perturb.report.sweep import sweep_as_csv
from perturb.report.validation import validation_as_dict
from perturb.report.workprecision import work_precision_as_csv
from perturb.scene.spec import MAP_PLOTS, PLOT_FORMATS, PLOT_NAMES, RESPONSE_PLOTS

__all__ = [
    "SUMMARY",
    "all_names",
    "prepare_folder",
    "report_files",
    "summary_markdown",
    "write_report",
]

#: The summary's file name (also printed by the CLI).
SUMMARY = "summary.md"

_DATA_FILES = (
    "sweep.csv",
    "response.csv",
    "response.json",
    "solution.csv",
    "solution.json",
    "euler.csv",
    "validation.json",
    "work_precision.csv",
    "solution.tex",
)

#: Instants of the orientation plot, as fractions of the first period (or the horizon if shorter).
ORIENTATION_FRACTIONS = (0.0, 0.25, 0.5, 0.75)


def all_names() -> list[str]:
    """Every name a report may write into its folder (files, plots and the sweep's store)."""
    names = [*_DATA_FILES, SUMMARY, "scene.toml", "sweep.zarr"]
    return names + [f"{plot}.{fmt}" for plot in PLOT_NAMES for fmt in PLOT_FORMATS]


def prepare_folder(path, scene=None, *, force: bool = False) -> ReportFolder:
    """Claim the report folder ``path`` for a report of ``scene``, before any work.

    The folder is created if missing (with its parents). It may hold an earlier report of the
    same scene file (recognised by the marker :data:`perturb.report.folder.MARKER`), whose
    files are replaced; anything perturb did not write is never removed or overwritten
    (:func:`perturb.report.folder.claim_folder`).

    Parameters
    ----------
    path : str or path-like
    scene : perturb.scene.Scene, optional
        The scene reported (None: check the folder only).
    force : bool
        Replace perturb's own files of the report of another scene.

    Raises
    ------
    perturb.errors.OutputError
        The folder cannot be created or written, or it holds a file the report would write or
        remove that perturb did not write (one line: the path, the file, the fix).
    """
    names = report_files(scene) if scene is not None else []
    return claim_folder(path, names, _scene_key(scene), known=all_names(), force=force)


def _scene_key(scene) -> str:
    """What a report is of: the scene file's resolved path (its text when it has no file)."""
    if scene is None:
        return ""
    source = Path(scene.source)
    if source.is_file():
        return str(source.resolve())
    return f"<text {hashlib.sha256(scene.text.encode()).hexdigest()[:16]}>"


def report_files(scene) -> list[str]:
    """The names of the files a report of ``scene`` consists of, in writing order."""
    out = scene.outputs
    names = ["scene.toml", SUMMARY]
    if out.table:
        names += ["solution.csv", "solution.json"]
    names += [name for flag, name in ((out.euler, "euler.csv"),) if flag]
    names += ["validation.json"] if out.validation else []
    names += ["work_precision.csv"] if out.work_precision else []
    names += ["solution.tex"] if out.latex else []
    names += ["sweep.zarr", "sweep.csv"] if out.sweep else []
    names += ["response.csv", "response.json"] if out.response else []
    names += [f"{plot}.{fmt}" for plot in out.plots for fmt in out.formats]
    return names


def _columns_csv(t: np.ndarray, columns: dict) -> str:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["t", *columns])
    for row in zip(t, *columns.values(), strict=True):
        writer.writerow([repr(float(v)) for v in row])
    return buffer.getvalue()


def _solution_json(result) -> dict:
    """The form of ``perturb solve --format json``."""
    return {
        "problem": result.scene.problem,
        "parameters": result.parameters,
        "epsilon": result.epsilon,
        "order": result.scene.order,
        "period": result.period,
        "t": result.t.tolist(),
        "state": {k: np.asarray(v, dtype=float).tolist() for k, v in result.state.items()},
        "warnings": list(result.notes),
    }


def _phase_pairs(result) -> list[tuple[str, str]]:
    """Coordinate against velocity for a quasilinear state, else consecutive components."""
    names = list(result.state)
    coordinates = list(result.solution.coordinates)
    pairs = [(c, f"{c}dot") for c in coordinates if c in names and f"{c}dot" in names]
    if not pairs:
        pairs = [(names[i], names[i + 1]) for i in range(0, len(names) - 1, 2)]
    return pairs[:3]


def _draw(name: str, result, notes: list[str]):
    """The figure of plot ``name``, or None (with a note) when its data is missing."""
    from perturb.report import plots

    t, state, truth = result.t, result.state, result.truth
    if name in ("time_series", "error", "phase") and (t is None or state is None):
        notes.append(f"plot {name!r} skipped: there is no analytic state ({result.failure})")
        return None
    if truth is not None:
        n = min(len(v) for v in truth.values())
        t_true, state_cut = t[:n], {k: np.asarray(v)[:n] for k, v in state.items()}
    if name == "time_series":
        return plots.plot_time_series(t, state, _full(truth, len(t)), time_unit="")
    if name == "error":
        if truth is None or n < 2:
            notes.append("plot 'error' skipped: the true trajectory has fewer than two points")
            return None
        return plots.plot_error(t_true, state_cut, truth, time_unit="")
    if name == "phase":
        return plots.plot_phase(state, _full(truth, len(t)), pairs=_phase_pairs(result))
    if name == "convergence":
        fit = None if result.validation is None else result.validation.slope
        if fit is None or sum(1 for e in fit.errors if math.isfinite(e) and e > 0) < 2:
            notes.append("plot 'convergence' skipped: the validation measured no ε scan")
            return None
        return plots.plot_convergence(
            np.abs(np.asarray(fit.epsilons, dtype=float)),
            fit.errors,
            order=result.scene.order,
            slope=fit.slope if math.isfinite(fit.slope) else None,
            slope_band=fit.band,
        )
    if name in RESPONSE_PLOTS:
        if result.response is None:
            notes.append(f"plot {name!r} skipped: the response was not computed")
            return None
        if name == "frequency_response":
            return plots.plot_frequency_response(result.response)
        return plots.plot_floquet_along_branches(result.response)
    if name in MAP_PLOTS:
        return _map(name, result, notes)
    if name == "work_precision":
        if result.work_precision is None:
            notes.append("plot 'work_precision' skipped: no work-precision runs")
            return None
        return plots.plot_work_precision(result.work_precision)
    if result.euler is None:
        notes.append(f"plot {name!r} skipped: there are no Euler angles ({result.failure})")
        return None
    if name == "euler":
        return plots.plot_euler_angles(t, result.euler, time_unit="")
    span = min(result.period, float(t[-1]))
    instants = [f * span for f in ORIENTATION_FRACTIONS]
    return plots.plot_orientation(t, result.euler, instants, time_unit="")


def _map(name: str, result, notes: list[str]):
    """A validity map of the scene's sweep (two axes)."""
    from perturb.report import plots

    ds = result.sweep
    if ds is None:
        notes.append(f"plot {name!r} skipped: the sweep was not computed")
        return None
    (xname, x), (yname, y) = [
        (axis["name"], np.asarray(axis["values"])) for axis in json.loads(ds.attrs["grid"])
    ]
    names = {"xname": xname, "yname": yname}
    if name == "verdict_map":
        labels = {int(k): v for k, v in json.loads(ds["verdict"].attrs["labels"]).items()}
        return plots.plot_verdict_map(x, y, ds["verdict"].values, labels, **names)
    if name == "error_map":
        tol = json.loads(ds.attrs["settings"])["tol"]
        return plots.plot_error_map(x, y, ds["orbit_error"].values, tol=tol, **names)
    if name == "slope_map":
        from perturb._defaults import SLOPE_TOLERANCE

        expected = result.scene.order + 1.0
        return plots.plot_slope_map(
            x, y, ds["order_slope"].values, expected=expected, band=SLOPE_TOLERANCE, **names
        )
    return plots.plot_period_map(x, y, ds["period"].values, **names)


def _sweep_lines(ds) -> list[str]:
    """The summary's lines about the sweep: its size and what became of its points."""
    import collections

    from perturb.sweep.status import PointStatus, member_of
    from perturb.validation import Verdict

    axes = [(a["name"], len(a["values"])) for a in json.loads(ds.attrs["grid"])]
    count = collections.Counter(int(c) for c in ds["status"].values.ravel())
    parts = [
        f"{member_of(PointStatus, c).name.lower()} {n}" for c, n in sorted(count.items()) if c >= 0
    ]
    lines = [
        f"- sweep: {int(ds['status'].size)} points over "
        + " × ".join(f"{n} ({k})" for n, k in axes)
        + f": {', '.join(parts)}"
    ]
    if "verdict" in ds:
        verdicts = collections.Counter(int(c) for c in ds["verdict"].values.ravel())
        lines.append(
            "- sweep verdicts: "
            + ", ".join(
                f"{member_of(Verdict, c).label} {n}" for c, n in sorted(verdicts.items()) if c >= 0
            )
        )
    return lines


def _response_lines(result) -> list[str]:
    """The summary's lines about the frequency response: branches, folds, the true motion."""
    response = result.response.response
    lines = [
        f"- response: {len(response.points)} steady states over {len(response.grid)} values of "
        f"{response.parameter} ({response.grid[0]:g} to {response.grid[-1]:g}), "
        f"{len(set(result.response.branches))} branches"
    ]
    outside = sum(1 for p in response.points if not getattr(p, "series_ok", True))
    if outside:
        lines.append(
            f"- {outside} steady states are roots of the order-{response.order} equations where "
            "the series is outside its domain (response.json says why, point by point)"
        )
    for fold in response.folds:
        where = "" if getattr(fold, "inside", True) else " (beside the sweep)"
        lines.append(f"- fold at {response.parameter} = {fold.value:.6g}{where}")
    for failure in response.failures:
        lines.append(f"- not solved: {failure}")
    from perturb.report.response import flag_lines

    lines += [f"- {line}" for line in flag_lines(result.response)]
    for shot in result.response.true:
        agree = "agree" if shot.stable_true == shot.stable_analytic else "DISAGREE"
        lines.append(
            f"- true orbit at {response.parameter} = {shot.value:.6g} ({shot.branch}): amplitude "
            f"error {shot.amplitude_error:.2e}, stable {shot.stable_true} (order "
            f"{response.order}: {shot.stable_analytic}, {agree})"
        )
    return lines


def _full(truth, n: int):
    """The true trajectory when it covers the whole grid (else None: drawn without it)."""
    if truth is None or min(len(v) for v in truth.values()) < n:
        return None
    return truth


def summary_markdown(result, files: list[str]) -> str:
    """``summary.md``: the problem, the verdict, the headline figures and the files written."""
    scene = result.scene
    lines = [f"# {result.label}: order {scene.order}", ""]
    params = ", ".join(f"{k} = {v:g}" for k, v in result.parameters.items())
    lines += [f"- parameters: {params}", f"- ε = {result.epsilon:.6g}"]
    if result.failure:
        lines += [f"- **construction failed**: {result.failure}"]
    else:
        lines += [f"- period T = {result.period:.12g} (physical time)"]
    report = result.validation
    if report is not None:
        lines += [f"- **verdict: {report.outcome.name}** — {report.verdict}"]
    elif not result.failure:
        lines += ["- verdict: not validated (add `validation = true` to [outputs])"]
    if result.sweep is not None:
        lines += _sweep_lines(result.sweep)
    if result.response is not None:
        lines += _response_lines(result)
    if result.work_precision is not None:
        wp = result.work_precision
        best = {}
        for p in wp.points:
            if math.isfinite(p.error) and (p.method not in best or p.error < best[p.method].error):
                best[p.method] = p
        lines += ["", f"## work–precision ({wp.periods:g} periods, reference {wp.reference})", ""]
        lines += ["| method | best setting | error | seconds |", "|---|---|---|---|"]
        lines += [
            f"| {p.method} | {p.setting} | {p.error:.2e} | {p.seconds:.3g} |" for p in best.values()
        ]
    if result.notes:
        lines += ["", "## notes", ""] + [f"- {note}" for note in result.notes]
    timings = ", ".join(f"{k} {v:.2f} s" for k, v in result.seconds.items())
    lines += ["", "## files", ""] + [f"- {name}" for name in files]
    lines += ["", f"computed: {timings}"]
    return "\n".join(lines) + "\n"


def write_report(result, folder) -> tuple[list[str], str]:
    """Write ``result``'s report into ``folder``; return the file names written and the summary.

    Parameters
    ----------
    result : perturb.scene.run.SceneResult
    folder : path or perturb.report.folder.ReportFolder
        A folder claimed by :func:`prepare_folder` (a path is claimed here).

    Returns
    -------
    (list of str, str)
        The files written (in ``folder``) and the text of ``summary.md``.
    """
    claimed = folder if isinstance(folder, ReportFolder) else prepare_folder(folder, result.scene)
    scene, out = result.scene, result.scene.outputs
    written: dict[str, bytes | str] = {"scene.toml": scene.text}
    notes: list[str] = []
    usable = not result.failure
    if out.table and result.state is not None:
        written["solution.csv"] = _columns_csv(result.t, dict(result.state))
        written["solution.json"] = json_text(_solution_json(result)) + "\n"
    if out.euler and result.euler is not None:
        written["euler.csv"] = _columns_csv(result.t, dict(result.euler))
    if out.validation and result.validation is not None:
        data = validation_as_dict(result.validation)
        written["validation.json"] = json_text(data, allow_nan=True, indent=1) + "\n"
    if out.work_precision and result.work_precision is not None:
        written["work_precision.csv"] = work_precision_as_csv(result.work_precision) + "\n"
    if out.latex and usable:
        written["solution.tex"] = solution_document(result.solution, result.label)
    if out.sweep and result.sweep is not None:
        written["sweep.csv"] = sweep_as_csv(result.sweep) + "\n"
    if out.response and result.response is not None:
        written["response.csv"] = response_as_csv(result.response) + "\n"
        data = response_as_dict(result.response)
        written["response.json"] = json_text(data, allow_nan=False, indent=1) + "\n"
    figures = {}
    if out.plots:
        for name in out.plots:
            figure = _draw(name, result, notes)
            if figure is not None:
                figures[name] = figure
    files = ["scene.toml", SUMMARY, *[n for n in written if n != "scene.toml"]]
    if out.sweep and result.sweep is not None:
        files.insert(files.index("sweep.csv"), "sweep.zarr")
    files += [f"{name}.{fmt}" for name in figures for fmt in out.formats]
    if notes:
        result = _with_notes(result, notes)
    summary = summary_markdown(result, files)
    written[SUMMARY] = summary
    try:
        claimed.begin(files, claimed.stale)
        for name, content in written.items():
            claimed.write(name, content)
        if "sweep.zarr" in files:
            from perturb.sweep.store import write_dataset

            token = claimed.store_token("sweep.zarr")
            write_dataset(result.sweep, claimed.folder / "sweep.zarr", {STORE_TOKEN: token})
            claimed.store_written("sweep.zarr")
        for name, figure in figures.items():
            for fmt in out.formats:
                buffer = io.BytesIO()
                figure.savefig(buffer, format=fmt)
                claimed.write(f"{name}.{fmt}", buffer.getvalue())
    except OSError as exc:
        raise OutputError(
            f"--output {str(claimed.folder)!r}: cannot write there ({exc.strerror or exc}); "
            "choose a writable folder"
        ) from None
    return files, summary


def _with_notes(result, notes: list[str]):
    from attrs import evolve

    return evolve(result, notes=(*result.notes, *notes))
