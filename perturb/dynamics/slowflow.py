"""The slow flow: the amplitude equations as ODEs in slow time, its equilibria and its separatrix.

A driven system's amplitudes u = (a₁, b₁, …) (the initial values x(0) = a, ẋ(0) = mνb of each
resonant coordinate in the strained time s = Ωt/p, :mod:`perturb.method.driven`) move by
:math:`\\Delta u = \\varepsilon D_N(u) + O(\\varepsilon^{N+2})` over one period of the response,
:math:`T = 2\\pi p/\\Omega`, where :math:`D_N = \\sum_{k \\le N+1} \\varepsilon^{k-1} P_k` is the
displacement function of :func:`~perturb.method.driven.amplitude_equations`. The slow flow is
that map made continuous,

.. math:: \\frac{du}{dt} = \\frac{\\varepsilon}{T} D_N(u),

first order (N = 0: :math:`P_1` alone) the classical averaged equations, higher orders the
displacement function the method provides (its equilibria are the order-N steady states exactly;
its dynamics away from them are those of the stroboscopic map to the same order only where the
map is near the identity, which is what the first order assumes). The section's state at drive
phase φ is, to first order, :math:`x_i = a_i\\cos\\psi_i + b_i\\sin\\psi_i`,
:math:`\\dot x_i = m_i\\nu(-a_i\\sin\\psi_i + b_i\\cos\\psi_i)` with :math:`\\psi_i = m_i\\varphi/p`,
ν = Ω/p (:meth:`SlowFlow.to_section`, :meth:`SlowFlow.from_section`); the non-resonant
coordinates are 0 at that order.

The **separatrix** of a basin map is the stable manifold of the slow flow's saddle (one resonant
coordinate: a plane flow, whose saddle has one stable direction): followed backwards in slow time
from the saddle along its stable eigenvector, both ways, and mapped to the section
(:meth:`SlowFlow.separatrix`).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import SEPARATRIX_MARGIN, SEPARATRIX_OFFSET, SEPARATRIX_SPAN, SLOW_FLOW_ZERO
from perturb.errors import InvalidParameterError, bad_value
from perturb.validation.capabilities import label_of

__all__ = ["Equilibrium", "SlowFlow", "slow_flow_of"]


@frozen
class Equilibrium:
    """An equilibrium of the slow flow (a steady state of the series at its order).

    Attributes
    ----------
    amplitudes : ndarray
        u = (a₁, b₁, …).
    eigenvalues : ndarray of complex
        Of the slow flow's Jacobian (per unit of physical time).
    kind : str
        ``"stable"``, ``"saddle"`` (real eigenvalues of both signs), ``"unstable"`` or
        ``"marginal"``.
    """

    amplitudes: np.ndarray = field(eq=False)
    eigenvalues: np.ndarray = field(eq=False)
    kind: str


@frozen
class SlowFlow:
    """The slow flow of a driven problem at its values (see the module notes).

    Attributes
    ----------
    order : int
        The user's order N >= 1: the displacement function to ε^N in Δu (1: averaging).
    amplitudes : tuple of str
        The names of u's components (``a_x``, ``b_x``, …).
    coordinates : tuple of str
        The resonant coordinates, in u's order of pairs.
    harmonics : tuple of int
        Their harmonics m_i.
    names : tuple of str
        The state's components (the section's).
    omega, epsilon : float
    response_periods : int
        p.
    """

    order: int
    amplitudes: tuple = field(converter=tuple)
    coordinates: tuple = field(converter=tuple)
    harmonics: tuple = field(converter=tuple)
    names: tuple = field(converter=tuple)
    omega: float
    epsilon: float
    response_periods: int
    _rows: object = field(eq=False, repr=False)
    _jacobian: object = field(eq=False, repr=False)
    _census: tuple = field(eq=False, repr=False, factory=tuple)

    @property
    def period(self) -> float:
        """The response's period T = 2πp/Ω (the slow flow's unit of Δu)."""
        return 2 * math.pi * self.response_periods / self.omega

    def rate(self, u) -> np.ndarray:
        """du/dt at ``u`` (one state, or shape (2r, M) for M at once)."""
        u = np.asarray(u, dtype=float)
        values = self._rows(*u)
        return (self.epsilon / self.period) * np.array(
            [np.broadcast_to(np.asarray(v, dtype=float), u.shape[1:]) for v in values]
        )

    def jacobian(self, u) -> np.ndarray:
        """∂(du/dt)/∂u at ``u``."""
        return (self.epsilon / self.period) * np.asarray(self._jacobian(*u), dtype=float)

    def integrate(self, u0, times) -> np.ndarray:
        """The slow flow from ``u0`` at t = 0, at ``times`` (increasing, from 0): shape
        (len(times), 2r). DOP853 at rtol 1e-10."""
        from scipy.integrate import solve_ivp

        times = np.asarray(times, dtype=float)
        result = solve_ivp(
            lambda t, u: self.rate(u), (0.0, float(times[-1])), np.asarray(u0, dtype=float),
            method="DOP853", t_eval=times, rtol=1e-10, atol=1e-12,
        )  # fmt: skip
        out = np.full((times.size, len(self.amplitudes)), np.nan)
        out[: result.y.shape[1]] = result.y.T
        return out

    # ---------------------------------------------------------------------- the section
    def _angles(self, phase, rows: int) -> list[np.ndarray]:
        phase = np.broadcast_to(np.asarray(phase, dtype=float), (rows,))
        return [m * phase / self.response_periods for m in self.harmonics]

    def to_section(self, u, phase=0.0) -> np.ndarray:
        """The state on the section at drive phase ``phase`` (a number, or one per row) of
        amplitudes ``u`` (shape (2r,) or (M, 2r)): shape (m,) or (M, m), by the first-order
        solution."""
        u = np.asarray(u, dtype=float)
        flat = u.reshape(-1, len(self.amplitudes))
        out = np.zeros((flat.shape[0], len(self.names)))
        nu = self.omega / self.response_periods
        n = len(self.names) // 2
        angles = self._angles(phase, flat.shape[0])
        for i, (c, m, psi) in enumerate(zip(self.coordinates, self.harmonics, angles, strict=True)):
            a, b = flat[:, 2 * i], flat[:, 2 * i + 1]
            k = self.names.index(c)
            out[:, k] = a * np.cos(psi) + b * np.sin(psi)
            out[:, k + n] = m * nu * (-a * np.sin(psi) + b * np.cos(psi))
        return out.reshape(*u.shape[:-1], len(self.names))

    def from_section(self, y, phase=0.0) -> np.ndarray:
        """The amplitudes of the state ``y`` (shape (m,) or (M, m)) at drive phase ``phase`` (a
        number, or one per row): the inverse of :meth:`to_section` on the resonant coordinates
        (the variation of constants of the first-order solution)."""
        y = np.asarray(y, dtype=float)
        flat = y.reshape(-1, len(self.names))
        out = np.zeros((flat.shape[0], len(self.amplitudes)))
        nu = self.omega / self.response_periods
        n = len(self.names) // 2
        angles = self._angles(phase, flat.shape[0])
        for i, (c, m, psi) in enumerate(zip(self.coordinates, self.harmonics, angles, strict=True)):
            k = self.names.index(c)
            x, w = flat[:, k], flat[:, k + n] / (m * nu)
            out[:, 2 * i] = x * np.cos(psi) - w * np.sin(psi)
            out[:, 2 * i + 1] = x * np.sin(psi) + w * np.cos(psi)
        return out.reshape(*y.shape[:-1], len(self.amplitudes))

    # ---------------------------------------------------------------------- equilibria
    def equilibria(self) -> tuple[Equilibrium, ...]:
        """Every equilibrium: the certified first-order roots (``perturb.steady.census.census``),
        carried to this order by Newton's method on D_N (N > 1), each with its kind."""
        from scipy.optimize import fsolve

        out = []
        for root in self._census:
            u = np.asarray(root, dtype=float)
            if self.order > 1:
                u, _, ok, _ = fsolve(self.rate, u, fprime=self.jacobian, full_output=True,
                                     xtol=1e-13)  # fmt: skip
                if ok != 1:
                    continue
            if any(np.max(np.abs(e.amplitudes - u)) <= 1e-8 * (1 + np.max(np.abs(u))) for e in out):
                continue
            eig = np.linalg.eigvals(self.jacobian(u))
            out.append(Equilibrium(u, eig, _kind(eig)))
        return tuple(out)

    def separatrix(self, box, phase: float = 0.0) -> list[np.ndarray]:
        """The saddles' stable manifolds mapped to the section at ``phase``: a list of curves,
        each of shape (K, m) (two per saddle); empty unless the flow is planar (one resonant
        coordinate).

        Parameters
        ----------
        box : sequence of (low, high)
            The section's extent in each of its components (the picture's); a curve stops when
            it leaves the box enlarged by :data:`~perturb._defaults.SEPARATRIX_MARGIN` or after
            :data:`~perturb._defaults.SEPARATRIX_SPAN` units of slow time ε t.
        """
        from scipy.integrate import solve_ivp

        if len(self.amplitudes) != 2:
            return []
        low = np.array([b[0] for b in box], dtype=float)
        high = np.array([b[1] for b in box], dtype=float)
        centre, half = (low + high) / 2, (high - low) / 2 * SEPARATRIX_MARGIN
        curves = []
        for eq in self.equilibria():
            if eq.kind != "saddle":
                continue
            values, vectors = np.linalg.eig(self.jacobian(eq.amplitudes))
            stable = vectors[:, int(np.argmin(values.real))].real
            stable /= np.linalg.norm(stable)
            size = max(float(np.linalg.norm(eq.amplitudes)), 1.0)

            def outside(t, u, phase=phase):
                y = self.to_section(u, phase)
                return 1.0 - float(np.max(np.abs((y - centre) / np.where(half > 0, half, 1.0))))

            outside.terminal = True
            for sign in (1.0, -1.0):
                start = eq.amplitudes + sign * SEPARATRIX_OFFSET * size * stable
                result = solve_ivp(
                    lambda t, u: -self.rate(u), (0.0, SEPARATRIX_SPAN / self.epsilon), start,
                    method="DOP853", rtol=1e-9, atol=1e-12, events=outside,
                    max_step=self.period,
                )  # fmt: skip
                curve = np.vstack([eq.amplitudes[None], result.y.T])
                curves.append(self.to_section(curve, phase))
        return curves


