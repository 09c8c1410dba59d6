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
from attrs import field, frozen

from perturb._defaults import (
    FD_REL_STEP,
    MAX_STEP_FRACTION,
    TRUE_CURVE_AFFINE_TOL,
    TRUE_CURVE_MARGIN,
    TRUE_CURVE_MULTIPLIER_TOL,
    TRUE_CURVE_POINTS,
    TRUE_CURVE_SAME_ORBIT,
    TRUE_CURVE_SAMPLES,
    TRUE_CURVE_TOL,
)
from perturb.errors import InvalidParameterError, PerturbError, bad_value

__all__ = [
    "Parting",
    "TrueBifurcation",
    "TrueCurve",
    "TrueCurves",
    "TruePoint",
    "true_curves",
]

#: The kinds of special points, as reported.
FOLD, BRANCH_POINT = "fold", "branch-point"
PERIOD_DOUBLING, NEIMARK_SACKER = "period-doubling", "neimark-sacker"


def _complexes(values) -> tuple:
    return tuple(complex(z) for z in values)


@frozen
class TruePoint:
    """One true periodic response on a continued curve.

    Attributes
    ----------
    value : float
        The swept parameter's value.
    state : tuple of float
        The state at t = 0 (θ = 0): ``(x..., xdot...)``.
    norms : dict
        Per resonant coordinate, the measure the analytic curve plots: the first harmonic's
        amplitude read from the initial values, :math:`\\sqrt{x(0)^2 + (\\dot x(0)\\,p/(m\\Omega))^2}`.
    peaks : dict
        Per coordinate, max |x| over one period.
    harmonics : dict
        Per resonant coordinate, the amplitude of its resonant harmonic (Fourier, over a period).
    multipliers : tuple of complex
        The Floquet multipliers (eigenvalues of the monodromy).
    stable : bool or None
        All multipliers inside the unit circle (None: the largest within
        ``TRUE_CURVE_MULTIPLIER_TOL`` of it, a conservative system's orbit).
    """

    value: float = field(converter=float)
    state: tuple = field(converter=lambda v: tuple(float(x) for x in v))
    norms: dict
    peaks: dict
    harmonics: dict
    multipliers: tuple = field(converter=_complexes)
    stable: bool | None

    def norm(self, coordinate: str | None = None) -> float:
        """The analytic curve's measure of ``coordinate`` (default: the first)."""
        return self.norms[coordinate] if coordinate else next(iter(self.norms.values()))


@frozen
class TrueBifurcation:
    """A special point of a true curve, located on it.

    Attributes
    ----------
    kind : str
        ``fold``, ``branch-point``, ``period-doubling`` or ``neimark-sacker``.
    value : float
    norms, peaks : dict
        As :class:`TruePoint`'s, at the point.
    multiplier : complex
        The critical multiplier (+1, −1, or on the circle), as computed there.
    multipliers : tuple of complex
    inside : bool
        Within the sweep (False: in the margin past an end).
    located : bool
        The sign change was located to the continuation's tolerance.
    note : str
    """

    kind: str
    value: float = field(converter=float)
    norms: dict
    peaks: dict
    multiplier: complex = field(converter=complex)
    multipliers: tuple = field(converter=_complexes)
    inside: bool
    located: bool = True
    note: str = ""


@frozen
class TrueCurve:
    """One continued curve of true responses.

    Attributes
    ----------
    branches : tuple of str
        The analytic branches whose seeds lie on it (the first one started it).
    points : tuple of TruePoint
        In the order of the continuation (special points included).
    bifurcations : tuple of TrueBifurcation
    status : str
        How the continuation ended (:class:`perturb.continuation.ContinuationStatus` name).
    success : bool
        It ended by leaving the range or the domain, or by closing.
    message : str
        Where and why it ended (both directions).
    shots : int
        Integrations of the variational equations it took.
    """

    branches: tuple = field(converter=tuple)
    points: tuple = field(converter=tuple)
    bifurcations: tuple = field(converter=tuple)
    status: str
    success: bool
    message: str
    shots: int = 0


