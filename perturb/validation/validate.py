"""The front door :func:`validate`: orchestration only (the measurements are in
:mod:`~perturb.validation.checks` and :mod:`~perturb.validation.orbit`, the rule in
:mod:`~perturb.validation.verdict`)."""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp
from attrs import evolve

from perturb._defaults import (
    DEFAULT_PERIODS,
    DEFAULT_RTOL,
    DEFAULT_TOL,
    ESTIMATE_FAILED_MAX_STEPS,
    MAX_OUTPUT_SAMPLES,
    SAMPLES_PER_PERIOD,
    SLOPE_FACTORS,
    STIFFNESS_SAMPLES,
)
from perturb.domain import DomainCheck, series_domain
from perturb.errors import PerturbError, bad_value
from perturb.oracle import Integrator, Trajectory
from perturb.progress import stage, track
from perturb.validation.capabilities import (
    integrals_of_motion,
    label_of,
    own_shooting_setup,
    validity_estimates,
)
from perturb.validation.checks import (
    analytic_states,
    component_errors,
    fit_slope,
    invariant_drift,
    one_period_error,
    stiffness_indicator,
)
from perturb.validation.frames import work_of
from perturb.validation.model import Model, ShootingSetup, parameter_value_of
from perturb.validation.report import SlopeFit, ValidationReport, Verdict
from perturb.validation.setup import (
    check_positive,
    cut_by_budget,
    derived_shooting_setup,
    integrator_for,
)
from perturb.validation.system_model import as_model
from perturb.validation.truth import original_equations, with_epsilon
from perturb.validation.verdict import accurate_order, decide, measurement_checks

__all__ = ["validate"]


def _check_arguments(order, periods, rtol, tol, samples_per_period, initial_state):
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or order < 1:
        raise bad_value("order", order, "pass an integer >= 1")
    periods = check_positive("periods", periods, "pass a positive number of periods, e.g. 10")
    rtol = check_positive("rtol", rtol, "pass a positive relative tolerance such as 1e-12")
    tol = check_positive("tol", tol, f"pass a positive relative tolerance such as {DEFAULT_TOL}")
    if (
        isinstance(samples_per_period, bool)
        or not isinstance(samples_per_period, int | np.integer)
        or samples_per_period < 4
    ):
        raise bad_value("samples_per_period", samples_per_period, "pass an integer >= 4")
    if periods * samples_per_period > MAX_OUTPUT_SAMPLES:
        raise bad_value(
            "periods",
            periods,
            f"at most {MAX_OUTPUT_SAMPLES // samples_per_period} periods at "
            f"{samples_per_period} samples per period (lower samples_per_period for longer runs)",
        )
    start = None
    if initial_state is not None:
        try:
            start = np.asarray(initial_state, dtype=float)
        except (TypeError, ValueError):
            raise bad_value(
                "initial_state", initial_state, "pass a vector of real numbers"
            ) from None
        if start.ndim != 1 or not np.all(np.isfinite(start)):
            raise bad_value(
                "initial_state", initial_state, "every component must be finite (no NaN/inf)"
            )
    return periods, rtol, tol, start


def _epsilon(model: Model) -> float:
    eps = float(model.epsilon())
    if not math.isfinite(eps) or eps == 0:
        raise bad_value(
            "epsilon",
            eps,
            "the expansion parameter must be finite and non-zero (at eps = 0 the generating "
            "solution is exact and there is no expansion to validate); set the problem's small "
            "parameter to a non-zero value",
        )
    return eps


def _generating_period(model: Model, solution) -> float:
    """2π/Ω₀ (the ε = 0 period), the time unit when the analytic period is unusable."""
    values = model.symbol_values()
    omega0 = sp.sympify(solution.frequency[0])
    omega0 = omega0.subs({s: values[s.name] for s in omega0.free_symbols if s.name in values})
    try:
        omega0 = float(omega0)
    except TypeError:
        return 2 * math.pi
    return 2 * math.pi / omega0 if omega0 > 0 else 2 * math.pi


