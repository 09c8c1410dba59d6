"""Periodic responses of a driven system along one parameter: the fixed-period shooting map.

A driven system :math:`\\dot y = f(y, \\theta; p)`, :math:`\\theta = \\Omega(p)\\,t`, whose
parameters :math:`p = p(\\lambda)` move with one scalar :math:`\\lambda` (the swept parameter: a
forcing frequency, a level, a damping…). Written with the phase as time,

.. math:: \\frac{dy}{d\\theta} = g(y, \\theta; p) = \\frac{f(y, \\theta; p)}{\\Omega(p)},

a response of N forcing periods has the period :math:`2\\pi N` whatever λ: the unknowns are the
initial state only (the forcing fixes the time origin, θ(0) = 0), and the periodic responses are
the zeros of

.. math:: R(y_0, \\lambda) = \\varphi_{2\\pi N}(y_0; p(\\lambda)) - y_0 ,

``m`` equations in ``m + 1`` unknowns: a curve, followed by pseudo-arclength continuation. Its
Jacobian comes from the variational equations integrated with the state,

.. math:: M' = g_y M,\\; M(0) = I; \\qquad s' = g_y s + g_p\\,\\frac{dp}{d\\lambda},\\; s(0) = 0;
          \\qquad \\partial R/\\partial(y_0, \\lambda) = [\\,M - I \\mid s\\,],

with :math:`M(2\\pi N)` the monodromy (its eigenvalues are the Floquet multipliers, the same in
either time) and :math:`s` the sensitivity to λ. The parameters and the direction
:math:`dp/d\\lambda` travel as constant components of the state, so one compiled field (heyoka's
Taylor integrator, or DOP853 without it) serves every λ, and the map from λ to p may be any
function (the caller gives both at each λ). The state may have any dimension (a chain of modes
as well as one oscillator).

:class:`DrivenFamily` builds that field once; :meth:`DrivenFamily.shoot` integrates it from one
``(y0, p, dp/dλ)`` and returns a :class:`Shot` (defect, monodromy, sensitivity, multipliers, and
the orbit sampled when asked).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import attrs
import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import FAMILY_COMPACT_MODE, SHOOTING_INTEGRATOR_RTOL
from perturb.errors import bad_value
from perturb.oracle.heyoka import Heyoka
from perturb.oracle.orbit import multipliers_of
from perturb.oracle.registry import choose
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["DrivenFamily", "Shot"]

#: The prefix of the auxiliary state symbols (direction, monodromy, sensitivity) of the augmented
#: field: names a user's system does not use (checked when the family is built).
_AUX = "_fam"


def _readonly(value) -> np.ndarray:
    array = np.array(value, dtype=float)
    array.setflags(write=False)
    return array


_array_eq = attrs.cmp_using(eq=np.array_equal)


@frozen
class Shot:
    """One integration of a :class:`DrivenFamily` over the response period, from ``y0``.

    Attributes
    ----------
    initial_state : ndarray, shape (m,)
    final_state : ndarray, shape (m,)
        The state after N forcing periods (NaN when the integration failed).
    monodromy : ndarray, shape (m, m)
        :math:`M`: the linearised period map.
    sensitivity : ndarray, shape (m,)
        :math:`\\partial\\varphi/\\partial\\lambda` along the direction given.
    success : bool
    message : str
        Empty on success, else why the integration failed.
    orbit : ndarray, shape (m, samples)
        The state at the equally spaced phases asked for (empty when none were).

    Examples
    --------
    A shot of x'' + x = 0 over one period returns where it started, its monodromy the identity:

    >>> import numpy as np, sympy as sp
    >>> from perturb.oracle import DrivenFamily
    >>> x, v, th, w = sp.symbols("x v theta w")
    >>> shot = DrivenFamily.build((x, v), th, (v, -x), w, (w,)).shoot([1.0, 0.0], [1.0], [0.0])
    >>> np.round(shot.defect, 12) + 0.0, np.round(shot.monodromy, 12) + 0.0
    (array([0., 0.]), array([[1., 0.],
           [0., 1.]]))
    >>> shot.jacobian.shape
    (2, 3)
    """

    initial_state: np.ndarray = field(converter=_readonly, eq=_array_eq)
    final_state: np.ndarray = field(converter=_readonly, eq=_array_eq)
    monodromy: np.ndarray = field(converter=_readonly, eq=_array_eq)
    sensitivity: np.ndarray = field(converter=_readonly, eq=_array_eq)
    success: bool = True
    message: str = ""
    orbit: np.ndarray = field(factory=lambda: np.empty((0, 0)), converter=_readonly, eq=_array_eq)

    @property
    def defect(self) -> np.ndarray:
        """:math:`R = y(2\\pi N) - y_0`."""
        return self.final_state - self.initial_state

    @property
    def jacobian(self) -> np.ndarray:
        """:math:`[M - I \\mid s]`, shape (m, m + 1): the derivative of the defect in (y0, λ)."""
        m = self.initial_state.size
        return np.column_stack((self.monodromy - np.eye(m), self.sensitivity))

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers (eigenvalues of the monodromy), sorted by distance from 1."""
        if not np.all(np.isfinite(self.monodromy)):
            return np.full(self.initial_state.size, complex(math.nan, math.nan))
        return multipliers_of(self.monodromy)