@frozen
class Parting:
    """Where an analytic branch leaves the true curve by more than the tolerance.

    Attributes
    ----------
    branch : str
    value : float
        The swept parameter where the relative difference crosses ``tolerance`` (interpolated
        between the grid values ``after`` and ``before``).
    analytic, true : float
        The two amplitudes (the analytic curve's measure) there; ``true`` NaN where no true
        orbit is left.
    difference : float
        At the first grid value past the crossing (inf: no true orbit there).
    tolerance : float
    before : float
        The last grid value where they agree (NaN: they agree nowhere on the branch).
    after : float
        The first grid value where they do not.
    note : str
        Empty, or that the branch is off the truth at every grid value (the parting is then the
        branch's first value, with the smallest difference met along it).
    """

    branch: str
    value: float = field(converter=float)
    analytic: float = field(converter=float)
    true: float = field(converter=float)
    difference: float = field(converter=float)
    tolerance: float = field(converter=float)
    before: float = field(converter=float)
    after: float = field(converter=float)
    note: str = ""


@frozen
class TrueCurves:
    """The true curves of a response (``perturb response --true``).

    Attributes
    ----------
    parameter : str
    curves : tuple of TrueCurve
    partings : tuple of Parting
    budget : int
        The most points of each curve.
    tolerance : float
        The relative difference at which the curves part.
    integrator : str
    failures : tuple of str
        Seeds that could not be corrected onto a true orbit, or why nothing was continued.
    """

    parameter: str
    curves: tuple = field(converter=tuple)
    partings: tuple = field(converter=tuple)
    budget: int
    tolerance: float
    integrator: str = ""
    failures: tuple = field(converter=tuple, factory=tuple)

    @property
    def bifurcations(self) -> tuple:
        """Every special point of every curve, sorted by value; one found on two curves (where
        they overlap, e.g. a curve stopped by its budget and another from a second seed) once."""
        out: list = []
        for b in sorted((b for c in self.curves for b in c.bifurcations), key=lambda b: b.value):
            if not any(_same_point(b, seen) for seen in out):
                out.append(b)
        return tuple(out)


def _same_point(a: TrueBifurcation, b: TrueBifurcation) -> bool:
    if a.kind != b.kind:
        return False
    pairs = [(a.value, b.value), *((a.norms[c], b.norms.get(c, math.nan)) for c in a.norms)]
    return all(abs(p - q) <= TRUE_CURVE_SAME_ORBIT * max(1.0, abs(p)) for p, q in pairs)


# ---------------------------------------------------------------------------------------------
# the problem as a family of true responses
# ---------------------------------------------------------------------------------------------


class _OutsideDomain(PerturbError):
    """A parameter value the problem refuses (the message is the problem's)."""


