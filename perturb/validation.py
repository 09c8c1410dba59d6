"""Check a problem's analytic periodic solution against the true motion: :func:`validate`.

:func:`validate` answers one question — *does the Poincaré solution describe the motion of the original
(unreduced) system?* — with numbers and a one-sentence verdict:

1. **Preconditions** (before integrating): the expansion parameter must be small
   (:math:`\\varepsilon \\le` :data:`EPSILON_LIMIT`) and every condition of the problem's
   ``validity_conditions()`` hook must hold.
2. **Trajectory error**: the original equations are integrated from the analytic initial state over
   ``periods`` periods and compared, component by component, with the analytic state (maximum
   absolute error, and relative to each component's amplitude).
3. **First integrals**: their drift along the numerical trajectory (an accuracy check of the oracle).
4. **True periodic orbit**: found by Newton shooting seeded by the analytic solution; its period,
   initial state and Floquet multipliers, and the analytic solution's error against it.
5. **Convergence slope**: the one-period error over a geometric range of ε around the user's value;
   a valid expansion of order :math:`n` has error :math:`O(\\varepsilon^{n+1})`, so the slope of
   :math:`\\log` error against :math:`\\log\\varepsilon` is :math:`\\ge n + 1`.
6. **Stiffness**: Jacobian eigenvalues along the analytic orbit; a stiff system is integrated with
   Radau instead of an explicit method.

Problems take part through the :class:`problems.Problem` API plus optional duck-typed hooks:

``original_symbolic()``
    ``(state symbols, sympy rhs)`` of the original system (lets heyoka run and gives exact Jacobians).
``first_integrals_function()``
    ``y -> array`` of first-integral values (``y`` of shape ``(n,)`` or ``(n, m)``).
``shooting_setup()``
    ``{"section_index", "fixed_indices", "direction", "n_trivial"}`` for :func:`find_periodic_orbit`.
``true_periodic_orbit(solution)``
    The true periodic orbit by a problem-specific method, used only when the generic shooting
    cannot resolve it (see :func:`_problem_true_orbit`).
``with_epsilon(eps)``
    The same problem with the expansion parameter set to ``eps`` (for the slope).
``validity_conditions()``
    ``[(name, value, ok, sentence), ...]``: problem-specific conditions of the expansion.

Problems whose original system *is* their quasilinear system (the default ``original_rhs``) get all of
these by default: the symbolic rhs, the declared first integrals plus the energy when the forces are
conservative, a section on the phase coordinate's velocity, and ``with_epsilon`` through an ``eps``
parameter.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import attrs
import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import SHOOTING_TOL
from perturb.errors import PerturbError, UnknownNameError, bad_value
from perturb.oracle import (
    INTEGRATORS,
    Integrator,
    Scipy,
    SymbolicRHS,
    Trajectory,
    TrajectoryStatus,
    choose,
    find_periodic_orbit,
    finite_difference_jacobian,
)

__all__ = [
    "Condition",
    "InvariantDrift",
    "OrbitCheck",
    "SlopeFit",
    "Stiffness",
    "ValidationReport",
    "original_system",
    "validate",
]

# --------------------------------------------------------------------------------------------------
# named constants
# --------------------------------------------------------------------------------------------------

#: Largest ε for which an expansion in powers of ε is trusted before any computation: the first
#: neglected term is then at most ~0.3 of the last kept one (for O(1) coefficients), and the textbook
#: series (Duffing, van der Pol) lose their accuracy beyond ~0.3.
EPSILON_LIMIT = 0.3

#: Largest error, relative to each component's amplitude, of a solution still called valid: 10 % is
#: the point where a plot of the analytic and the true curves visibly separate.
MAX_RELATIVE_ERROR = 0.1

#: A measured slope may fall this far below the theoretical order + 1 and still count as consistent:
#: four ε points a factor 2 apart leave an uncertainty of a few tenths from the next-order terms.
SLOPE_TOLERANCE = 0.5

#: Factors applied to the user's ε for the slope fit (geometric, around the user's value).
SLOPE_FACTORS = (0.25, 0.5, 1.0, 2.0)

#: Relative errors below this are at the level of the oracle's own accuracy (rtol 1e-12 over a
#: period plus the evaluation round-off of the series); such points are dropped from the slope fit.
ERROR_FLOOR = 1e-10

#: Output samples per period of the trajectory comparison: 40 points resolve a harmonic of order
#: ~10 well enough that the sampled maximum of the error is within a few % of the true maximum.
SAMPLES_PER_PERIOD = 40

#: Default number of periods of the trajectory comparison.
DEFAULT_PERIODS = 10

#: Points of the analytic orbit at which the Jacobian eigenvalues are sampled for stiffness.
STIFFNESS_SAMPLES = 16

#: Stiffness ratio max|Re λ| / max(max|Im λ|, 2π/T) above which explicit methods are abandoned for
#: Radau: the decay rate then exceeds the oscillation rate tenfold, and an explicit method's stability
#: limit (|h λ| ≲ 3) sets its step instead of the accuracy.
STIFFNESS_THRESHOLD = 10.0

#: Distance from 1 below which a trivial Floquet multiplier counts as 1.  A conservative family has a
#: Jordan block at 1 whose computed eigenvalues split like sqrt(integration error) ~ sqrt(1e-13) ~ 3e-7.
FLOQUET_TOL = 1e-5
#: Smallest periodicity defect a double-precision shooting can certify (relative to the amplitudes):
#: round-off of the state over one period.
SHOOTING_PRECISION = 1e-13
#: Distance from 1 below which a Floquet multiplier cannot be told from a trivial one: the monodromy
#: of a double-precision variational integration (error ~1e-12) splits a double multiplier 1 by
#: about the square root of that error.
MULTIPLIER_FLOOR = 1e-6
#: Largest shooting uncertainty (relative to the amplitudes) at which the orbit is still used to judge
#: the analytic solution: 1 % of the 10 % error limit of the verdict.
ORBIT_RESOLUTION_LIMIT = 1e-3

#: Amplitudes below this fraction of the largest one are raised to it for the relative errors
#: (a component identically zero would otherwise divide by zero).
AMPLITUDE_FLOOR = 1e-9

#: Relative tolerance of the scipy integrators of the oracle (DOP853/Radau): three digits above
#: float64 round-off, as the reference's DOP853 oracle (integral drift <= 1e-11).
DEFAULT_RTOL = 1e-12

#: Newton iterations allowed to the shooting: from a seed within O(ε^(n+1)) it converges in < 8;
#: the cap bounds the time spent when the expansion is wrong and the seed is far from any orbit.
SHOOTING_ITERATIONS = 20

#: Shooting on a stiff system: Radau at rtol 1e-11 (explicit and Taylor methods crawl at the
#: stability limit).  The periodicity tolerance is looser than for smooth motion because the fast
#: transitions of a relaxation cycle amplify the per-step error ~1e4-fold over one period
#: (van der Pol at eps = 10 stalls at a residual ~1e-7).
STIFF_SHOOTING_INTEGRATOR = Scipy("Radau", rtol=1e-11)
STIFF_SHOOTING_TOL = 1e-6

#: Factor by which a parameter is scaled to test whether it is a pure-ε knob (see `_epsilon_knob`);
#: any value far enough from 1 to measure the exponent to ~1e-12 works.
KNOB_PROBE = 2.0

#: A component whose analytic value varies over one period by less than this fraction of its size
#: is treated as a family parameter (a first integral's value: a spin, a direction cosine) and is
#: pinned in the default shooting set-up of problems without a ``shooting_setup`` hook.
SLOW_COMPONENT = 1e-2

#: Relative tolerance of Radau on stiff systems: its Newton iterations stop converging much
#: below 1e-10, and a stiff relaxation cycle is not reproducible to better than that anyway.
STIFF_RTOL = 1e-10

#: Step budget of the integration when the preconditions fail: the verdict is already "invalid",
#: the run only shows how the motion departs; 20 000 Taylor steps take ~0.1 s, whereas a tumbling
#: body integrated from a meaningless analytic state can need 1e7 steps over the horizon.
INVALID_MAX_STEPS = 20_000

#: A velocity component counts as zero at the start (candidate Poincaré section) below this fraction
#: of the state scale.
SECTION_ZERO = 1e-8


# --------------------------------------------------------------------------------------------------
# result objects
# --------------------------------------------------------------------------------------------------


def _float(value) -> float:
    return float(np.real(value))


def _jsonable(value: Any) -> Any:
    """Plain Python containers and floats, for :func:`json.dumps`."""
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, complex | np.complexfloating):
        return [float(value.real), float(value.imag)]
    if isinstance(value, float | np.floating):
        return float(value)
    return value


@frozen
class Condition:
    """A condition under which the expansion can hold, checked before integrating.

    Attributes
    ----------
    name : str
        Short label, e.g. ``"epsilon small"``.
    value : float
        The quantity tested (ε, or a ratio that must be small).
    ok : bool
    sentence : str
        What the condition says, with the numbers.
    """

    name: str
    value: float = field(converter=float)
    ok: bool = field(converter=bool)
    sentence: str

    def as_dict(self) -> dict:
        return {"name": self.name, "value": self.value, "ok": self.ok, "sentence": self.sentence}


@frozen
class InvariantDrift:
    """Drift of one first integral along the numerical trajectory.

    Attributes
    ----------
    name : str
    initial : float
        Value at ``t = 0``.
    max_drift : float
        :math:`\\max_t |I(t) - I(0)|`.
    relative_drift : float
        ``max_drift / |I(0)|`` (``max_drift`` itself when ``I(0) = 0``).
    final_drift : float
        :math:`|I(t_{end}) - I(0)|`.
    """

    name: str
    initial: float = field(converter=float)
    max_drift: float = field(converter=float)
    relative_drift: float = field(converter=float)
    final_drift: float = field(converter=float)

    def as_dict(self) -> dict:
        return {
            "initial": self.initial,
            "max_drift": self.max_drift,
            "relative_drift": self.relative_drift,
            "final_drift": self.final_drift,
        }


@frozen
class SlopeFit:
    """Convergence of the analytic solution's error in ε.

    Attributes
    ----------
    slope : float
        Least-squares slope of log(error) against log(ε) (NaN if fewer than two usable points).
    expected : float
        ``order + 1``: the slope of an :math:`O(\\varepsilon^{n+1})` error.
    epsilons, errors : tuple of float
        The ε values and the one-period relative errors (NaN where a point failed).
    consistent : bool or None
        ``slope >= expected - SLOPE_TOLERANCE``; None if the slope could not be measured.
    note : str
        Why points were dropped or the slope is missing.
    """

    slope: float = field(converter=float)
    expected: float = field(converter=float)
    epsilons: tuple = field(converter=tuple)
    errors: tuple = field(converter=tuple)
    consistent: bool | None
    note: str = ""

    def as_dict(self) -> dict:
        return {
            "value": self.slope,
            "expected": self.expected,
            "consistent": self.consistent,
            "epsilons": list(self.epsilons),
            "errors": list(self.errors),
            "note": self.note,
        }


@frozen
class OrbitCheck:
    """The true periodic orbit found by shooting, and the analytic solution's error against it.

    Attributes
    ----------
    success : bool
        Whether the shooting converged.
    period : float
        True period (NaN on failure).
    initial_state : dict
        True state at the section crossing, by name.
    floquet : tuple of complex
        Floquet multipliers, sorted by distance from 1 (trivial ones first).
    n_trivial : int
        Number of multipliers expected at 1 (autonomy + first integrals / families).
    trivial_multiplier_error : float
        Largest distance from 1 among the trivial multipliers.
    trivial_ok : bool
        ``trivial_multiplier_error <= FLOQUET_TOL``.
    period_error : float
        (analytic period − true period) / true period.
    initial_state_error : float
        Max over components of |analytic − true| initial state, relative to the amplitudes.
    orbit_error : float
        Max relative error of the analytic solution over one period, at equal phases.
    message : str
        The shooting's own message.
    status : int
        The shooting's status (0 converged).
    integrator : str
    resolution : float
        How far (relative to the amplitudes) the shooting's own uncertainty may move the orbit:
        the Newton residual over the distance of the first non-trivial Floquet multiplier from 1.
        A nearly neutral direction (two oscillations with almost the same frequency) makes the orbit
        numerically non-isolated; above ``ORBIT_RESOLUTION_LIMIT`` it is reported as unresolved
        and not used in the verdict.
    """

    success: bool
    period: float = field(converter=float)
    initial_state: dict
    floquet: tuple = field(converter=tuple)
    n_trivial: int
    trivial_multiplier_error: float = field(converter=float)
    trivial_ok: bool
    period_error: float = field(converter=float)
    initial_state_error: float = field(converter=float)
    orbit_error: float = field(converter=float)
    message: str
    status: int
    integrator: str = ""
    resolution: float = field(default=0.0, converter=float)

    @property
    def resolved(self) -> bool:
        """Whether shooting at this precision determines the orbit well enough to judge against it."""
        return self.success and self.resolution <= ORBIT_RESOLUTION_LIMIT

    def as_dict(self) -> dict:
        return {
            "success": self.success,
            "resolved": self.resolved,
            "resolution": self.resolution if math.isfinite(self.resolution) else None,
            "period": self.period,
            "initial_state": dict(self.initial_state),
            "floquet": [[float(z.real), float(z.imag)] for z in self.floquet],
            "floquet_abs": [float(abs(z)) for z in self.floquet],
            "n_trivial": self.n_trivial,
            "trivial_multiplier_error": self.trivial_multiplier_error,
            "trivial_ok": self.trivial_ok,
            "period_error": self.period_error,
            "initial_state_error": self.initial_state_error,
            "orbit_error": self.orbit_error,
            "status": self.status,
            "message": self.message,
            "integrator": self.integrator,
        }


@frozen
class Stiffness:
    """Stiffness indicator from Jacobian eigenvalues sampled along the analytic orbit.

    Attributes
    ----------
    ratio : float
        :math:`\\max|\\mathrm{Re}\\,\\lambda| / \\max(\\max|\\mathrm{Im}\\,\\lambda|, 2\\pi/T)`.
    max_real : float
    max_imag : float
    stiff : bool
        ``ratio > STIFFNESS_THRESHOLD``.
    """

    ratio: float = field(converter=float)
    max_real: float = field(converter=float)
    max_imag: float = field(converter=float)
    stiff: bool

    def as_dict(self) -> dict:
        return {
            "ratio": self.ratio,
            "max_real": self.max_real,
            "max_imag": self.max_imag,
            "stiff": self.stiff,
            "threshold": STIFFNESS_THRESHOLD,
        }


@frozen
class ValidationReport:
    """Outcome of :func:`validate`: numbers, a verdict and how the run went.

    Attributes
    ----------
    problem : str
        Registry name of the problem.
    parameters : dict
        Every parameter value in force.
    order : int
    epsilon : float
        The expansion parameter ε of the problem.
    valid : bool
        The verdict: does the analytic solution describe the true motion?
    verdict : str
        One sentence giving the reason.
    completed : bool
        False only when the run failed numerically (integration failure or non-finite analytic
        state); then ``message``, ``status`` and ``t_reached`` carry the solver's report.
    message : str
    status : int
        0 on success, the integrator's (negative) status on failure.
    t_reached : float
        How far the integration got.
    conditions : tuple of Condition
        The preconditions checked before integrating.
    period : float
        The analytic period.
    periods : float
        Number of periods integrated.
    errors : dict
        ``{"components": {name: {"abs", "relative", "amplitude"}}, "max_abs", "max_relative",
        "first_period_max_relative", "horizon"}``.
    slope : SlopeFit or None
    periodic_orbit : OrbitCheck or None
    invariants : dict of InvariantDrift
    integrator : str
        The integrator that actually ran the trajectory comparison.
    stiffness : Stiffness or None
    timings : dict
        Wall time in seconds of each stage.
    """

    problem: str
    parameters: dict
    order: int
    epsilon: float = field(converter=float)
    valid: bool
    verdict: str
    completed: bool
    message: str
    status: int
    t_reached: float = field(converter=float)
    conditions: tuple = field(converter=tuple)
    period: float = field(converter=float)
    periods: float = field(converter=float)
    errors: dict
    slope: SlopeFit | None
    periodic_orbit: OrbitCheck | None
    invariants: dict
    integrator: str
    stiffness: Stiffness | None
    timings: dict

    def as_dict(self) -> dict:
        """The JSON contract (see ``docs/validation.md``): plain containers and floats."""
        orbit = self.periodic_orbit.as_dict() if self.periodic_orbit is not None else None
        return _jsonable(
            {
                "problem": self.problem,
                "parameters": self.parameters,
                "order": self.order,
                "epsilon": self.epsilon,
                "valid": self.valid,
                "verdict": self.verdict,
                "completed": self.completed,
                "message": self.message,
                "status": self.status,
                "t_reached": self.t_reached,
                "conditions": [c.as_dict() for c in self.conditions],
                "period": self.period,
                "periods": self.periods,
                "errors": self.errors,
                "slope": self.slope.as_dict() if self.slope is not None else None,
                "periodic_orbit": orbit,
                "invariants": {k: v.as_dict() for k, v in self.invariants.items()},
                "integrator": self.integrator,
                "stiffness": self.stiffness.as_dict() if self.stiffness is not None else None,
                "timings": self.timings,
            }
        )

    def as_table(self) -> str:
        """A human-readable summary, one block per check."""
        lines = [
            f"# validate {self.problem}  order {self.order}  epsilon {self.epsilon:.6g}",
            "# " + "  ".join(f"{k}={v:g}" for k, v in self.parameters.items()),
            f"verdict: {'VALID' if self.valid else 'INVALID'} - {self.verdict}",
        ]
        if not self.completed:
            lines.append(
                f"run failed: {self.message} (status {self.status}, t reached {self.t_reached:g})"
            )
        elif self.status != 0:
            lines.append(f"note: {self.message}")
        lines.append("conditions:")
        for c in self.conditions:
            lines.append(f"  [{'ok' if c.ok else 'FAIL'}] {c.name} = {c.value:.6g}: {c.sentence}")
        lines.append(
            f"trajectory: {self.periods:g} periods of T = {self.period:.12g}, integrator "
            f"{self.integrator}"
        )
        comps = self.errors.get("components", {})
        if "note" in self.errors:
            lines.append(f"  {self.errors['note']}")
        if comps:
            lines.append(
                f"  {'component':>12s} {'max abs err':>13s} {'rel err':>11s} {'amplitude':>11s}"
            )
            for name, e in comps.items():
                lines.append(
                    f"  {name:>12s} {e['abs']:13.4e} {e['relative']:11.3e} {e['amplitude']:11.4g}"
                )
        if self.invariants:
            lines.append("first integrals (drift along the numerical trajectory):")
            for name, d in self.invariants.items():
                lines.append(
                    f"  {name:>12s} I(0) = {d.initial:.12g}  max drift {d.max_drift:.2e} "
                    f"(relative {d.relative_drift:.2e})"
                )
        orbit = self.periodic_orbit
        if orbit is not None:
            lines.append(f"periodic orbit (shooting, {orbit.integrator}): {orbit.message}")
            if orbit.success:
                state = "  ".join(f"{k}={v:.10g}" for k, v in orbit.initial_state.items())
                lines.append(f"  period {orbit.period:.12g}   initial state {state}")
                mults = "  ".join(f"{z.real:+.6f}{z.imag:+.6f}j" for z in orbit.floquet)
                lines.append(f"  Floquet multipliers {mults}")
                lines.append(
                    f"  trivial multipliers ({orbit.n_trivial}) within "
                    f"{orbit.trivial_multiplier_error:.1e} of 1: {'ok' if orbit.trivial_ok else 'NO'}"
                )
                lines.append(
                    f"  analytic vs true: period {orbit.period_error:.3e} (relative), initial state "
                    f"{orbit.initial_state_error:.3e}, orbit {orbit.orbit_error:.3e}"
                )
        if self.slope is not None:
            s = self.slope
            pts = ", ".join(f"{e:.3g}:{r:.2e}" for e, r in zip(s.epsilons, s.errors, strict=True))
            lines.append(
                f"slope: {s.slope:.3f} (expected >= {s.expected:g} - {SLOPE_TOLERANCE}) "
                f"[{pts}] {s.note}".rstrip()
            )
        if self.stiffness is not None:
            st = self.stiffness
            lines.append(
                f"stiffness: ratio {st.ratio:.3g} (max|Re| {st.max_real:.3g}, max|Im| "
                f"{st.max_imag:.3g}): {'stiff' if st.stiff else 'not stiff'}"
            )
        lines.append("timings [s]: " + "  ".join(f"{k} {v:.3f}" for k, v in self.timings.items()))
        return "\n".join(lines)


# --------------------------------------------------------------------------------------------------
# the original system of a problem (hooks and defaults)
# --------------------------------------------------------------------------------------------------


@frozen
class OriginalSystem:
    """The original equations of a problem in the form the oracle needs.

    Attributes
    ----------
    names : tuple of str
        State names, in the order of the state vector.
    rhs : callable
        ``rhs(y) -> dy/dt`` (a :class:`SymbolicRHS` when the problem gives symbolic equations).
    symbolic : bool
        Whether ``rhs`` is a :class:`SymbolicRHS` (heyoka and exact Jacobians available).
    integrals : callable or None
        ``y -> array`` of first-integral values.
    integral_names : tuple of str
    """

    names: tuple
    rhs: Callable
    symbolic: bool
    integrals: Callable | None
    integral_names: tuple


def _uses_default_equations(problem) -> bool:
    """True if ``problem``'s original system is its quasilinear system (base ``original_rhs``)."""
    from problems.base import Problem

    return type(problem).original_rhs is Problem.original_rhs