def _check_symbols(name: str, values) -> tuple[sp.Symbol, ...]:
    out = tuple(values)
    if not out or not all(isinstance(s, sp.Symbol) for s in out):
        raise bad_value(name, values, "give a non-empty sequence of sympy Symbols")
    return out


@frozen(eq=False)
class DrivenFamily:
    """The fixed-period shooting map of a driven system along a parameter (module notes).

    Build it with :meth:`build`; then :meth:`shoot` at any ``(y0, p, dp/dλ)``.

    Attributes
    ----------
    rhs : SymbolicRHS
        The augmented field: ``(y, θ, p, dp/dλ, M, s)`` in the phase as time.
    state_size : int
        m, the dimension of the state ``y``.
    parameters : tuple of str
        The parameters' names, in the order :meth:`shoot` takes their values.
    cycles : int
        N, the forcing periods in one response period (the period in θ is 2πN).
    integrator : Integrator
        What integrates ``rhs`` (default: heyoka at machine precision in compact mode,
        ``FAMILY_COMPACT_MODE``, else DOP853 at ``SHOOTING_INTEGRATOR_RTOL``).

    Examples
    --------
    The linear oscillator x'' + 0.2 x' + x = F cos(Ω t): at Ω = 1 its response is
    x = 5F sin t, so (x(0), x'(0)) = (0, 5F) moves by (0, 5) per unit of F; the tangent
    :math:`-(M - I)^{-1} s` along F says so.

    >>> import numpy as np, sympy as sp
    >>> x, v, th, F, W = sp.symbols("x v theta F Omega")
    >>> family = DrivenFamily.build((x, v), th, (v, -0.2 * v - x + F * sp.cos(th)), W, (F, W))
    >>> shot = family.shoot([0.0, 5.0], values=[1.0, 1.0], direction=[1.0, 0.0])
    >>> bool(np.max(np.abs(shot.defect)) < 1e-12)
    True
    >>> np.round(np.linalg.solve(shot.monodromy - np.eye(2), -shot.sensitivity), 9) + 0.0
    array([0., 5.])
    """

    rhs: SymbolicRHS
    state_size: int
    parameters: tuple
    cycles: int
    integrator: object

    @classmethod
    def build(
        cls,
        state: Sequence[sp.Symbol],
        phase: sp.Symbol,
        expressions: Sequence[sp.Expr],
        frequency: sp.Expr,
        parameters: Sequence[sp.Symbol],
        cycles: int = 1,
        integrator=None,
    ) -> DrivenFamily:
        """The family of ``y' = expressions`` (in physical time, θ' = ``frequency``).

        Parameters
        ----------
        state : sequence of sympy.Symbol
            y, without the phase.
        phase : sympy.Symbol
            θ = Ωt, as it appears in ``expressions``.
        expressions : sequence of sympy.Expr
            f(y, θ; p), one per state symbol.
        frequency : sympy.Expr
            Ω(p) > 0.
        parameters : sequence of sympy.Symbol
            Every other symbol of ``expressions`` and ``frequency``.
        cycles : int
            N >= 1.
        integrator : Integrator or str, optional

        Raises
        ------
        perturb.errors.InvalidParameterError
            Mismatched lengths, a symbol that is neither state, phase nor parameter, N < 1, or an
            auxiliary name (prefix ``_fam``) taken by the system.
        """
        state = _check_symbols("state", state)
        params = _check_symbols("parameters", parameters)
        exprs = tuple(sp.sympify(e) for e in expressions)
        if len(exprs) != len(state):
            raise bad_value("expressions", len(exprs), f"give one per state symbol ({len(state)})")
        if isinstance(cycles, bool) or not isinstance(cycles, int | np.integer) or cycles < 1:
            raise bad_value("cycles", cycles, "give the forcing periods per response period (>= 1)")
        omega = sp.sympify(frequency)
        known = set(state) | {phase} | set(params)
        stray = set().union(omega.free_symbols, *(e.free_symbols for e in exprs)) - known
        if stray:
            raise bad_value(
                "parameters", [p.name for p in params],
                f"{sorted(map(str, stray))} appear in the equations: list every parameter",
            )  # fmt: skip
        if any(s.name.startswith(_AUX) for s in known):
            raise bad_value("state", [s.name for s in known], f"rename symbols named {_AUX}*")
        m, n_p = len(state), len(params)
        g = sp.Matrix([e / omega for e in exprs])
        g_y = g.jacobian(sp.Matrix(state))
        g_p = g.jacobian(sp.Matrix(params))
        direction = sp.Matrix([sp.Symbol(f"{_AUX}_d{k}") for k in range(n_p)])
        mono = sp.Matrix(m, m, lambda i, j: sp.Symbol(f"{_AUX}_M{i}_{j}"))
        sens = sp.Matrix([sp.Symbol(f"{_AUX}_s{i}") for i in range(m)])
        mono_dot = g_y * mono
        sens_dot = g_y * sens + g_p * direction
        symbols = (*state, phase, *params, *direction, *mono, *sens)
        rhs_exprs = (
            *g, sp.Integer(1), *([sp.Integer(0)] * (2 * n_p)), *mono_dot, *sens_dot,
        )  # fmt: skip
        rhs = SymbolicRHS(symbols, rhs_exprs)
        if integrator is None:
            solver = choose(None, rtol=SHOOTING_INTEGRATOR_RTOL, symbolic=True)
            if isinstance(solver, Heyoka):
                solver = attrs.evolve(solver, compact_mode=FAMILY_COMPACT_MODE)
        else:
            solver = choose(integrator, symbolic=True)
        return cls(rhs, m, tuple(p.name for p in params), int(cycles), solver)

    @property
    def period(self) -> float:
        """The response period in the phase: 2πN."""
        return 2.0 * math.pi * self.cycles

    def _start(self, y0, values, direction) -> np.ndarray:
        m, n_p = self.state_size, len(self.parameters)
        y0 = np.asarray(y0, dtype=float).reshape(-1)
        values = np.asarray(values, dtype=float).reshape(-1)
        direction = np.asarray(direction, dtype=float).reshape(-1)
        for name, array, size in (
            ("y0", y0, m),
            ("values", values, n_p),
            ("direction", direction, n_p),
        ):
            if array.size != size or not np.all(np.isfinite(array)):
                raise bad_value(name, array.tolist(), f"give {size} finite numbers")
        return np.concatenate((y0, [0.0], values, direction, np.eye(m).ravel(), np.zeros(m)))

    def shoot(self, y0, values, direction, samples: int = 0, span: float | None = None) -> Shot:
        """Integrate over one response period from ``y0`` at parameter ``values``.

        Parameters
        ----------
        y0 : array_like, shape (m,)
        values : array_like
            p, in the order of :attr:`parameters`.
        direction : array_like
            dp/dλ, likewise (the sensitivity's direction).
        samples : int
            Also keep the state at this many equally spaced phases in [0, 2πN) (0: none).
        span : float, optional
            Integrate over [0, span] of the phase instead of the period (half of it for the
            half-period map of a symmetric response); the shot's defect and monodromy are then
            those of that map.

        Returns
        -------
        Shot
            A failed one (NaN, with the integrator's message) when the integration fails.
        """
        m = self.state_size
        start = self._start(y0, values, direction)
        end = self.period if span is None else float(span)
        t_eval = None
        if samples:
            t_eval = np.linspace(0.0, end, int(samples) + 1)
        traj = self.integrator.integrate(self.rhs, (0.0, end), start, t_eval=t_eval)
        z = np.asarray(traj.y_final, dtype=float) if traj.success else None
        if z is None or not np.all(np.isfinite(z)):
            nan = np.full(m, math.nan)
            why = traj.message if not traj.success else "the state became non-finite"
            return Shot(start[:m], nan, np.full((m, m), math.nan), nan, False, why)
        offset = m + 1 + 2 * len(self.parameters)
        mono = z[offset : offset + m * m].reshape(m, m)
        orbit = np.asarray(traj.y, dtype=float)[:m, :-1] if samples else np.empty((m, 0))
        return Shot(start[:m], z[:m], mono, z[offset + m * m :], True, "", orbit)
