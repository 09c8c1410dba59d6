"""Phase diagrams: how many steady states, and how many stable ones, over two parameters.

A driven problem's steady states are counted at every point of a grid over two of its parameters
x and y (e.g. the excitation frequency and the forcing, or the pump and the coupling) — the map
HarmonicBalance.jl draws as its phase diagram — on the sweep machinery: one task per line of the
grid, run on Dask (:func:`perturb.sweep.driver.run_calls`), the maps kept as an
:class:`xarray.Dataset` and written to a Zarr store.

* **Rows** (y fixed): the order-N frequency response along x (:func:`perturb.response.model.
  problem_response`: every branch continued from the certified first-order census through its
  folds, each point's stability from the Floquet multipliers along the order-N orbit) gives, at
  each grid value, the number of steady states (``n_states``), of stable ones (``n_stable``) and
  of marginal ones (``n_marginal``: a multiplier on the unit circle), and the special points the
  continuation located on the row: folds, branch points, Neimark-Sacker and period-doubling
  points — the boundaries of the map where they cross the row.
* **The proved count**: at every point the certified first-order census
  (:func:`perturb.steady.census.census`: every real root of the amplitude equations isolated in
  a box that holds exactly one, distinct orbits counted once): ``n_first_order``, and the stable
  ones by the first-order slow flow (Malkin: the Jacobian's eigenvalues in the left half-plane):
  ``n_stable_first_order`` — the first-order phase diagram, point by point, with nothing
  continued (HarmonicBalance.jl's, with a certificate for every root). On each row the exact
  first-order folds and branch points (:func:`perturb.steady.singular.singular_points`: the
  real solutions of {P₁ = 0, det J = 0}, told apart by the left null vector of J) are its
  boundaries.
* **Columns** (x fixed, optional): the same along y; their counts at every point are a second
  route to the rows' (``n_states_columns``, ``n_stable_columns``) and their special points the
  boundaries that run along the rows.
"""

from __future__ import annotations

import json
import time

import numpy as np
import sympy as sp

from perturb._defaults import SINGULAR_SECONDS
from perturb.errors import InvalidParameterError, PerturbError
from perturb.validation.capabilities import label_of

__all__ = ["SPECIAL_KINDS", "phase_diagram", "phase_line"]

#: Codes of the special points' kinds (``special_kind``); anything else is ``other``.
SPECIAL_KINDS = ("fold", "branch-point", "neimark-sacker", "period-doubling", "other")
#: A count that could not be had (the line's response failed there, or its census).
NOT_COUNTED = -1
#: Orders of the special points: located on a continued order-N curve, or exact first-order ones.
ORDER_N, FIRST_ORDER = 1, 0


class _FirstOrder:
    """The first-order census and slow flow of one line, compiled once (see the module notes)."""

    def __init__(self, problem):
        from perturb._lambdify import numpy_lambdify
        from perturb.method.driven import amplitude_equations
        from perturb.steady.census import shift_symmetry

        self.equations = amplitude_equations(problem.system(), 0)
        system = self.equations.system
        rows = [sp.expand(r) for r in self.equations.displacement(0)]
        unknowns = list(self.equations.amplitudes)
        self.parameters = list(system.parameters)
        jacobian = [[sp.diff(r, u) for u in unknowns] for r in rows]
        self.jacobian = numpy_lambdify([*unknowns, *self.parameters], jacobian)
        self.group = system.excitation.p * shift_symmetry(system)

    def count(self, case) -> tuple[int, int]:
        """``(states, stable)`` at ``case``'s point (certified roots; Malkin's stability)."""
        from perturb.method.driven import SLOW_FLOW_ZERO
        from perturb.steady.branches import exact_number
        from perturb.steady.census import census, distinct_orbits

        values = case.symbol_values
        fixed = {p: exact_number(values[p.name]) for p in self.parameters}
        roots, why = census(self.equations, fixed)
        if why:
            return NOT_COUNTED, NOT_COUNTED
        kept = distinct_orbits(roots, self.equations.harmonics, self.group)
        stable = 0
        args = [float(values[p.name]) for p in self.parameters]
        for i in kept:
            eig = np.linalg.eigvals(np.asarray(self.jacobian(*roots[i], *args), dtype=float))
            top = float(np.max(eig.real))
            stable += top < -SLOW_FLOW_ZERO * max(float(np.max(np.abs(eig))), 1e-300)
        return len(kept), stable

    def singular(self, case, along: str, low: float, high: float) -> tuple[list, str]:
        """The exact first-order folds and branch points on the line, ``[(kind, value)]``: found
        in the one system symbol ``along`` moves (over the range the case's map gives it on
        [low, high]) and carried back to ``along`` through the map's exact inverse."""
        from perturb.case.parameters import EPSILON_KEY
        from perturb.steady.branches import exact_number
        from perturb.steady.singular import singular_points

        names = {p.name: p for p in self.parameters}
        moved = [n for n in case.moves(along) if n != EPSILON_KEY and n in names]
        if len(moved) != 1:
            return [], f"the first-order boundaries need {along} to move one system parameter"
        swept = names[moved[0]]
        values = case.symbol_values
        fixed = {p: exact_number(values[p.name]) for p in self.parameters if p != swept}
        rows = [sp.expand(r.xreplace(fixed)) for r in self.equations.displacement(0)]
        s0, s1 = case.span(along, swept.name, low, high)
        found = singular_points(rows, self.equations.amplitudes, swept, s0, s1,
                                self.equations.coordinates, seconds=SINGULAR_SECONDS)  # fmt: skip

        def back(kind, value):  # a system value on the line: every user value that gives it
            return [
                (kind, v) for v in case.user_roots(along, swept.name, value) if low <= v <= high
            ]

        points = [p for v, _, _ in found.folds for p in back("fold", v)]
        points += [p for v, _, _ in found.branch_points for p in back("branch-point", v)]
        return points, found.why