def _system_substitutions(problem, y0: np.ndarray | None) -> dict:
    system = problem.system()
    values = problem.symbol_values()
    subs = {p: values[p.name] for p in system.parameters if p.name in values}
    subs[system.parameter] = problem.parameter_value()
    if system.initial_values:
        if y0 is None:
            return {}
        subs.update(zip(system.initial_values, map(float, y0), strict=True))
    return subs


def _default_symbolic(problem, y0) -> SymbolicRHS:
    """y' = (xdot, f(x, xdot) - omega**2 x) of the quasilinear system, with numbers substituted."""
    system = problem.system()
    subs = _system_substitutions(problem, y0)
    n = system.n
    state = system.state_symbols
    forces = [sp.sympify(f).subs(subs) for f in system.rhs]
    w2 = [sp.sympify(w**2).subs(subs) for w in system.frequencies]
    exprs = list(state[n:]) + [forces[i] - w2[i] * state[i] for i in range(n)]
    return SymbolicRHS(state, exprs)


def _conservative_energy(problem, y0) -> sp.Expr | None:
    """The energy of ẍ_i + ω_i² x_i = f_i(x) when the forces f derive from a potential, else None.

    With ``f = -grad V`` (velocity-free, symmetric Jacobian), :math:`H = \\sum \\dot x_i^2/2 +
    \\omega_i^2 x_i^2/2 + V` and :math:`V(x) = -\\int_0^1 f(s x)\\cdot x\\,ds`.
    """
    system = problem.system()
    subs = _system_substitutions(problem, y0)
    n = system.n
    xs, vs = system.state_symbols[:n], system.state_symbols[n:]
    forces = [sp.sympify(f).subs(subs) for f in system.rhs]
    if any(f.free_symbols & set(vs) for f in forces):
        return None
    jac = sp.Matrix(forces).jacobian(sp.Matrix(xs))
    if any(sp.simplify(jac[i, j] - jac[j, i]) != 0 for i in range(n) for j in range(i)):
        return None
    s = sp.Dummy("s")
    scaled = {x: s * x for x in xs}
    work = sp.integrate(
        sp.expand(
            sum(f.subs(scaled, simultaneous=True) * x for f, x in zip(forces, xs, strict=True))
        ),
        (s, 0, 1),
    )
    w2 = [sp.sympify(w**2).subs(subs) for w in system.frequencies]
    kinetic = sum(v**2 for v in vs) / 2
    return sp.expand(kinetic + sum(w2[i] * xs[i] ** 2 for i in range(n)) / 2 - work)


