"""The lazy pipeline of a scene: :func:`run_scene` computes only what the scene's outputs need.

=======================================  =============================================
computed                                 only when the scene asks for
=======================================  =============================================
the analytic solution                    always (the summary's first line)
the analytic state over the horizon      ``table``, or a plot of the state
the true trajectory (an integration)     the ``time_series``, ``error``, ``phase`` plots
the validation (integrations, shooting)  ``validation``, the ``convergence`` plot
the work–precision runs                  ``work_precision`` (table or plot)
the sweep over ``[sweep]``'s grid        ``sweep``, a validity map (on Dask, in memory)
the frequency response of ``[response]`` ``response``, its plots (every branch, folds, backbone)
the Euler angles                         ``euler``, the ``euler``/``orientation`` plots
=======================================  =============================================

The problem comes in already loaded, as a :class:`perturb.validation.Model` (the CLI loads it with
``problems.load_problem``: ``perturb`` never imports ``problems``). The result,
:class:`SceneResult`, holds data only; :mod:`perturb.report.scene_output` writes it to a folder.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable

import attrs
import numpy as np
from attrs import field, frozen

from perturb.cache import held_warnings
from perturb.domain import series_domain
from perturb.progress import track
from perturb.scene.spec import Scene
from perturb.solution import PeriodicSolution
from perturb.validation.capabilities import has_euler_angles, label_of
from perturb.validation.model import Model, parameter_value_of
from perturb.validation.system_model import as_model

__all__ = ["SceneResult", "check_scene", "run_scene", "with_order"]


def with_order(scene: Scene, problem) -> Scene:
    """``scene`` with its order: its own ``[solve] order``, else the one default order of every
    command for ``problem``'s kind (:attr:`perturb.validation.frames.FrameWork.default_order`:
    3 for a driven problem, 1 for a free one).

    Examples
    --------
    >>> from perturb.scene import parse_scene
    >>> from problems import get_problem
    >>> scene = parse_scene('[problem]\\nname = "forced-duffing"')
    >>> with_order(scene, get_problem("forced-duffing").create()).order
    3
    """
    if scene.order is not None:
        return scene
    from perturb.validation.frames import work_of

    model = as_model(problem)
    return attrs.evolve(scene, order=work_of(model.system()).default_order)


@frozen
class SceneResult:
    """What a scene computed (data only; every entry not asked for is None).

    Attributes
    ----------
    scene : Scene
    label : str
        The problem's name in reports.
    parameters : dict
        Every parameter value in force (defaults included).
    epsilon : float
    solution : PeriodicSolution
    failure : str
        Why the analytic solution cannot be used ("" when it can).
    period : float
        The analytic period in physical time (NaN on failure).
    t : ndarray or None
        The times of the tables and plots: ``scene.periods`` periods, ``scene.samples`` a period.
    state : dict or None
        The analytic state at ``t``, by name.
    truth : dict or None
        The true state at ``t`` (the original equations integrated from the analytic initial
        state), by name; cut where the integration stopped.
    truth_integrator : str
        The integrator of ``truth``.
    euler : dict or None
        The Euler angles of the analytic solution at ``t``.
    validation : perturb.validation.ValidationReport or None
    work_precision : perturb.workprecision.WorkPrecision or None
    sweep : xarray.Dataset or None
        The ``[sweep]``'s points (:func:`perturb.sweep`), kept in memory.
    response : perturb.response.model.ProblemResponse or None
        The ``[response]``'s frequency response (every branch, its stability, the folds, the
        backbone, the points shot against the true motion).
    notes : tuple of str
        Warnings raised while computing, and steps skipped with the reason.
    computed : tuple of str
        The steps run, in order (``"solve"``, ``"state"``, ``"truth"``, ``"euler"``,
        ``"validation"``, ``"work_precision"``, ``"sweep"``, ``"response"``).
    seconds : dict
        Wall time of each step.
    """

    scene: Scene
    label: str
    parameters: dict
    epsilon: float
    solution: PeriodicSolution
    failure: str = ""
    period: float = math.nan
    t: np.ndarray | None = field(default=None, eq=False)
    state: dict | None = field(default=None, eq=False)
    truth: dict | None = field(default=None, eq=False)
    truth_integrator: str = ""
    euler: dict | None = field(default=None, eq=False)
    validation: object | None = None
    work_precision: object | None = None
    sweep: object | None = field(default=None, eq=False)
    response: object | None = field(default=None, eq=False)
    notes: tuple = ()
    computed: tuple = ()
    seconds: dict = field(factory=dict, eq=False)

    @property
    def success(self) -> bool:
        """Whether the analytic solution was constructed and, if validated, not found invalid."""
        if self.failure:
            return False
        return self.validation is None or bool(self.validation.completed)


def _truth(model: Model, solution, t: np.ndarray, integrator) -> tuple[dict, str, str]:
    """The original equations integrated from the analytic initial state over ``t``."""
    from perturb.oracle import choose
    from perturb.validation import DEFAULT_RTOL, STIFFNESS_SAMPLES, stiffness_indicator
    from perturb.validation.checks import analytic_states
    from perturb.validation.truth import original_equations

    names = tuple(model.state_names())
    y0 = analytic_states(model, solution, np.zeros(1))[:, 0]
    equations = original_equations(model, y0)
    period = float(model.period(solution))
    with np.errstate(all="ignore"):
        samples = analytic_states(
            model, solution, np.linspace(0.0, period, STIFFNESS_SAMPLES, endpoint=False)
        )
    stiff = stiffness_indicator(equations.rhs, samples, period).stiff
    solver = choose(integrator, rtol=DEFAULT_RTOL, stiff=stiff, symbolic=equations.symbolic)
    traj = solver.integrate(equations.rhs, (0.0, float(t[-1])), y0, t_eval=t)
    y = np.asarray(traj.y, dtype=float)
    note = "" if traj.success else (
        f"the true trajectory stopped at t = {traj.t_reached:.6g} ({traj.message}); the plots "
        "show it up to there"
    )  # fmt: skip
    return {n: y[i] for i, n in enumerate(names)}, traj.integrator or solver.name, note


def check_scene(scene: Scene, problem, yes: bool = False) -> None:
    """Raise if ``scene`` asks ``problem`` for what it cannot give, or for more work than it
    should do unconfirmed (``yes``; :mod:`perturb.cost`), before anything is computed.

    Raises
    ------
    perturb.errors.SceneError
        Euler angles (``euler``, the ``euler``/``orientation`` plots) of a problem without them.
    perturb.errors.UnknownNameError
        An unknown ``[solve] integrator`` of a scene that integrates.
    perturb.errors.SceneError
        A ``[response]`` of a problem that is not driven, over a parameter it does not have or
        also set in ``[parameters]``; a ``[response]`` and
        ``[sweep]`` estimated past :data:`perturb._defaults.CONFIRM_SECONDS` of work without
        ``yes``.
    """
    model = as_model(problem)
    scene = with_order(scene, model)
    outputs = scene.outputs
    from perturb.cost import modes_of

    _check_cost(scene, yes, modes_of(problem))
    if scene.response is not None and outputs.needs_response:
        from perturb.errors import InvalidParameterError
        from perturb.response.model import check_request, parse_sweep

        name, _ = parse_sweep(scene.response.sweep, "sweep")
        try:
            check_request(problem, name)
        except InvalidParameterError as exc:
            raise scene.error(f"[response] {exc}") from None
        if name in scene.parameters:
            raise scene.error(
                f"[response] sweep = {scene.response.sweep!r}: {name!r} is also set in "
                "[parameters]; sweep it or set it, not both"
            )
    if outputs.needs_euler and not has_euler_angles(model):
        asked = ["euler = true"] if outputs.euler else []
        asked += [f"plot {p!r}" for p in outputs.plots if p in ("euler", "orientation")]
        raise scene.error(
            f"[outputs] {' and '.join(asked)}: problem {label_of(model)!r} has no Euler angles "
            "(rigid bodies only); remove it from [outputs]"
        )
    if scene.integrator is not None and (
        outputs.needs_truth_trajectory or outputs.needs_validation
    ):
        from perturb.oracle import choose

        choose(scene.integrator)  # an unknown name fails here, before any work


def _check_cost(scene: Scene, yes: bool, modes: int = 1) -> None:
    """The scene's expensive sections, estimated together (:func:`perturb.cost.check_cost`;
    ``modes``: the problem's, for the certified census of a ``[response]``)."""
    from perturb.cost import Cost, check_cost, response_cost, sweep_cost
    from perturb.errors import InvalidParameterError

    outputs = scene.outputs
    cost = Cost("", 0, 0.0)
    parts = []
    if scene.response is not None and outputs.needs_response:
        from perturb.axis import axis_size

        values = axis_size(scene.response.sweep, "sweep")  # counted, not made again
        parts.append(response_cost(values, scene.order, scene.response.validate, 0, modes))
    if scene.sweep is not None and outputs.needs_sweep:
        from perturb.axis import axis_size

        size = math.prod(axis_size(a) for a in scene.sweep.grid)  # counted, not made
        parts.append(sweep_cost(size, scene.order, scene.sweep.validate, len(scene.sweep.times)))
    for part in parts:
        cost = part if not cost.what else cost + part
    try:
        check_cost(cost, yes)
    except InvalidParameterError as exc:
        fix = "perturb report --yes (yes=True in Python)"
        raise scene.error(str(exc).replace("--yes (yes=True in Python)", fix)) from None


