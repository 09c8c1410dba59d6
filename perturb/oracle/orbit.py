"""The one true periodic orbit: :class:`PeriodicOrbit`, its :class:`OrbitStatus` and its
:class:`OrbitRoute`.

Every route to a true orbit returns this value — the autonomous shooting, the driven (period
given) shooting, the disk's conditioned extended-precision shooting and its 40-digit mpmath
route, a model's own finder (:class:`perturb.validation.OrbitEstimate` builds one) — with its
Floquet multipliers under one name, :attr:`PeriodicOrbit.multipliers`, and the route that found
it, :attr:`PeriodicOrbit.found_by`. What a client measures about an orbit (a validation's errors,
a response's amplitudes, a catalogue's capture radius) lives in the client's own result, beside
the orbit, never as another orbit type."""

from __future__ import annotations

import enum
import math
from typing import Any

import attrs
import numpy as np
from attrs import field, frozen

from perturb.errors import PerturbError

__all__ = ["OrbitRoute", "OrbitStatus", "PeriodicOrbit", "multipliers_of"]


class OrbitStatus(enum.Enum):
    """How a shooting search ended; the values are the user-facing messages.

    :attr:`PeriodicOrbit.message` gives the numbers of the particular run.

    Examples
    --------
    >>> from perturb.oracle import OrbitStatus
    >>> print(OrbitStatus.CONVERGED.value)
    The shooting converged to a periodic orbit.
    >>> [status.name for status in OrbitStatus][:3]
    ['CONVERGED', 'MAX_ITER', 'INTEGRATION_FAILED']
    """

    CONVERGED = "The shooting converged to a periodic orbit."
    MAX_ITER = "The Newton iteration did not converge within `max_iter` iterations."
    INTEGRATION_FAILED = "An integration of the state and variational equations failed."
    STALLED = "The Newton iteration stalled: no step reduces the residual (integration accuracy)."
    WRONG_DIRECTION = "Converged, but the orbit crosses the section in the wrong direction."
    EQUILIBRIUM = (
        "Converged onto an equilibrium, not a periodic orbit (a family parameter was not pinned)."
    )
    UNAVAILABLE = "The orbit finder cannot run here (a capability it needs is not installed)."
    REFUSED = "The orbit finder refused its seed or its problem."
    UNRESOLVED = (
        "Converged, but the defect does not determine the orbit (a singular Newton matrix)."
    )
    FAILED = "The orbit finder failed; its message says why."

    @property
    def success(self) -> bool:
        """True only for :attr:`CONVERGED`."""
        return self is OrbitStatus.CONVERGED

    @property
    def code(self) -> int:
        """The legacy integer code (0 converged, negative failure), for integer JSON fields."""
        return _ORBIT_CODES[self]

    @classmethod
    def of_code(cls, code: int) -> OrbitStatus:
        """The status of a legacy integer code (:attr:`code`'s inverse).

        Examples
        --------
        >>> OrbitStatus.of_code(-3).name
        'STALLED'
        """
        return _BY_CODE[int(code)]


_ORBIT_CODES = {
    OrbitStatus.CONVERGED: 0,
    OrbitStatus.MAX_ITER: -1,
    OrbitStatus.INTEGRATION_FAILED: -2,
    OrbitStatus.STALLED: -3,
    OrbitStatus.WRONG_DIRECTION: -4,
    OrbitStatus.EQUILIBRIUM: -5,
    OrbitStatus.UNAVAILABLE: -10,
    OrbitStatus.REFUSED: -11,
    OrbitStatus.UNRESOLVED: -12,
    OrbitStatus.FAILED: -13,
}
_BY_CODE = {code: status for status, code in _ORBIT_CODES.items()}


class OrbitRoute(enum.Enum):
    """How a true orbit was found; the values are the sentences a report gives.

    Examples
    --------
    >>> from perturb.oracle import OrbitRoute
    >>> print(OrbitRoute.SHOOTING.value)
    Newton shooting on a Poincaré section (the period among the unknowns).
    """

    SHOOTING = "Newton shooting on a Poincaré section (the period among the unknowns)."
    FORCED = "Newton shooting with the period given by the forcing."
    CONDITIONED = (
        "Newton shooting in conditioned coordinates, in extended precision, from exact inputs."
    )
    MPMATH = "Newton shooting on a Taylor flow in mpmath arithmetic (40 digits)."
    CONTINUATION = "Pseudo-arclength continuation of the fixed-period shooting map."
    MODEL = "The model's own true-orbit finder."


def _readonly(value: Any) -> np.ndarray:
    array = np.array(value)
    array.setflags(write=False)
    return array


_array_eq = attrs.cmp_using(eq=np.array_equal)


