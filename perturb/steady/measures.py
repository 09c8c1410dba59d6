"""How large a response is, and how far its series can be trusted, from the whole series.

Three amplitude measures of a coordinate x(s) = Σ_j c_j cos js + s_j sin js (all orders summed):

* ``peak``: max ``|x|`` over a period, the engineer's peak (found on ``PEAK_SAMPLES`` samples and
  polished by Newton's method on the trigonometric polynomial itself: exact to rounding);
* ``first-harmonic``: √(c_m² + s_m²) of the harmonic m the coordinate resonates at;
* ``initial``: |(x(0), ẋ(0)/(mν))|, the norm of the initial values — the generating amplitudes
  √(a² + b²), since every correction starts at zero (the measure drawn before issue 29).

The size of each order's term, ε^k Σ_j √(c_kj² + s_kj²) (a bound on its largest value), must
decrease from the first order on (:func:`series_estimate`); the error estimate of a point is the
last correction (:mod:`perturb.steady.evaluate`).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import NEGLIGIBLE_TERM, PEAK_NEWTON, PEAK_SAMPLES
from perturb.steady.compiled import _compile, _key, variables
from perturb.system import EPS

__all__ = ["MEASURES", "SeriesTerms", "compiled_terms", "peak_abs", "series_estimate"]

#: The amplitude measures, by the name the CLI and the JSON use, with what they are.
MEASURES = {
    "peak": "max |x| over a period",
    "first-harmonic": "first-harmonic amplitude",
    "initial": "initial-value norm |(x(0), xdot(0)/(m nu))|",
}


def peak_abs(cos: np.ndarray, sin: np.ndarray) -> np.ndarray:
    """max_s |Σ_j cos_j cos js + sin_j sin js| for rows of coefficients (shape (..., H + 1))."""
    shape, h = cos.shape[:-1], cos.shape[-1]
    c = (cos - 1j * sin).reshape(-1, h)
    j = np.arange(h)
    s = 2 * np.pi * np.arange(PEAK_SAMPLES) / PEAK_SAMPLES
    samples = (c @ np.exp(1j * np.outer(j, s))).real
    best = np.empty(c.shape[0])
    for sign in (1.0, -1.0):
        at = s[np.argmax(sign * samples, axis=1)]
        for _ in range(PEAK_NEWTON):
            z = np.exp(1j * np.outer(at, j))
            slope = (c * z * 1j * j).real.sum(axis=1)
            curve = -(c * z * j * j).real.sum(axis=1)
            with np.errstate(all="ignore"):
                step = np.where(sign * curve < 0, slope / curve, 0.0)
            at = at - np.where(np.isfinite(step) & (np.abs(step) < 0.1), step, 0.0)
        value = sign * (c * np.exp(1j * np.outer(at, j))).real.sum(axis=1)
        extreme = np.maximum(value, np.max(sign * samples, axis=1))  # never below the samples
        best = extreme if sign > 0 else np.maximum(best, extreme)
    return np.maximum(best, 0.0).reshape(shape)  # |x| >= 0 (never a signed zero)


@frozen
class SeriesTerms:
    """Each order's term of each coordinate, compiled: ``sizes(x)`` gives ε^k Σ_j |harmonic j|
    of order k, shape (P, n, N + 1)."""

    coordinates: tuple = field(converter=tuple)
    orders: int
    harmonics: int
    rows: object = field(eq=False)

    def coefficients(self, x) -> np.ndarray:
        """Each order's cosine and sine coefficients: shape (P, n, N + 1, 2, H + 1)."""
        values = self.rows.values(np.atleast_2d(x))  # (P, n (N+1) 2 (H+1))
        n, h = len(self.coordinates), self.harmonics + 1
        return values.reshape(-1, n, self.orders + 1, 2, h)

    def sizes(self, x) -> np.ndarray:
        terms = self.coefficients(x)
        return np.sum(np.hypot(terms[:, :, :, 0, :], terms[:, :, :, 1, :]), axis=-1)


def compiled_terms(equations) -> SeriesTerms:
    """The order-by-order terms of ``equations.solution`` (ε^k included) as :class:`SeriesTerms`."""
    solution = equations.solution
    h = max((t.max_harmonic for row in solution.terms for t in row), default=0)
    depth = max(len(row) for row in solution.terms)

    def rows():
        out = []
        for row in solution.terms:
            for k in range(depth):
                for which in (0, 1):
                    for j in range(h + 1):
                        term = row[k].coefficient(j)[which] if k < len(row) else sp.S.Zero
                        out.append(EPS**k * term)
        return out

    compiled = _compile(
        lambda: _key(equations, "terms", equations.order), rows, variables(equations), False
    )
    names = tuple(c.name for c in solution.system.coordinates)
    return SeriesTerms(names, depth - 1, h, compiled)


def series_estimate(sizes: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """From term sizes (n, N + 1) of one point: the geometric tail of each coordinate's last two
    terms (NaN at order 0 or when they do not decrease) and the reasons the series is outside
    its domain, empty when inside: terms of order >= 1 that do not decrease (the order-0 term is
    the generating solution, whose size the amplitudes set: a small resonant response beside
    larger forced harmonics, as the superharmonic's, is not a diverging series). A term counts
    in that check above :data:`~perturb._defaults.NEGLIGIBLE_TERM` of the largest term of the
    whole solution, not of its own coordinate: a coordinate that stays near zero (a mode the
    drive barely excites, of size 5e-8 beside 0.6) cannot put a right answer outside."""
    n, depth = sizes.shape
    error = np.full(n, math.nan)
    reasons = []
    finite = sizes[np.isfinite(sizes)]
    top = float(finite.max()) if finite.size else 0.0
    for i in range(n):
        kept = [(k, float(v)) for k, v in enumerate(sizes[i]) if v != 0]
        for (k0, s0), (k1, s1) in zip(kept, kept[1:], strict=False):
            if not math.isfinite(s1):
                reasons.append(f"the order-{k1} term is not finite")
            elif k0 >= 1 and s1 >= s0 and s1 > NEGLIGIBLE_TERM * top:
                reasons.append(f"order-{k1} term {s1:.3g} >= order-{k0} term {s0:.3g}")
        if len(kept) >= 2 and kept[-1][1] < kept[-2][1]:
            ratio = kept[-1][1] / kept[-2][1]
            error[i] = kept[-1][1] * ratio / (1 - ratio)
        elif len(kept) == 1 and depth > 1:
            error[i] = 0.0  # every correction vanishes: the generating solution is exact
    return error, reasons
