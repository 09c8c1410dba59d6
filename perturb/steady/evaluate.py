"""Everything about order-N response points (u, λ), in one batch: how large (three measures), how
stable (Floquet along the order-N series), and how far the series can be trusted there.

**The series' own estimate.** An order-N point is carried to the order-(N−1) equations at the
same λ — Newton from it, else the homotopy in the truncation from τ = 1 to 0 — and the estimate of
its error is the largest distance over a period between the order-N state and the order-(N−1)
state at that root: the last correction, which bounds the error of order N wherever the series
converges (the next correction is smaller). A point with no order-(N−1) root reached from it (the
homotopy turns back) is a root of the order-N equations that the series one order lower does not
have: the series does not vouch for it (in the O(ε^N) band beside a fold it may be a true orbit or
none; only a shooting from it tells, and the label never claims either); a
point whose terms of order ≥ 1 do not decrease is outside the series' domain too. Both are
``series_ok`` False, with the reason.
"""

from __future__ import annotations

import numpy as np

from perturb._defaults import (
    ALONG_STRIDE,
    HOMOTOPY_MARGIN,
    LOWER_CAP,
    LOWER_LEAP,
    MAGNUS_DRAW_STEPS,
    MAGNUS_STEPS,
)
from perturb.continuation import ContinuationStatus, continue_curve
from perturb.continuation.newton import newton_fixed
from perturb.steady.compiled import compiled_displacement, compiled_motion, compiled_series
from perturb.steady.floquet import stability_along
from perturb.steady.measures import compiled_terms, peak_abs, series_estimate
from perturb.steady.traced import _homotopy, homotopy_steps, line_equations

__all__ = ["PointEvaluator"]


