"""Whether a steady state's labels can be trusted: the series' checks of one response point.

A point of an order-N response carries an amplitude and a stability read off a truncated series.
Three checks say when the series cannot vouch for them, and the point is then marked wherever it
is shown — in the table, the CSV, the JSON (``mark``) and the plot (hollow grey, with a legend
entry):

* the series is outside its domain there (``series_ok`` false: its terms do not decrease, or no
  lower-order root leads to it);
* it is beyond its validity: its own estimate of its error is more than
  :data:`~perturb._defaults.VALIDITY_ESTIMATE_LIMIT` of the amplitude;
* its stability is within the series' error of 1: the largest Floquet multiplier's distance from
  the unit circle is not larger than the estimated relative error of the orbit, so the order-N
  multipliers cannot tell stable from unstable (the middle branch of a forced Helmholtz–Duffing
  near its upper fold, "stable" at max|λ| 0.975 with a relative error estimate of 0.5, while the
  true orbit has |λ| 1.097). To first order the multipliers move with the orbit: a relative
  error r of the orbit moves them by O(r).

The marks are read from the point alone (its amplitudes, error estimate and multipliers): the
same point is marked the same way by every output.
"""

from __future__ import annotations

import enum
import math

from perturb._defaults import VALIDITY_ESTIMATE_LIMIT

__all__ = ["PointMark", "point_mark", "relative_error"]


class PointMark(enum.Enum):
    """Why a response point's labels are not vouched for (the value is the sentence)."""

    NONE = ""
    OUTSIDE = "outside the series' domain"
    BEYOND = "beyond the series' validity"
    UNCERTAIN = "stability within the series' error of 1"

    @property
    def code(self) -> str:
        """The mark in one word (``""``, ``outside``, ``beyond``, ``uncertain``)."""
        return "" if self is PointMark.NONE else self.name.lower()


def relative_error(point) -> float:
    """The series' own estimate of the point's error, relative to its amplitude: the largest
    error of a coordinate over the largest amplitude of the point (the solution's scale, so a
    coordinate near zero cannot make a right answer look wrong); NaN when there is no estimate."""
    scale = max((size for size in point.peak.values() if math.isfinite(size)), default=0.0)
    errors = [e for c, e in point.error.items() if c in point.peak and math.isfinite(e)]
    if not errors or not scale > 0:
        return math.nan
    return max(errors) / scale


def point_mark(point) -> PointMark:
    """The first check ``point`` fails (:class:`PointMark`), or ``PointMark.NONE``."""
    if not point.series_ok:
        return PointMark.OUTSIDE
    error = relative_error(point)
    if error > VALIDITY_ESTIMATE_LIMIT:
        return PointMark.BEYOND
    largest = max((abs(z) for z in point.multipliers), default=math.nan)
    if math.isfinite(error) and math.isfinite(largest) and abs(largest - 1) <= error:
        return PointMark.UNCERTAIN
    return PointMark.NONE