def _lambdify_integrals(state, exprs) -> Callable:
    fn = sp.lambdify(state, list(exprs), modules="numpy", cse=True)

    def integrals(y):
        y = np.asarray(y, dtype=float)
        return np.array(np.broadcast_arrays(*fn(*y)), dtype=float)

    return integrals


def original_system(problem, y0: np.ndarray | None = None) -> OriginalSystem:
    """The original equations of ``problem`` for the oracle (hooks first, then defaults).

    Parameters
    ----------
    problem : problems.Problem
    y0 : ndarray, optional
        Initial state, needed only by systems whose equations depend on the initial values.

    Returns
    -------
    OriginalSystem
    """
    names = tuple(problem.state_names())
    symbolic_rhs = None
    if hasattr(problem, "original_symbolic"):
        state, exprs = problem.original_symbolic()
        symbolic_rhs = SymbolicRHS(state, exprs)
    elif _uses_default_equations(problem):
        system = problem.system()
        if not system.initial_values or y0 is not None:
            symbolic_rhs = _default_symbolic(problem, y0)
    if symbolic_rhs is not None:
        rhs: Callable = symbolic_rhs
    else:
        f = problem.original_rhs()

        def rhs(y, _f=f):
            return np.asarray(_f(0.0, y), dtype=float)

    integrals, integral_names = None, ()
    if hasattr(problem, "first_integrals_function"):
        integrals = problem.first_integrals_function()
        integral_names = tuple(getattr(integrals, "names", ()))
        if not integral_names and hasattr(problem, "first_integral_names"):
            integral_names = tuple(problem.first_integral_names())
    elif callable(getattr(problem, "integrals", None)):
        integrals = problem.integrals
        integral_names = tuple(getattr(problem, "integral_names", ()))
    elif _uses_default_equations(problem):
        system = problem.system()
        subs = _system_substitutions(problem, y0)
        exprs = [sp.sympify(h).subs(subs) for h in system.first_integrals] if subs else []
        integral_names = tuple(f"I{i}" for i in range(len(exprs)))
        if not exprs:
            energy = _conservative_energy(problem, y0) if subs else None
            if energy is not None:
                exprs, integral_names = [energy], ("energy",)
        if exprs:
            integrals = _lambdify_integrals(system.state_symbols, exprs)
    return OriginalSystem(
        names=names,
        rhs=rhs,
        symbolic=isinstance(rhs, SymbolicRHS),
        integrals=integrals,
        integral_names=integral_names,
    )