def phase_line(problem, along: str, values, across: str, at: float, order: int, proved: bool):
    """One line of a phase diagram: ``problem`` with ``across`` = ``at``, swept along ``along``
    over ``values`` (see the module notes). Runs on a worker.

    Returns
    -------
    dict
        ``states``, ``stable``, ``marginal`` (order N, continued), ``first_order``,
        ``stable_first_order`` (per value, only when ``proved``), ``special`` (``[(kind, value,
        order)]`` inside the line), ``failures`` (strings), ``seconds``.
    """
    from perturb.response.model import problem_response

    clock = time.perf_counter()
    values = np.asarray(values, dtype=float)
    n = len(values)
    out = {key: [NOT_COUNTED] * n for key in
           ("states", "stable", "marginal", "first_order", "stable_first_order")}  # fmt: skip
    out.update(special=[], failures=[])
    case = problem.case().at(**{across: float(at)})
    where = f"{across} = {at:g}"
    try:
        result = problem_response(case.model, along, values, order=order)
    except PerturbError as exc:
        out["failures"].append(f"{where}: {' '.join(str(exc).split())}")
    else:
        response = result.response
        index = {float(v): i for i, v in enumerate(values)}
        for key in ("states", "stable", "marginal"):
            out[key] = [0] * n
        for point in response.points:
            i = index[float(point.value)]
            out["states"][i] += 1
            out["stable"][i] += point.stable is True
            out["marginal"][i] += point.stable is None
        out["failures"] += [f"{where}: {f}" for f in response.failures]
        out["special"] = [(s.kind, float(s.value), ORDER_N) for s in response.special if s.inside]
    first = _FirstOrder(problem)
    if proved:
        for i, v in enumerate(values):
            counted = first.count(case.at(**{along: float(v)}))
            out["first_order"][i], out["stable_first_order"][i] = counted
    points, why = first.singular(case, along, float(values[0]), float(values[-1]))
    out["special"] += [(kind, value, FIRST_ORDER) for kind, value in points]
    if why:
        out["failures"].append(f"{where}: the first-order boundaries: {why}")
    out["seconds"] = time.perf_counter() - clock
    return out


def _axes(problem, grid) -> list[tuple[str, np.ndarray]]:
    from perturb.sweep.api import axes_of
    from perturb.sweep.grid import check_names

    axes = axes_of(grid)
    if len(axes) != 2:
        raise InvalidParameterError(
            f"`grid` = {[a.name for a in axes]}: a phase diagram needs two axes, e.g. "
            "--grid Omega=0.98:1.1:41 --grid F=0.5:2:21"
        )
    check_names(
        axes, list(problem.values), label_of(problem),
        advice=lambda name: problem.case().map.set_by(name, "sweep"),
    )  # fmt: skip
    out = []
    for axis in axes:
        values = np.asarray(axis.values, dtype=float)
        if values.size < 2 or not np.all(np.diff(values) > 0):
            raise InvalidParameterError(
                f"--grid {axis.name}: give at least 2 increasing values (START:STOP:N, N >= 2)"
            )
        out.append((axis.name, values))
    if out[0][0] == out[1][0]:
        raise InvalidParameterError(f"--grid {out[0][0]} twice: give two different parameters")
    return out