def _report(base: dict, outcome: Verdict, sentence: str, **fields) -> ValidationReport:
    values = dict(
        completed=True,
        message="",
        status=None,
        t_reached=0.0,
        period=math.nan,
        errors={},
        slope=None,
        periodic_orbit=None,
        invariants={},
        integrator="",
        stiffness=None,
        timings={},
        checks=(),
    )
    values.update(fields)
    return ValidationReport(
        **base, valid=outcome.success, verdict=sentence, outcome=outcome, **values
    )


def _scan(model, eps, order, integrator, rtol, stiff, budget) -> tuple[SlopeFit | None, str]:
    """The one-period error along ε × SLOPE_FACTORS (the problem's own small parameter rescaled)."""
    eps_grid, err_grid = [], []
    for factor in track(SLOPE_FACTORS, label=f"validate {label_of(model)}: order check"):
        try:
            variant = with_epsilon(model, eps * factor)
        except (PerturbError, ValueError):
            variant = None
        if variant is None:
            continue
        eps_grid.append(eps * factor)
        try:
            err_grid.append(one_period_error(variant, order, integrator, rtol, stiff, budget))
        except (PerturbError, ValueError):
            err_grid.append(math.nan)
    if not eps_grid:
        return None, (
            "the problem cannot be re-created at other epsilon (its with_epsilon gives none), so "
            "the order cannot be measured: declare epsilon in its parameter_map "
            "(e.g. {'epsilon': 'amplitude**2'}) or give it a with_epsilon"
        )
    return fit_slope(eps_grid, err_grid, order), ""