def _epsilon_knob(problem) -> tuple[str, float] | None:
    """A parameter that changes ε as a power law and nothing else the solution depends on.

    Each parameter is scaled by :data:`KNOB_PROBE`; it qualifies if ``symbol_values()`` (the
    solution's parameters) stay the same while ε changes.  Returns ``(name, exponent)`` with
    :math:`\varepsilon \\propto p^{exponent}`, preferring exponents of modulus 1 (e.g. the disk's
    ``r0``: ε = c/r0).
    """
    eps = float(problem.epsilon())
    values = problem.symbol_values()
    best = None
    for name, value in problem.values.items():
        if not (isinstance(value, float | int) and math.isfinite(value) and value != 0):
            continue
        try:
            probe = type(problem).create(**{**problem.values, name: value * KNOB_PROBE})
        except (PerturbError, ValueError):
            continue
        if probe.symbol_values() != values:
            continue
        ratio = float(probe.epsilon()) / eps
        if not (ratio > 0 and math.isfinite(ratio)) or abs(ratio - 1) < 1e-12:
            continue
        exponent = math.log(ratio) / math.log(KNOB_PROBE)
        if best is None or abs(abs(exponent) - 1) < abs(abs(best[1]) - 1):
            best = (name, exponent)
    return best


def _with_epsilon(problem, eps: float):
    """``problem`` with ε replaced (hook ``with_epsilon``, the ``eps`` parameter, or a pure-ε knob).

    Returns None when none of these exists.
    """
    if hasattr(problem, "with_epsilon"):
        return problem.with_epsilon(eps)
    if "eps" in problem.values:
        return type(problem).create(**{**problem.values, "eps": eps})
    knob = _epsilon_knob(problem)
    if knob is None:
        return None
    name, exponent = knob
    factor = (eps / float(problem.epsilon())) ** (1.0 / exponent)
    return type(problem).create(**{**problem.values, name: problem.values[name] * factor})