def phase_diagram(
    problem,
    grid,
    *,
    order: int = 1,
    columns: bool = True,
    proved: bool = True,
    output=None,
    workers: int | None = None,
    scheduler: str | None = None,
    client=None,
    timeout: float | None = None,
    yes: bool = False,
):
    """The phase diagram of a driven ``problem`` over two of its parameters.

    Parameters
    ----------
    problem
        A driven problem (its other parameters at their values).
    grid : sequence of str or mapping
        The two axes, x first: ``["Omega=1.98:2.02:21", "h=0.5:3:11"]`` (``NAME=START:STOP:N``).
    order : int
        The order N of the responses along the lines.
    columns : bool
        Also continue along y at every x (a second count at every point, and the boundaries
        that run along x).
    proved : bool
        Count the certified first-order steady states at every point (``n_first_order``).
    output : path, optional
        A Zarr store to write (a new one, or a perturb store there replaced).
    workers, scheduler, client, timeout
        As for :func:`perturb.sweep` (a LocalCluster of ``workers`` processes by default).
    yes : bool
        Confirm a request past :func:`perturb.cost.check_cost`'s limits (the points of the grid,
        the responses along its lines).

    Returns
    -------
    xarray.Dataset
        Dimensions y and x (named by the parameters); variables ``n_states``, ``n_stable``,
        ``n_marginal``, ``n_first_order``, ``n_stable_first_order`` (``-1``: not counted), with
        ``columns`` ``n_states_columns`` and ``n_stable_columns``; the special points
        ``special_x``, ``special_y``, ``special_kind`` (codes of :data:`SPECIAL_KINDS`),
        ``special_line`` (the row's or the column's), ``special_order`` (first order exact, or
        order N continued), meanings in their attributes, along dimension ``special``; attributes
        ``problem``, ``order``, ``parameters``, ``failures`` (JSON) and ``seconds``.

    Raises
    ------
    perturb.errors.InvalidParameterError
        Not two axes, an unknown parameter, a problem that is not driven, values the problem
        refuses, an ``output`` that exists, a request too large without ``yes`` (checked before
        any work).
    perturb.errors.MissingDependencyError
        The extra ``perturb[sweep]`` is not installed.

    Examples
    --------
    HarmonicBalance.jl's coupled parametrons over the pump's frequency and depth (the counts of
    stable states at every point, the first-order ones certified):

    >>> import perturb
    >>> from problems import get_problem
    >>> pair = get_problem("coupled-parametrons").create()
    >>> ds = perturb.phase_diagram(pair, ["Omega=1.98:2.02:21", "h=0.1:2.9:15"])  # doctest: +SKIP
    >>> ds.n_stable_first_order.sel(h=2.1, method="nearest").values.tolist()  # doctest: +SKIP
    [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 4, 4, 4, 5, 5, 5]

    (30 minutes on 2 shared cores: ``docs/forced.md``.)
    """
    from perturb._defaults import SWEEP_CONNECT_SECONDS
    from perturb.response.model import check_request
    from perturb.sweep.api import require_extra

    require_extra()
    if output is not None:
        from perturb.sweep.store import check_new_store

        check_new_store(output)
    (x_name, xs), (y_name, ys) = _axes(problem, grid)
    check_request(problem, x_name)
    from perturb.cost import Cost, census_seconds, check_cost, modes_of, response_cost

    case = problem.case()
    modes = modes_of(problem)
    seconds = ys.size * response_cost(xs.size, order, shots=0, modes=modes).seconds
    if columns:
        seconds += xs.size * response_cost(ys.size, order, shots=0, modes=modes).seconds
    if proved:  # the certified first-order count at every point
        seconds += xs.size * ys.size * census_seconds(modes)
    what = f"{xs.size * ys.size:,} points" + (f" of {modes} modes" if modes > 1 else "")
    check_cost(Cost(what, xs.size * ys.size, seconds), yes)
    for name, values in ((x_name, xs), (y_name, ys)):
        for value in values:  # the problem's own checks at every value (one line, exit 2)
            case.at(**{name: float(value)})
    from perturb.sweep.driver import Cluster, run_calls

    calls = [(x_name, xs, y_name, float(y), order, proved) for y in ys]
    if columns:
        calls += [(y_name, ys, x_name, float(x), order, False) for x in xs]
    clock = time.perf_counter()
    wait = SWEEP_CONNECT_SECONDS if timeout is None else timeout
    with Cluster(workers, scheduler, client, wait) as cluster:
        results = run_calls(cluster, phase_line, problem, calls, label=f"phase {label_of(problem)}")
    seconds = time.perf_counter() - clock
    dataset = _assemble(problem, order, (x_name, xs), (y_name, ys), results, columns, seconds)
    if output is not None:
        from perturb.sweep.store import open_dataset, write_dataset

        write_dataset(dataset, output)
        return open_dataset(output)
    return dataset


