"""The results of the true curve (``perturb response --true``): the true points, special points,
curves and partings (:mod:`perturb.response.true_curve` computes them)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from attrs import field, frozen

from perturb._defaults import TRUE_CURVE_SAME_ORBIT
from perturb.errors import bad_value

if TYPE_CHECKING:
    from perturb.oracle import PeriodicOrbit

__all__ = ["Parting", "TrueBifurcation", "TrueCurve", "TrueCurves", "TruePoint", "same_point"]

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
    orbit : PeriodicOrbit
        The true orbit (``found_by`` :attr:`~perturb.oracle.OrbitRoute.CONTINUATION`): its state
        at t = 0 (θ = 0), ``(x..., xdot...)``, its period in physical time, its multipliers and
        monodromy; :attr:`state` and :attr:`multipliers` read them.
    norms : dict
        Per resonant coordinate, the measure the analytic curve plots: the first harmonic's
        amplitude read from the initial values, :math:`\\sqrt{x(0)^2 + (\\dot x(0)\\,p/(m\\Omega))^2}`.
    peaks : dict
        Per coordinate, max ``|x|`` over one period.
    harmonics : dict
        Per resonant coordinate, the amplitude of its resonant harmonic (Fourier, over a period).
    stable : bool or None
        All multipliers inside the unit circle (None: the largest within
        ``TRUE_CURVE_MULTIPLIER_TOL`` of it, a conservative system's orbit).
    """

    value: float = field(converter=float)
    orbit: PeriodicOrbit
    norms: dict
    peaks: dict
    harmonics: dict
    stable: bool | None

    @property
    def state(self) -> tuple:
        """The orbit's state at t = 0 (θ = 0), as floats."""
        return tuple(float(x) for x in self.orbit.initial_state)

    @property
    def multipliers(self) -> tuple:
        """The orbit's Floquet multipliers (eigenvalues of the monodromy), as complex numbers."""
        return _complexes(self.orbit.multipliers)

    def norm(self, coordinate: str | None = None) -> float:
        """The initial-value measure of ``coordinate`` (default: the first resonant one)."""
        return self.norms[coordinate] if coordinate else next(iter(self.norms.values()))

    def amplitude(self, coordinate: str | None = None, measure: str = "initial") -> float:
        """``coordinate``'s amplitude by ``measure``: ``peak`` (max ``|x|`` over a period),
        ``first-harmonic`` or ``initial`` (as the analytic response's points)."""
        return _by_measure(self.norms, self.peaks, self.harmonics, coordinate, measure)


