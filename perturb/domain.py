"""Whether a series solution is inside its domain at the given parameter values: :func:`series_domain`.

A truncated series :math:`x = \\sum_k \\varepsilon^k x_k`, :math:`\\Omega = \\sum_k \\varepsilon^k
\\Omega_k` says nothing when its frequency is not a positive number or when its terms do not
decrease at the given ε (van der Pol at ε = 5 gives a negative period at order 2; the disk's
defaults have ε = 232).  This is a cheap necessary condition, checked before any state is printed;
whether the series describes the motion is measured by :func:`perturb.validation.validate`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import (
    NEGLIGIBLE_TERM,
    SERIES_NUMBERS_CACHE_ENTRIES,
    VALIDITY_ESTIMATE_LIMIT,
)
from perturb.cache import cached
from perturb.solution import PeriodicSolution, SolutionFailed
from perturb.system import Regime

__all__ = ["DomainCheck", "next_term", "next_terms", "series_domain"]


@frozen
class DomainCheck:
    """Outcome of :func:`series_domain`.

    Attributes
    ----------
    ok : bool
        True when the frequency is positive and finite and the terms decrease.
    reasons : tuple of str
        Why the series is outside its domain (empty when ``ok``).
    frequency : float
        Ω at the given values.
    term_sizes : tuple of float
        Size of each order's contribution to the coordinates,
        :math:`|\\varepsilon|^k \\max_i|x_{i,k}|`.
    coordinate_term_sizes : dict
        ``{coordinate: (|eps|^k max|x_ik|, ...)}``: each coordinate's own terms, which must
        decrease (a coordinate that starts at a power of ε is compared with itself, not with the
        others).
    frequency_terms : tuple of float
        :math:`|\\varepsilon^k \\Omega_k|`.
    estimate : float
        The first neglected term, relative to the leading one, extrapolated from the last two
        kept terms (:func:`next_term`) of the frequency and of each coordinate: the largest. An
        estimate of the series' relative error, not a measurement (``perturb validate`` measures).
    """

    ok: bool
    reasons: tuple = field(converter=tuple)
    frequency: float = field(converter=float)
    term_sizes: tuple = field(converter=tuple)
    frequency_terms: tuple = field(converter=tuple)
    coordinate_term_sizes: dict = field(factory=dict)
    estimate: float = 0.0

    @property
    def beyond_validity(self) -> bool:
        """Whether the estimated relative error passes :data:`VALIDITY_ESTIMATE_LIMIT`."""
        return not self.estimate <= VALIDITY_ESTIMATE_LIMIT

    def validity_note(self) -> str:
        """One sentence when :attr:`beyond_validity` (else ``""``)."""
        if not self.beyond_validity:
            return ""
        return (
            f"beyond the series' validity: its next term is estimated at {self.estimate:.2g} of "
            f"the leading one (more than {VALIDITY_ESTIMATE_LIMIT:g}); check it with "
            "`perturb validate`"
        )


def next_term(sizes) -> float:
    """The first neglected term of a series, relative to its leading term, extrapolated
    geometrically from its last two non-zero terms: :math:`s_{n}^2 / s_{n-1} / s_0`.

    Zero when fewer than two terms are non-zero (nothing to extrapolate from); for a driven
    system's frequency :math:`(\\Omega_0, \\varepsilon\\sigma)`, exact in itself, it is
    :math:`(\\varepsilon\\sigma/\\Omega_0)^2`, the size of the detuning effects the
    expansion about the resonance leaves out.

    Examples
    --------
    >>> next_term([1.0, 0.1, 0.01])
    0.001
    >>> next_term([1.0, 0.0])
    0.0
    """
    kept = [float(s) for s in sizes if s != 0]
    if len(kept) < 2:
        return 0.0
    return kept[-1] ** 2 / kept[-2] / kept[0]


def next_terms(terms) -> np.ndarray:
    """:func:`next_term` of many series at once: ``terms`` has one row per order, one column per
    series (a sweep's points); returns one estimate per column.

    Examples
    --------
    >>> next_terms(np.array([[1.0, 2.0], [0.1, 0.0], [0.01, 0.5]])).tolist()
    [0.001, 0.0625]
    """
    terms = np.asarray(terms, dtype=float)
    if terms.ndim != 2 or terms.shape[0] < 2:
        return np.zeros(terms.shape[-1] if terms.ndim else 1)
    count, columns = terms.shape
    index = np.arange(columns)
    nonzero = terms != 0
    first = np.argmax(nonzero, axis=0)
    last = count - 1 - np.argmax(nonzero[::-1], axis=0)
    before = nonzero.copy()
    before[last, index] = False
    second = count - 1 - np.argmax(before[::-1], axis=0)
    usable = before.any(axis=0)
    with np.errstate(all="ignore"):
        estimate = terms[last, index] ** 2 / terms[second, index] / terms[first, index]
    return np.where(usable, estimate, 0.0)


def _solution_numbers(solution: PeriodicSolution, subs: dict) -> tuple[list, list]:
    """The frequency's terms and, per coordinate and order, its harmonic coefficients, as
    numbers at ``subs``; kept in the disk cache (kind ``series-numbers``) under the solution's
    :attr:`~perturb.solution.PeriodicSolution.numeric_digest` and the values, so that a warm run
    evaluates no sympy expression."""

    def compute() -> tuple[list, list]:
        rows = [
            [
                _numbers([c for j in range(t.max_harmonic + 1) for c in t.coefficient(j)], subs)
                for t in row
            ]
            for row in solution.terms
        ]
        return _numbers(solution.frequency, subs), rows

    key = solution.numeric_digest
    if key is None:
        return compute()
    return cached(
        "series-numbers",
        lambda: (key, tuple((p.name, type(v).__name__, repr(v)) for p, v in subs.items())),
        compute,
        keep=SERIES_NUMBERS_CACHE_ENTRIES,
    )


def _numbers(exprs, subs) -> list[float]:
    out = []
    for expr in exprs:
        try:
            out.append(float(sp.sympify(expr).xreplace(subs)))
        except (TypeError, ValueError):
            out.append(math.nan)
    return out


def _not_decreasing(sizes, what: str, eps: float, floor: float = 0.0) -> list[str]:
    """Consecutive non-zero terms that do not decrease (zero terms are skipped, not compared),
    unless the later one is at most ``floor``: below the series' own truncation error on the
    solution's scale, where no term can make an answer wrong."""
    reasons = []
    kept = [(k, s) for k, s in enumerate(sizes) if s != 0]
    for (k0, s0), (k1, s1) in zip(kept, kept[1:], strict=False):
        if not (s1 < s0) and not s1 <= floor:
            reasons.append(
                f"the order-{k1} term of the {what} ({s1:.3g}) is not smaller than the order-{k0} "
                f"term ({s0:.3g}) at eps = {eps:.6g}"
            )
    return reasons


def _negligible(sizes) -> float:
    """The size below which a coordinate's term does not count in the check that the terms
    decrease: :data:`~perturb._defaults.NEGLIGIBLE_TERM` of the largest term of the solution
    (its scale) — the rule the response's points are checked by
    (:func:`perturb.steady.measures.series_estimate`). A coordinate that stays near zero (a mode
    the drive barely excites: terms of 5e-8 beside an amplitude of 0.6) is then not "outside its
    domain" because its tiny terms do not decrease."""
    finite = [float(s) for s in sizes if math.isfinite(s)]
    return NEGLIGIBLE_TERM * max(finite, default=0.0)


def series_domain(
    solution: PeriodicSolution, parameter_value: float, values: Mapping[str, float] | None = None
) -> DomainCheck:
    """Check that ``solution``'s series is inside its domain at these values.

    Parameters
    ----------
    solution : PeriodicSolution
    parameter_value : float
        ε (or μ in the large-parameter regime), as for :meth:`PeriodicSolution.evaluate`.
    values : mapping, optional
        Values of the system's free parameters, by name.

    Returns
    -------
    DomainCheck
    """
    values = dict(values or {})
    system = solution.system
    eps = 1.0 / parameter_value if system.regime is Regime.LARGE else float(parameter_value)
    subs = {p: values[p.name] for p in system.parameters if p.name in values}
    frequency, rows = _solution_numbers(solution, subs)
    freq_terms = [abs(eps**k * f) for k, f in enumerate(frequency)]
    per_coordinate = {}
    for name, row in zip(solution.coordinates, rows, strict=True):
        own = []
        for k, numbers in enumerate(row):
            own.append(abs(eps) ** k * max([0.0, *(abs(c) for c in numbers)]))
        per_coordinate[name] = tuple(own)
    depth = max((len(own) for own in per_coordinate.values()), default=0)
    sizes = [
        max([0.0, *(own[k] for own in per_coordinate.values() if k < len(own))])
        for k in range(depth)
    ]
    reasons = []
    with np.errstate(all="ignore"):
        try:
            omega = float(np.asarray(solution.coefficients(parameter_value, values)[0]).ravel()[0])
        except SolutionFailed as exc:  # coefficients not finite here: no series at all
            omega = math.nan
            reasons.append(" ".join(str(exc).split()))
    if not (math.isfinite(omega) and omega > 0):
        period = 2 * math.pi / omega if omega else math.inf
        reasons.append(
            f"the frequency Omega = {omega:.6g} at eps = {eps:.6g} is not a positive number (the "
            f"period would be {period:.6g})"
        )
    if not all(math.isfinite(s) for s in sizes + freq_terms):
        reasons.append(f"some terms of the series are not finite at eps = {eps:.6g}")
    else:
        reasons += _not_decreasing(freq_terms, "frequency", eps)
        floor = _negligible(sizes)
        for name, own in per_coordinate.items():
            reasons += _not_decreasing(own, f"coordinate {name}", eps, floor)
    estimate = max(
        [next_term(freq_terms), *(next_term(own) for own in per_coordinate.values())],
        default=0.0,
    )
    if not math.isfinite(estimate):
        estimate = math.inf
    return DomainCheck(not reasons, reasons, omega, sizes, freq_terms, per_coordinate, estimate)