def _assemble(problem, order, x_axis, y_axis, results, columns: bool, seconds: float):
    from perturb.sweep.memory import dataset_of
    from perturb.sweep.store import MARK

    (x_name, xs), (y_name, ys) = x_axis, y_axis
    shape = (len(ys), len(xs))
    maps = {
        name: np.full(shape, NOT_COUNTED, dtype=np.int16)
        for name in ("n_states", "n_stable", "n_marginal", "n_first_order", "n_stable_first_order")
    }
    if columns:
        for name in ("n_states_columns", "n_stable_columns"):
            maps[name] = np.full(shape, NOT_COUNTED, dtype=np.int16)
    special, failures, cpu = [], [], 0.0
    for k, result in enumerate(results):
        row = k < len(ys)
        if isinstance(result, BaseException):
            at = ys[k] if row else xs[k - len(ys)]
            failures.append(f"{y_name if row else x_name} = {at:g}: the task failed ({result})")
            continue
        cpu += result["seconds"]
        failures += result["failures"]
        if row:
            for key, name in (
                ("states", "n_states"),
                ("stable", "n_stable"),
                ("marginal", "n_marginal"),
                ("first_order", "n_first_order"),
                ("stable_first_order", "n_stable_first_order"),
            ):
                maps[name][k, :] = result[key]
            special += [(v, float(ys[k]), kind, 0, o) for kind, v, o in result["special"]]
        else:
            j = k - len(ys)
            maps["n_states_columns"][:, j] = result["states"]
            maps["n_stable_columns"][:, j] = result["stable"]
            special += [(float(xs[j]), v, kind, 1, o) for kind, v, o in result["special"]]
    counts = "steady states at the point"
    meanings = {
        "n_states": f"{counts} (order-N responses continued along {x_name})",
        "n_stable": f"stable {counts} (Floquet multipliers along the order-N orbit)",
        "n_marginal": f"{counts} with a multiplier on the unit circle",
        "n_first_order": f"{counts} of the first-order amplitude equations, certified (proved)",
        "n_stable_first_order": f"stable {counts} of the first-order equations (slow flow)",
        "n_states_columns": f"{counts} (order-N responses continued along {y_name})",
        "n_stable_columns": f"stable {counts} (continued along {y_name})",
    }
    data = {
        name: ((y_name, x_name), values, {"long_name": meanings[name], "missing": NOT_COUNTED})
        for name, values in maps.items()
    }
    codes = {kind: i for i, kind in enumerate(SPECIAL_KINDS)}
    data["special_x"] = (("special",), np.array([p[0] for p in special], dtype=float), {})
    data["special_y"] = (("special",), np.array([p[1] for p in special], dtype=float), {})
    data["special_kind"] = (
        ("special",),
        np.array([codes.get(p[2], codes["other"]) for p in special], dtype=np.int8),
        {"meanings": json.dumps(dict(enumerate(SPECIAL_KINDS)))},
    )
    data["special_line"] = (
        ("special",),
        np.array([p[3] for p in special], dtype=np.int8),
        {"meanings": json.dumps({0: f"along {x_name}", 1: f"along {y_name}"})},
    )
    data["special_order"] = (
        ("special",),
        np.array([p[4] for p in special], dtype=np.int8),
        {
            "meanings": json.dumps(
                {FIRST_ORDER: "first order, exact", ORDER_N: "order N, continued"}
            )
        },
    )
    fixed = {k: float(v) for k, v in problem.values.items() if k not in (x_name, y_name)}
    attrs = {
        MARK: json.dumps({"kind": "phase-diagram"}),
        "problem": label_of(problem),
        "order": int(order),
        "parameters": json.dumps(fixed),
        "failures": json.dumps(failures),
        "seconds": float(seconds),
        "task_cpu_seconds": float(cpu),
    }
    coords = {x_name: np.asarray(xs, dtype=float), y_name: np.asarray(ys, dtype=float)}
    return dataset_of(coords, data, attrs)