def _shooting_setup(problem, y0, rhs, n_integrals, samples, override=None) -> dict:
    """Section, pinned components and number of trivial multipliers.

    From ``override`` (the ``shooting_setup`` argument of :func:`validate`), else the problem's
    ``shooting_setup()`` hook, else defaults: for a quasilinear problem, the section is the phase
    coordinate's velocity and the coordinates with user-fixed amplitudes are pinned; otherwise the
    components that stay constant to :data:`SLOW_COMPONENT` along the analytic period (family
    parameters) are pinned and the section is the component closest to zero at the start, relative
    to its amplitude.
    """
    setup = override
    if setup is None and hasattr(problem, "shooting_setup"):
        setup = problem.shooting_setup()
    if setup is not None:
        setup = dict(setup)
        setup.setdefault("fixed_indices", ())
        setup.setdefault("direction", 0)
        setup.setdefault("n_trivial", 1 + n_integrals)
        return setup
    scale = max(float(np.max(np.abs(y0))), 1.0)
    amp = _amplitudes(samples)
    pinned: list[int] = []
    section = None
    if _uses_default_equations(problem):
        system = problem.system()
        n = system.n
        options = problem.method_options()
        amplitudes = [str(k) for k in options.get("amplitudes", {})]
        coords = [c.name for c in system.coordinates]
        phase = options.get("phase_coordinate") or (
            amplitudes[0] if len(amplitudes) == 1 else coords[0]
        )
        section = n + coords.index(phase)
        pinned = [coords.index(a) for a in amplitudes if a in coords]
        n_trivial = 1 + max(len(pinned), n_integrals)
    else:
        spread = (np.max(samples, axis=1) - np.min(samples, axis=1)) / amp
        pinned = [i for i in range(len(y0)) if spread[i] < SLOW_COMPONENT]
        n_trivial = 1 + n_integrals
    velocity = np.asarray(rhs(y0), dtype=float)
    section_value = 0.0
    if section is None or abs(y0[section]) > SECTION_ZERO * scale:
        # a section through the seed itself, on the most transversal free component: moving the
        # seed onto some "zero" section would break the first integrals it satisfies
        candidates = [i for i in range(len(y0)) if i not in pinned]
        section = max(candidates, key=lambda i: abs(velocity[i]) / amp[i])
        section_value = float(y0[section])
        if not _uses_default_equations(problem):
            # one pinned component per first integral (each makes the orbits a family): add the
            # free components at their extremes (|y0|/amplitude largest, stationary on the section)
            extra = sorted(
                (i for i in candidates if i != section), key=lambda i: -abs(y0[i]) / amp[i]
            )
            pinned += extra[: max(0, n_integrals - len(pinned))]
    crossing = float(velocity[section])
    direction = int(np.sign(crossing)) if abs(crossing) > SECTION_ZERO * amp[section] else 0
    return {
        "section_index": section,
        "section_value": section_value,
        "fixed_indices": tuple(sorted(pinned)),
        "direction": direction,
        "n_trivial": min(n_trivial, len(y0)),
    }


# --------------------------------------------------------------------------------------------------
# checks of arguments
# --------------------------------------------------------------------------------------------------


