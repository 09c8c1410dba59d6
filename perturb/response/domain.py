"""Whether each steady state of a response is inside its series' domain: :func:`branch_domains`.

A response point is the periodic solution of its branch at the point's parameter values
(:func:`perturb.response.branches.branch_solution`); it is checked exactly as ``perturb solve``
checks a solution (:func:`perturb.domain.series_domain`: the frequency positive, the terms of the
frequency and of each coordinate decreasing at ε). A point outside is kept in the response and
flagged with the reason: its amplitudes are not the motion's. A point inside whose next term is
estimated large (:attr:`perturb.domain.DomainCheck.beyond_validity`) is flagged as beyond the
series' validity.
"""

from __future__ import annotations

import warnings

import numpy as np

from perturb.domain import series_domain
from perturb.response.branches import branch_solution

__all__ = ["branch_domains"]


def branch_domains(equations, found, problem) -> list[tuple[str, str]]:
    """For each branch point of ``found`` (at ``problem``'s values): ``(outside, beyond)``, why
    its series is outside its domain and why it is beyond its estimated validity (each ``""``
    when it is not; :class:`perturb.domain.DomainCheck`).

    Examples
    --------
    >>> from problems import get_problem
    >>> from perturb.method.driven import amplitude_equations
    >>> from perturb.response.branches import branches_at
    >>> duffing = get_problem("forced-duffing").create(Omega=1.05)
    >>> equations = amplitude_equations(duffing.system(), 1)
    >>> found, _ = branches_at(equations, duffing.symbol_values(), duffing.epsilon(), 1)
    >>> branch_domains(equations, found, duffing)
    [('', ''), ('', ''), ('', '')]
    """
    out = []
    for point in found:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            try:
                check = series_domain(
                    branch_solution(equations, point),
                    problem.parameter_value(),
                    problem.symbol_values(),
                )
            except (ArithmeticError, ValueError) as exc:
                out.append((f"the series cannot be evaluated here ({exc})", ""))
                continue
        out.append(("; ".join(check.reasons), check.validity_note()))
    return out
