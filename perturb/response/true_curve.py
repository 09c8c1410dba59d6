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
    MAX_PERIOD_CAP,
    MAX_PERIOD_DEFAULT,
    SEED_TRIES,
    TRUE_CURVE_MULTIPLIER_TOL,
    TRUE_CURVE_POINTS,
    TRUE_CURVE_SAME_ORBIT,
    TRUE_CURVE_SAMPLES,
)
from perturb.errors import PerturbError, bad_value
from perturb.progress import track
from perturb.response.true_branches import follow_births
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
    "check_max_period",
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
    max_period: int = MAX_PERIOD_DEFAULT,
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
    max_period : int
        Follow the branches born at branch points, and the period doublings while the period
        (in response periods) stays at most this (1: the branches born at branch points only;
        :mod:`perturb.response.true_branches`).

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
    max_period = check_max_period(max_period)
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
    lo, hi, step = setup.continuation_range()
    records, unborn = follow_births(
        setup, equations, covered, lam_range=(lo, hi), step=step, budget=budget,
        max_period=max_period, grid=grid,
    )  # fmt: skip
    anchors = [(i, *r) for i, record in enumerate(records) for r in record.refined]
    built = tuple(_true_curve(setup, record, grid, anchors, records) for record in records)
    found = partings(setup, equations, response, names, covered, tol, measure)
    return TrueCurves(
        parameter, built, found, int(budget), float(tol), setup.family.integrator.name,
        (*failures, *unborn), measure, max_period,
    )  # fmt: skip


def check_max_period(value) -> int:
    """A cascade's longest period: a whole number from 1 to ``MAX_PERIOD_CAP``, else one line."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise bad_value("max_period", value, f"give a whole number from 1 to {MAX_PERIOD_CAP}")
    if not 1 <= value <= MAX_PERIOD_CAP:
        raise bad_value(
            "max_period", value,
            f"give a whole number from 1 (no period doubling followed) to {MAX_PERIOD_CAP} (the "
            "cap: a cascade's later steps are closer than their location's tolerance)",
        )  # fmt: skip
    return int(value)


def _seeds(response, names):
    """Per analytic branch (as traced): its name, its points ordered by how far the series can
    be trusted there (inside its domain first, then by its own relative error estimate), then
    from the middle out."""
    by_id = {id(p): n for p, n in zip(response.points, names, strict=True)}
    out = []

    def trust(point) -> tuple:
        size = max(max(point.norms.values(), default=0.0), 1e-300)
        error = max((v for v in point.error.values() if math.isfinite(v)), default=math.inf)
        return (not point.series_ok, error / size)

    for branch in response.branches():
        if not branch:
            continue
        mid = (len(branch) - 1) / 2
        ordered = sorted(range(len(branch)), key=lambda k: (*trust(branch[k]), abs(k - mid), k))
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
    point = setup.problem.case().at(**{setup.parameter: lam})
    state = state_along(solution, [0.0], point.parameter_value, point.symbol_values)
    return np.array([float(state[s.name][0]) for s in setup.system.state_symbols])


def _on_curve(curve, x) -> bool:
    """Whether the scaled point ``x`` lies on ``curve`` (read at its λ)."""
    if curve.points.shape[0] < 2:
        return False
    readings = curve.values_at([float(x[-1])])[0]
    scale = max(1.0, float(np.max(np.abs(x))))
    return any(float(np.max(np.abs(r - x))) <= TRUE_CURVE_SAME_ORBIT * scale for r in readings)


def _true_curve(setup, record, grid, anchors=(), records=()) -> TrueCurve:
    """A record of the diagram as true points (one sampled shot each) and special points (the
    refined ones in place of the secant's). ``anchors``: ``(record index, kind, x, located,
    note)`` of every refined point of the diagram: a branch point or fold the secant found
    where this curve meets another at one of them (its birth, or where it rejoins its parent) is
    that point (kind ``crossing`` on a curve of another period: a doubled orbit meets its
    parent, as a period-k orbit is a 2k-periodic one, at its period doubling)."""
    lo, hi = setup.range
    curve, equations = record.curve, record.equations
    points = []
    for x in _with_ends(curve, lo, hi):
        y0, lam = equations.unscale(x)
        try:
            points.append(_point(setup, record, lam, y0)[0])
        except OutsideDomain:
            continue
    special = []
    refined = list(record.refined)
    for found, note in _special_points(curve):
        x, located = found.x, found.located
        match = _refined_match(refined, found)
        if match is not None:
            kind, x, located, extra = refined.pop(match)
            note = "; ".join(n for n in (note, extra) if n)
        elif found.kind == BRANCH_POINT and any(r[0] == BRANCH_POINT for r in record.refined):
            continue  # the secant's trace of a pitchfork refined elsewhere on the curve
        elif found.kind in (BRANCH_POINT, FOLD) and (anchor := _anchor(anchors, found)):
            index, kind, x, located, extra = anchor
            lam = equations.unscale(x)[1]
            if any(abs(b.value - lam) <= 1e-9 * max(1.0, abs(lam)) for b in special):
                continue  # met once already (a fold twinned with the branch point)
            crossing = kind if records[index].period == record.period else "crossing"
            found = type(found)(crossing, x, found.tangent, found.index, 0.0, located, "")
            note = f"where it meets curve {index + 1} (the {kind} there)"
        y0, lam = equations.unscale(x)
        try:
            here, monodromy = _point(setup, record, lam, y0)
        except OutsideDomain:
            continue
        special.append(_bifurcation(found.kind, lam, here, monodromy, lo, hi, located,
                                    "; ".join(n for n in (found.note if not located else "", note)
                                              if n)))  # fmt: skip
    for kind, x, located, note in refined:  # refined points the continuation did not flag
        y0, lam = equations.unscale(x)
        try:
            here, monodromy = _point(setup, record, lam, y0)
        except OutsideDomain:
            continue
        special.append(_bifurcation(kind, lam, here, monodromy, lo, hi, located, note))
    special.sort(key=lambda b: b.value)
    message = curve.message
    if not curve.success and record.failure:
        message += f" (last failure: {record.failure})"
    parent = record.parent
    return TrueCurve(
        record.branches, points, special, curve.status.name, curve.success,
        _in_parameter(message, setup, equations), record.shots, record.period,
        parent, record.birth, record.born_at,
    )  # fmt: skip


def _with_ends(curve, lo: float, hi: float) -> list:
    """The curve's points with its crossings of the sweep's ends inserted where they fall: the
    true curve reaches the ends exactly (read on the segments that cross them, polished)."""
    from perturb.continuation.reading import read_segment

    out = []
    for k, x in enumerate(curve.points):
        out.append(x)
        if k + 1 == len(curve.points):
            break
        a, b = float(x[-1]), float(curve.points[k + 1][-1])
        ends = [e for e in (lo, hi) if min(a, b) < e < max(a, b)]
        for end in sorted(ends, reverse=b < a):
            here = read_segment(curve, k, end)
            if here is not None:
                out.append(here)
    return out


def _anchor(anchors, found):
    """The refined point of the diagram at the λ of ``found`` (a relative 1e-5: the secant's
    reach beside a crossing of two curves), if any."""
    reach = 1e-5 if found.located else 1e-3  # a secant that did not converge: its bracket
    near = [a for a in anchors if abs(a[2][-1] - found.x[-1]) <= reach * max(1.0, abs(found.x[-1]))]
    return min(near, key=lambda a: float(np.max(np.abs(a[2] - found.x)))) if near else None


def _refined_match(refined, found):
    """The index of the refined point of the same kind nearest the continuation's ``found``, if
    within the secant's reach (a relative 1e-3 in λ)."""
    same = [i for i, r in enumerate(refined) if r[0] == found.kind]
    if not same:
        return None
    best = min(same, key=lambda i: abs(refined[i][1][-1] - found.x[-1]))
    if abs(refined[best][1][-1] - found.x[-1]) <= 1e-3 * max(1.0, abs(found.x[-1])):
        return best
    return None