@frozen
class TrueBifurcation:
    """A special point of a true curve, located on it.

    Attributes
    ----------
    kind : str
        ``fold``, ``branch-point``, ``period-doubling`` or ``neimark-sacker``; ``crossing`` on
        a doubled orbit's curve where it meets its parent (the parent's period doubling, where
        the two are one orbit).
    value : float
    norms, peaks : dict
        As :class:`TruePoint`'s, at the point.
    multiplier : complex
        The critical multiplier (+1, −1, or on the circle), as computed there.
    orbit : PeriodicOrbit or None
        The true orbit there (None when not known); :attr:`multipliers` and :attr:`state` read
        it (empty when not known).
    inside : bool
        Within the sweep (False: in the margin past an end).
    located : bool
        The sign change was located to the continuation's tolerance.
    note : str
    harmonics : dict
        As :class:`TruePoint`'s, at the point.
    rotation : float
        At a Neimark–Sacker point, the rotation number of the torus born there: the argument of
        the complex multiplier over 2π (NaN at the other kinds).
    """

    kind: str
    value: float = field(converter=float)
    norms: dict
    peaks: dict
    multiplier: complex = field(converter=complex)
    orbit: PeriodicOrbit | None
    inside: bool
    located: bool = True
    note: str = ""
    harmonics: dict = field(factory=dict)
    rotation: float = field(default=math.nan, converter=float)

    @property
    def state(self) -> tuple:
        """The state at t = 0 there (empty when not known)."""
        return () if self.orbit is None else tuple(float(x) for x in self.orbit.initial_state)

    @property
    def multipliers(self) -> tuple:
        """The Floquet multipliers there (empty when not known)."""
        return () if self.orbit is None else _complexes(self.orbit.multipliers)

    def amplitude(self, coordinate: str | None = None, measure: str = "initial") -> float:
        """As :meth:`TruePoint.amplitude`, at the special point."""
        return _by_measure(self.norms, self.peaks, self.harmonics, coordinate, measure)


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
    period : int
        The responses' period in response periods of the problem (1; 2 past a period doubling,
        4 past the next…).
    parent : int or None
        The index (in :attr:`TrueCurves.curves`) of the curve it was born on; None for a curve
        through the analytic branches.
    birth : str
        How it was born: ``seed`` (through an analytic branch's state), ``branch-point`` (the
        other branch through a branch point: the asymmetric pair at a symmetric system's
        pitchfork) or ``period-doubling``.
    born_at : float
        The swept parameter at its birth (NaN for a seeded curve).
    """

    branches: tuple = field(converter=tuple)
    points: tuple = field(converter=tuple)
    bifurcations: tuple = field(converter=tuple)
    status: str
    success: bool
    message: str
    shots: int = 0
    period: int = 1
    parent: int | None = None
    birth: str = "seed"
    born_at: float = field(default=math.nan, converter=float)


@frozen
class Parting:
    """Where an analytic branch leaves the true curve by more than the tolerance.

    Attributes
    ----------
    branch : str
    value : float
        The swept parameter where the relative difference crosses ``tolerance`` (interpolated
        between ``before`` and ``after``), or the true fold ``before`` where the true orbit the
        branch agreed with ends.
    analytic, true : float
        The two amplitudes (the analytic curve's measure) there; ``true`` NaN where no true
        orbit is left.
    difference : float
        At the first grid value past the crossing (inf: no true orbit there).
    tolerance : float
    before : float
        The last value read where they agree: a grid value, or a fold of a true curve between
        two (NaN: they agree nowhere on the branch).
    after : float
        The first value read where they do not.
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
    measure : str
        The amplitude measure of the partings (and of a plot): ``initial``, ``peak`` or
        ``first-harmonic``.
    max_period : int
        The longest period (in response periods) whose period doublings were followed.
    """

    parameter: str
    curves: tuple = field(converter=tuple)
    partings: tuple = field(converter=tuple)
    budget: int
    tolerance: float
    integrator: str = ""
    failures: tuple = field(converter=tuple, factory=tuple)
    measure: str = "initial"
    max_period: int = 1

    @property
    def bifurcations(self) -> tuple:
        """Every special point of every curve, sorted by value; one found on two curves (where
        they overlap, e.g. a curve stopped by its budget and another from a second seed) once."""
        out: list = []
        for b in sorted((b for c in self.curves for b in c.bifurcations), key=lambda b: b.value):
            if not any(same_point(b, seen) for seen in out):
                out.append(b)
        return tuple(out)


def _by_measure(norms, peaks, harmonics, coordinate, measure) -> float:
    table = {"peak": peaks, "first-harmonic": harmonics, "initial": norms}
    if measure not in table:
        raise bad_value("measure", measure, f"choose one of {sorted(table)}")
    values = table[measure]
    coordinate = coordinate or next(iter(norms))
    return float(values.get(coordinate, math.nan))


def same_point(a: TrueBifurcation, b: TrueBifurcation) -> bool:
    """The same special point: the same kind, value and amplitudes. A branch point is where two
    curves cross, met on each: located in the parameter to the secant's tolerance, but on the
    curve that turns there (a pitchfork) in amplitude only to its square root."""
    if a.kind != b.kind:
        return False
    close = TRUE_CURVE_SAME_ORBIT
    spread = math.sqrt(close) if a.kind == BRANCH_POINT else close
    if abs(a.value - b.value) > close * max(1.0, abs(a.value)):
        return False
    return all(
        abs(a.norms[c] - b.norms.get(c, math.nan)) <= spread * max(1.0, abs(a.norms[c]))
        for c in a.norms
    )
