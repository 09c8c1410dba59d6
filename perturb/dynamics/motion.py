"""The true motion of a driven problem at its values: the equations every study here integrates.

A driven problem's original equations (:func:`perturb.validation.original_equations`) are
integrated in their autonomous form: the state ``(y_1..y_m, θ)`` with :math:`\\theta' = \\Omega`
last. A *section* is the state at the drive phases :math:`\\theta \\equiv \\varphi \\pmod{2\\pi}`:
the stroboscopic map advances it by one drive period :math:`T = 2\\pi/\\Omega`; a response of
``p`` drive periods (a subharmonic or parametric resonance, :class:`perturb.Excitation`'s ratio)
is ``p`` points of it.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb.errors import InvalidParameterError, bad_value
from perturb.oracle import SymbolicRHS
from perturb.validation.capabilities import label_of
from perturb.validation.truth import original_equations

__all__ = ["DrivenMotion", "heyoka_equations", "motion_of"]


@frozen
class DrivenMotion:
    """The autonomous equations of a driven problem at its parameter values.

    Attributes
    ----------
    rhs : SymbolicRHS
        State ``(y_1..y_m, θ)``, θ' = Ω last.
    names : tuple of str
        The state's names without θ (``("x", "xdot")``).
    omega : float
        The drive frequency Ω (θ' as integrated).
    response_periods : int
        Drive periods in one period of the response (the excitation's p).
    label : str
        The problem's name.
    """

    rhs: SymbolicRHS = field(eq=False)
    names: tuple = field(converter=tuple)
    omega: float
    response_periods: int
    label: str = ""

    @property
    def m(self) -> int:
        """Dimension of the state without θ."""
        return len(self.names)

    @property
    def drive_period(self) -> float:
        """T = 2π/Ω."""
        return 2 * math.pi / self.omega

    def index(self, name: str, argument: str) -> int:
        """The position of the state component ``name``.

        Raises
        ------
        InvalidParameterError
            ``name`` is not a component of the state (one line naming ``argument``).
        """
        if name not in self.names:
            raise InvalidParameterError(
                f"{argument} {name!r}: not a coordinate of the state of {self.label}; give one "
                f"of {', '.join(self.names)}"
            )
        return self.names.index(name)

    def state(self, values, argument: str) -> np.ndarray:
        """A state from ``{name: value}`` (unnamed components 0), checked: every name a component
        of the state, every value finite.

        Raises
        ------
        InvalidParameterError
            An unknown name, a value not finite (outside the problem's state space).
        """
        y = np.zeros(self.m)
        for name, value in dict(values).items():
            y[self.index(name, argument)] = _finite(value, f"{argument} {name}")
        return y

    def vector_field(self):
        """``f(Y, theta) -> dY`` on arrays of shape (m, M): the right-hand side of the state
        without θ, vectorised over M states (numpy)."""
        return _numpy_field(self.rhs, self.m)

    def heyoka_system(self):
        """The equations as heyoka's ``[(variable, expression)]`` and its variables."""
        return heyoka_equations(self.rhs)


def _finite(value, argument: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise bad_value(argument, value, "give a finite number", InvalidParameterError) from None
    if not math.isfinite(number):
        raise bad_value(
            argument, value, "give a finite number: the state must lie in the problem's "
            "state space", InvalidParameterError,
        )  # fmt: skip
    return number


@functools.lru_cache(maxsize=16)
def _numpy_field(rhs: SymbolicRHS, m: int):
    from perturb._lambdify import numpy_lambdify

    function = numpy_lambdify(list(rhs.state), list(rhs.expressions[:m]))

    def field_(y: np.ndarray, theta: np.ndarray) -> np.ndarray:
        out = function(*y, theta)
        return np.array([np.broadcast_to(np.asarray(c, dtype=float), theta.shape) for c in out])

    return field_


@functools.lru_cache(maxsize=16)
def heyoka_equations(rhs: SymbolicRHS):
    """``rhs`` as heyoka's ``[(variable, expression)]`` (compiled once per equations)."""
    import heyoka as hy

    from perturb.oracle import to_heyoka

    variables = hy.make_vars(*[f"y{i}" for i in range(rhs.n)])
    table = dict(zip(rhs.state, variables, strict=True))
    return [
        (v, to_heyoka(e, table, float)) for v, e in zip(variables, rhs.expressions, strict=True)
    ]


def motion_of(problem) -> DrivenMotion:
    """The true motion of the driven ``problem`` (a :class:`problems.base.Problem` or any
    :class:`perturb.validation.Model`) at its parameter values.

    Raises
    ------
    InvalidParameterError
        The problem is not driven (no excitation), or its equations are not symbolic (the
        ensemble integrators compile them).
    """
    system = problem.system()
    system.frame.require_driven(
        "problem", label_of(problem), "its system has no excitation: basins, transients and ramps "
        "are studies of a driven system (give one with excitation=...)",
    )  # fmt: skip
    rhs = original_equations(problem).rhs
    if not isinstance(rhs, SymbolicRHS):
        raise bad_value(
            "problem", label_of(problem), "its equations are a numeric function; these studies "
            "compile symbolic equations (give original_symbolic, or no original_rhs)",
            InvalidParameterError,
        )  # fmt: skip
    phase = rhs.expressions[-1]
    if rhs.state[-1] != system.excitation.phase or phase.free_symbols:
        raise bad_value(
            "problem", label_of(problem), "its equations do not end with the phase theta' = Omega",
            InvalidParameterError,
        )  # fmt: skip
    omega = float(sp.sympify(phase))
    names = tuple(str(s) for s in rhs.state[:-1])
    return DrivenMotion(rhs, names, omega, int(system.excitation.p), label_of(problem))