@frozen
class PeriodicOrbit:
    """A periodic orbit found by shooting, with its Floquet multipliers and how the search ended.

    Attributes
    ----------
    period : float
        The period :math:`T`.
    initial_state : ndarray, shape (n,)
        :math:`y(0)`, on the section.
    multipliers : ndarray, shape (n,), complex
        The Floquet multipliers: eigenvalues of :attr:`monodromy`, sorted by distance from 1 (the
        trivial ones first). :attr:`floquet_multipliers` is the same array by its older name.
    monodromy : ndarray, shape (n, n)
        :math:`\\Phi(T)`, the linearised flow over one period.
    residual : float
        Relative periodicity defect :math:`\\|y(T) - y(0)\\|_\\infty / s`, ``s`` the state scale.
    iterations : int
        Newton iterations performed.
    status : OrbitStatus
        :attr:`OrbitStatus.CONVERGED`, or why the search failed: ``MAX_ITER``,
        ``INTEGRATION_FAILED``, ``STALLED`` (no step reduces the residual: integrator accuracy limits
        it), ``WRONG_DIRECTION`` (converged but crossing the section in the wrong direction) or
        ``EQUILIBRIUM`` (a fixed point is "periodic" with any period, typically because a family
        parameter was not pinned).
    message : str
        What happened, with the numbers.
    trivial_multiplier_error : float
        Largest distance from 1 among the ``n_trivial`` multipliers closest to 1.  For a double
        multiplier (a Jordan block, e.g. a conservative family) it scales like the square root of the
        integration error, so expect ~1e-7 there rather than ~1e-13.
    integrator : str
        The integrator that ran.
    precision_floor : float
        The smallest residual the working precision can show at the orbit (relative, as
        ``residual``): the round-off of the defect and, when Newton stopped gaining above ``tol``,
        the integration error measured a posteriori. A residual above ``tol`` but within
        ``FLOOR_SAFETY`` of it is converged (the message says so).
    n_trivial_expected : int or None
        Multipliers that must equal 1: the ``n_trivial`` given, or the count derived from the
        integrals and ``hamiltonian`` by :func:`~perturb.oracle.floquet.expected_trivial_multipliers`
        (None: a model's own finder left it to validation).
    n_trivial_found : int
        Multipliers found within ``TRIVIAL_MULTIPLIER_TOL`` of 1 (0 when the monodromy is not
        finite).  More than expected: a nearly neutral direction or an unlisted integral; fewer: an
        integral that is not one, or an inaccurate monodromy.
    defect : ndarray or None
        The periodicity defect :math:`y(T) - y(0)` of each component at :attr:`initial_state` (the
        shot :attr:`residual` is of), None where no shot succeeded. The residual is its largest
        component; the components tell which rows of the Newton system are how far from zero
        (an error bound through the Newton matrix needs them, not their maximum).

    Examples
    --------
    The van der Pol limit cycle at ε = 1, found by shooting from a rough guess:

    >>> import numpy as np
    >>> from perturb.oracle import find_periodic_orbit
    >>> def vdp(y):
    ...     return np.array([y[1], (1 - y[0] ** 2) * y[1] - y[0]])
    >>> orbit = find_periodic_orbit(vdp, [2.0, 0.0], 6.5, section_index=1)
    >>> bool(orbit.success), round(orbit.period, 6)
    (True, 6.663287)
    >>> bool(abs(orbit.multipliers[0] - 1) < 1e-6)  # the trivial multiplier of an autonomous orbit
    True
    >>> orbit.found_by.name
    'SHOOTING'

    """

    period: float = field(converter=float)
    initial_state: np.ndarray = field(converter=_readonly, eq=_array_eq)
    multipliers: np.ndarray = field(converter=_readonly, eq=_array_eq)
    monodromy: np.ndarray = field(converter=_readonly, eq=_array_eq)
    residual: float = field(converter=float)
    iterations: int
    status: OrbitStatus = field(validator=attrs.validators.instance_of(OrbitStatus))
    message: str
    trivial_multiplier_error: float = math.nan
    integrator: str = ""
    n_trivial_expected: int | None = 0
    n_trivial_found: int = 0
    precision_floor: float = math.nan
    defect: np.ndarray | None = field(
        default=None, converter=attrs.converters.optional(_readonly), eq=False
    )
    found_by: OrbitRoute = field(
        default=OrbitRoute.SHOOTING, validator=attrs.validators.instance_of(OrbitRoute)
    )
    resolution: float = field(default=math.nan, converter=float)

    @property
    def floquet_multipliers(self) -> np.ndarray:
        """:attr:`multipliers`, by the name of earlier versions."""
        return self.multipliers

    @property
    def success(self) -> bool:
        """True if the iteration converged to an orbit crossing the section as requested."""
        return self.status.success

    def raise_for_status(self) -> PeriodicOrbit:
        """Return ``self`` if successful, else raise :class:`perturb.errors.PerturbError`."""
        if not self.success:
            raise PerturbError(f"shooting failed ({self.status.name}): {self.message}")
        return self


def multipliers_of(phi: np.ndarray) -> np.ndarray:
    """Eigenvalues of the monodromy matrix sorted by distance from 1."""
    values = np.linalg.eigvals(phi).astype(complex)
    return values[np.argsort(np.abs(values - 1.0), kind="stable")]
