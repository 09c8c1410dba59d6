"""One steady-state response at one point: the one record of the branch solver, the continued
curve, the response's table and its JSON (``BranchPoint`` is the same type, by its older name)."""

from __future__ import annotations

import math

from attrs import field, frozen

from perturb._defaults import TRIVIAL_AMPLITUDE

__all__ = ["BranchPoint", "ResponsePoint", "by_measure"]


@frozen
class ResponsePoint:
    """One steady-state response at one point of the parameters.

    Attributes
    ----------
    amplitudes : dict
        ``{"a_x": ..., "b_x": ...}``: the cosine and sine amplitudes (strained time) at order N.
    norms : dict
        ``{coordinate: sqrt(a**2 + b**2)}`` of each resonant coordinate's first harmonic: the
        initial-value norm.
    stable : bool or None
        From the Floquet multipliers along the order-N orbit (None: the largest on the unit
        circle, a fold or an undamped system).
    eigenvalues : tuple of complex
        The Floquet exponents per unit of ε, log μ / ε (the slow flow's eigenvalues they stand
        for).
    multipliers : tuple of complex
        The Floquet multipliers they predict (:mod:`perturb.steady.floquet`).
    first_order : dict
        Empty: no point keeps first-order amplitudes (kept for the JSON contract).
    note : str
        Empty, or what to know: the series outside its domain there, a continuation in the
        window that failed.
    peak, first_harmonic : dict
        Of each resonant coordinate, from the whole order-N series: max ``|x|`` over a period, and
        the amplitude of the harmonic it resonates at (:mod:`perturb.steady.measures`).
    error : dict
        The series' own estimate of its state's error, per coordinate (NaN: none).
    series_ok : bool
        The series' terms decrease there (``note`` says which do not).
    liouville : float
        exp(∮ div f dt) along the orbit: the product of ``multipliers``.
    value : float
        The swept parameter's value (NaN: a point solved at fixed parameters).
    branch : int
        The continued curve the point lies on (-1: not from a continuation).
    """

    amplitudes: dict
    norms: dict
    stable: bool | None
    eigenvalues: tuple = field(converter=tuple)
    multipliers: tuple = field(converter=tuple)
    first_order: dict = field(factory=dict)
    note: str = ""
    peak: dict = field(factory=dict)
    first_harmonic: dict = field(factory=dict)
    error: dict = field(factory=dict)
    series_ok: bool = True
    liouville: float = field(default=math.nan, converter=float)
    value: float = field(default=math.nan, converter=float)
    branch: int = -1

    @property
    def trivial(self) -> bool:
        """Every resonant coordinate at rest (x = 0)."""
        return all(n <= TRIVIAL_AMPLITUDE for n in self.norms.values())

    def norm(self, coordinate: str | None = None) -> float:
        """The response amplitude of ``coordinate`` (default: the first resonant one)."""
        if coordinate is None:
            return next(iter(self.norms.values()))
        return self.norms[coordinate]

    def amplitude(self, coordinate: str | None = None, measure: str = "initial") -> float:
        """``coordinate``'s amplitude by ``measure`` (``peak``, ``first-harmonic`` or
        ``initial``; :data:`perturb.steady.measures.MEASURES`)."""
        return by_measure(self, coordinate, measure)


def by_measure(point, coordinate: str | None, measure: str) -> float:
    """``coordinate``'s amplitude of anything with ``peak``, ``first_harmonic`` and ``norms``
    (a point, a fold, a special point) by ``measure``; the initial-value norm where the measure's
    table is empty."""
    table = {"peak": point.peak, "first-harmonic": point.first_harmonic, "initial": point.norms}
    values = table[measure] or point.norms
    return next(iter(values.values())) if coordinate is None else values[coordinate]


#: The same type by the name the branch solver first gave it.
BranchPoint = ResponsePoint
