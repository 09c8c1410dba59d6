"""Our Table 2, first half: the corrected first-order solution (the ``disk`` problem) at Table 1's t.

The corrected solution is the project's own Poincaré construction for the disk, with the paper's
data (31).  At the paper's eps = c/r0 = 232 it is as meaningless as the paper's; it is tabulated so
that the two constructions can be compared on equal terms.

References
----------
.. [1] The seed paper, equations (26), (30) and Table 1.
"""

from __future__ import annotations

import warnings

import numpy as np

from perturb.cache import held_warnings
from perturb.errors import UnknownNameError
from perturb.validation.model import parameter_value_of
from problems.rigid_body.paper.data import PAPER_INPUTS, TABLE1_T_END

__all__ = ["corrected_columns", "create_paper_disk"]

#: Names of (31) that are not parameters of the body: the paper's lambda and its period T.
_NOT_BODY_PARAMETERS = ("lambda", "T")


def create_paper_disk(cls):
    """The ``disk`` problem ``cls`` with the paper's data (31), whatever subset of names it accepts."""
    known = {s.name for s in cls.parameter_specs}
    candidates = {k: v for k, v in PAPER_INPUTS.items() if k not in _NOT_BODY_PARAMETERS}
    return cls.create(**{k: v for k, v in candidates.items() if k in known})


def corrected_columns(t: np.ndarray) -> dict:
    """Our Table 2 from the corrected first-order solution (the ``disk`` problem), if registered.

    The columns are the solution's own reduced variables P, G (the paper's p2, gamma2) at
    tau = r0 t, with x, y = d/dh = (300/T) r0 d/dtau: the solution is native in them, and its
    rebuilt full state (series in eps) is meaningless at eps = 232.

    Parameters
    ----------
    t : numpy.ndarray
        Table 1's time column (seconds).

    Returns
    -------
    dict
        ``{"description", "t", "p2a", "gamma2a", "xa", "ya", "period_seconds", "regime",
        "warnings"}``, or ``{"description", "p2a": None, "unavailable": reason}`` when the ``disk``
        problem cannot be built or solved.
    """
    description = (
        "corrected first-order solution (problem 'disk', eps = c/r0) at tau = r0 t, t in "
        "seconds; P, G are the paper's p2, gamma2; x, y = d/dh with h = T t/300"
    )
    try:
        from problems import get_problem

        cls = get_problem("disk")
    except (UnknownNameError, ImportError) as exc:
        return {"description": description, "p2a": None, "unavailable": str(exc)}
    try:
        problem = create_paper_disk(cls)
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            solution = problem.solve(1)
            r0 = PAPER_INPUTS["r0"]
            z = solution.evaluate(r0 * t, parameter_value_of(problem), problem.symbol_values())
            period = problem.period(solution)
            extras = problem.report_extras()
    except Exception as exc:  # noqa: BLE001 - a colleague's module: report, do not crash
        return {"description": description, "p2a": None, "unavailable": repr(exc)}
    cols = dict(zip(solution.state_names, z, strict=True))
    per_h = PAPER_INPUTS["r0"] * TABLE1_T_END / PAPER_INPUTS["T"]
    return {
        "description": description,
        "t": t,
        "p2a": cols["P"],
        "gamma2a": cols["G"],
        "xa": per_h * cols["dP"],
        "ya": per_h * cols["dG"],
        "period_seconds": period,
        "regime": extras.get("regime", ""),
        "warnings": sorted({str(w.message) for w in caught}),
    }