def _kind(eig: np.ndarray) -> str:
    scale = max(float(np.max(np.abs(eig))), 1e-300)
    re = eig.real
    if np.all(re < -SLOW_FLOW_ZERO * scale):
        return "stable"
    if np.any(np.abs(re) <= SLOW_FLOW_ZERO * scale):
        return "marginal"
    if np.all(np.abs(eig.imag) <= SLOW_FLOW_ZERO * scale) and np.any(re < 0) and np.any(re > 0):
        return "saddle"
    return "unstable"


def slow_flow_of(problem, order: int = 1) -> SlowFlow:
    """The slow flow of the driven ``problem`` at its values, to ``order`` (1: averaging).

    Raises
    ------
    InvalidParameterError
        A problem that is not driven, an order below 1.
    """
    from perturb._lambdify import numpy_lambdify
    from perturb.method.driven import amplitude_equations
    from perturb.steady.branches import exact_number
    from perturb.steady.census import census, distinct_orbits, shift_symmetry
    from perturb.steady.line import excitation_frequency
    from perturb.system import EPS

    if isinstance(order, bool) or not isinstance(order, int) or order < 1:
        raise bad_value("order", order, "give an integer >= 1", InvalidParameterError)
    system = problem.system()
    system.frame.require_driven("problem", label_of(problem), "give a driven problem")
    values = problem.symbol_values()
    eps = float(problem.epsilon())
    equations = amplitude_equations(system, order - 1)
    subs = {p: float(values[p.name]) for p in system.parameters}
    subs[EPS] = eps
    rows = [sp.expand(r).xreplace(subs) for r in equations.displacement()]
    unknowns = list(equations.amplitudes)
    jacobian = [[sp.diff(r, u) for u in unknowns] for r in rows]
    first = amplitude_equations(system, 0)
    fixed = {p: exact_number(values[p.name]) for p in system.parameters}
    roots, _ = census(first, fixed)
    group = system.excitation.p * shift_symmetry(system)
    kept = [roots[i] for i in distinct_orbits(roots, first.harmonics, group)]
    names = tuple(problem.state_names())
    names = tuple(n for n in names if n != system.excitation.phase.name)
    return SlowFlow(
        order=order, amplitudes=tuple(u.name for u in unknowns),
        coordinates=equations.coordinates, harmonics=equations.harmonics, names=names,
        omega=excitation_frequency(system, values, eps), epsilon=eps,
        response_periods=system.excitation.p,
        rows=numpy_lambdify(unknowns, rows), jacobian=numpy_lambdify(unknowns, jacobian),
        census=tuple(kept),
    )  # fmt: skip