def validate(
    problem,
    order: int = 1,
    integrator: Integrator | str | None = None,
    periods: float = DEFAULT_PERIODS,
    *,
    rtol: float = DEFAULT_RTOL,
    tol: float = DEFAULT_TOL,
    initial_state: Sequence[float] | None = None,
    shoot: bool | None = None,
    slope: bool | None = None,
    samples_per_period: int = SAMPLES_PER_PERIOD,
    shooting_setup: Mapping | ShootingSetup | None = None,
    values: Mapping | None = None,
    options: Mapping | None = None,
    domain: DomainCheck | None = None,
) -> ValidationReport:
    """Check ``problem``'s analytic periodic solution against the true motion.

    Parameters
    ----------
    problem : problems.Problem, Model or QuasilinearSystem
        A problem instance (``get_problem(name).create(...)``), any :class:`Model`, or a bare
        system together with ``values`` (and ``options``).
    order : int, optional
        Order of the analytic solution (>= 1).
    integrator : str or Integrator, optional
        The oracle: a name of :data:`perturb.oracle.INTEGRATORS` or an integrator object (default:
        :func:`perturb.oracle.choose`: Radau if stiff, heyoka when the equations are symbolic,
        else DOP853).
    periods : float, optional
        Horizon of the trajectory information, in analytic periods (> 0); not in the verdict.
    rtol : float, optional
        Relative tolerance of the scipy integrators (> 0).
    tol : float, optional
        Accuracy tolerance (> 0): the largest distance of the analytic orbit from the true one
        (relative to its size) and the largest relative period error of a valid solution.
    initial_state : array_like, optional
        Start the trajectory here instead of at the analytic initial state.
    shoot, slope : bool, optional
        Run the existence/accuracy checks (shooting) and the order check (ε scan); default True.
        A check not run leaves the verdict UNDECIDED.
    samples_per_period : int, optional
        Output points per period of the trajectory (>= 4).
    shooting_setup : ShootingSetup or mapping, optional
        Overrides the model's set-up of :func:`perturb.oracle.find_periodic_orbit`.
    values, options : mapping, optional
        With a bare :class:`perturb.QuasilinearSystem`: numbers for its parameters and its own
        small parameter, by name, and options of :class:`perturb.PoincareMethod`.
    domain : perturb.domain.DomainCheck, optional
        :func:`perturb.domain.series_domain` of the solution at the model's values, when the
        caller has it already (a sweep checks its points together); only its ``ok`` and
        ``reasons`` are read. Default: checked here.

    Returns
    -------
    ValidationReport
        Always returned for valid input; ``outcome`` is VALID, INVALID or UNDECIDED, and a
        numerical failure gives ``completed = False``.

    Raises
    ------
    perturb.errors.UnknownNameError
        For an unknown integrator name (the message lists the known ones).
    perturb.errors.InvalidParameterError
        For ``order < 1``, non-positive ``periods``/``rtol``/``tol``, a horizon beyond
        :data:`MAX_OUTPUT_SAMPLES` samples, ε = 0, a non-finite ``initial_state``.

    Examples
    --------
    >>> from problems import get_problem
    >>> report = validate(get_problem("duffing").create(eps=0.05), periods=2)
    >>> report.outcome.label, report.completed
    ('valid', True)
    """
    model = as_model(problem, values, options)
    periods, rtol, tol, start_override = _check_arguments(
        order, periods, rtol, tol, samples_per_period, initial_state
    )
    integrator_for(integrator, rtol, False, True)  # an unknown name fails here, before any work
    eps = _epsilon(model)
    names = tuple(model.state_names())
    if start_override is not None and start_override.size != len(names):
        raise bad_value(
            "initial_state",
            initial_state,
            f"give {len(names)} components, in the order {list(names)}",
        )
    timings: dict[str, float] = {}
    clock = time.perf_counter()
    conditions = validity_estimates(model)
    base = dict(
        problem=label_of(model),
        parameters=model.case().values,
        order=int(order),
        epsilon=eps,
        conditions=conditions,
        periods=periods,
        tol=tol,
    )
    solution = model.solve(order)
    timings["solve"] = time.perf_counter() - clock
    if not solution.success:
        outcome, sentence = decide(
            (),
            failure=f"the analytic construction failed ({solution.status.value}), so there is "
            "nothing to validate",
        )
        return _report(
            base, outcome, sentence, completed=False, message=solution.message or "",
            timings=timings,
        )  # fmt: skip

    with np.errstate(all="ignore"):
        period = float(model.period(solution))
        y_analytic0 = analytic_states(model, solution, np.zeros(1))[:, 0]
    breakdown = None
    if not (math.isfinite(period) and period > 0):
        breakdown = (
            f"the analytic period is {period:.6g}, not a positive number, so the series for the "
            "frequency has broken down"
        )
        period = _generating_period(model, solution)
    elif start_override is None:
        # the same domain check as ``perturb solve``: terms that do not decrease are no series
        if domain is None:
            domain = series_domain(solution, parameter_value_of(model), model.symbol_values())
        if not domain.ok:
            breakdown = "the series is outside its domain: " + "; ".join(domain.reasons)
    if not np.all(np.isfinite(y_analytic0)):
        breakdown = f"the analytic initial state {y_analytic0.tolist()} is not finite"
        if start_override is None:
            outcome, sentence = decide((), breakdown=breakdown, conditions=conditions)
            return _report(
                base, outcome, sentence, completed=False, message=breakdown, period=period,
                timings=timings,
            )  # fmt: skip
    y0 = y_analytic0 if start_override is None else start_override
    equations = original_equations(model, y0)
    integrals = integrals_of_motion(model, y0)

    # stiffness, from the Jacobian along one analytic period
    clock = time.perf_counter()
    with np.errstate(all="ignore"):
        samples = analytic_states(
            model, solution, np.linspace(0.0, period, STIFFNESS_SAMPLES, endpoint=False)
        )
    stiffness = stiffness_indicator(equations.rhs, samples, period)
    hopeless = any(not c.ok for c in conditions) or breakdown is not None
    budget = ESTIMATE_FAILED_MAX_STEPS if hopeless else None
    solver = integrator_for(integrator, rtol, stiffness.stiff, equations.symbolic, budget)
    timings["stiffness"] = time.perf_counter() - clock

    # trajectory information over the horizon
    clock = time.perf_counter()
    t = np.linspace(0.0, periods * period, int(math.ceil(periods * samples_per_period)) + 1)
    with stage(f"validate {label_of(model)}: integrating the true motion over {periods:g} periods"):
        traj: Trajectory = solver.integrate(equations.rhs, (0.0, t[-1]), y0, t_eval=t)
    timings["integrate"] = time.perf_counter() - clock
    numeric = np.asarray(traj.y, dtype=float)
    reached = numeric.shape[1]
    with np.errstate(all="ignore"):
        analytic = analytic_states(model, solution, t[:reached])
    errors: dict = {"horizon": float(t[-1])}
    max_rel = math.nan
    if reached <= 1:  # only t = 0, where both start from the same state: nothing was compared
        errors["note"] = (
            f"the integration stopped at t = {traj.t_reached:.6g}, before the first comparison time "
            f"{t[1]:.6g}: no error was measured"
        )
    else:
        components, max_abs, max_rel = component_errors(names, analytic, numeric)
        first = min(reached, samples_per_period + 1)
        _, _, first_rel = component_errors(names, analytic[:, :first], numeric[:, :first])
        errors.update(
            components=components,
            max_abs=max_abs,
            max_relative=max_rel,
            first_period_max_relative=first_rel,
        )
    invariants = invariant_drift(integrals, numeric)
    cut = hopeless and cut_by_budget(traj)
    # a broken-down series is INVALID as it stands: no orbit or scan can change that
    measurable = (traj.success or cut) and breakdown is None

    # existence and accuracy: the true orbit
    orbit = None
    work = work_of(model.system())  # free: shot on a section; driven: over the given period
    if measurable and shoot is not False:
        clock = time.perf_counter()

        def setup():
            return _setup(model, shooting_setup, equations, y_analytic0, len(invariants), samples)

        with stage(f"validate {label_of(model)}: shooting the true periodic orbit"):
            orbit = work.measure_orbit(
                model, solution, equations, y_analytic0, period, integrator, rtol,
                stiffness.stiff, setup, budget,
            )  # fmt: skip
        timings["shooting"] = time.perf_counter() - clock

    # order: the ε scan
    fit, why_no_fit = None, "the order check was not run (slope=False)"
    if measurable and slope is not False:
        clock = time.perf_counter()
        fit, why = _scan(model, eps, order, integrator, rtol, stiffness.stiff, budget)
        why_no_fit = why or why_no_fit
        timings["slope"] = time.perf_counter() - clock
    why_no_orbit = "the existence check was not run (shoot=False)"
    if shoot is not False:
        why_no_orbit = "the true motion was not measurable, so no orbit was searched for"
    checks = measurement_checks(orbit, fit, tol, why_no_fit, why_no_orbit)
    checks = work.checks(checks, model, solution, orbit, why_no_orbit)  # the fourth: the frame's

    completed, message = traj.success, traj.message
    failure = None
    if cut:  # a deliberate cut under a failed estimate, not a numerical failure
        completed = True
        message = (
            f"stopped at t = {traj.t_reached:.6g} by the step budget {ESTIMATE_FAILED_MAX_STEPS} "
            "of a run whose own validity estimate fails (errors cover [0, t_reached]); pass an "
            "integrator with a larger max_steps to go further"
        )
    elif not traj.success:
        failure = f"the integration stopped at t = {traj.t_reached:.6g} ({traj.message})"
    info = (
        f"Trajectory (information): error {max_rel:.2e} of the amplitude over {periods:g} periods"
        if math.isfinite(max_rel)
        else ""
    )
    outcome, sentence = decide(
        checks, breakdown=breakdown, failure=failure, conditions=conditions, trajectory=info
    )
    timings["total"] = sum(timings.values())
    return _report(
        base,
        outcome,
        sentence,
        completed=completed,
        message=message,
        status=traj.status,
        t_reached=traj.t_reached,
        period=period,
        errors=errors,
        slope=fit,
        periodic_orbit=orbit,
        invariants=invariants,
        integrator=traj.integrator or solver.name,
        stiffness=stiffness,
        timings=timings,
        checks=checks,
        accurate_order=accurate_order(checks) if outcome is Verdict.LOWER_ORDER else None,
    )


def _setup(model: Model, override, equations, y0, n_integrals, samples) -> ShootingSetup:
    """The shooting set-up: the argument, else the model's, else derived; n_trivial completed."""
    setup = override if override is not None else own_shooting_setup(model)
    if setup is None:
        return derived_shooting_setup(model, equations, y0, n_integrals, samples)
    if isinstance(setup, Mapping):
        setup = ShootingSetup.from_mapping(setup)
    if not isinstance(setup, ShootingSetup):
        raise bad_value("shooting_setup", setup, "pass a ShootingSetup or a mapping")
    if setup.n_trivial is None:
        setup = evolve(setup, n_trivial=1 + n_integrals)
    return setup
