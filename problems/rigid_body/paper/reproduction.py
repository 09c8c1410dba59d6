"""``perturb reproduce paper``: the orchestration only (each step lives in its own module).

Order of the work: the constants (32) from (31) (:mod:`.data`), Table 1 from the closed form (30)
(:mod:`.closed_form`), the true motion and the verdict (:mod:`.truth`), the corrected solution
(:mod:`.corrected`), the RK4 experiment (33) (:mod:`.rk4_experiment`), the Euler angles (28)–(29)
(:mod:`.euler`) and the errata (:mod:`.errata`); the report (:mod:`.report`) is formatted by
:mod:`.output`.
"""

from __future__ import annotations

import time

import numpy as np

from perturb.errors import UnknownNameError
from problems.reproductions import Reproduction, register_reproduction
from problems.rigid_body.paper import output as _output
from problems.rigid_body.paper.closed_form import check_table, closed_form, closed_form_columns
from problems.rigid_body.paper.corrected import corrected_columns
from problems.rigid_body.paper.data import TABLE1_COLUMNS, derived_constants, paper_table1
from problems.rigid_body.paper.errata import errata
from problems.rigid_body.paper.euler import euler_angle_study
from problems.rigid_body.paper.geometry_orbit import paper_geometry_orbit
from problems.rigid_body.paper.report import ReproductionReport
from problems.rigid_body.paper.rk4_experiment import rk4_experiment
from problems.rigid_body.paper.truth import true_motion, verdict

__all__ = ["KNOWN_PAPERS", "NOTES", "PaperReproduction", "reproduce"]

#: Papers this module can reproduce (``perturb reproduce NAME``).
KNOWN_PAPERS = ("paper",)

#: The readings used throughout, stated in the report.
NOTES = (
    "Table 1 / closed form (30): phase h = T t/300 (T = 18.78775142), x, y = d/dh; "
    "v1, v2, k* from (21), (23) as printed with gamma0'^2 read as y0'^2 and M3 = 1",
    "true motion: t in seconds, initial state (26) at tau = 0 with the printed mu "
    "(its mu^-1 terms are ~1e-11), gamma normalised; z0 = 0, g = 1.5e-7",
    "paper variables of a motion: the exact map (3) with eps = c/r0 (the only eps "
    "consistent with p1 = p/c, r1 = r/r0); derivatives d/dh = (300/T) d/dt",
    "experiment (33): RK4 in the phase h from Table 1's first row, with the project's "
    "derived F2, Phi2",
    "Euler angles (28)-(29): fast-spin disks (paper's A, B, C, x0, y0; c = 1, r0 = 1/eps), "
    "mu^-1 read as eps = c/r0, t0 = 0, initial angles from the true motion; true psi by "
    "integrating the kinematic equation along the Euler-Poisson trajectory",
)


def _max_diff(columns: dict, reference: dict) -> dict[str, float]:
    return {c: float(np.max(np.abs(columns[c] - np.asarray(reference[c])))) for c in TABLE1_COLUMNS}


def reproduce(name: str, output=None) -> ReproductionReport:
    """Reproduce a paper's numbers beside the corrected solution and the true motion.

    Parameters
    ----------
    name : str
        One of :data:`KNOWN_PAPERS`.
    output : str or path-like, optional
        Directory (created if missing) receiving ``paper-report.json``, ``constants.csv``,
        ``table1.csv``, ``table2.csv`` and ``errata.csv``.

    Returns
    -------
    ReproductionReport

    Raises
    ------
    perturb.errors.UnknownNameError
        If ``name`` is not a known paper (the message lists them).
    perturb.errors.InvalidParameterError
        If ``output`` cannot be created or written.

    Examples
    --------
    >>> report = reproduce("paper")  # doctest: +SKIP
    >>> report.constants["mu"]["matches"]  # doctest: +SKIP
    False
    """
    if name not in KNOWN_PAPERS:
        raise UnknownNameError(f"`paper` = {name!r} is unknown: choose from {list(KNOWN_PAPERS)}")
    path = None if output is None else _output.prepare_output(output)
    start = time.perf_counter()

    consts = derived_constants()
    cf = closed_form()
    printed = paper_table1()
    t = np.asarray(printed["t"])
    table1 = {"t": t, **closed_form_columns(t, cf)}
    check = check_table(table1, printed)

    motion = true_motion(cf, printed)
    truth_block = motion.block
    corrected = corrected_columns(t)
    if corrected.get("p2a") is not None:
        corrected["max_diff_vs_table1"] = _max_diff(corrected, printed)
        corrected["max_diff_vs_true_motion"] = _max_diff(corrected, truth_block)

    judged = verdict(consts["eps"]["computed"], cf, motion)
    experiment = rk4_experiment(cf, printed, truth_block)
    euler = euler_angle_study()
    orbit = paper_geometry_orbit()
    found = errata(consts, cf, printed, check, judged, experiment, euler)
    report = ReproductionReport(
        paper=name,
        constants=consts,
        closed_form=cf,
        table1=table1,
        table1_printed={c: printed[c] for c in ("t", *TABLE1_COLUMNS)},
        table1_check=check,
        table2={"corrected": corrected, "true_motion": truth_block},
        experiment=experiment,
        verdict=judged,
        errata=found,
        notes=NOTES,
        elapsed=time.perf_counter() - start,
        euler_angles=euler,
        true_orbit=orbit,
    )
    if path is not None:
        _output.write_outputs(report, path)
    return report


@register_reproduction("paper")
class PaperReproduction(Reproduction):
    """The seed paper (disk in a Newtonian field and gravity) for ``perturb reproduce paper``."""

    def run(self, output=None) -> ReproductionReport:
        return reproduce(self.name, output=output)

    def as_dict(self, report: ReproductionReport) -> dict:
        return _output.report_dict(report)

    def summary(self, report: ReproductionReport) -> str:
        return _output.summary_text(report)

    def full(self, report: ReproductionReport) -> str:
        return _output.full_text(report)
