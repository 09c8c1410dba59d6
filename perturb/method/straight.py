"""Whether a family's orbit stays on the line of its generating amplitudes (for its name)."""

from __future__ import annotations

import sympy as sp

from perturb.method.exact import is_zero
from perturb.solution import PeriodicSolution

__all__ = ["straight_orbit"]


def straight_orbit(solution: PeriodicSolution) -> bool | None:
    """Whether the orbit stays on the line of its generating amplitudes at every order computed.

    The generating solution of a line has cosine amplitudes only (a direction ``d`` in the
    coordinates); the orbit is straight when every term of every order and harmonic is parallel
    to ``d`` (exact zero tests of the 2 x 2 minors). None when the generating solution is not a
    line (sine amplitudes, non-resonant coordinates) or the solution failed.
    """
    if not solution.success:
        return None
    generating = solution.generating
    if any(m is None for m in generating.harmonics):
        return None
    if any(not is_zero(b) for b in generating.sin_amplitudes):
        return None
    direction = [sp.sympify(a) for a in generating.cos_amplitudes]
    rows = solution.terms
    top = max(len(row) for row in rows)
    for k in range(top):
        terms = [row[k] if k < len(row) else None for row in rows]
        harmonics = {j for t in terms if t is not None for j in t.terms}
        for j in harmonics:
            for part in (0, 1):
                values = [t.coefficient(j)[part] if t is not None else 0 for t in terms]
                for i in range(len(values)):
                    for m in range(i + 1, len(values)):
                        if not is_zero(
                            sp.expand(direction[m] * values[i] - direction[i] * values[m])
                        ):
                            return False
    return True
