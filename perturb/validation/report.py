"""The result value objects of :func:`perturb.validation.validate` (data only).

Their JSON dictionary and text table are built by :mod:`perturb.report.validation`
(``validation_as_dict``, ``validation_as_table``); the ``as_dict``/``as_table`` methods below only
delegate there, for code written against earlier versions.
"""

from __future__ import annotations

import enum
import math

from attrs import field, frozen

__all__ = [
    "Check",
    "Condition",
    "InvariantDrift",
    "OrbitCheck",
    "SlopeFit",
    "Stiffness",
    "ValidationReport",
    "Verdict",
]


class Verdict(enum.Enum):
    """The outcome of a validation; the values are the messages shown to users.

    Examples
    --------
    >>> from perturb.validation import Verdict
    >>> [verdict.name for verdict in Verdict]
    ['VALID', 'INVALID', 'UNDECIDED', 'LOWER_ORDER']
    >>> print(Verdict.UNDECIDED.value)
    the checks could not decide whether the analytic solution describes the true motion
    """

    VALID = "the analytic solution describes the true motion"
    INVALID = "the analytic solution does not describe the true motion"
    UNDECIDED = (
        "the checks could not decide whether the analytic solution describes the true motion"
    )
    LOWER_ORDER = (
        "the analytic solution describes the true motion, but to a lower order than asked: its "
        "error falls like eps^(k+1) with k < N"
    )

    @property
    def success(self) -> bool:
        """True only for :attr:`VALID` (a lower order than asked is not what was asked)."""
        return self is Verdict.VALID

    @property
    def label(self) -> str:
        """``"valid"``, ``"invalid"``, ``"undecided"`` or ``"lower_order"`` (the JSON ``outcome``)."""
        return self.name.lower()


@frozen
class Check:
    """One measurement of the verdict: a number against its tolerance.

    Attributes
    ----------
    name : str
        ``"existence"``, ``"orbit_error"``, ``"period_error"`` or ``"order"``.
    value : float
        The measured number (NaN when the check could not run).
    tolerance : float
        The bound it is compared with.
    passed : bool or None
        None when the check could not run (the verdict is then at best UNDECIDED).
    sentence : str
        What was measured, with the numbers, or why it could not be.
    comparison : str
        ``"<="`` (value must not exceed the tolerance) or ``">="`` (the slope: value must reach it).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, validate
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> report = validate(vdp, values={"epsilon": 0.1}, order=2)
    >>> check = report.check("period_error")
    >>> check.passed, check.tolerance, check.comparison
    (True, 0.1, '<=')
    >>> [c.name for c in report.checks]
    ['existence', 'orbit_error', 'period_error', 'order']
    """

    name: str
    value: float = field(converter=float)
    tolerance: float = field(converter=float)
    passed: bool | None
    sentence: str
    comparison: str = "<="