def run_scene(scene: Scene, problem, yes: bool = False) -> SceneResult:
    """Compute what ``scene`` asks for, and nothing else (see the module docstring).

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`perturb.scene.read_scene`); without an order, the default order
        of ``problem``'s kind (:func:`with_order`), which ``result.scene`` carries.
    problem : perturb.validation.Model
        The scene's problem, already created with the scene's parameters (and family).
    yes : bool
        Confirm sections estimated past an hour of work (:mod:`perturb.cost`).

    Returns
    -------
    SceneResult
        A failed construction is ``result.failure`` (never an exception); the validation's own
        outcome is in ``result.validation``.

    Raises
    ------
    perturb.errors.SceneError
        Euler angles asked of a problem that has none (before anything is computed).
    perturb.errors.UnknownNameError
        An unknown integrator name (from the oracle, before any integration).
    """
    model = as_model(problem)
    scene = with_order(scene, model)
    check_scene(scene, model, yes)
    outputs = scene.outputs

    state: dict = {"notes": [], "computed": [], "seconds": {}}
    values: dict = {}

    def step(name: str, work: Callable[[], object]) -> None:
        clock = time.perf_counter()
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            values[name] = work()
        state["seconds"][name] = time.perf_counter() - clock
        state["computed"].append(name)
        for w in caught:
            if str(w.message) not in state["notes"]:
                state["notes"].append(str(w.message))

    step("solve", lambda: model.solve(scene.order))
    solution = values["solve"]
    failure = ""
    if not solution.success:
        failure = f"{solution.status.value}: {solution.message}"
    else:
        domain = series_domain(solution, parameter_value_of(model), model.symbol_values())
        if not domain.ok:
            failure = "the series is outside its domain: " + "; ".join(domain.reasons)
    period = math.nan if failure else float(model.period(solution))

    t = None
    todo: list[tuple[str, Callable[[], object]]] = []
    if not failure and (outputs.needs_state or outputs.needs_euler):
        n = int(math.ceil(scene.periods * scene.samples)) + 1
        t = np.linspace(0.0, scene.periods * period, n)
        if outputs.needs_state:
            todo.append(("state", lambda: model.state(solution, t)))
        if outputs.needs_truth_trajectory:
            todo.append(("truth", lambda: _truth(model, solution, t, scene.integrator)))
        if outputs.needs_euler:
            todo.append(("euler", lambda: model.euler_angles(solution, t)))
    if outputs.needs_validation:  # also on a failed construction: it says why, with a verdict
        todo.append(("validation", lambda: _validate(scene, model)))
    if not failure and outputs.needs_work_precision:
        todo.append(("work_precision", lambda: _work_precision(scene, model)))
    if scene.sweep is not None and outputs.needs_sweep:  # each point says why it failed
        todo.append(("sweep", lambda: _sweep(scene, model, yes)))
    if scene.response is not None and outputs.needs_response:  # failures are in the result
        todo.append(("response", lambda: _response(scene, problem)))
    for name, work in track(todo, label=f"report {label_of(model)}"):
        step(name, work)

    truth, truth_integrator = None, ""
    if "truth" in values:
        truth, truth_integrator, note = values["truth"]
        if note:
            state["notes"].append(note)
    return SceneResult(
        scene=scene,
        label=label_of(model),
        parameters=dict(model.case().values),
        epsilon=float(model.epsilon()),
        solution=solution,
        failure=failure,
        period=period,
        t=t,
        state=values.get("state"),
        truth=truth,
        truth_integrator=truth_integrator,
        euler=values.get("euler"),
        validation=values.get("validation"),
        work_precision=values.get("work_precision"),
        sweep=values.get("sweep"),
        response=values.get("response"),
        notes=tuple(state["notes"]),
        computed=tuple(state["computed"]),
        seconds=dict(state["seconds"]),
    )