class PointEvaluator:
    """Measures, stability and the series' estimate of order-N points on a parameter line."""

    def __init__(self, equations, line, order: int | None = None):
        self.equations, self.line = equations, line
        self.series = compiled_series(equations)
        self.terms = compiled_terms(equations)
        self.motion = compiled_motion(equations.system)
        names = list(self.series.coordinates)
        self.resonant = [names.index(c) for c in equations.coordinates]
        self.order = equations.order if order is None else order
        self.lower = self.upper = None
        if self.order >= 1:
            n = len(equations.amplitudes)
            self.lower = line_equations(compiled_displacement(equations, self.order - 1), line, n)
            self.upper = line_equations(compiled_displacement(equations, self.order), line, n)

    def rows(self, u, lam):
        """The compiled variables (u, parameters, ε) of points, and the parameters and ε apart."""
        values, eps = zip(*(self.line.at(float(v)) for v in lam), strict=True)
        params, eps = np.array(values).reshape(len(lam), -1), np.array(eps, dtype=float)
        return np.hstack((np.atleast_2d(u), params, eps[:, None])), params, eps

    def _newton_lower(self, x):
        near = newton_fixed(self.lower, x)
        size = max(float(np.max(np.abs(x[:-1]))), 1e-12)
        if near.converged and float(np.max(np.abs(near.x - x))) <= LOWER_LEAP * size:
            return near.x[:-1]
        return None

    def lower_root(self, u, lam: float):
        """``("", u_lower)`` when the order-N point (u, λ) is carried continuously to a root of
        the order-(N−1) equations at the same λ; else ``(why not, None)``."""
        if self.lower is None:
            return "", None
        x = np.append(np.asarray(u, dtype=float), float(self.line.mu(lam)))
        found = self._newton_lower(x)
        if found is not None:
            return "", found
        size = max(float(np.max(np.abs(x[:-1]))), 1e-12)
        path = continue_curve(
            _homotopy(self.upper, self.lower, float(x[-1])), np.append(x[:-1], 1.0),
            lam_range=(-HOMOTOPY_MARGIN, 1 + HOMOTOPY_MARGIN), direction=-1.0,
            domain=lambda y: "" if float(np.max(np.abs(y[:-1]))) <= LOWER_CAP * size else "far",
            **homotopy_steps(size),
        )  # fmt: skip
        if path.status is ContinuationStatus.LEFT_RANGE and path.points[-1][-1] < 0:
            reached = path.values_at(0.0)[0]
            if len(reached):
                return "", reached[-1][:-1]
        return (
            f"no order-{self.order - 1} root is reached from it at this {self.line.parameter} "
            "(the homotopy in the truncation turns back): the series does not vouch for it "
            "(a shooting from it tells whether a true orbit is near)",
            None,
        )

    def lower_order_along(self, u, lam) -> list[str]:
        """Whether each of consecutive points of a curve has its order-(N−1) counterpart: Newton
        at each point; a run of points where Newton does not decide is decided by the homotopy
        at its ends and middle (the answer changes along a curve only where the lower order's
        root ends)."""
        if self.lower is None:
            return [""] * len(lam)

        def newton(i):
            x = np.append(np.asarray(u[i], dtype=float), float(self.line.mu(lam[i])))
            return "" if self._newton_lower(x) is not None else None

        # Newton at every ALONG_STRIDE-th point; between two that agree the others do too (the
        # answer changes only where the lower order's root ends: there every point is tried)
        out: list[str | None] = [
            newton(i) if i % ALONG_STRIDE == 0 else "?" for i in range(len(lam))
        ]
        if out[-1] == "?":
            out[-1] = newton(len(lam) - 1)
        checked = [i for i, v in enumerate(out) if v != "?"]
        for a, b in zip(checked, checked[1:], strict=False):
            same = out[a] == out[b]
            for i in range(a + 1, b):
                out[i] = out[a] if same else newton(i)
        k = 0
        while k < len(out):
            if out[k] is not None:
                k += 1
                continue
            end = k
            while end + 1 < len(out) and out[end + 1] is None:
                end += 1
            probes = sorted({k, (k + end) // 2, end})
            answers = [self.lower_root(u[i], lam[i])[0] for i in probes]
            for i, why in zip(probes, answers, strict=True):
                out[i] = why
            for i in range(k, end + 1):
                if out[i] is None:
                    out[i] = answers[len(answers) // 2]
            k = end + 1
        return out

    def _estimate(self, cos, sin, lowers, lam) -> list[dict]:
        """max over a period of |x_N − x_{N−1}| per resonant coordinate (NaN without x_{N−1})."""
        coords = self.equations.coordinates
        out = [dict.fromkeys(coords, float("nan")) for _ in lowers]
        have = [i for i, v in enumerate(lowers) if v is not None]
        if not have:
            return out
        x, _, _ = self.rows(np.array([lowers[i] for i in have]), lam[have])
        terms = self.terms.coefficients(x)[:, :, : self.order]  # orders 0..N-1
        lower_cos, lower_sin = terms[:, :, :, 0, :].sum(axis=2), terms[:, :, :, 1, :].sum(axis=2)
        for name, j in zip(coords, self.resonant, strict=True):
            sizes = peak_abs(cos[have, j] - lower_cos[:, j], sin[have, j] - lower_sin[:, j])
            for row, i in enumerate(have):
                out[i][name] = float(sizes[row])
        return out

    def evaluate(self, u, lam, check_lower: bool | str = True) -> dict:
        """Measures, estimate, reasons and stability of points ``u`` (P, 2r) at ``lam`` (P,).

        ``check_lower``: True, each point's order-(N−1) counterpart and the estimate from it;
        ``"along"``, points of one curve (:meth:`lower_order_along`, no estimate); False, none.
        """
        u = np.atleast_2d(np.asarray(u, dtype=float))
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        if len(lam) == 0:
            return {"peak": {}, "first-harmonic": {}, "initial": {}, "stability": None}
        x, params, eps = self.rows(u, lam)
        _, cos, sin = self.series.evaluate(x)
        coords = self.equations.coordinates
        measures = {"peak": {}, "first-harmonic": {}, "initial": {}}
        for k, (name, i) in enumerate(zip(coords, self.resonant, strict=True)):
            m = self.equations.harmonics[k]
            measures["peak"][name] = peak_abs(cos[:, i], sin[:, i])
            measures["first-harmonic"][name] = np.hypot(cos[:, i, m], sin[:, i, m])
            measures["initial"][name] = np.hypot(u[:, 2 * k], u[:, 2 * k + 1])
        sizes = self.terms.sizes(x)[:, self.resonant]
        reasons = [series_estimate(s)[1] for s in sizes]
        error = [dict.fromkeys(coords, float("nan")) for _ in lam]
        lowers: list = [None] * len(lam)
        if check_lower == "along":
            lower = self.lower_order_along(u, lam)
            reasons = [[*r, *filter(None, [why])] for r, why in zip(reasons, lower, strict=True)]
        elif check_lower:
            found = [self.lower_root(v, w) for v, w in zip(u, lam, strict=True)]
            reasons = [
                [*r, *filter(None, [why])] for r, (why, _) in zip(reasons, found, strict=True)
            ]
            lowers = [v for _, v in found]
            error = self._estimate(cos, sin, lowers, lam)
        steps = MAGNUS_DRAW_STEPS if check_lower == "along" else MAGNUS_STEPS
        stability = stability_along(self.motion, self.series, x, params, eps, steps)
        return {
            **measures,
            "stability": stability,
            "error": error,
            "reasons": reasons,
            "lower": lowers,
            "eps": eps,
        }
