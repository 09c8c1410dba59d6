"""The true motion at chosen points of the order-N curves: ``perturb response --validate K``.

Where to look (:func:`choose_points`): on each continued curve, inside the sweep, K points spread
by arclength, and besides them always the point of largest amplitude, both sides of every fold (a
short arclength away from it, where the shooting's Newton matrix Φ(T) − I is still regular) and
the curve's ends — where a response curve goes wrong, not its first points.

Each is shot with the period fixed (:func:`perturb.oracle.find_forced_orbit`, seeded by the
order-N state), its orbit sampled over one period and its amplitude measured the way the curve's
is (the trigonometric interpolant of the samples, :func:`perturb.steady.measures.peak_abs`), so
that the true point is drawn where the truth is. The orbit error is the largest distance of the
analytic orbit from the true one over the period, relative to the true amplitude.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from perturb._defaults import DEFAULT_RTOL, FOLD_SIDE, TRUTH_SAMPLES
from perturb.oracle import SymbolicRHS, choose
from perturb.oracle.forced import find_forced_orbit
from perturb.progress import track
from perturb.steady.measures import peak_abs
from perturb.system import EPS

__all__ = ["choose_points", "shoot_point"]


def choose_points(curve, folds, low: float, high: float, count: int, measure: str) -> list:
    """Indices of ``curve``'s points to shoot and why: ``[(index, reason)]`` (see the module
    notes); ``folds`` the fold values on this curve."""
    values = np.asarray(curve.values)
    inside = np.flatnonzero((values >= low) & (values <= high))
    if count <= 0 or inside.size == 0:
        return []
    s = np.asarray(curve.arclength)
    chosen: dict[int, str] = {}
    size = np.max(np.stack(list(curve.measures[measure].values())), axis=0)
    top = int(inside[np.argmax(size[inside])])
    chosen[top] = "largest amplitude"
    length = float(s[inside[-1]] - s[inside[0]]) or 1.0
    for fold in folds:
        at = int(np.argmin(np.abs(values - fold.value) + np.abs(size - max(fold.peak.values()))))
        for sign, side in ((-1, "before"), (1, "after")):
            target = s[at] + sign * max(FOLD_SIDE * length, 0.0)
            k = int(inside[np.argmin(np.abs(s[inside] - target))])
            if k == at:
                k = int(np.clip(at + sign, inside[0], inside[-1]))
            chosen.setdefault(k, f"{side} the fold at {fold.value:.6g}")
    chosen.setdefault(int(inside[0]), "end of the branch in the sweep")
    chosen.setdefault(int(inside[-1]), "end of the branch in the sweep")
    for target in np.linspace(s[inside[0]], s[inside[-1]], count + 2)[1:-1]:
        k = int(inside[np.argmin(np.abs(s[inside] - target))])
        chosen.setdefault(k, "spread by arclength")
    return sorted(chosen.items())


def _rhs(system, values: dict, eps: float, omega: float) -> SymbolicRHS:
    subs = {p: values[p.name] for p in system.parameters}
    subs[EPS] = eps
    state = system.state_symbols
    n = system.n
    forces = [sp.sympify(f).subs(system.parameter, EPS).xreplace(subs) for f in system.rhs]
    w2 = [sp.sympify(w**2).xreplace(subs) for w in system.frequencies]
    exprs = [*state[n:], *(forces[i] - w2[i] * state[i] for i in range(n))]
    return SymbolicRHS((*state, system.excitation.phase), (*exprs, sp.Float(omega)))


def shoot_point(evaluator, line, u: np.ndarray, lam: float) -> dict:
    """The true response near the order-N point (u, λ): its amplitudes by every measure, the
    orbit (a :class:`~perturb.oracle.PeriodicOrbit`), the orbit error; ``success`` False with
    the shooting's message when it fails."""
    equations = evaluator.equations
    system = equations.system
    x, params, eps = evaluator.rows(np.atleast_2d(u), np.array([lam]))
    nu, cos, sin = evaluator.series.evaluate(x)
    nu, cos, sin = float(nu[0]), cos[0], sin[0]
    j = np.arange(cos.shape[-1])
    y0 = np.concatenate((cos.sum(axis=1), nu * (sin * j).sum(axis=1)))
    values = dict(zip(line.names, params[0], strict=True))
    omega = system.excitation.p * nu
    period = 2 * math.pi / nu
    rhs = _rhs(system, values, float(eps[0]), omega)
    orbit = find_forced_orbit(rhs, y0, period)
    if not orbit.success:
        return {"success": False, "message": orbit.message}
    t = period * np.arange(TRUTH_SAMPLES) / TRUTH_SAMPLES
    traj = choose(None, rtol=DEFAULT_RTOL, symbolic=True).integrate(
        rhs, (0.0, period), np.append(orbit.initial_state, 0.0), t_eval=t
    )
    if not traj.success:
        return {"success": False, "message": f"integrating the true orbit: {traj.message}"}
    samples = np.asarray(traj.y, dtype=float)[: system.n]  # (n, TRUTH_SAMPLES)
    s = nu * t
    analytic = cos @ np.cos(np.outer(j, s)) + sin @ np.sin(np.outer(j, s))
    names = [c.name for c in system.coordinates]
    out = {"success": True, "message": orbit.message, "peak": {}, "first-harmonic": {}}
    spectrum = np.fft.rfft(samples, axis=1) / TRUTH_SAMPLES
    half = spectrum.shape[1] - 1
    c_true = 2 * spectrum.real
    c_true[:, 0] /= 2
    s_true = -2 * spectrum.imag
    for k, name in enumerate(equations.coordinates):
        i = names.index(name)
        m = equations.harmonics[k]
        out["peak"][name] = float(peak_abs(c_true[i, :half], s_true[i, :half]))
        out["first-harmonic"][name] = float(math.hypot(c_true[i, m], s_true[i, m]))
    out["initial"] = {
        name: float(math.hypot(orbit.initial_state[names.index(name)],
                               orbit.initial_state[system.n + names.index(name)]
                               / (equations.harmonics[k] * nu)))
        for k, name in enumerate(equations.coordinates)
    }  # fmt: skip
    scale = max(float(np.max(np.abs(samples))), 1e-300)
    out["orbit_error"] = float(np.max(np.abs(analytic - samples))) / scale
    out["orbit"] = orbit
    out["multipliers"] = tuple(complex(z) for z in orbit.multipliers)  # the orbit's, read off it
    return out


