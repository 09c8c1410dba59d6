"""The frequency response of a driven system: every branch, its stability, its folds.

For each value of the swept parameter (the detuning σ, the excitation frequency Ω, the forcing
level …), the first-order amplitude equations :math:`P_1(a, b) = 0`
(:func:`perturb.method.driven.amplitude_equations`, derived once with every parameter symbolic)
are solved for **every** real root with exact rational coefficients
(:func:`perturb.response.roots.real_roots`: the count is proved). Each root is

* continued to order N on the displacement function :math:`D_N = \\sum_{k\\le N+1}
  \\varepsilon^{k-1} P_k` by Newton's method started at that exact root (ε small: the root moves by
  O(ε)); near a fold, where the first-order roots merge, the continuation may not converge and the
  point keeps its first-order amplitudes with that said in its ``note``;
* judged stable or not by the slow flow's Jacobian (:func:`perturb.method.driven.slow_flow`, Malkin).

The **folds** (saddle-node points, where a branch turns and the response jumps) are where the
first-order roots meet: the real solutions of :math:`\\{P_1 = 0, \\det \\partial P_1/\\partial(a,
b) = 0\\}` in (a, b, σ), found by the same exact elimination. Branches are traced across the grid
by the nearest root (:func:`trace_branches`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import sympy as sp
from attrs import field, frozen

from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import AmplitudeEquations
from perturb.response.branches import BranchPoint, branches_at, exact_number
from perturb.response.singular import singular_points

__all__ = ["Fold", "FrequencyResponse", "ResponsePoint", "frequency_response", "trace_branches"]


@frozen
class ResponsePoint:
    """One steady-state response at one value of the swept parameter.

    Attributes
    ----------
    value : float
        The swept parameter's value.
    amplitudes : dict
        ``{"a_x": ..., "b_x": ...}``: the cosine and sine amplitudes (strained time) at order N.
    norms : dict
        ``{coordinate: sqrt(a**2 + b**2)}`` of each resonant coordinate's first harmonic.
    stable : bool or None
        From the slow flow (None: on a fold, or undamped).
    eigenvalues : tuple of complex
        The slow flow's eigenvalues (per unit of ε per period).
    multipliers : tuple of complex
        The Floquet multipliers they predict.
    first_order : dict
        The first-order root it was continued from.
    note : str
        Empty, or why the order-N continuation kept the first-order amplitudes.
    """

    value: float = field(converter=float)
    amplitudes: dict
    norms: dict
    stable: bool | None
    eigenvalues: tuple = field(converter=tuple)
    multipliers: tuple = field(converter=tuple)
    first_order: dict = field(factory=dict)
    note: str = ""

    @classmethod
    def of(cls, value: float, branch: BranchPoint) -> ResponsePoint:
        """The branch point ``branch`` at the swept value ``value``."""
        return cls(
            value, branch.amplitudes, branch.norms, branch.stable, branch.eigenvalues,
            branch.multipliers, branch.first_order, branch.note,
        )  # fmt: skip

    def norm(self, coordinate: str | None = None) -> float:
        """The response amplitude of ``coordinate`` (default: the first resonant one)."""
        if coordinate is None:
            return next(iter(self.norms.values()))
        return self.norms[coordinate]


@frozen
class Fold:
    """A saddle-node point of the response: where two branches meet.

    ``value`` is the fold of the order-N response (continued from the exact first-order fold,
    ``first_order``); ``note`` says when the continuation did not converge (then both agree).
    """

    value: float = field(converter=float)
    amplitudes: dict
    norms: dict
    first_order: float = field(default=math.nan, converter=float)
    note: str = ""


@frozen
class FrequencyResponse:
    """Every steady-state branch over a sweep (see the module docstring).

    Attributes
    ----------
    system : str
    parameter : str
        The swept parameter's name.
    order : int
    epsilon : float
    values : dict
        The other parameters' values.
    grid : tuple of float
        The swept values.
    points : tuple of ResponsePoint
        Every root at every grid value, in grid order.
    folds : tuple of Fold
        Inside the swept range, sorted.
    failures : tuple of str
        Grid values where the roots could not be enumerated, with the reason (never dropped
        silently).
    coordinates : tuple of str
        The resonant coordinates.
    branch_points : tuple of Fold
        Where a branch crosses another and goes on (a symmetric response losing its symmetry, a
        mode at rest starting to move, a trivial response at the edge of its tongue), sorted
        (:mod:`perturb.response.singular`).
    """

    system: str
    parameter: str
    order: int
    epsilon: float = field(converter=float)
    values: dict
    grid: tuple = field(converter=tuple)
    points: tuple = field(converter=tuple)
    folds: tuple = field(converter=tuple)
    failures: tuple = field(converter=tuple, factory=tuple)
    coordinates: tuple = field(converter=tuple, factory=tuple)
    branch_points: tuple = field(converter=tuple, factory=tuple)

    def at(self, value: float) -> tuple[ResponsePoint, ...]:
        """The responses at the grid value nearest ``value``."""
        nearest = min(self.grid, key=lambda g: abs(g - value))
        return tuple(p for p in self.points if p.value == nearest)

    def branches(self, coordinate: str | None = None) -> list[list[ResponsePoint]]:
        """The points traced into continuous branches (:func:`trace_branches`)."""
        return trace_branches(self.points, self.grid, coordinate)


def frequency_response(
    equations: AmplitudeEquations,
    parameter: str,
    grid: Sequence[float],
    values: Mapping[str, float],
    epsilon: float,
    order: int = 1,
) -> FrequencyResponse:
    """Every branch of the steady-state response over ``grid`` values of ``parameter``.

    Parameters
    ----------
    equations : AmplitudeEquations
        Of the driven system, to at least ``order`` (:func:`amplitude_equations`).
    parameter : str
        The swept parameter: one of the system's parameters (σ, a forcing level…).
    grid : sequence of float
    values : mapping
        Values of every other parameter of the system.
    epsilon : float
        ε (> 0).
    order : int
        The order of the state (0: the first-order response equations only).

    Returns
    -------
    FrequencyResponse

    Raises
    ------
    InvalidParameterError
        An unknown swept parameter or a missing value.

    Examples
    --------
    >>> import numpy as np
    >>> from problems import get_problem
    >>> from perturb import amplitude_equations, frequency_response
    >>> system = get_problem("forced-duffing").system()
    >>> response = frequency_response(
    ...     amplitude_equations(system, 0), "sigma", np.linspace(0.0, 2.0, 5),
    ...     {"zeta": 0.1, "gamma": 1.0, "F": 1.0}, epsilon=0.05, order=0)
    >>> [len(response.at(value)) for value in response.grid]  # one branch, then three
    [1, 1, 3, 3, 3]
    >>> [round(fold.value, 4) for fold in response.folds]
    [0.8497]
    """
    system = equations.system
    names = {p.name: p for p in system.parameters}
    if parameter not in names:
        raise bad_value(
            "parameter", parameter, f"sweep one of the system's parameters {sorted(names)}",
            InvalidParameterError,
        )  # fmt: skip
    missing = sorted(set(names) - {parameter} - set(values))
    if missing:
        raise bad_value("values", dict(values), f"give values for {missing}", InvalidParameterError)
    swept = names[parameter]
    fixed = {names[k]: exact_number(v) for k, v in values.items() if k in names and k != parameter}
    first = [sp.expand(e.xreplace(fixed)) for e in equations.displacement(0)]
    unknowns = list(equations.amplitudes)
    points, failures = [], []
    for value in grid:
        at = {**{k.name: v for k, v in fixed.items()}, parameter: exact_number(value)}
        found, why = branches_at(equations, at, epsilon, order)
        if why:
            failures.append(f"{parameter} = {value:g}: {why}")
        points.extend(ResponsePoint.of(float(value), branch) for branch in found)
    folds, branch_points = _singular(first, unknowns, swept, min(grid), max(grid), equations)
    return FrequencyResponse(
        system=system.name,
        parameter=parameter,
        order=order,
        epsilon=float(epsilon),
        values={k.name: float(v) for k, v in fixed.items()},
        grid=tuple(float(g) for g in grid),
        points=tuple(points),
        folds=tuple(folds),
        failures=tuple(failures),
        coordinates=equations.coordinates,
        branch_points=tuple(branch_points),
    )


def _folds(first, unknowns, swept, low, high, equations) -> list[Fold]:
    """Where a branch turns: the folds of :func:`_singular` (its branch points left out)."""
    return _singular(first, unknowns, swept, low, high, equations)[0]


def _singular(first, unknowns, swept, low, high, equations) -> tuple[list[Fold], list[Fold]]:
    """Folds and branch points: {P1 = 0, det J = 0} in (amplitudes, swept), exactly, each told
    apart by the left null vector of J (:mod:`perturb.response.singular`); a point where a mode at
    rest starts to move is a branch point by either test."""
    found = singular_points(first, unknowns, swept, low, high, equations.coordinates)
    jac = sp.Matrix([[sp.diff(e, u) for u in unknowns] for e in first]) if found.folds else None
    folds, branch_points = [], []
    for value, amplitudes, norms in found.folds:
        root = {**{u: amplitudes[u.name] for u in unknowns}, swept: value}
        kind = branch_points if _branch_point(jac, root, unknowns, norms) else folds
        kind.append(Fold(value, amplitudes, norms, value))
    branch_points += [Fold(v, a, n, v) for v, a, n in found.branch_points]
    return folds, sorted(branch_points, key=lambda f: f.value)


#: Relative distance below which two folds are one: the same value and the same amplitude of
#: every coordinate (a shift by a forcing period rotates the phases, never the norms); the roots
#: come from one certified isolation, far finer than this.
SAME_FOLD = 1e-9


def _same_orbit(fold: Fold, value: float, norms: dict) -> bool:
    pairs = [(fold.value, value), *((fold.norms[c], n) for c, n in norms.items())]
    return all(abs(p - q) <= SAME_FOLD * max(1.0, abs(p)) for p, q in pairs)


#: Share of the Jacobian's null vector on the amplitudes of the modes at rest above which a root of
#: {P1 = 0, det J = 0} is a branch point, not a fold: the null vector leaves the invariant subspace
#: (at a fold within it the share is zero, at a branch point one: any value between is far from both).
BRANCH_SHARE = 0.5


def _branch_point(jac, root, unknowns, norms) -> bool:
    """Whether a singular root lies where a coordinate at rest starts to move (a pitchfork off the
    invariant subspace where it is zero), which stability reports, rather than on a turn of a branch
    inside that subspace."""
    import numpy as np

    resting = [c for c, n in norms.items() if n == 0]
    if not resting:
        return False
    matrix = np.array(jac.xreplace(dict(root)).evalf(), dtype=float)
    null = np.linalg.svd(matrix)[2][-1]
    share = sum(
        null[i] ** 2
        for i, u in enumerate(unknowns)
        if any(u.name in (f"a_{c}", f"b_{c}") for c in resting)
    )
    return share > BRANCH_SHARE


#: Newton iterations of a fold's continuation to order N.
FOLD_ITERATIONS = 20


def continue_fold(fold: Fold, equations, order: int, fixed: dict, swept, epsilon: float) -> Fold:
    """The order-N fold near a first-order one: Newton on {D_N = 0, det dD_N/d(a, b) = 0} in the
    amplitudes and the swept parameter, started at the exact first-order fold.

    D_N and its Jacobian are the compiled functions (:mod:`perturb.response.compiled`); the
    derivatives of the bordered system in (a, b, swept) are central differences of them (the
    determinant of a 4 x 4 Jacobian of the forced pair, written out and differentiated
    symbolically, took 215 s)."""
    import numpy as np

    from perturb.response.compiled import compiled

    if order == 0:
        return fold
    ready = compiled(equations, order)
    values = {p.name: float(v) for p, v in fixed.items()}
    names = [a.name for a in equations.amplitudes]
    n = len(names)

    def system(x):
        at = {**values, swept.name: float(x[-1])}
        rows = ready.residual(x[:n], at, epsilon)
        return np.append(rows, np.linalg.det(ready.jacobian(x[:n], at, epsilon)))

    def derivative(x):
        columns = []
        for j in range(n + 1):
            h = FOLD_STEP * max(1.0, abs(x[j]))
            up, down = x.copy(), x.copy()
            up[j] += h
            down[j] -= h
            columns.append((system(up) - system(down)) / (2 * h))
        return np.array(columns).T

    x = np.array([*(fold.amplitudes[a] for a in names), fold.value], dtype=float)
    start = x.copy()
    for _ in range(FOLD_ITERATIONS):
        residual = system(x)
        if np.max(np.abs(residual)) <= 1e-12 * max(1.0, float(np.max(np.abs(x)))):
            break
        try:
            x = x + np.linalg.lstsq(derivative(x), -residual, rcond=None)[0]
        except np.linalg.LinAlgError:
            break
    residual = system(x)
    moved = float(np.max(np.abs(x - start)))
    if (
        not np.all(np.isfinite(x))
        or np.max(np.abs(residual)) > 1e-9
        or moved > 0.5 * max(1.0, float(np.max(np.abs(start))))
    ):
        return Fold(fold.value, fold.amplitudes, fold.norms, fold.value,
                    f"the order-{order} fold did not converge: first-order value kept")  # fmt: skip
    amplitudes = {a: float(v) for a, v in zip(names, x, strict=False)}
    norms = {
        c: math.hypot(amplitudes[f"a_{c}"], amplitudes[f"b_{c}"]) for c in equations.coordinates
    }
    return Fold(float(x[-1]), amplitudes, norms, fold.value)


#: Relative step of the central differences in :func:`continue_fold` (the functions are smooth
#: polynomials evaluated in double precision: ~eps**(1/3) balances truncation and rounding).
FOLD_STEP = 1e-5


def trace_branches(points, grid, coordinate: str | None = None) -> list[list[ResponsePoint]]:
    """Join the roots of neighbouring grid values into continuous branches.

    Between two folds the roots keep their order in amplitude (two roots of the response
    equations meet only at a fold), so equal counts are matched rank by rank. Where the count
    changes, a fold was crossed: the roots that appear (or disappear) are chosen among the
    adjacent pairs by the least total distance to the others' predicted amplitudes (linear
    extrapolation of each branch). A plotting aid: the points themselves are exact.
    """
    from itertools import combinations

    by_value: dict[float, list] = {}
    for p in points:
        by_value.setdefault(p.value, []).append(p)
    branches: list[list] = []
    open_: list[list] = []

    def predicted(branch, value):
        if len(branch) < 2:
            return branch[-1].norm(coordinate)
        (a, b) = branch[-2], branch[-1]
        if b.value == a.value:
            return b.norm(coordinate)
        slope = (b.norm(coordinate) - a.norm(coordinate)) / (b.value - a.value)
        return b.norm(coordinate) + slope * (value - b.value)

    for value in sorted(by_value):
        here = sorted(by_value[value], key=lambda p: p.norm(coordinate))
        guesses = [predicted(b, value) for b in open_]
        n, m = len(open_), len(here)
        best, best_cost = None, math.inf
        if m >= n:  # choose which of the current roots continue the open branches
            for kept in combinations(range(m), n):
                cost = sum(
                    abs(here[j].norm(coordinate) - g) for j, g in zip(kept, guesses, strict=True)
                )
                if cost < best_cost:
                    best, best_cost = [(i, j) for i, j in enumerate(kept)], cost
        else:  # choose which open branches end here
            for kept in combinations(range(n), m):
                cost = sum(abs(here[j].norm(coordinate) - guesses[i]) for j, i in enumerate(kept))
                if cost < best_cost:
                    best, best_cost = [(i, j) for j, i in enumerate(kept)], cost
        continued = dict(best or [])
        next_open = []
        taken = set(continued.values())
        for i, j in sorted(continued.items(), key=lambda item: item[1]):
            open_[i].append(here[j])
        for j, p in enumerate(here):
            if j in taken:
                continue
            branch = [p]
            branches.append(branch)
        for j, p in enumerate(here):
            owner = next((open_[i] for i, jj in continued.items() if jj == j), None)
            if owner is None:
                owner = next(b for b in branches if b[-1] is p)
            next_open.append(owner)
        open_ = next_open
    return branches
