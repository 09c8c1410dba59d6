"""The analytic quantities of a sweep's points: period, frequency, amplitudes, state at times.

Two routes, the same numbers to rounding:

* **vectorised** — for models whose state and period are the solution's own at their parameter
  values (:attr:`perturb.case.Case.evaluates_directly`): the points sharing one
  solution are evaluated in one call of :meth:`perturb.PeriodicSolution.coefficients` and
  :meth:`~perturb.PeriodicSolution.evaluate` over arrays of parameter values;
* **per point** — :meth:`Model.period` and :meth:`Model.state` (the disk's physical state goes
  through its exact inverse map, which is compiled per parameter set).

The domain check of ``perturb solve`` (:func:`perturb.domain.series_domain`) is screened for all
the points of a solution at once by :class:`DomainScreen`; a point it cannot clear beyond
rounding is checked by ``series_domain`` itself, so a status never differs from that function's.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from perturb._defaults import (
    NOT_PERIODIC_STEP,
    SWEEP_AMPLITUDE_SAMPLES,
    SWEEP_DOMAIN_MARGIN,
    SWEEP_NEWTON_STEPS,
    SWEEP_SAMPLE_BLOCK,
)
from perturb._lambdify import numpy_lambdify
from perturb.domain import DomainCheck, next_terms, series_domain
from perturb.solution import PeriodicSolution, SolutionFailed
from perturb.system import Regime
from perturb.validation.model import parameter_value_of

__all__ = [
    "DomainScreen",
    "Evaluated",
    "SolutionFailed",
    "evaluate_group",
    "evaluate_one",
    "group_arrays",
    "half_range",
    "trig_half_range",
]

#: What the evaluation of a point gives (arrays are NaN where it could not be computed).
Evaluated = dict


def half_range(samples: np.ndarray) -> np.ndarray:
    """Half the range of periodic samples along the last axis (one period, without the end
    point), each extreme refined by two Newton steps on the quartic through it and its four
    neighbours (an error ~(2 pi h / K)^6 of the amplitude for the h-th harmonic, K samples);
    NaN for a component that does not return to its start (:data:`NOT_PERIODIC_STEP`)."""
    samples = np.asarray(samples, dtype=float)
    n = samples.shape[-1]
    out = []
    for sign in (1.0, -1.0):
        y = sign * samples
        k = np.argmax(y, axis=-1)[..., None]
        ym2, ym1, y0, yp1, yp2 = (
            np.take_along_axis(y, (k + d) % n, axis=-1)[..., 0] for d in (-2, -1, 0, 1, 2)
        )
        d1 = (ym2 - 8 * ym1 + 8 * yp1 - yp2) / 12
        d2 = (-ym2 + 16 * ym1 - 30 * y0 + 16 * yp1 - yp2) / 12
        d3 = (-ym2 + 2 * ym1 - 2 * yp1 + yp2) / 2
        d4 = ym2 - 4 * ym1 + 6 * y0 - 4 * yp1 + yp2
        u = np.zeros_like(y0)
        with np.errstate(all="ignore"):
            for _ in range(2):
                slope = d1 + d2 * u + d3 * u**2 / 2 + d4 * u**3 / 6
                curve = d2 + d3 * u + d4 * u**2 / 2
                u = np.where(curve < 0, u - slope / curve, u)
            u = np.where(np.isfinite(u) & (np.abs(u) <= 1), u, 0.0)
            peak = y0 + d1 * u + d2 * u**2 / 2 + d3 * u**3 / 6 + d4 * u**4 / 24
        out.append(sign * np.where(np.isfinite(peak) & (peak >= y0), peak, y0))
    # a component that does not come back over the period (a driven system's phase) has no
    # amplitude: its step from the last sample to the first dwarfs every step in between
    steps = np.abs(np.diff(samples, axis=-1))
    wrap = np.abs(samples[..., 0] - samples[..., -1])
    closed = wrap <= NOT_PERIODIC_STEP * np.max(steps, axis=-1, initial=0.0)
    return np.where(closed, (out[0] - out[1]) / 2, np.nan)


def trig_half_range(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Half the range over one period of :math:`x(s) = \\sum_j a_j \\cos js + b_j \\sin js`.

    ``a``, ``b``: shape (..., H + 1). The extremes are found on :data:`SWEEP_AMPLITUDE_SAMPLES`
    samples and polished by Newton's method on the polynomial itself: exact to rounding.
    """
    shape, h = a.shape[:-1], a.shape[-1]
    j = np.arange(h)
    s = 2 * np.pi * np.arange(SWEEP_AMPLITUDE_SAMPLES) / SWEEP_AMPLITUDE_SAMPLES
    flat_a, flat_b = a.reshape(-1, h), b.reshape(-1, h)
    coefficients = np.concatenate([flat_a, flat_b], axis=1)
    table = np.concatenate([np.cos(np.outer(j, s)), np.sin(np.outer(j, s))], axis=0)
    c = flat_a - 1j * flat_b
    out = np.empty(coefficients.shape[0])
    for lo in range(0, out.size, SWEEP_SAMPLE_BLOCK):  # every temporary of a block stays small
        rows = slice(lo, lo + SWEEP_SAMPLE_BLOCK)
        out[rows] = _block_half_range(coefficients[rows] @ table, c[rows], s)
    return out.reshape(shape)


