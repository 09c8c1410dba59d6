"""Every order-N branch on a line of parameters, continued from the certified first-order census.

1. **Seeds.** The first-order equations are solved for every real root, with a certificate, at
   the ends of the window (:func:`perturb.steady.census.census`), and their exact folds on the
   line are found (:func:`~perturb.steady.census.line_folds`): every first-order branch in the
   window either crosses one of its ends or is a closed curve inside it, which has folds.
2. **First-order curves.** Each seed not already on a curve is continued both ways through the
   window (:func:`perturb.continuation.continue_both`).
3. **Order N.** On each first-order curve, a point where the first-order Jacobian is best
   conditioned is carried to the order-N equations by a homotopy in the truncation,
   (1 − τ) D₁ + τ D_N = 0 continued from τ = 0 to 1 at fixed λ (a root of the series truncated
   later, reached continuously: never a jump to another or a spurious root); the order-N point
   is continued both ways. An order-N
   curve met twice is kept once, under the time shifts that map a response onto itself
   (:func:`~perturb.steady.census.same_orbit`). No order-N point is a first-order one.
4. **Reading.** :meth:`Traced.at` gives every order-N point at given λ, each on its curve.

A first-order curve that cannot be lifted, and an order-N curve that stops inside the window
(its step below the floor, a non-finite value), are listed in ``failures`` with where and why.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import (
    AMPLITUDE_CAP,
    HOMOTOPY_MARGIN,
    HOMOTOPY_MAX_STEP,
    HOMOTOPY_STEP,
    INITIAL_STEP_FRACTION,
    LIFT_TRIES,
    MAX_STEP_FRACTION,
    REACH_STEP_SHARE,
)
from perturb.continuation import ContinuationStatus, CurveEquations, continue_both, continue_curve
from perturb.errors import InvalidParameterError
from perturb.steady.census import census, distinct_orbits, line_folds, same_orbit
from perturb.steady.compiled import compiled_displacement
from perturb.steady.exact import exact_number
from perturb.system import EPS

__all__ = ["Branch", "Traced", "line_equations", "trace"]


@frozen
class Branch:
    """One order-N curve of the response (its λ in μ, see :mod:`perturb.steady.line`) and the
    first-order curve it was lifted from (None: seeded by the order-N census itself)."""

    curve: object = field(eq=False)
    first: object = field(eq=False)


@frozen
class Traced:
    """The order-N curves on a line, their seeds and what failed (see the module notes).

    Attributes
    ----------
    line : ParameterLine
    window : (float, float)
        In the swept parameter.
    order : int
    branches : tuple of Branch
    first : tuple of Curve
        The first-order curves.
    failures : tuple of str
        Curves that could not be followed (their status and where), census that failed.
    harmonics : tuple of int
    group : int
        The number of time shifts that map a response onto itself (p G).
    notes : tuple of str
        First-order curves with no order-N curve over them in the window (the first-order
        equations' artefact there: the homotopy to order N turns back from each of its points).
    """

    line: object = field(eq=False)
    window: tuple
    order: int
    branches: tuple = field(converter=tuple)
    first: tuple = field(converter=tuple, eq=False)
    failures: tuple = field(converter=tuple)
    harmonics: tuple = field(converter=tuple)
    group: int = 1
    notes: tuple = field(converter=tuple, factory=tuple)

    def at(self, values) -> list[list[tuple[np.ndarray, int]]]:
        """Every order-N response at each λ in ``values``: per value, a list of ``(amplitudes,
        branch index)``, one per distinct motion."""
        mus = self.line.mu(np.atleast_1d(np.asarray(values, dtype=float)))
        out: list[list] = [[] for _ in mus]
        for index, branch in enumerate(self.branches):
            for i, found in enumerate(branch.curve.values_at(mus)):
                for point in found:
                    u = point[:-1]
                    if not any(same_orbit(v, u, self.harmonics, self.group) for v, _ in out[i]):
                        out[i].append((u, index))
        return out


def line_equations(compiled, line, n: int) -> CurveEquations:
    """G(u, μ) = D(u, p(λ(μ)), ε(λ(μ))) and [G_u | G_μ] of compiled rows ``D`` on ``line``."""
    names = list(line.names)
    special = None
    if line.affine:
        fixed, moving = {}, {}
        for name, v, dv in zip(names, line.base, line.slope, strict=True):
            if dv == 0:
                fixed[name] = v
            else:
                moving[name] = (v, dv / line.scale)
        if line.eps_slope == 0:
            fixed[EPS.name] = line.eps
        else:
            moving[EPS.name] = (line.eps, line.eps_slope / line.scale)
        special = compiled.specialized(fixed, moving, "mu")
        special = special.function() if special is not None else None
    memo: dict = {}

    def both(x):
        x = np.asarray(x, dtype=float)
        key = x.tobytes()
        if key not in memo:
            memo.clear()
            if special is not None:
                memo[key] = special(x)
            else:
                lam = float(line.lam(x[-1]))
                try:
                    values, eps = line.at(lam)
                    rate, eps_rate = line.rate(lam)
                except InvalidParameterError:  # a step past the problem's values: not a point
                    nan = np.full(n, math.nan)  # of the curve (the corrector fails, the step
                    memo[key] = (nan, np.full((n, n + 1), math.nan))  # is shortened)
                    return memo[key]
                g, grad = compiled.values_and_gradient(np.concatenate((x[:-1], values, [eps])))
                g_mu = (grad[:, n : n + len(names)] @ rate + grad[:, -1] * eps_rate) / line.scale
                memo[key] = (g, np.hstack((grad[:, :n], g_mu[:, None])))
        return memo[key]

    return CurveEquations(lambda x: both(x)[0], lambda x: both(x)[1])


def _exact_line(line, mu: sp.Symbol) -> tuple[dict, dict]:
    base = {sp.Symbol(n): exact_number(v) for n, v in zip(line.names, line.base, strict=True)}
    slope = {
        sp.Symbol(n): exact_number(dv / line.scale)
        for n, dv in zip(line.names, line.slope, strict=True)
        if dv != 0
    }
    return base, slope


def _on(curve, x, harmonics, group) -> bool:
    return any(
        same_orbit(point[:-1], x[:-1], harmonics, group) for point in curve.values_at(x[-1])[0]
    )


def _homotopy(order_n: CurveEquations, first_order: CurveEquations, mu: float) -> CurveEquations:
    """H(u, τ) = (1 − τ) D₁(u, μ) + τ D_N(u, μ) at fixed μ: τ carries a first-order root to
    order N along the truncation of the series."""

    def both(y):
        x = np.append(y[:-1], mu)
        tau = float(y[-1])
        g0, j0 = first_order.residual(x), np.asarray(first_order.jacobian(x))
        g1, j1 = order_n.residual(x), np.asarray(order_n.jacobian(x))
        h = (1 - tau) * np.asarray(g0) + tau * np.asarray(g1)
        jac = np.hstack(((1 - tau) * j0[:, :-1] + tau * j1[:, :-1], (g1 - g0)[:, None]))
        return h, jac

    return CurveEquations(lambda y: both(y)[0], lambda y: both(y)[1])


def _lift(order_n: CurveEquations, first_order: CurveEquations, curve, cap: float, mu_range):
    """A point of the order-N curve over a first-order one: from its best-conditioned points,
    the homotopy τ: 0 → 1 (:func:`_homotopy`) continued until it reaches τ = 1; None when every
    one turns back (a fold in τ: that first-order root has no order-N counterpart there)."""
    inside = [k for k, x in enumerate(curve.points) if mu_range[0] <= x[-1] <= mu_range[1]] or list(
        range(len(curve.points))
    )
    conditioning = []
    for k in inside:
        jac = np.asarray(first_order.jacobian(curve.points[k]))[:, :-1]
        singular = np.linalg.svd(jac, compute_uv=False)
        conditioning.append(singular[-1] / max(singular[0], 1e-300))
    for k in [inside[i] for i in np.argsort(conditioning)[::-1][:LIFT_TRIES]]:
        x = curve.points[k]
        path = continue_curve(
            _homotopy(order_n, first_order, float(x[-1])), np.append(x[:-1], 0.0),
            lam_range=(-HOMOTOPY_MARGIN, 1 + HOMOTOPY_MARGIN), direction=1.0,
            domain=lambda y: "" if float(np.max(np.abs(y[:-1]))) <= cap else "too large",
            **homotopy_steps(float(np.max(np.abs(x[:-1])))),
        )  # fmt: skip
        if path.status is not ContinuationStatus.LEFT_RANGE or path.points[-1][-1] < 1:
            continue
        reached = path.values_at(1.0)[0]
        if len(reached):
            return np.append(reached[-1][:-1], x[-1])
    return None


def homotopy_steps(size: float) -> dict:
    """Step options of a homotopy in the truncation from a point of amplitude ``size``."""
    scale = 1.0 + size
    return {"step": HOMOTOPY_STEP * scale, "max_step": HOMOTOPY_MAX_STEP * scale}


def _where(line, x) -> str:
    return f"{line.parameter} = {float(line.lam(x[-1])):.8g}, amplitudes {np.round(x[:-1], 6).tolist()}"


def trace(
    equations, order: int, line, low: float, high: float, census_at=None, folds: bool = True,
    reach: tuple | None = None, order_seeds=None,
) -> Traced:  # fmt: skip
    """The order-N curves of ``equations`` on ``line`` over the window [low, high] of the swept
    parameter (see the module notes). ``census_at``: where the census is taken (default the
    window's ends); ``folds``: seed from the exact first-order folds too (closed curves).

    ``reach``: a range of the swept parameter holding the window, over which the curves are
    followed and from whose first-order folds they are seeded (default the window): a branch
    whose first-order counterpart turns just outside the window is continued into it.
    ``order_seeds``: ``callable(cap) -> [(u, λ)]``, points of the order-N equations themselves
    (the order-N census at the window's ends), each continued unless already on a curve."""
    n = len(equations.amplitudes)
    symbols = {p.name: p for p in equations.system.parameters}
    harmonics = tuple(equations.harmonics)
    from perturb.steady.census import shift_symmetry

    group = equations.system.excitation.p * shift_symmetry(equations.system)
    first_eqs = line_equations(compiled_displacement(equations, 0), line, n)
    order_eqs = line_equations(compiled_displacement(equations, order), line, n)
    mu_range = (float(line.mu(low)), float(line.mu(high)))
    reach_low, reach_high = (low, high) if reach is None else reach
    mu_reach = (float(line.mu(reach_low)), float(line.mu(reach_high)))
    failures: list[str] = []
    notes: list[str] = []
    seeds = []
    for lam in (low, high) if census_at is None else census_at:
        values, eps = line.at(lam)
        fixed = {symbols[k]: exact_number(v) for k, v in zip(line.names, values, strict=True)}
        roots, why = census(equations, fixed)
        if why:
            failures.append(f"{line.parameter} = {lam:g}: {why}")
        for i in distinct_orbits(roots, harmonics, group):
            seeds.append(np.append(roots[i], line.mu(lam)))
    if line.affine and folds:
        mu = sp.Symbol("mu_line")
        base, slope = _exact_line(line, mu)
        folds, why = line_folds(equations, base, slope, mu)
        if why:
            failures.append(f"the first-order folds on the line: {why}")
        seeds.extend(f for f in folds if mu_reach[0] <= f[-1] <= mu_reach[1])
    top = max((float(np.max(np.abs(s[:-1]))) for s in seeds), default=1.0)
    cap = AMPLITUDE_CAP * max(1.0, top)

    def domain(x):
        if float(np.max(np.abs(x[:-1]))) > cap:
            return f"an amplitude beyond {cap:.3g}, {AMPLITUDE_CAP:g} times the census'"
        return "" if line.affine else line.invalid(float(line.lam(x[-1])))

    options = {"lam_range": mu_reach, "domain": domain}
    if mu_reach != mu_range:  # the window's resolution, and steps of the reach beside it
        width, total = mu_range[1] - mu_range[0], mu_reach[1] - mu_reach[0]
        options["step"] = INITIAL_STEP_FRACTION * width
        options["max_step"] = MAX_STEP_FRACTION * max(width, REACH_STEP_SHARE * total)
    firsts = []
    for seed in seeds:
        if any(_on(c, seed, harmonics, group) for c in firsts):
            continue
        curve = continue_both(first_eqs, seed, **options)
        if len(curve.points) < 2:
            failures.append(f"first order, from {_where(line, seed)}: {curve.message}")
            continue
        firsts.append(curve)
    branches = []
    for curve in firsts:
        lifted = _lift(order_eqs, first_eqs, curve, cap, mu_range)
        if lifted is None:
            notes.append(
                f"the first-order branch through {_where(line, curve.points[0])} has no order-"
                f"{order} branch over it: from its {LIFT_TRIES} best-conditioned points, the "
                "homotopy from the first-order equations to the order-N ones turns back"
            )
            continue
        if any(_on(b.curve, lifted, harmonics, group) for b in branches):
            continue
        traced = continue_both(order_eqs, lifted, **options)
        branches.append(Branch(traced, curve))
        if not traced.success:
            failures.append(f"order {order}: {traced.message}")
    for u, lam in order_seeds(cap) if order_seeds is not None else ():
        seed = np.append(np.asarray(u, dtype=float), float(line.mu(lam)))
        if any(_on(b.curve, seed, harmonics, group) for b in branches):
            continue
        traced = continue_both(order_eqs, seed, **options)
        if len(traced.points) < 2:
            failures.append(f"order {order}, from {_where(line, seed)}: {traced.message}")
            continue
        branches.append(Branch(traced, None))
        if not traced.success:
            failures.append(f"order {order}: {traced.message}")
    return Traced(
        line, (low, high), order, branches, firsts, failures, harmonics, group, tuple(notes)
    )