@frozen
class Condition:
    """A problem's own validity estimate (it explains and warns; it does not decide the verdict).

    Attributes
    ----------
    name : str
        Short label, e.g. ``"detuning dominates"``.
    value : float
        The quantity estimated (a ratio that must be small).
    ok : bool
    sentence : str
        What the estimate says, with the numbers.

    Examples
    --------
    The disk's own estimates at the paper's data, where ε = c/r0 = 232 is far from small:

    >>> from problems import get_problem
    >>> conditions = get_problem("disk").create().validity_estimates()
    >>> [(c.name, c.ok) for c in conditions][:1]
    [('ε = c/r0 small', False)]
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

    Examples
    --------
    Duffing's oscillator conserves its energy; the drift along the integrated trajectory measures the
    integrator:

    >>> from perturb import validate
    >>> from problems import get_problem
    >>> report = validate(get_problem("duffing").create(eps=0.1), order=1)
    >>> drift = report.invariants["energy"]
    >>> drift.name, bool(drift.relative_drift < 1e-10)
    ('energy', True)
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
    """Convergence of the analytic solution's error in ε (the order check).

    Attributes
    ----------
    slope : float
        Least-squares slope of log(error) against log|ε| (NaN if fewer than two usable points).
    expected : float
        ``order + 1``: the slope of an :math:`O(\\varepsilon^{n+1})` error.
    epsilons, errors : tuple of float
        The ε values (the user's sign kept) and the one-period relative errors (NaN where a point
        failed).
    consistent : bool or None
        ``slope >= expected - SLOPE_TOLERANCE``; True without a slope when every error is at the
        oracle's floor; None if the slope could not be measured.
    note : str
        Why points were dropped or the slope is missing.
    band : float
        How far below ``expected`` the slope may fall (:data:`SLOPE_TOLERANCE`).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, validate
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> report = validate(vdp, values={"epsilon": 0.1}, order=2)
    >>> fit = report.slope
    >>> fit.expected, round(fit.slope, 1), fit.consistent
    (3.0, 3.0, True)
    >>> [float(e) for e in fit.epsilons]
    [0.0125, 0.025, 0.05, 0.1]
    """

    slope: float = field(converter=float)
    expected: float = field(converter=float)
    epsilons: tuple = field(converter=tuple)
    errors: tuple = field(converter=tuple)
    consistent: bool | None
    note: str = ""
    band: float = field(default=0.5, converter=float)

    def as_dict(self) -> dict:
        return {
            "value": self.slope,
            "expected": self.expected,
            "band": self.band,
            "consistent": self.consistent,
            "epsilons": list(self.epsilons),
            "errors": list(self.errors),
            "note": self.note,
        }


@frozen
class OrbitCheck:
    """The true periodic orbit found by shooting, and the analytic solution's distance from it.

    Attributes
    ----------
    success : bool
        Whether the shooting converged.
    period : float
        True period (NaN on failure).
    initial_state : dict
        True state at the section crossing, by name.
    multipliers : tuple of complex
        Floquet multipliers of the true orbit, sorted by distance from 1 (trivial ones first);
        given to the constructor as ``floquet``, and read as :attr:`floquet` too (the name of
        the report's contract).
    n_trivial : int
        Number of multipliers expected at 1 (autonomy + first integrals / families).
    trivial_multiplier_error : float
        Largest distance from 1 among the trivial multipliers.
    trivial_ok : bool
        ``trivial_multiplier_error <= FLOQUET_TOL``.
    period_error : float
        (analytic period − true period) / true period.
    initial_state_error : float
        Max over components of ``|analytic − true|`` initial state, relative to the amplitudes.
    orbit_error : float
        Max distance of the analytic orbit from the true one over one period, at equal phases,
        relative to the orbit's size (the largest amplitude).
    message : str
        The shooting's own message.
    status : enum member or None
        The shooting's status (:class:`perturb.oracle.OrbitStatus`); None when the seed was
        refused before any shooting (``message`` says why).
    integrator : str
    resolution : float
        How far (relative to the amplitudes) the shooting's own uncertainty may move the orbit:
        the Newton residual over the distance of the first non-trivial Floquet multiplier from 1.
        A nearly neutral direction (two oscillations with almost the same frequency) makes the orbit
        numerically non-isolated; above ``ORBIT_RESOLUTION_LIMIT`` it is reported as unresolved
        and the existence check cannot pass.
    resolution_limit : float
        ``ORBIT_RESOLUTION_LIMIT``.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, validate
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> report = validate(vdp, values={"epsilon": 0.1}, order=2)
    >>> orbit = report.periodic_orbit
    >>> orbit.success, orbit.n_trivial, orbit.trivial_ok
    (True, 1, True)
    >>> round(orbit.period, 6), bool(orbit.period_error < 1e-5)
    (6.287111, True)
    """

    success: bool
    period: float = field(converter=float)
    initial_state: dict
    multipliers: tuple = field(converter=tuple, alias="floquet")
    n_trivial: int
    trivial_multiplier_error: float = field(converter=float)
    trivial_ok: bool
    period_error: float = field(converter=float)
    initial_state_error: float = field(converter=float)
    orbit_error: float = field(converter=float)
    message: str
    status: object
    integrator: str = ""
    resolution: float = field(default=0.0, converter=float)
    resolution_limit: float = field(default=1e-3, converter=float)

    @property
    def floquet(self) -> tuple:
        """:attr:`multipliers`, by the name of the report (its JSON keys ``floquet``)."""
        return self.multipliers

    @property
    def resolved(self) -> bool:
        """Whether shooting at this precision determines the orbit well enough to judge against it."""
        return self.success and self.resolution <= self.resolution_limit


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
        ``ratio > threshold``.
    threshold : float

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, validate
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> report = validate(vdp, values={"epsilon": 0.1}, order=2)
    >>> report.stiffness.stiff, report.stiffness.threshold
    (False, 10.0)
    """

    ratio: float = field(converter=float)
    max_real: float = field(converter=float)
    max_imag: float = field(converter=float)
    stiff: bool
    threshold: float = field(default=10.0, converter=float)

    def as_dict(self) -> dict:
        return {
            "ratio": self.ratio,
            "max_real": self.max_real,
            "max_imag": self.max_imag,
            "stiff": self.stiff,
            "threshold": self.threshold,
        }


@frozen
class ValidationReport:
    """Outcome of :func:`perturb.validation.validate`: measurements, a verdict and how the run went.

    Attributes
    ----------
    problem : str
        Name of the problem (or system).
    parameters : dict
        Every parameter value in force.
    order : int
    epsilon : float
        The expansion parameter ε of the problem.
    valid : bool
        True only when :attr:`outcome` is :attr:`Verdict.VALID`.
    verdict : str
        One sentence giving the outcome and its reason, with the figures.
    completed : bool
        False only when the run failed numerically (the construction failed, the integration
        failed, or the analytic state is not finite); then ``message``, ``status`` and
        ``t_reached`` carry the report of what failed.
    message : str
    status : enum member or None
        The trajectory integrator's status (:class:`perturb.oracle.TrajectoryStatus`); None when
        nothing was integrated.
    t_reached : float
        How far the trajectory integration got.
    conditions : tuple of Condition
        The problem's own validity estimates (information and warnings).
    period : float
        The analytic period.
    periods : float
        Number of periods integrated for the trajectory information.
    errors : dict
        Trajectory information: ``{"components": {name: {"abs", "relative", "amplitude"}},
        "max_abs", "max_relative", "first_period_max_relative", "horizon"}``.
    slope : SlopeFit or None
    periodic_orbit : OrbitCheck or None
    invariants : dict of InvariantDrift
    integrator : str
        The integrator that actually ran the trajectory comparison.
    stiffness : Stiffness or None
    timings : dict
        Wall time in seconds of each stage.
    outcome : Verdict
        VALID, INVALID, UNDECIDED or LOWER_ORDER.
    accurate_order : int or None
        With LOWER_ORDER: the k of "accurate to O(eps^(k+1))" the measured slope supports (the
        solution is then as good as an order-k one); None otherwise.
    checks : tuple of Check
        The measurements the verdict rests on (existence, orbit error, period error, order).
    tol : float
        The accuracy tolerance in force.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, validate
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> report = validate(vdp, values={"epsilon": 0.1}, order=2)
    >>> report.outcome
    <Verdict.VALID: 'the analytic solution describes the true motion'>
    >>> report.problem, report.order, report.epsilon
    ('van der Pol', 2, 0.1)
    >>> print(report.verdict[:62])
    The analytic solution describes the true motion: a true period
    """

    problem: str
    parameters: dict
    order: int
    epsilon: float = field(converter=float)
    valid: bool
    verdict: str
    completed: bool
    message: str
    status: object
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
    outcome: Verdict = Verdict.UNDECIDED
    checks: tuple = field(default=(), converter=tuple)
    tol: float = field(default=math.nan, converter=float)
    accurate_order: int | None = None

    def check(self, name: str) -> Check | None:
        """The check called ``name``, or None if it is not in the report."""
        return next((c for c in self.checks if c.name == name), None)