class _Setup:
    """The problem's driven family along ``parameter``: symbols, parameter map, measures."""

    def __init__(self, problem, parameter: str, grid: np.ndarray, order: int, integrator=None):
        from perturb._lambdify import numpy_lambdify
        from perturb.method.driven import amplitude_equations
        from perturb.oracle import DrivenFamily
        from perturb.validation._quasilinear import excitation_frequency, first_order_expressions

        system = problem.system()
        self.problem, self.parameter, self.system, self.order = problem, parameter, system, order
        if system.initial_values:
            raise _OutsideDomain("the system's equations contain initial values")
        drive = system.excitation
        self.cycles = drive.p
        self.params = (*system.parameters, system.parameter)
        exprs = first_order_expressions(system, {})
        self.frequency = excitation_frequency(system, {})
        self.family = DrivenFamily.build(
            system.state_symbols, drive.phase, exprs, self.frequency, self.params, drive.p,
            integrator,
        )  # fmt: skip
        self._omega = numpy_lambdify(self.params, self.frequency)
        self.names = [c.name for c in system.coordinates]
        self.n = system.n
        self.amplitude_equations = amplitude_equations(system, order)
        index = {c.name: i for i, c in enumerate(system.coordinates)}
        self.harmonics = {
            c: (index[c], int(m))
            for c, m in zip(
                self.amplitude_equations.coordinates, self.amplitude_equations.harmonics,
                strict=True,
            )
        }  # fmt: skip
        self._values: dict[float, np.ndarray] = {}
        lo, hi = float(grid[0]), float(grid[-1])
        self.affine = self._affine(lo, hi)
        self.range = (lo, hi)

    def continuation_range(self) -> tuple[float, float, float]:
        """The sweep widened by ``TRUE_CURVE_MARGIN`` of its width at each end, and the largest
        step (``MAX_STEP_FRACTION`` of the widened width). An end is widened only where the
        problem accepts the values one largest step beyond it (a predictor may overshoot the
        range by a step); where it does not (a parameter's own bound, e.g. F > 0), the curve ends
        at the sweep."""
        lo, hi = self.range
        margin = TRUE_CURVE_MARGIN * (hi - lo)
        step = MAX_STEP_FRACTION * (hi - lo + 2 * margin)
        ends = []
        for end, sign in ((lo, -1.0), (hi, 1.0)):
            try:
                self.values(end + sign * (margin + step))
            except _OutsideDomain:
                ends.append(end)
            else:
                ends.append(end + sign * margin)
        return ends[0], ends[1], step

    def values(self, lam: float) -> np.ndarray:
        """The system's parameter values (and ε last) at λ; _OutsideDomain if refused."""
        lam = float(lam)
        if lam not in self._values:
            try:
                variant = self.problem.with_parameters(**{self.parameter: lam})
            except InvalidParameterError as exc:
                raise _OutsideDomain(f"{self.parameter} = {lam:.10g}: {exc}") from None
            named = variant.symbol_values()
            missing = [p.name for p in self.params[:-1] if p.name not in named]
            if missing:
                raise _OutsideDomain(f"the problem gives no value for {missing}")
            vector = [named[p.name] for p in self.params[:-1]] + [variant.parameter_value()]
            if len(self._values) > 4096:
                self._values.clear()
            self._values[lam] = np.array(vector, dtype=float)
        return self._values[lam]

    def _affine(self, lo: float, hi: float) -> np.ndarray | None:
        """dp/dλ when the parameters move affinely with λ over the sweep (checked at its middle)."""
        try:
            a, b, mid = self.values(lo), self.values(hi), self.values(0.5 * (lo + hi))
        except _OutsideDomain:
            return None
        scale = np.maximum(1.0, np.maximum(np.abs(a), np.abs(b)))
        if np.all(np.abs(mid - 0.5 * (a + b)) <= TRUE_CURVE_AFFINE_TOL * scale):
            return (b - a) / (hi - lo)
        return None

    def direction(self, lam: float) -> np.ndarray:
        """dp/dλ at λ: exact for an affine map, else centred (one-sided at a domain edge)."""
        if self.affine is not None:
            return self.affine
        h = FD_REL_STEP * max(1.0, abs(lam))
        try:
            up = self.values(lam + h)
        except _OutsideDomain:
            return (self.values(lam) - self.values(lam - h)) / h
        try:
            down = self.values(lam - h)
        except _OutsideDomain:
            return (up - self.values(lam)) / h
        return (up - down) / (2 * h)

    def omega(self, lam: float) -> float:
        return float(self._omega(*self.values(lam)))

    def point(self, lam: float, y0) -> TruePoint:
        """The true point at (y0, λ): a shot with the orbit sampled, its measures."""
        shot = self.family.shoot(y0, self.values(lam), self.direction(lam), TRUE_CURVE_SAMPLES)
        return self.point_of(lam, shot)

    def point_of(self, lam: float, shot) -> TruePoint:
        y0 = np.asarray(shot.initial_state)
        mu = shot.multipliers
        largest = float(np.max(np.abs(mu))) if np.all(np.isfinite(mu)) else math.nan
        stable = None if abs(largest - 1.0) <= TRUE_CURVE_MULTIPLIER_TOL else largest < 1.0
        if not math.isfinite(largest):
            stable = None
        return TruePoint(
            lam, y0, self.norms(lam, y0), self._peaks(shot), self._harmonics(shot), mu, stable
        )

    def norms(self, lam: float, y0) -> dict:
        """The analytic curve's measure of each resonant coordinate at (y0, λ)."""
        nu = self.omega(lam) / self.cycles
        out = {}
        for name, (i, m) in self.harmonics.items():
            out[name] = math.hypot(float(y0[i]), float(y0[self.n + i]) / (m * nu))
        return out

    def _peaks(self, shot) -> dict:
        orbit = np.asarray(shot.orbit)
        if orbit.size == 0:
            return {name: math.nan for name in self.names}
        return {name: _peak(orbit[i]) for i, name in enumerate(self.names)}

    def _harmonics(self, shot) -> dict:
        orbit = np.asarray(shot.orbit)
        out = {}
        for name, (i, m) in self.harmonics.items():
            if orbit.size == 0:
                out[name] = math.nan
                continue
            samples = orbit[i]
            k = np.arange(samples.size)
            # resonant harmonic m of s = θ/p: exp(-i m θ_k/p), θ_k = 2πp k/n
            phase = np.exp(-2j * math.pi * m * k / samples.size)
            out[name] = float(2.0 * abs(np.sum(samples * phase)) / samples.size)
        return out