def _block_half_range(samples: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """:func:`trig_half_range` of a block of rows: ``samples`` of each row on ``s``, ``c`` its
    complex coefficients a_j - i b_j."""
    h = c.shape[1]
    rows_in = np.arange(samples.shape[0])
    # x = Re sum_j c_j z^j, dx/ds = Re sum_j i j c_j z^j, d2x/ds2 = -Re sum_j j^2 c_j z^j
    found = []
    for sign, pick in ((1.0, np.argmax), (-1.0, np.argmin)):
        where = pick(samples, axis=-1)
        extreme = sign * samples[rows_in, where]
        at = s[where]
        for _ in range(SWEEP_NEWTON_STEPS):
            z = np.exp(1j * at)
            d1 = d2 = 0j
            for k in range(h - 1, 0, -1):  # Horner in z of j c_j and j^2 c_j (j >= 1)
                d1 = d1 * z + k * c[:, k]
                d2 = d2 * z + k * k * c[:, k]
            slope, curve = (1j * d1 * z).real, -(d2 * z).real
            with np.errstate(all="ignore"):
                step = np.where(sign * curve < 0, slope / curve, 0.0)
            at = at - np.where(np.isfinite(step), step, 0.0)
        z = np.exp(1j * at)
        value = np.zeros(at.shape, dtype=complex)
        for k in range(h - 1, -1, -1):
            value = value * z + c[:, k]
        found.append(sign * np.maximum(sign * value.real, extreme))  # never below the samples
    return (found[0] - found[1]) / 2


def evaluate_group(
    solution: PeriodicSolution,
    parameter_values: np.ndarray,
    values: Mapping[str, np.ndarray],
    times: np.ndarray,
) -> Evaluated:
    """Period, frequency, amplitudes and state of many points of one solution, vectorised.

    Parameters
    ----------
    solution : PeriodicSolution
    parameter_values : ndarray, shape (P,)
        Each point's value of the solution's own parameter (ε, or μ).
    values : mapping name -> ndarray of shape (P,)
        Each point's values of the solution's parameters.
    times : ndarray, shape (T,)

    Returns
    -------
    dict
        ``omega``, ``period``, ``frequency`` (P,), ``amplitude`` (P, 2n), ``state`` (P, T, 2n).

    Raises
    ------
    perturb.solution.SolutionFailed
        Some point's coefficients are not finite (the caller then goes point by point).
    """
    omega, cos, sin = solution.coefficients(parameter_values, values)
    period = 2 * np.pi / omega
    j = np.arange(cos.shape[1])[None, :, None]
    # x(s) = sum_j a_j cos(js) + b_j sin(js); dx/dt = Omega sum_j j (b_j cos(js) - a_j sin(js))
    a = np.concatenate([cos, sin * j * omega], axis=0)  # (2n, H+1, P): the state's cos and sin
    b = np.concatenate([sin, -cos * j * omega], axis=0)
    amplitude = trig_half_range(np.moveaxis(a, -1, 0), np.moveaxis(b, -1, 0))
    state = solution.evaluate(times, parameter_values, values)  # (2n, P, T)
    return {
        "omega": omega,
        "period": period,
        "frequency": 2 * np.pi / period,
        "amplitude": amplitude,
        "state": np.moveaxis(state, 0, -1),
    }


def evaluate_one(model, solution: PeriodicSolution, times: np.ndarray) -> Evaluated:
    """Period, frequency, amplitudes and state of one point through the model's own maps."""
    names = tuple(model.state_names())
    period = float(model.period(solution))
    state = model.state(solution, times)
    out = {
        "period": period,
        "frequency": 2 * math.pi / period,
        "state": np.array([np.asarray(state[n], dtype=float) for n in names]).T,
    }
    if math.isfinite(period) and period > 0:
        t = period * np.arange(SWEEP_AMPLITUDE_SAMPLES) / SWEEP_AMPLITUDE_SAMPLES
        samples = model.state(solution, t)
        out["amplitude"] = half_range(np.array([np.asarray(samples[n], float) for n in names]))
    else:
        out["amplitude"] = np.full(len(names), np.nan)
    return out


class DomainScreen:
    """:func:`perturb.domain.series_domain` for many points at once, where it is clear.

    The sizes of the series' terms — each coordinate's own, order by order, and the frequency's —
    are evaluated in float64 for all points (one compiled function of the solution's
    parameters). A point is cleared when every test ``series_domain`` makes passes by more than
    :data:`SWEEP_DOMAIN_MARGIN` (relative) and no term that may vanish is near zero; every other
    point gets ``series_domain`` itself. Either way the outcome is that function's.
    """

    def __init__(self, solution: PeriodicSolution):
        self.solution = solution
        self.parameters = list(solution.system.parameters)
        frequency = [sp.sympify(f) for f in solution.frequency]
        coordinates = []
        for row in solution.terms:
            orders = []
            for term in row:
                orders.append(
                    [
                        sp.sympify(c)
                        for j in range(term.max_harmonic + 1)
                        for c in term.coefficient(j)
                    ]
                )
            coordinates.append(orders)
        #: terms whose every coefficient is the number 0: their size is exactly zero either way
        self.zero_frequency = [f == 0 for f in frequency]
        self.zero_terms = [
            [all(c == 0 for c in coeffs) for coeffs in orders] for orders in coordinates
        ]
        self.function = numpy_lambdify(self.parameters, [frequency, coordinates], cse=True)

    def _sizes(self, eps: np.ndarray, args: Sequence[np.ndarray]):
        shape = eps.shape
        with np.errstate(all="ignore"):
            frequency, coordinates = self.function(*args)
            freq = np.array(
                [np.broadcast_to(np.abs(np.asarray(f, float)), shape) for f in frequency]
            )
            freq = freq * np.abs(eps) ** np.arange(len(frequency))[:, None]
            own = []
            for orders in coordinates:
                sizes = []
                for k, coeffs in enumerate(orders):
                    top = np.zeros(shape)
                    for c in coeffs:
                        top = np.maximum(top, np.broadcast_to(np.abs(np.asarray(c, float)), shape))
                    sizes.append(np.abs(eps) ** k * top)
                own.append(np.array(sizes))
        return freq, own

    @staticmethod
    def _clear(terms: np.ndarray, structural_zero: list[bool]) -> np.ndarray:
        """Points whose terms (rows: orders) clearly decrease, none near zero unless zero by form
        (``series_domain`` skips the zero terms; a float zero that is not zero by form, or a term
        near its neighbour, is left to it)."""
        margin = SWEEP_DOMAIN_MARGIN
        ok = np.all(np.isfinite(terms), axis=0)
        kept = [k for k in range(terms.shape[0]) if not structural_zero[k]]
        for k in kept:
            ok &= terms[k] > 0
        for k0, k1 in zip(kept, kept[1:], strict=False):
            ok &= terms[k1] < terms[k0] * (1 - margin)
        return ok

    def screen(self, parameter_values, values: Mapping[str, np.ndarray], omega):
        """``(clear, frequency sizes, coordinate sizes)``: which points are clearly inside the
        domain (boolean, shape (P,)), and the sizes of the series' terms the test read."""
        pv = np.atleast_1d(np.asarray(parameter_values, dtype=float))
        large = self.solution.system.regime is Regime.LARGE
        with np.errstate(all="ignore"):
            eps = 1.0 / pv if large else pv
        args = [np.asarray(values.get(p.name, np.nan), dtype=float) for p in self.parameters]
        args = [np.broadcast_to(a, pv.shape) for a in args]
        freq, own = self._sizes(eps, args)
        omega = np.broadcast_to(np.asarray(omega, dtype=float), pv.shape)
        scale = np.max(np.where(np.isfinite(freq), freq, 0.0), axis=0)
        clear = np.isfinite(omega) & (omega > SWEEP_DOMAIN_MARGIN * scale)
        clear &= self._clear(freq, self.zero_frequency)
        for sizes, zeros in zip(own, self.zero_terms, strict=True):
            clear &= self._clear(sizes, zeros)
        return clear, freq, own

    @staticmethod
    def estimates(freq: np.ndarray, own) -> np.ndarray:
        """Each point's :attr:`perturb.domain.DomainCheck.estimate` from the screen's sizes."""
        rows = [next_terms(freq), *(next_terms(sizes) for sizes in own)]
        with np.errstate(all="ignore"):
            return np.max(np.vstack(rows), axis=0) if rows else np.zeros(freq.shape[-1])

    def check(self, parameter_values, values: Mapping[str, np.ndarray], omega) -> list:
        """For each point, its :class:`perturb.domain.DomainCheck`: built from the screen's
        numbers when the point is clearly inside the domain (``ok``, no reasons), else
        ``series_domain``'s own.

        ``omega`` are the points' frequencies (from the evaluation), ``values`` the solution's
        parameters by name.
        """
        pv = np.atleast_1d(np.asarray(parameter_values, dtype=float))
        clear, freq, own = self.screen(pv, values, omega)
        omega = np.broadcast_to(np.asarray(omega, dtype=float), pv.shape)
        estimates = self.estimates(freq, own)
        names = self.solution.coordinates
        out: list = []
        for i in range(pv.size):
            if clear[i]:
                per_coordinate = {
                    n: tuple(sizes[:, i]) for n, sizes in zip(names, own, strict=True)
                }
                depth = max((len(t) for t in per_coordinate.values()), default=0)
                overall = [
                    max([0.0, *(t[k] for t in per_coordinate.values() if k < len(t))])
                    for k in range(depth)
                ]
                out.append(
                    DomainCheck(
                        True, (), omega[i], overall, freq[:, i], per_coordinate, estimates[i]
                    )
                )
                continue
            point = {name: float(np.asarray(a).ravel()[i]) for name, a in values.items()}
            out.append(series_domain(self.solution, float(pv[i]), point))
        return out


def group_arrays(points: Sequence) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The parameter values of ``points`` (models) as arrays: (parameter_value, symbol_values)."""
    pv = np.array([float(parameter_value_of(m)) for m in points])
    rows = [m.symbol_values() for m in points]
    names = dict.fromkeys(name for row in rows for name in row)
    columns = {
        name: np.array([row.get(name, np.nan) for row in rows], dtype=float) for name in names
    }
    return pv, columns
