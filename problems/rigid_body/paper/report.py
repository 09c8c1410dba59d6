"""The result of ``perturb reproduce paper``: one immutable value object, data only.

Formatting (the JSON dict, the text tables, the one-screen summary, the CSV files) lives in
:mod:`problems.rigid_body.paper.output`; :meth:`ReproductionReport.as_dict` and
:meth:`ReproductionReport.as_table` are kept as entry points and only delegate to it.
"""

from __future__ import annotations

from attrs import field, frozen

__all__ = ["ReproductionReport"]


@frozen
class ReproductionReport:
    """Everything ``perturb reproduce paper`` computes (immutable; see :func:`reproduce`).

    Attributes
    ----------
    paper : str
        The paper's name.
    constants : dict
        ``name -> {"computed", "printed", "matches", "note"}`` for the derived constants (32) and
        the readings of mu.
    closed_form : dict
        v1, v2, k* and the amplitudes of (30), under the printed (21) and the corrected reading.
    table1 : dict
        Table 1 recomputed from (30): ``{"t", "p2a", "gamma2a", "xa", "ya"}`` (lists).
    table1_printed : dict
        The printed Table 1, same keys.
    table1_check : dict
        Per column: max deviation, max deviation/tolerance, rows outside tolerance.
    table2 : dict
        "Our Table 2": the same columns from the corrected solution and from the true motion.
    experiment : dict
        The paper's RK4 experiment on (33) redone, against Table 1 and the true motion.
    verdict : dict
        Whether the expansion is valid for the paper's parameters, with the numbers.
    errata : dict
        ``id -> {"status", "where", "claim", "witness"}``; status ``wrong``, ``confirmed`` or
        ``unverifiable``.
    notes : tuple of str
        The readings used (units of t, which mu, initial state).
    elapsed : float
        Wall-clock seconds of the reproduction.
    euler_angles : dict
        The check of the Euler angles (28)–(29) in the fast-spin regime
        (:func:`problems.rigid_body.paper.euler.euler_angle_study`).
    true_orbit : dict
        The true periodic orbit at the paper's geometry in its fast-spin reading, ε = 1e-4
        (:func:`problems.rigid_body.paper.geometry_orbit.paper_geometry_orbit`).
    """

    paper: str
    constants: dict
    closed_form: dict
    table1: dict
    table1_printed: dict
    table1_check: dict
    table2: dict
    experiment: dict
    verdict: dict
    errata: dict
    notes: tuple[str, ...] = field(converter=tuple)
    elapsed: float = 0.0
    euler_angles: dict = field(factory=dict)
    true_orbit: dict = field(factory=dict)

    def as_dict(self) -> dict:
        """A JSON-serialisable dict (:func:`~problems.rigid_body.paper.output.report_dict`)."""
        from problems.rigid_body.paper.output import report_dict

        return report_dict(self)

    def as_table(self) -> str:
        """The full plain-text report (:func:`~problems.rigid_body.paper.output.full_text`)."""
        from problems.rigid_body.paper.output import full_text

        return full_text(self)
