"""The seed paper's reproduction (``perturb reproduce paper``), one module per concern.

The seed paper ("periodic solutions of a disk about a fixed point in a Newtonian force field and
gravity, large parameter technique") prints input data (31), derived constants (32), a closed form
(30) and its values in Table 1, and claims agreement with an RK4 integration of its system (33).
:func:`reproduce` recomputes all of it and sets it beside

* the corrected first-order solution (the ``disk`` problem, when registered), and
* the true motion: the full Euler–Poisson equations integrated from the paper's initial state (26).

Readings used throughout (each stated in the report):

* ``t`` of Table 1 is in seconds for the true motion; the closed form (30) is evaluated, as the paper
  evidently did, at the phase :math:`h = T t/300` (reference (e)).
* The consistent expansion parameter is :math:`\\varepsilon = c/r_0` (our derivation); the printed
  :math:`\\mu` enters only where the paper's own formulas use it (the :math:`\\mu^{-1}` terms of (26),
  system (33)).

Modules
-------
``data``
    inputs (31), printed constants (32), Table 1 (shipped as ``problems/rigid_body/data/table1.csv``).
``closed_form``
    the paper's (21)–(23), (30) as claims under test, and Table 1 recomputed.
``truth``
    the true motion (full Euler–Poisson) and the verdict.
``corrected``
    the project's corrected first-order solution at Table 1's t.
``rk4_experiment``
    the paper's experiment (33) redone.
``euler``
    the Euler angles (28)–(29) against the true motion (E12).
``witness``
    the printed coefficients (10)–(14), (20)–(23) beside the derived reduction.
``errata``
    every erratum with its status and witness.
``report``
    :class:`ReproductionReport`, data only.
``output``
    formatting: JSON dict, one-screen summary, full tables, report files.
``reproduction``
    :func:`reproduce` (orchestration) and its registration for the CLI.

References
----------
.. [1] The seed paper, equations (1)–(5), (19)–(23), (26), (30)–(33) and Table 1.
.. [2] Reference derivation ``derivation.md``, sections (b), (e), (f); SUMMARY, errata 1–9.
"""

from __future__ import annotations

from problems.rigid_body.paper.data import TABLE1_COLUMNS, paper_table1
from problems.rigid_body.paper.report import ReproductionReport
from problems.rigid_body.paper.reproduction import KNOWN_PAPERS, PaperReproduction, reproduce

__all__ = [
    "KNOWN_PAPERS",
    "TABLE1_COLUMNS",
    "PaperReproduction",
    "ReproductionReport",
    "paper_table1",
    "reproduce",
]