def _check_positive(name: str, value, fix: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise bad_value(name, value, fix) from None
    if not (math.isfinite(number) and number > 0):
        raise bad_value(name, value, fix)
    return number


def _resolve_integrator(
    integrator, rtol: float, stiff: bool, symbolic: bool, max_steps: int | None = None
) -> Integrator:
    """Thin alias of :func:`perturb.oracle.choose`, the one rule for "which integrator"."""
    return choose(integrator, rtol=rtol, stiff=stiff, symbolic=symbolic, max_steps=max_steps)


# --------------------------------------------------------------------------------------------------
# numerical pieces
# --------------------------------------------------------------------------------------------------


def _generating_period(problem, solution) -> float:
    """2π/Ω₀ (the ε = 0 period), the time unit when the analytic period is unusable."""
    values = problem.symbol_values()
    omega0 = sp.sympify(solution.frequency[0]).subs(
        {
            s: values[s.name]
            for s in sp.sympify(solution.frequency[0]).free_symbols
            if s.name in values
        }
    )
    try:
        omega0 = float(omega0)
    except TypeError:
        return 2 * math.pi
    return 2 * math.pi / omega0 if omega0 > 0 else 2 * math.pi


def _analytic(problem, solution, names, t) -> np.ndarray:
    state = problem.state(solution, t)
    return np.array([np.asarray(state[name], dtype=float) for name in names])


def stiffness_indicator(rhs, points: np.ndarray, period: float) -> Stiffness:
    """Stiffness ratio from Jacobian eigenvalues at ``points`` (shape ``(n, m)``).

    Parameters
    ----------
    rhs : callable or SymbolicRHS
    points : ndarray, shape (n, m)
        States at which the Jacobian is evaluated.
    period : float
        Period of the motion; ``2π/period`` is the floor of the oscillation rate.

    Returns
    -------
    Stiffness
    """
    max_real, max_imag = 0.0, 0.0
    for y in np.asarray(points, dtype=float).T:
        if not np.all(np.isfinite(y)):
            continue
        jac = (
            rhs.jacobian(y) if isinstance(rhs, SymbolicRHS) else finite_difference_jacobian(rhs, y)
        )
        if not np.all(np.isfinite(jac)):
            continue
        eig = np.linalg.eigvals(jac)
        max_real = max(max_real, float(np.max(np.abs(eig.real))))
        max_imag = max(max_imag, float(np.max(np.abs(eig.imag))))
    floor = 2 * math.pi / period if period > 0 and math.isfinite(period) else 1.0
    ratio = max_real / max(max_imag, floor)
    return Stiffness(
        ratio=ratio, max_real=max_real, max_imag=max_imag, stiff=ratio > STIFFNESS_THRESHOLD
    )


def _amplitudes(values: np.ndarray) -> np.ndarray:
    amp = np.max(np.abs(values), axis=1) if values.size else np.zeros(values.shape[0])
    top = float(np.max(amp)) if amp.size else 0.0
    return np.maximum(amp, AMPLITUDE_FLOOR * top if top > 0 else 1.0)


def _component_errors(names, analytic, numeric) -> dict:
    amp = _amplitudes(numeric)
    diff = np.abs(analytic - numeric)
    abs_err = np.max(diff, axis=1) if diff.shape[1] else np.full(len(names), np.nan)
    rel = abs_err / amp
    components = {
        name: {"abs": float(abs_err[i]), "relative": float(rel[i]), "amplitude": float(amp[i])}
        for i, name in enumerate(names)
    }
    return components, float(np.max(abs_err)), float(np.max(rel))


def _one_period_error(problem, order, integrator_choice, rtol, stiff=False) -> float:
    """Max relative error of the analytic solution over one period, from its initial state."""
    solution = problem.solve(order)
    if not solution.success:
        return math.nan
    names = tuple(problem.state_names())
    with np.errstate(all="ignore"):
        period = float(problem.period(solution))
        if not (math.isfinite(period) and period > 0):
            return math.nan
        t = np.linspace(0.0, period, SAMPLES_PER_PERIOD + 1)
        analytic = _analytic(problem, solution, names, t)
    if not np.all(np.isfinite(analytic)):
        return math.nan
    original = original_system(problem, analytic[:, 0])
    solver = _resolve_integrator(integrator_choice, rtol, stiff, original.symbolic)
    traj = solver.integrate(original.rhs, (0.0, period), analytic[:, 0], t_eval=t)
    if not traj.success:
        return math.nan
    numeric = np.asarray(traj.y, dtype=float)
    return _component_errors(names, analytic, numeric)[2]


def _fit_slope(epsilons, errors, order) -> SlopeFit:
    eps = np.asarray(epsilons, dtype=float)
    err = np.asarray(errors, dtype=float)
    usable = np.isfinite(err) & (err > ERROR_FLOOR)
    notes = []
    if np.any(np.isfinite(err) & (err <= ERROR_FLOOR)):
        notes.append(f"points with error <= {ERROR_FLOOR:g} (oracle accuracy) dropped")
    if np.any(~np.isfinite(err)):
        notes.append("some points failed (NaN)")
    expected = order + 1.0
    if usable.sum() < 2:
        notes.append("fewer than two usable points: slope not measured")
        return SlopeFit(math.nan, expected, eps, err, None, "; ".join(notes))
    slope = float(np.polyfit(np.log(eps[usable]), np.log(err[usable]), 1)[0])
    return SlopeFit(
        slope, expected, eps, err, slope >= expected - SLOPE_TOLERANCE, "; ".join(notes)
    )


def _orbit_check(
    problem, solution, original, y0, period, setup, integrator_choice, rtol, stiff=False
) -> OrbitCheck:
    names = original.names
    orbit = find_periodic_orbit(
        original.rhs,
        y0,
        period,
        section_index=setup["section_index"],
        section_value=setup.get("section_value", 0.0),
        fixed_indices=setup["fixed_indices"],
        direction=setup["direction"],
        n_trivial=setup["n_trivial"],
        max_iter=SHOOTING_ITERATIONS,
        integrator=setup.get("integrator", STIFF_SHOOTING_INTEGRATOR if stiff else None),
        tol=STIFF_SHOOTING_TOL if stiff else SHOOTING_TOL,
    )
    nan = math.nan
    if not orbit.success:
        return OrbitCheck(
            success=False,
            period=orbit.period,
            initial_state=dict(zip(names, map(float, orbit.initial_state), strict=True)),
            floquet=tuple(complex(z) for z in orbit.floquet_multipliers),
            n_trivial=setup["n_trivial"],
            trivial_multiplier_error=orbit.trivial_multiplier_error,
            trivial_ok=False,
            period_error=nan,
            initial_state_error=nan,
            orbit_error=nan,
            message=orbit.message,
            status=orbit.status.code,
            integrator=orbit.integrator,
        )
    true_period = orbit.period
    init_error, orbit_error = _errors_against_orbit(
        problem,
        solution,
        original,
        y0,
        period,
        orbit.initial_state,
        true_period,
        integrator_choice,
        rtol,
        stiff,
    )
    multipliers = list(orbit.floquet_multipliers)
    n_trivial = setup["n_trivial"]
    gap = abs(complex(multipliers[n_trivial]) - 1) if len(multipliers) > n_trivial else 1.0
    defect = max(float(orbit.residual), SHOOTING_PRECISION)
    # below MULTIPLIER_FLOOR the gap itself is round-off: the orbit cannot be certified at all
    resolution = math.inf if gap < MULTIPLIER_FLOOR else defect / gap
    message = orbit.message
    if resolution > ORBIT_RESOLUTION_LIMIT:
        message += (
            f" Not resolved: the first non-trivial Floquet multiplier is {gap:.1e} from 1 (floor "
            f"{MULTIPLIER_FLOOR:g}), so a periodicity defect of {defect:.1e} leaves the orbit "
            f"uncertain by ~{resolution:.1e} of its amplitude; the orbit error is not used in the "
            "verdict."
        )
    return OrbitCheck(
        success=True,
        period=true_period,
        initial_state=dict(zip(names, map(float, orbit.initial_state), strict=True)),
        floquet=tuple(complex(z) for z in orbit.floquet_multipliers),
        n_trivial=setup["n_trivial"],
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        trivial_ok=orbit.trivial_multiplier_error <= FLOQUET_TOL,
        period_error=(period - true_period) / true_period,
        initial_state_error=init_error,
        orbit_error=orbit_error,
        message=message,
        status=orbit.status.code,
        integrator=orbit.integrator,
        resolution=resolution,
    )


def _errors_against_orbit(
    problem, solution, original, y0, period, true_y0, true_period, integrator_choice, rtol, stiff
) -> tuple[float, float]:
    """(initial-state error, orbit error) of the analytic solution against a true periodic orbit."""
    names = original.names
    true_y0 = np.asarray(true_y0, dtype=float)
    phases = np.linspace(0.0, 1.0, SAMPLES_PER_PERIOD + 1)
    analytic = _analytic(problem, solution, names, phases * period)
    solver = _resolve_integrator(integrator_choice, rtol, stiff, original.symbolic)
    traj = solver.integrate(original.rhs, (0.0, true_period), true_y0, t_eval=phases * true_period)
    if traj.success:
        _, _, orbit_error = _component_errors(names, analytic, np.asarray(traj.y, dtype=float))
        amp = _amplitudes(np.asarray(traj.y, dtype=float))
    else:
        orbit_error, amp = math.nan, _amplitudes(analytic)
    return float(np.max(np.abs(y0 - true_y0) / amp)), orbit_error


def _problem_true_orbit(
    problem, solution, original, y0, period, unresolved, integrator_choice, rtol, stiff=False
) -> OrbitCheck:
    """The problem's own ``true_periodic_orbit(solution)`` in place of an unresolved shooting.

    Called only when the generic double-precision shooting converged but could not resolve the
    orbit (:attr:`OrbitCheck.resolved` False): the hook (the disk's conditioned extended-precision
    shooting, ~0.5 s, needs heyoka) is dearer and problem-specific, and where double precision
    suffices it adds nothing. The hook returns an object with ``success``, ``period`` (physical),
    ``initial_state`` (the original state on the analytic solution's section), ``status``,
    ``message`` and optionally ``floquet``, ``n_trivial``, ``trivial_multiplier_error``,
    ``resolution``, ``integrator``. If it fails (e.g. no heyoka) the unresolved check is kept, with
    the hook's message appended.
    """
    try:
        true = problem.true_periodic_orbit(solution)
    except PerturbError as exc:
        return attrs.evolve(unresolved, message=f"{unresolved.message} {exc}")
    if not getattr(true, "success", False):
        return attrs.evolve(
            unresolved,
            message=f"{unresolved.message} The problem's own true-orbit finder did not run or "
            f"failed: {getattr(true, 'message', '')}",
        )
    true_y0 = np.asarray(true.initial_state, dtype=float)
    true_period = float(true.period)
    init_error, orbit_error = _errors_against_orbit(
        problem,
        solution,
        original,
        y0,
        period,
        true_y0,
        true_period,
        integrator_choice,
        rtol,
        stiff,
    )
    trivial_error = float(getattr(true, "trivial_multiplier_error", math.nan))
    return OrbitCheck(
        success=True,
        period=true_period,
        initial_state=dict(zip(original.names, map(float, true_y0), strict=True)),
        floquet=tuple(complex(z) for z in getattr(true, "floquet", ())),
        n_trivial=int(getattr(true, "n_trivial", unresolved.n_trivial)),
        trivial_multiplier_error=trivial_error,
        trivial_ok=trivial_error <= FLOQUET_TOL,
        period_error=(period - true_period) / true_period,
        initial_state_error=init_error,
        orbit_error=orbit_error,
        message=(
            f"Double-precision shooting could not resolve the orbit (resolution "
            f"{unresolved.resolution:.1e}); the problem's own true-orbit finder "
            f"ran instead: {true.message}"
        ),
        status=int(getattr(true, "status", 0)),
        integrator=str(getattr(true, "integrator", "")),
        resolution=float(getattr(true, "resolution", 0.0)),
    )


def _invariant_drift(original: OriginalSystem, y: np.ndarray) -> dict:
    if original.integrals is None or y.shape[1] == 0:
        return {}
    values = np.atleast_2d(np.asarray(original.integrals(y), dtype=float))
    if values.shape[-1] != y.shape[1]:  # a function of one state only: apply column by column
        values = np.array([np.asarray(original.integrals(col), dtype=float) for col in y.T]).T
    names = original.integral_names or tuple(f"I{i}" for i in range(values.shape[0]))
    out = {}
    for name, row in zip(names, values, strict=False):
        drift = np.abs(row - row[0])
        size = abs(row[0]) if row[0] != 0 else 1.0
        out[name] = InvariantDrift(
            name=name,
            initial=row[0],
            max_drift=float(np.max(drift)),
            relative_drift=float(np.max(drift)) / size,
            final_drift=float(drift[-1]),
        )
    return out


# --------------------------------------------------------------------------------------------------
# the front door
# --------------------------------------------------------------------------------------------------


def _preconditions(problem, eps: float) -> list[Condition]:
    conditions = [
        Condition(
            "epsilon small",
            eps,
            abs(eps) <= EPSILON_LIMIT,
            f"the expansion parameter {eps:.6g} must be small (|eps| <= {EPSILON_LIMIT})"
            if abs(eps) <= EPSILON_LIMIT
            else f"the expansion parameter {eps:.6g} is not small (> {EPSILON_LIMIT}), so a series "
            "in its powers cannot converge to the motion",
        )
    ]
    if hasattr(problem, "validity_conditions"):
        for name, value, ok, sentence in problem.validity_conditions():
            conditions.append(Condition(name, value, ok, sentence))
    return conditions


def _not_run(base: dict, *, verdict: str, message: str, period: float, timings: dict):
    """The report of a validation that could not start (nothing was integrated)."""
    return ValidationReport(
        **base,
        valid=False,
        verdict=verdict,
        completed=False,
        message=message,
        status=-1,
        t_reached=0.0,
        period=period,
        errors={},
        slope=None,
        periodic_orbit=None,
        invariants={},
        integrator="",
        stiffness=None,
        timings=timings,
    )


def validate(
    problem,
    order: int = 1,
    integrator: Integrator | str | None = None,
    periods: float = DEFAULT_PERIODS,
    *,
    rtol: float = DEFAULT_RTOL,
    initial_state: Sequence[float] | None = None,
    shoot: bool | None = None,
    slope: bool | None = None,
    samples_per_period: int = SAMPLES_PER_PERIOD,
    shooting_setup: Mapping | None = None,
) -> ValidationReport:
    """Check ``problem``'s analytic periodic solution against the true motion.

    Parameters
    ----------
    problem : problems.Problem
        A problem instance (``get_problem(name).create(...)``).
    order : int, optional
        Order of the analytic solution (>= 1).
    integrator : str or Integrator, optional
        The oracle for the trajectory: a name of :data:`perturb.oracle.INTEGRATORS` ('rk4',
        'dop853', 'rk45', 'radau', 'lsoda', 'heyoka') or an integrator object.  Default: Radau if the
        system is stiff, else heyoka when the problem's equations are symbolic, else DOP853.
    periods : float, optional
        Length of the comparison in analytic periods (> 0).
    rtol : float, optional
        Relative tolerance of the scipy integrators (> 0).
    initial_state : array_like, optional
        Start the integration here instead of at the analytic initial state (same order as
        ``problem.state_names()``); the comparison is still with the analytic solution.
    shoot : bool, optional
        Find the true periodic orbit by shooting.  Default: only when the preconditions hold.
    slope : bool, optional
        Measure the convergence slope in ε.  Default: only when the preconditions hold.
    samples_per_period : int, optional
        Output points per period of the comparison (>= 4).
    shooting_setup : mapping, optional
        Overrides the problem's ``shooting_setup()`` hook: ``section_index``, ``fixed_indices``,
        ``direction``, ``n_trivial`` (and optionally ``integrator``) for
        :func:`perturb.oracle.find_periodic_orbit`.

    Returns
    -------
    ValidationReport
        Always returned for valid input; a numerical failure gives ``completed = False``.

    Raises
    ------
    perturb.errors.UnknownNameError
        For an unknown integrator name (the message lists the known ones).
    perturb.errors.InvalidParameterError
        For ``order < 1``, ``periods <= 0``, ``rtol <= 0``, a non-finite ``initial_state`` or an
        analytic initial state that is not finite.

    Examples
    --------
    >>> from problems import get_problem
    >>> report = validate(get_problem("duffing").create(eps=0.05), periods=2, slope=False)
    >>> report.valid, report.completed
    (True, True)
    """
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or order < 1:
        raise bad_value("order", order, "pass an integer >= 1")
    periods = _check_positive("periods", periods, "pass a positive number of periods, e.g. 10")
    rtol = _check_positive("rtol", rtol, "pass a positive relative tolerance such as 1e-12")
    if (
        isinstance(samples_per_period, bool)
        or not isinstance(samples_per_period, int | np.integer)
        or samples_per_period < 4
    ):
        raise bad_value("samples_per_period", samples_per_period, "pass an integer >= 4")
    if isinstance(integrator, str) and integrator.lower() not in INTEGRATORS:
        raise UnknownNameError(
            f"`integrator` = {integrator!r} is not a known integrator: use one of "
            f"{sorted(INTEGRATORS)}"
        )
    start_override = None
    if initial_state is not None:
        try:
            start_override = np.asarray(initial_state, dtype=float)
        except (TypeError, ValueError):
            raise bad_value(
                "initial_state", initial_state, "pass a vector of real numbers"
            ) from None
        if start_override.ndim != 1 or not np.all(np.isfinite(start_override)):
            raise bad_value(
                "initial_state", initial_state, "every component must be finite (no NaN/inf)"
            )

    timings: dict[str, float] = {}
    clock = time.perf_counter()
    eps = float(problem.epsilon())
    conditions = _preconditions(problem, eps)
    names = tuple(problem.state_names())
    base = dict(
        problem=getattr(problem, "name", type(problem).__name__),
        parameters=problem.resolved_parameters(),
        order=int(order),
        epsilon=eps,
        conditions=conditions,
        periods=periods,
    )
    if start_override is not None and start_override.size != len(names):
        raise bad_value(
            "initial_state",
            initial_state,
            f"give {len(names)} components, in the order {list(names)}",
        )

    solution = problem.solve(order)
    timings["solve"] = time.perf_counter() - clock
    if not solution.success:
        return _not_run(
            base,
            verdict=f"the analytic construction failed ({solution.status.value}), so there is "
            "nothing to validate.",
            message=solution.message or solution.status.value,
            period=math.nan,
            timings=timings,
        )

    with np.errstate(all="ignore"):
        period = float(problem.period(solution))
        y_analytic0 = _analytic(problem, solution, names, np.zeros(1))[:, 0]
    breakdown = None
    if not (math.isfinite(period) and period > 0):
        breakdown = (
            f"the analytic period is {period:.6g}, not a positive number, so the series for the "
            "frequency has broken down"
        )
        period = _generating_period(problem, solution)
    if not np.all(np.isfinite(y_analytic0)):
        breakdown = f"the analytic initial state {y_analytic0.tolist()} is not finite"
        if start_override is None:
            return _not_run(
                base,
                verdict=f"The analytic solution breaks down: {breakdown}.",
                message=breakdown,
                period=period,
                timings=timings,
            )
    y0 = y_analytic0 if start_override is None else start_override
    original = original_system(problem, y0)

    # stiffness, from the Jacobian along one analytic period
    clock = time.perf_counter()
    samples = _analytic(
        problem, solution, names, np.linspace(0.0, period, STIFFNESS_SAMPLES, endpoint=False)
    )
    stiffness = stiffness_indicator(original.rhs, samples, period)
    hopeless = any(not c.ok for c in conditions) or breakdown is not None
    budget = INVALID_MAX_STEPS if hopeless else None
    solver = _resolve_integrator(integrator, rtol, stiffness.stiff, original.symbolic, budget)
    timings["stiffness"] = time.perf_counter() - clock

    # trajectory comparison
    clock = time.perf_counter()
    n_out = int(math.ceil(periods * samples_per_period)) + 1
    horizon = periods * period
    t = np.linspace(0.0, horizon, n_out)
    traj: Trajectory = solver.integrate(original.rhs, (0.0, horizon), y0, t_eval=t)
    timings["integrate"] = time.perf_counter() - clock
    clock = time.perf_counter()
    numeric = np.asarray(traj.y, dtype=float)
    reached = numeric.shape[1]
    analytic = _analytic(problem, solution, names, t[:reached])
    errors: dict[str, Any] = {"horizon": horizon}
    max_rel = math.nan
    if reached <= 1:  # only t = 0, where both start from the same state: nothing was compared
        errors["note"] = (
            f"the integration stopped at t = {traj.t_reached:.6g}, before the first comparison time "
            f"{t[1]:.6g}: no error was measured"
        )
    else:
        components, max_abs, max_rel = _component_errors(names, analytic, numeric)
        first = min(reached, samples_per_period + 1)
        _, _, first_rel = _component_errors(names, analytic[:, :first], numeric[:, :first])
        errors.update(
            components=components,
            max_abs=max_abs,
            max_relative=max_rel,
            first_period_max_relative=first_rel,
        )
    invariants = _invariant_drift(original, numeric)
    timings["compare"] = time.perf_counter() - clock

    # the true periodic orbit
    orbit = None
    if shoot is None:
        shoot = not hopeless
    if slope is None:
        slope = not hopeless
    if shoot and traj.success:
        clock = time.perf_counter()
        setup = _shooting_setup(
            problem, y_analytic0, original.rhs, len(invariants), samples, shooting_setup
        )
        try:
            orbit = _orbit_check(
                problem,
                solution,
                original,
                y_analytic0,
                period,
                setup,
                integrator,
                rtol,
                stiff=stiffness.stiff,
            )
            if orbit.success and not orbit.resolved and hasattr(problem, "true_periodic_orbit"):
                orbit = _problem_true_orbit(
                    problem,
                    solution,
                    original,
                    y_analytic0,
                    period,
                    orbit,
                    integrator,
                    rtol,
                    stiff=stiffness.stiff,
                )
        except PerturbError as exc:  # the seed itself was rejected: report, do not abort
            orbit = OrbitCheck(
                success=False,
                period=math.nan,
                initial_state={},
                floquet=(),
                n_trivial=setup["n_trivial"],
                trivial_multiplier_error=math.nan,
                trivial_ok=False,
                period_error=math.nan,
                initial_state_error=math.nan,
                orbit_error=math.nan,
                message=str(exc),
                status=-99,
            )
        timings["shooting"] = time.perf_counter() - clock

    # convergence slope
    fit = None
    if slope and traj.success:
        clock = time.perf_counter()
        eps_grid, err_grid = [], []
        for factor in SLOPE_FACTORS:
            try:
                variant = _with_epsilon(problem, eps * factor)
            except (PerturbError, ValueError):
                variant = None
            if variant is None:
                continue
            eps_grid.append(eps * factor)
            try:
                err_grid.append(
                    _one_period_error(variant, order, integrator, rtol, stiffness.stiff)
                )
            except (PerturbError, ValueError):
                err_grid.append(math.nan)
        if eps_grid:
            fit = _fit_slope(eps_grid, err_grid, order)
        else:
            fit = SlopeFit(
                math.nan,
                order + 1,
                (),
                (),
                None,
                "the problem cannot be re-created at other epsilon (no `with_epsilon` hook or "
                "`eps` parameter)",
            )
        timings["slope"] = time.perf_counter() - clock

    valid, verdict = _verdict(conditions, breakdown, traj, errors, max_rel, fit, orbit, periods)
    timings["total"] = sum(timings.values())
    completed, message = traj.success, traj.message
    if (
        hopeless and traj.status is TrajectoryStatus.MAX_STEPS
    ):  # a deliberate cut, not a numerical failure
        completed = True
        message = (
            f"stopped at t = {traj.t_reached:.6g} by the step budget {INVALID_MAX_STEPS} of a run "
            "whose preconditions fail (errors cover [0, t_reached]); pass an integrator with a "
            "larger max_steps to go further"
        )
    return ValidationReport(
        **base,
        valid=valid,
        verdict=verdict,
        completed=completed,
        message=message,
        status=traj.status.code,
        t_reached=traj.t_reached,
        period=period,
        errors=errors,
        slope=fit,
        periodic_orbit=orbit,
        invariants=invariants,
        integrator=traj.integrator or solver.name,
        stiffness=stiffness,
        timings=timings,
    )


def _verdict(conditions, breakdown, traj, errors, max_rel, fit, orbit, periods) -> tuple[bool, str]:
    """The verdict rules, in order (see ``docs/validation.md``)."""
    failed = [c for c in conditions if not c.ok]
    if failed:
        return False, f"The expansion cannot hold: {failed[0].sentence}."
    if breakdown is not None:
        return False, f"The analytic solution breaks down: {breakdown}."
    if not traj.success:
        return False, (
            f"The true motion could not be computed: the integration stopped at t = "
            f"{traj.t_reached:.6g} ({traj.message})."
        )
    if not (max_rel <= MAX_RELATIVE_ERROR):
        worst = max(errors["components"].items(), key=lambda kv: kv[1]["relative"])[0]
        return False, (
            f"The analytic solution departs from the true motion by {max_rel:.3g} of the amplitude "
            f"(component {worst}) within {periods:g} periods (limit {MAX_RELATIVE_ERROR:g})."
        )
    if orbit is not None and orbit.resolved and not (orbit.orbit_error <= MAX_RELATIVE_ERROR):
        return False, (
            f"The analytic solution is {orbit.orbit_error:.3g} (relative) away from the true "
            f"periodic orbit (limit {MAX_RELATIVE_ERROR:g})."
        )
    if fit is not None and fit.consistent is False:
        return False, (
            f"The error does not shrink like eps^{fit.expected:g}: its measured slope is "
            f"{fit.slope:.2f}, so the agreement at this eps is accidental."
        )
    detail = f"error {max_rel:.2e} of the amplitude over {periods:g} periods"
    if fit is not None and fit.consistent:
        detail += f", slope {fit.slope:.2f} (expected {fit.expected:g})"
    if orbit is not None and orbit.resolved:
        detail += f", {orbit.orbit_error:.2e} from the true periodic orbit"
    elif orbit is not None and orbit.success:
        detail += (
            "; the true periodic orbit is not resolved by shooting at this precision (a Floquet "
            "multiplier next to the trivial ones)"
        )
    elif orbit is not None:
        detail += "; the true periodic orbit was not found by shooting"
    return True, f"The analytic solution describes the true motion: {detail}."