def _validate(scene: Scene, model: Model):
    from perturb.validation import DEFAULT_TOL, validate

    return validate(
        model,
        order=scene.order,
        integrator=scene.integrator,
        periods=scene.periods,
        tol=DEFAULT_TOL if scene.tol is None else scene.tol,
    )


def _work_precision(scene: Scene, model: Model):
    from perturb.workprecision import work_precision

    settings = scene.work_precision
    return work_precision(
        model,
        periods=settings.periods or scene.periods,
        orders=settings.orders or scene.order,
        repeat=settings.repeat,
    )


def _sweep(scene: Scene, model: Model, yes: bool = False):
    from perturb.sweep.api import sweep
    from perturb.validation import DEFAULT_TOL

    settings = scene.sweep
    return sweep(
        model,
        list(settings.grid),
        order=scene.order,
        validate=settings.validate,
        times=settings.times,
        tol=DEFAULT_TOL if scene.tol is None else scene.tol,
        periods=scene.periods,
        integrator=scene.integrator,
        derive=settings.derive,
        workers=settings.workers,
        yes=yes,
    )


def _response(scene: Scene, problem):
    from perturb.response.model import parse_sweep, problem_response

    settings = scene.response
    name, grid = parse_sweep(settings.sweep, "sweep")
    return problem_response(problem, name, grid, order=scene.order, validate=settings.validate)