def _on_curve(curve, special) -> bool:
    """Whether a special point lies on ``curve`` (its λ and amplitudes among the curve's)."""
    u = np.array(list(special.amplitudes.values()))
    near = np.abs(np.asarray(curve.values) - special.value) <= 1e-9 * max(1.0, abs(special.value))
    return bool(np.any(near & (np.max(np.abs(curve.amplitudes - u), axis=1) <= 1e-6)))


def shoot_along(result, response, count: int, measure: str, tol: float) -> list[dict]:
    """Shoot ``count`` points of every curve of a continued response (:func:`choose_points`):
    one dict each, with the analytic and true amplitudes by ``measure``, the multipliers of both,
    the orbit error and whether it is within ``tol``."""
    from perturb.steady.sampled import name_at

    evaluator = result.evaluator
    line = result.traced.line
    low, high = response.grid[0], response.grid[-1]
    out = []
    picks = []
    for index, curve in enumerate(result.curves):
        folds = [s for s in result.special if s.kind == "fold" and _on_curve(curve, s)]
        picks += [(index, curve, k, why)
                  for k, why in choose_points(curve, folds, low, high, count, measure)]  # fmt: skip
    for index, curve, k, why in track(picks, label=f"response {response.system}: true orbits"):
        lam, u = float(curve.values[k]), curve.amplitudes[k]
        entry = {
            "value": lam,
            "branch": name_at(result, lam, u, measure) or f"curve-{index + 1}",
            "curve": index,
            "reason": why,
            "analytic": {c: float(curve.measures[measure][c][k]) for c in response.coordinates},
            "stable_analytic": curve.stable[k],
            "multipliers_analytic": tuple(complex(z) for z in curve.multipliers[k]),
        }
        shot = shoot_point(evaluator, line, u, lam)
        entry.update(shot)
        if shot["success"]:
            entry["true"] = shot[measure]
            entry["within_tol"] = bool(shot["orbit_error"] <= tol)
        out.append(entry)
    return out