def _bifurcation(kind, lam, here, monodromy, lo, hi, located, note) -> TrueBifurcation:
    multiplier = _critical(kind, monodromy)  # +1 at a crossing
    rotation = math.nan
    if kind == NEIMARK_SACKER and math.isfinite(abs(multiplier)):
        rotation = abs(math.atan2(multiplier.imag, multiplier.real)) / (2 * math.pi)
    return TrueBifurcation(
        kind=kind, value=lam, norms=here.norms, peaks=here.peaks, multiplier=multiplier,
        orbit=here.orbit, harmonics=here.harmonics, inside=bool(lo <= lam <= hi),
        located=located, note=note, rotation=rotation,
    )  # fmt: skip


def _point(setup, record, lam: float, y0):
    """``(TruePoint, monodromy)`` of the record's map at (y0, λ): one period by the family's own
    shot, k periods composed (peaks and harmonics over the whole k periods)."""
    if record.period == 1:
        shot = setup.family.shoot(y0, setup.values(lam), setup.direction(lam), TRUE_CURVE_SAMPLES)
        return setup.point_of(lam, shot), shot.monodromy
    at = record.equations.compose(y0, lam, TRUE_CURVE_SAMPLES)
    if at is None:
        raise OutsideDomain(record.equations.last_failure or f"a shot failed at {lam:g}")
    _, monodromy, _, orbit = at
    return setup.point_of_orbit(lam, y0, monodromy, orbit, record.period), monodromy


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
    """The continuation's message speaks of λ and u, the scaled state: say them as the swept
    parameter and the state itself."""
    import re

    names = ", ".join(s.name for s in setup.system.state_symbols)

    def state(match) -> str:
        values = [float(v) / equations.factor for v in match.group(1).split(",")]
        return f"({names}) = ({', '.join(f'{v:.6g}' for v in values)})"

    message = re.sub(r"u = \[([^\]]*)\]", state, message)
    return message.replace("λ", setup.parameter)