def _peak(samples: np.ndarray) -> float:
    """max |x| over a period from equally spaced samples, refined by the parabola through the
    largest sample and its neighbours (periodic)."""
    a = np.abs(samples)
    k = int(np.argmax(a))
    y0, y1, y2 = a[k - 1], a[k], a[(k + 1) % a.size]
    curvature = y0 - 2 * y1 + y2
    if curvature >= 0:
        return float(y1)
    shift = 0.5 * (y0 - y2) / curvature
    return float(y1 - 0.25 * (y0 - y2) * shift)


class _Equations:
    """G(x) = R(y0, λ)·W/U on x = (y0·W/U, λ): the state scaled to the sweep's width W (U the
    amplitudes' scale), so that a step moves state and parameter alike; shots cached."""

    def __init__(self, setup: _Setup, scale: float, width: float):
        self.setup, self.width = setup, width
        self.factor = width / scale
        self.shots = 0
        self._cache: dict[bytes, object] = {}
        self.last_failure = ""

    def unscale(self, x) -> tuple[np.ndarray, float]:
        x = np.asarray(x, dtype=float)
        return x[:-1] / self.factor, float(x[-1])

    def scaled(self, y0, lam) -> np.ndarray:
        return np.append(np.asarray(y0, dtype=float) * self.factor, float(lam))

    def shot(self, x):
        key = np.asarray(x, dtype=float).tobytes()
        if key not in self._cache:
            y0, lam = self.unscale(x)
            setup = self.setup
            try:
                shot = setup.family.shoot(y0, setup.values(lam), setup.direction(lam))
            except _OutsideDomain as exc:
                self.last_failure = str(exc)
                shot = None
            else:
                self.shots += 1
                if not shot.success:
                    self.last_failure = f"integration at {self.setup.parameter} = {lam:.10g}: " + (
                        shot.message
                    )
            if len(self._cache) > 8:
                self._cache.clear()
            self._cache[key] = shot
        return self._cache[key]

    def residual(self, x) -> np.ndarray:
        shot = self.shot(x)
        if shot is None or not shot.success:
            return np.full(len(x) - 1, math.nan)
        return shot.defect * self.factor

    def jacobian(self, x) -> np.ndarray:
        shot = self.shot(x)
        m = len(x) - 1
        if shot is None or not shot.success:
            return np.full((m, m + 1), math.nan)
        jac = np.array(shot.jacobian)
        jac[:, -1] *= self.factor
        return jac

    def domain(self, x) -> str:
        _, lam = self.unscale(x)
        try:
            self.setup.values(lam)
        except _OutsideDomain as exc:
            return str(exc)
        return ""


def _monodromy(jac) -> np.ndarray:
    m = jac.shape[0]
    return np.asarray(jac[:, :m], dtype=float) + np.eye(m)


