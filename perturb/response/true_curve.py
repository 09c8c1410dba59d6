"""The true curve past the series: the driven problem's true periodic responses, continued.

``perturb response PROBLEM --sweep NAME=A:B:N --true`` follows the **true** periodic orbits of the
driven system along the swept parameter λ, as AUTO-07p, MATCONT, BifurcationKit.jl, COCO and
NLvib do: the period is fixed (p forcing periods of the resonance p/q), so a response is a zero of
the shooting map :math:`R(y_0, \\lambda) = \\varphi(y_0; \\lambda) - y_0`
(:class:`perturb.oracle.driven_family.DrivenFamily`: monodromy and sensitivity from the variational
equations), and the zeros form curves that pseudo-arclength continuation
(:mod:`perturb.continuation`) follows through their folds. Each curve starts from a point of an
analytic branch (the order-N response: its state at t = 0, corrected by Newton at fixed λ); a seed
already on a curve found is not followed twice (the middle and upper branches of a hardening
Duffing are one true curve through the fold).

Along each curve the Floquet multipliers are the monodromy's eigenvalues and the special points are
the sign changes of test functions, located on the curve (:mod:`perturb.oracle.bifurcation`):
**folds** (the tangent turns in λ: a multiplier at +1), **branch points** (the bordered Jacobian
is singular: a multiplier at +1 where two curves cross, e.g. where the parametric response leaves
x = 0 at an edge of the instability tongue), **period doubling** (:math:`\\det(M + I)`: a
multiplier at −1) and **Neimark–Sacker** (a complex pair on the unit circle; neutral saddles,
:math:`\\mu_1\\mu_2 = 1` with real multipliers, are dropped). Points a little outside the sweep
(``TRUE_CURVE_MARGIN`` of its width) are followed too, so that a special point just past an end is
reported (``inside`` False).

Where the analytic and true curves **part**: along each analytic branch, the first grid value, from
where they agree, at which the analytic amplitude differs from the true one at the same λ by more
than ``tol`` (relative), or where no true orbit is left at all; the crossing of ``tol`` is
interpolated between the grid values.

A continuation that cannot go on (a singular point it cannot pass, a step below its floor, the
budget spent, a parameter value the problem refuses: "a branch leaving the domain") keeps what it
has and says where and why in its ``message``; the curves are never extrapolated.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from perturb._defaults import (
    DEFAULT_TOL,
    SEED_TRIES,
    TRUE_CURVE_MULTIPLIER_TOL,
    TRUE_CURVE_POINTS,
    TRUE_CURVE_SAME_ORBIT,
    TRUE_CURVE_SAMPLES,
)
from perturb.errors import PerturbError, bad_value
from perturb.progress import track
from perturb.response.true_family import OutsideDomain, ScaledEquations, TrueFamily, floquet_tests
from perturb.response.true_partings import partings
from perturb.response.true_results import (
    BRANCH_POINT,
    FOLD,
    NEIMARK_SACKER,
    PERIOD_DOUBLING,
    Parting,
    TrueBifurcation,
    TrueCurve,
    TrueCurves,
    TruePoint,
)

#: The amplitude measures a true point carries, by the analytic response's names.
MEASURES = ("initial", "peak", "first-harmonic")

__all__ = [
    "Parting",
    "TrueBifurcation",
    "TrueCurve",
    "TrueCurves",
    "TruePoint",
    "true_curves",
]


def true_curves(
    problem,
    parameter: str,
    response,
    names: Sequence[str],
    order: int,
    budget: int = TRUE_CURVE_POINTS,
    tol: float = DEFAULT_TOL,
    integrator=None,
    measure: str | None = None,
) -> TrueCurves:
    """The true curves of a driven ``problem``'s response over ``parameter`` (module notes).

    Parameters
    ----------
    problem : problems.base.Problem
        The driven problem (its ``system()``, ``case()`` and ``name``).
    parameter : str
        The swept parameter.
    response : FrequencyResponse
        The analytic response (its points seed the curves; its grid is the range).
    names : sequence of str
        The branch name of each of ``response.points``.
    order : int
        The analytic response's order (the seeds' states are of this order).
    budget : int
        The most points of each curve (>= 2).
    tol : float
        The relative amplitude difference at which the analytic and true curves part (> 0).
    integrator : Integrator or str, optional
    measure : str, optional
        The amplitude compared where the curves part: ``initial`` (the initial-value norm),
        ``peak`` (max ``|x|``) or ``first-harmonic`` (default: the analytic response's own).

    Returns
    -------
    TrueCurves

    Examples
    --------
    The undamped linear Mathieu oscillator: x = 0 is its only analytic branch, and the true curve
    through it has two branch points, the first instability tongue's edges:

    >>> import numpy as np
    >>> from problems import get_problem
    >>> from perturb.response.model import problem_response
    >>> mathieu = get_problem("parametric-duffing").create(zeta=0.0, gamma=0.0)
    >>> result = problem_response(mathieu, "Omega", np.linspace(1.9, 2.1, 3))
    >>> curves = true_curves(mathieu, "Omega", result.response, result.branches, order=3)
    >>> [(b.kind, round(b.value, 9)) for b in curves.bifurcations]
    [('branch-point', 1.949698438), ('branch-point', 2.049678773)]
    """
    if isinstance(budget, bool) or not isinstance(budget, int | np.integer) or budget < 2:
        raise bad_value("budget", budget, "give the most points of each true curve (>= 2)")
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise bad_value("tol", tol, "give a positive relative tolerance, e.g. 0.01")
    measure = response.measure if measure is None else measure
    if measure not in MEASURES:
        raise bad_value("measure", measure, f"choose one of {list(MEASURES)}")
    grid = np.asarray(response.grid, dtype=float)
    try:
        setup = TrueFamily(problem, parameter, grid, order, integrator)
    except OutsideDomain as exc:
        why = (f"not continued: {exc}",)
        return TrueCurves(parameter, (), (), budget, tol, "", why, measure)
    width = float(grid[-1] - grid[0])
    seeds = _seeds(response, names)
    scale = max([1.0] + [float(np.max(np.abs(s[2]))) for s in seeds if s[2] is not None])
    equations = ScaledEquations(setup, scale, width)
    curves, failures, covered = [], [], []
    for name, candidates, _ in track(seeds, label="true curves: branches followed"):
        seeded = _follow(setup, equations, name, candidates, curves, covered, budget)
        if isinstance(seeded, str):
            failures.append(seeded)
    built = tuple(_true_curve(setup, equations, *entry, grid) for entry in covered)
    found = partings(setup, equations, response, names, covered, tol, measure)
    return TrueCurves(
        parameter, built, found, int(budget), float(tol), setup.family.integrator.name,
        tuple(failures), measure,
    )  # fmt: skip


def _seeds(response, names):
    """Per analytic branch (as traced): its name, its points ordered from the middle out."""
    by_id = {id(p): n for p, n in zip(response.points, names, strict=True)}
    out = []
    for branch in response.branches():
        if not branch:
            continue
        mid = (len(branch) - 1) / 2
        ordered = sorted(range(len(branch)), key=lambda k: (abs(k - mid), k))
        candidates = [branch[k] for k in ordered]
        name = by_id.get(id(branch[int(round(mid))]), "branch")
        top = max(max(p.norms.values(), default=0.0) for p in branch)
        out.append((name, candidates, np.array([top])))
    return out


def _follow(setup, equations, name, candidates, curves, covered, budget):
    """Continue the true curve through the first seed of branch ``name`` that corrects onto a
    true orbit, unless that orbit lies on a curve already found (then record the branch there)."""
    from perturb.continuation import continue_both
    from perturb.continuation.newton import newton_fixed

    reasons = []
    for point in candidates[:SEED_TRIES]:
        lam = float(point.value)
        try:
            y0 = _analytic_state(setup, lam, name, point)
        except PerturbError as exc:
            reasons.append(f"{setup.parameter} = {lam:g}: {exc}")
            continue
        x0 = equations.scaled(y0, lam)
        first = newton_fixed(equations, x0)
        if not first.converged:
            reasons.append(
                f"{setup.parameter} = {lam:g}: Newton at fixed {setup.parameter} did not converge "
                f"from the order-{setup.order} state"
                + (f" ({equations.last_failure})" if not first.finite else "")
            )
            continue
        for curve, names_, *_ in covered:
            if _on_curve(curve, first.x):
                names_.append(name)
                return None
        before = equations.shots
        equations.last_failure = ""
        lo, hi, step = setup.continuation_range()
        curve = continue_both(
            equations, first.x, lam_range=(lo, hi), tests=floquet_tests(), max_step=step,
            domain=equations.domain, max_points=max(2, (budget + 1) // 2),
        )  # fmt: skip
        covered.append((curve, [name], equations.shots - before, equations.last_failure))
        curves.append(curve)
        return None
    return f"branch {name}: no seed corrected onto a true orbit: " + "; ".join(reasons)


def _analytic_state(setup, lam: float, name: str, point) -> np.ndarray:
    """The order-N state at t = 0 of the analytic branch point ``point`` at λ (the seed): its
    series with the point's amplitudes put in (:func:`~perturb.steady.branches.branch_solution`)."""
    from perturb.steady.branches import branch_solution
    from perturb.validation import state_along

    solution = branch_solution(setup.amplitude_equations, point, name)
    variant = setup.problem.with_parameters(**{setup.parameter: lam})
    state = state_along(solution, [0.0], variant.parameter_value(), variant.symbol_values())
    return np.array([float(state[s.name][0]) for s in setup.system.state_symbols])


def _on_curve(curve, x) -> bool:
    """Whether the scaled point ``x`` lies on ``curve`` (read at its λ)."""
    if curve.points.shape[0] < 2:
        return False
    readings = curve.values_at([float(x[-1])])[0]
    scale = max(1.0, float(np.max(np.abs(x))))
    return any(float(np.max(np.abs(r - x))) <= TRUE_CURVE_SAME_ORBIT * scale for r in readings)


def _true_curve(setup, equations, curve, branches, shots, failure, grid) -> TrueCurve:
    """The continued curve as true points (one sampled shot each) and special points."""
    lo, hi = setup.range
    points = []
    for x in curve.points:
        y0, lam = equations.unscale(x)
        try:
            points.append(setup.point(lam, y0))
        except OutsideDomain:
            continue
    special = []
    for found, note in _special_points(curve):
        y0, lam = equations.unscale(found.x)
        try:
            shot = setup.family.shoot(
                y0, setup.values(lam), setup.direction(lam), TRUE_CURVE_SAMPLES
            )
        except OutsideDomain:
            continue
        here = setup.point_of(lam, shot)
        special.append(
            TrueBifurcation(
                kind=found.kind, value=lam, norms=here.norms, peaks=here.peaks,
                multiplier=_critical(found.kind, shot.monodromy), multipliers=here.multipliers,
                harmonics=here.harmonics,
                inside=bool(lo <= lam <= hi), located=found.located,
                note="; ".join(n for n in (found.note, note) if n),
            )
        )  # fmt: skip
    message = curve.message
    if not curve.success and failure:
        message += f" (last failure: {failure})"
    return TrueCurve(
        branches, points, special, curve.status.name, curve.success,
        _in_parameter(message, setup, equations), shots,
    )  # fmt: skip


def _special_points(curve):
    """The continuation's special points, a fold at a branch point dropped (a pitchfork: the
    curve turns in λ where it crosses the other, which the branch point's note says)."""
    out = []
    for p in curve.special:
        twins = [
            q for q in curve.special
            if q is not p and float(np.max(np.abs(q.x - p.x))) <= TRUE_CURVE_SAME_ORBIT
            * max(1.0, float(np.max(np.abs(p.x))))
        ]  # fmt: skip
        if p.kind == FOLD and any(q.kind == BRANCH_POINT for q in twins):
            continue
        turns = p.kind == BRANCH_POINT and any(q.kind == FOLD for q in twins)
        out.append((p, "the curve also turns there (a pitchfork)" if turns else ""))
    return out


def _critical(kind: str, monodromy) -> complex:
    """The multiplier that crosses the circle at a special point of ``kind``."""
    from perturb.oracle import critical_multiplier, is_neimark_sacker

    if not np.all(np.isfinite(monodromy)):
        return complex(math.nan, math.nan)
    if kind == NEIMARK_SACKER:
        return is_neimark_sacker(monodromy, math.sqrt(TRUE_CURVE_MULTIPLIER_TOL))[1]
    return critical_multiplier(monodromy, -1.0 if kind == PERIOD_DOUBLING else 1.0)


def _in_parameter(message: str, setup, equations) -> str:
    """The continuation's message speaks of λ and u: say what they are."""
    return f"{message} [λ is {setup.parameter}; u the state x {equations.factor:.6g}]"