def _tests():
    """The period-doubling and Neimark–Sacker test functions on J = [M − I | ·]."""
    from perturb.continuation import TestFunction
    from perturb.oracle import is_neimark_sacker, neimark_sacker_test, period_doubling_test

    def ns_value(x, t, jac):
        value = neimark_sacker_test(_monodromy(jac))
        # a conservative map: every pair's product is 1 and the test is round-off (module notes)
        return 0.0 if abs(value) <= TRUE_CURVE_MULTIPLIER_TOL else value

    def ns_kind(x, t, jac):
        found, _ = is_neimark_sacker(_monodromy(jac), math.sqrt(TRUE_CURVE_MULTIPLIER_TOL))
        return NEIMARK_SACKER if found else None

    return (
        TestFunction(PERIOD_DOUBLING, lambda x, t, jac: period_doubling_test(_monodromy(jac))),
        TestFunction(NEIMARK_SACKER, ns_value, ns_kind),
    )


# ---------------------------------------------------------------------------------------------
# seeds, curves, partings
# ---------------------------------------------------------------------------------------------


def true_curves(
    problem,
    parameter: str,
    response,
    names: Sequence[str],
    order: int,
    budget: int = TRUE_CURVE_POINTS,
    tol: float = TRUE_CURVE_TOL,
    integrator=None,
) -> TrueCurves:
    """The true curves of a driven ``problem``'s response over ``parameter`` (module notes).

    Parameters
    ----------
    problem
        The driven problem (``system()``, ``with_parameters()``, ``solve(order, family=)``).
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

    Returns
    -------
    TrueCurves
    """
    if isinstance(budget, bool) or not isinstance(budget, int | np.integer) or budget < 2:
        raise bad_value("budget", budget, "give the most points of each true curve (>= 2)")
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise bad_value("tol", tol, "give a positive relative tolerance, e.g. 0.01")
    grid = np.asarray(response.grid, dtype=float)
    try:
        setup = _Setup(problem, parameter, grid, order, integrator)
    except _OutsideDomain as exc:
        return TrueCurves(parameter, (), (), budget, tol, "", (f"not continued: {exc}",))
    width = float(grid[-1] - grid[0])
    seeds = _seeds(response, names)
    scale = max([1.0] + [float(np.max(np.abs(s[2]))) for s in seeds if s[2] is not None])
    equations = _Equations(setup, scale, width)
    curves, failures, covered = [], [], []
    for name, candidates, _ in seeds:
        seeded = _follow(setup, equations, name, candidates, curves, covered, budget)
        if isinstance(seeded, str):
            failures.append(seeded)
    built = tuple(_true_curve(setup, equations, *entry, grid) for entry in covered)
    partings = _partings(setup, equations, response, names, covered, tol)
    return TrueCurves(
        parameter, built, partings, int(budget), float(tol), setup.family.integrator.name,
        tuple(failures),
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


#: Seeds tried on one analytic branch before it is given up (each costs an analytic solution at
#: its value and a Newton correction).
SEED_TRIES = 3


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
            equations, first.x, lam_range=(lo, hi), tests=_tests(), max_step=step,
            domain=equations.domain, max_points=max(2, (budget + 1) // 2),
        )  # fmt: skip
        covered.append((curve, [name], equations.shots - before, equations.last_failure))
        curves.append(curve)
        return None
    return f"branch {name}: no seed corrected onto a true orbit: " + "; ".join(reasons)


def _analytic_state(setup, lam: float, name: str, point) -> np.ndarray:
    """The order-N state at t = 0 of the analytic branch point ``point`` at λ (the seed): its
    series with the point's amplitudes put in (:func:`~perturb.response.branches.branch_solution`)."""
    from perturb.response.branches import BranchPoint, branch_solution
    from perturb.validation import state_along

    branch = BranchPoint(
        point.amplitudes, point.norms, point.stable, point.eigenvalues, point.multipliers,
        point.first_order, point.note,
    )  # fmt: skip
    solution = branch_solution(setup.amplitude_equations, branch, name)
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
        except _OutsideDomain:
            continue
    special = []
    for found, note in _special_points(curve):
        y0, lam = equations.unscale(found.x)
        try:
            shot = setup.family.shoot(
                y0, setup.values(lam), setup.direction(lam), TRUE_CURVE_SAMPLES
            )
        except _OutsideDomain:
            continue
        here = setup.point_of(lam, shot)
        special.append(
            TrueBifurcation(
                kind=found.kind, value=lam, norms=here.norms, peaks=here.peaks,
                multiplier=_critical(found.kind, shot.monodromy), multipliers=here.multipliers,
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


def _partings(setup, equations, response, names, covered, tol) -> tuple[Parting, ...]:
    """Along each analytic branch, where it leaves the true curves by more than ``tol``: the
    largest difference over the resonant coordinates, relative to the true orbit's largest
    amplitude, against the true point nearest it at the same grid value."""
    grid = [float(g) for g in response.grid]
    readings: dict[float, list[dict]] = {g: [] for g in grid}
    for curve, *_ in covered:
        if curve.points.shape[0] < 2:
            continue
        for g, found in zip(grid, curve.values_at(grid), strict=True):
            for x in found:
                y0, lam = equations.unscale(x)
                try:
                    readings[g].append(setup.norms(lam, y0))
                except _OutsideDomain:
                    continue
    coords = [c for c in response.coordinates if c in setup.harmonics]
    first = coords[0] if coords else None
    by_id = {id(p): n for p, n in zip(response.points, names, strict=True)}
    out = []
    for branch in response.branches():
        if not branch or first is None:
            continue
        name = by_id.get(id(branch[len(branch) // 2]), "branch")
        rows = []
        for p in branch:
            analytic = {c: float(p.norms[c]) for c in coords}

            def distance(true, analytic=analytic):
                size = max(max(true[c] for c in coords), max(analytic.values()))
                if size <= TRIVIAL_AMPLITUDE:
                    return 0.0
                gap = max(abs(analytic[c] - true[c]) for c in coords)
                return gap / max(max(true[c] for c in coords), TRIVIAL_AMPLITUDE)

            trues = readings.get(float(p.value), [])
            if trues:
                best = min(trues, key=distance)
                rows.append((float(p.value), analytic[first], best[first], distance(best)))
            else:
                rows.append((float(p.value), analytic[first], math.nan, math.inf))
        out.extend(_crossings(name, rows, tol))
    return tuple(out)


#: Amplitudes below this are the trivial response x = 0 (as the analytic branches' TRIVIAL).
TRIVIAL_AMPLITUDE = 1e-12


def _crossings(name, rows, tol) -> list[Parting]:
    """Each passage from agreement (<= tol) to disagreement along the branch, either way; a
    branch that agrees nowhere parts at its first value (and says so)."""
    if rows and all(not row[3] <= tol for row in rows):
        first = min(rows, key=lambda r: r[0])
        least = min(row[3] for row in rows)
        note = f"the analytic branch is off the truth at every grid value (by {least:.3g} at least)"
        return [
            Parting(name, first[0], first[1], first[2], first[3], tol, math.nan, first[0], note)
        ]
    out = []
    for order in (rows, rows[::-1]):
        agreed = None
        for row in order:
            if row[3] <= tol:
                agreed = row
                continue
            if agreed is not None:
                out.append(_parting(name, agreed, row, tol))
            agreed = None
    unique = {}
    for p in out:
        unique.setdefault((round(p.before, 12), round(p.after, 12)), p)
    return sorted(unique.values(), key=lambda p: p.value)


def _parting(name, agreed, row, tol) -> Parting:
    v0, a0, t0, d0 = agreed
    v1, a1, t1, d1 = row
    if math.isfinite(d1) and d1 != d0:
        w = (tol - d0) / (d1 - d0)
    else:
        w = 0.0  # no true orbit at the next value: the parting is somewhere after the last agreement
    value = v0 + w * (v1 - v0)
    analytic = a0 + w * (a1 - a0)
    true = t0 + w * (t1 - t0) if math.isfinite(t1) else t0
    return Parting(name, value, analytic, true, d1, tol, v0, v1)
