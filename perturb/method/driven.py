"""Driven systems: Poincaré's method when the period is given by the forcing.

For :math:`\\ddot x_i + \\omega_i^2 x_i = \\varepsilon f_i(x, \\dot x, \\Omega t, \\varepsilon)` with
:math:`\\Omega = (p/q)\\omega_{ref} + \\varepsilon\\sigma` (:class:`perturb.Excitation`) the response
is sought with the period :math:`T = 2\\pi p/\\Omega`. In :math:`s = \\Omega t/p` the equations are

.. math:: \\nu^2 x_i'' + \\omega_i^2 x_i = \\varepsilon f_i(x, \\nu x', p s), \\qquad
          \\nu = \\Omega/p = \\omega_{ref}/q + \\varepsilon\\sigma/p,

the free construction's strained-time form (:mod:`perturb.method.poincare`) with a **known**
frequency series :math:`(\\omega_{ref}/q, \\sigma/p, 0, \\dots)`. Coordinate i is resonant with
harmonic :math:`m_i = q\\omega_i/\\omega_{ref}` when that is a positive integer. What changes:

1. the time origin is fixed by the forcing: **both** amplitudes :math:`a_{i,0}, b_{i,0}` of every
   resonant coordinate are unknowns, and so are both corrections at every order;
2. no frequency correction is sought: the two periodicity conditions of each resonant coordinate
   are the equations for its two amplitudes; at the first order that involves them they are the
   **amplitude (frequency-response) equations**, nonlinear; every later order is linear in the
   corrections, with the Jacobian of the amplitude equations as its matrix (singular at a fold);
3. every condition is imposed (a driven system has no first integral that makes one redundant).

**Stability (Malkin; averaging).** Over one period the resonant mode's amplitudes change by
:math:`\\Delta a_i = \\varepsilon\\, g_{i,1}(2\\pi)`, :math:`\\Delta b_i = \\varepsilon\\, \\dot g_{i,1}(2\\pi)/m_i`
(the periodicity conditions are the displacement of the initial values), so the monodromy in the
amplitudes is :math:`I + \\varepsilon J` with :math:`J = \\partial(g_i, \\dot g_i/m_i)/\\partial(a_j, b_j)`
at the root, and the Floquet multipliers are :math:`1 + \\varepsilon\\lambda(J) + O(\\varepsilon^2)`:
the response is asymptotically stable when every eigenvalue of J has a negative real part; a zero
eigenvalue is a fold or a pitchfork (:func:`slow_flow`). Unlike a free orbit, a driven one has no
trivial multiplier: time is not a free phase.

:func:`amplitude_equations` gives the displacement function to order N with the generating
amplitudes kept as symbols: :math:`D(a, b) = \\sum_{k=1}^{N} \\varepsilon^{k-1} P_k(a, b)`, the
conditions of each order with the initial values fixed to :math:`(a, b)` exactly (corrections zero).
Its real roots are the response's branches to order N, without the blow-up of the order-by-order
corrections at a fold (:mod:`perturb.response` solves it at every Ω).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Mapping

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import SLOW_FLOW_ZERO
from perturb.cache import cached
from perturb.errors import InvalidSystemError, bad_value
from perturb.method.given_period import DrivenOrderByOrder
from perturb.method.poincare import PoincareMethod
from perturb.solution import PeriodicSolution, Status
from perturb.steps import GeneratingSolution
from perturb.system import EPS, QuasilinearSystem

__all__ = ["AmplitudeEquations", "SlowFlow", "amplitude_equations", "slow_flow"]


# ------------------------------------------------------------------------ amplitude equations
@frozen
class AmplitudeEquations:
    """The displacement function of a driven system to order N, its amplitudes kept as symbols.

    Attributes
    ----------
    system : QuasilinearSystem
        The driven system (its parameters, σ among them, stay symbols).
    order : int
        N: the state to order N, and the conditions of orders 1..N + 1 that fix its amplitudes
        to :math:`O(\varepsilon^{N+1})` (N = 0: the classical first-order response equations).
    amplitudes : tuple of sympy.Symbol
        ``(a_x, b_x, a_y, b_y, ...)``: cosine and sine amplitudes of each resonant coordinate in
        the strained time, the unknowns of the equations.
    harmonics : tuple of int
        :math:`m_i` of each resonant coordinate, in the order of ``amplitudes``' pairs.
    coordinates : tuple of str
        The resonant coordinates, in that order.
    conditions : tuple of tuple of sympy.Expr
        ``conditions[k-1]`` (k = 1..N+1) are the 2 x (resonant coordinates) conditions of order k,
        :math:`(g_{i,k}(2\\pi), \\dot g_{i,k}(2\\pi))` per coordinate, with the initial values
        fixed to the amplitudes exactly (no corrections).
    solution : PeriodicSolution
        The series with the amplitudes as parameters (``solution.system.parameters`` holds them):
        evaluate it at a root to get the response.
    """

    system: QuasilinearSystem = field(eq=False)
    order: int
    amplitudes: tuple
    harmonics: tuple
    coordinates: tuple
    conditions: tuple = field(eq=False)
    solution: PeriodicSolution = field(eq=False, repr=False)

    def displacement(self, order: int | None = None) -> tuple[sp.Expr, ...]:
        """:math:`D = \\sum_{k=1}^{n+1} \\varepsilon^{k-1} P_k` for the state to order n (default N),
        row-scaled to the slow flow: :math:`(g_i, \\dot g_i/m_i)` per resonant coordinate."""
        top = (self.order if order is None else order) + 1
        rows = []
        for r in range(len(self.amplitudes)):
            m = self.harmonics[r // 2]
            scale = 1 if r % 2 == 0 else sp.Rational(1, m)
            rows.append(
                sp.expand(
                    sum(EPS ** (k - 1) * self.conditions[k - 1][r] for k in range(1, top + 1))
                    * scale
                )
            )
        return tuple(rows)


class _Collecting(DrivenOrderByOrder):
    """The driven template with the initial values fixed to symbolic amplitudes: the conditions
    of every order are collected, none solved (:func:`amplitude_equations`)."""

    def run(self) -> PeriodicSolution:
        self.collected: list[tuple] = []
        return super().run()

    def _solve_conditions(self, k: int, generating: GeneratingSolution) -> tuple[dict, tuple]:
        to_sympy, expand = self.conv.to_sympy, self.conv.ring.expand
        # the generating amplitudes become the user's symbols, every correction is zero (the
        # generating symbols are read off the generating solution, never parsed from names: a
        # coordinate named x1 has the generating amplitude a_x10, which no name split tells from
        # the order-10 correction of a coordinate x)
        given = {}
        for i, name in enumerate(self.names):
            for ab, symbol in (
                ("a", generating.cos_amplitudes[i]),
                ("b", generating.sin_amplitudes[i]),
            ):
                if isinstance(symbol, sp.Symbol) and symbol in self.unknowns:
                    given[symbol] = sp.Symbol(f"{ab}_{name}")
        mapping = {u: given.get(u, sp.S.Zero) for u in self.unknowns}
        self.collected.append(
            tuple(sp.expand(to_sympy(expand(e)).xreplace(mapping)) for e in self.pending)
        )
        self.pending = []
        self._substitute(mapping)
        return mapping, ()

    def _open_unknowns(self, uniform: bool = False) -> set:
        return set()


def amplitude_equations(system: QuasilinearSystem, order: int = 1) -> AmplitudeEquations:
    """The amplitude (frequency-response) equations of a driven system to ``order``.

    Parameters
    ----------
    system : QuasilinearSystem
        A driven system (``excitation`` set); its parameters, the detuning σ among them, stay
        symbols: the equations are derived once for every σ and parameter value.
    order : int
        N >= 0: the state to order N and the conditions of orders 1..N + 1 (0: the classical
        first-order response equations alone).

    Returns
    -------
    AmplitudeEquations
        Kept in the disk cache (kind ``amplitude-equations``).

    Raises
    ------
    InvalidSystemError
        For a free system (no excitation) or an order below 1.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem
    >>> x, v, th, s, F = sp.symbols("x v theta sigma F")
    >>> duffing = QuasilinearSystem([x], [v], [1], [EPS * (F * sp.cos(th) - x**3 - v)],
    ...     parameters=[s, F], excitation=Excitation(th, 1, s))
    >>> eqs = amplitude_equations(duffing, 1)
    >>> eqs.amplitudes
    (a_x, b_x)
    """
    system.frame.require_driven(
        "system", system.name, "it has no excitation: give a driven system (excitation=...)",
        InvalidSystemError,
    )  # fmt: skip
    if isinstance(order, bool) or not isinstance(order, int) or order < 0:
        raise bad_value("order", order, "give an integer >= 0", InvalidSystemError)
    method = PoincareMethod(order=max(order, 1), cache=False)

    def derive() -> AmplitudeEquations:
        runner = _Collecting(method, system)
        solution = _collect(runner, order)
        resonant = [i for i, m in enumerate(runner.harmonics) if m is not None]
        names = tuple(runner.names[i] for i in resonant)
        amplitudes = tuple(
            sp.Symbol(f"{ab}_{name}") for name in names for ab in ("a", "b")
        )  # fmt: skip
        conditions = tuple(runner.collected[: order + 1])
        return AmplitudeEquations(
            system=system,
            order=order,
            amplitudes=amplitudes,
            harmonics=tuple(runner.harmonics[i] for i in resonant),
            coordinates=names,
            conditions=conditions,
            solution=solution,
        )

    return cached("amplitude-equations", lambda: _key(system, order), derive)


def _collect(runner: _Collecting, order: int) -> PeriodicSolution:
    """Run the collecting template until the conditions of ``order`` are in; the solution's
    series with the amplitudes as parameters."""
    import attrs

    system = runner.system
    names = [c.name for i, c in enumerate(system.coordinates) if runner.harmonics[i] is not None]
    params = [sp.Symbol(f"{ab}_{n}") for n in names for ab in ("a", "b")]
    runner.system = attrs.evolve(system, parameters=(*system.parameters, *params))
    runner.collected = []
    runner.expansion = runner.system.expansion(order + 1)
    generating = runner.generating()
    for k in range(1, order + 2):
        runner.step(k, generating)
    return runner.result(generating, Status.SUCCESS, "")


def _key(system: QuasilinearSystem, order: int) -> tuple:
    method = PoincareMethod(order=1, cache=False)
    return ("amplitude-equations", method.cache_key(system), order)


# ------------------------------------------------------------------------ stability
@frozen
class SlowFlow:
    """The linearisation of a driven response's amplitudes over one period (Malkin).

    Attributes
    ----------
    jacobian : ndarray, shape (2r, 2r)
        :math:`J = \\partial(g_i, \\dot g_i/m_i)/\\partial(a_j, b_j)` at the root (r resonant
        coordinates): the monodromy in the amplitudes is :math:`I + \\varepsilon J`.
    eigenvalues : ndarray of complex
    stable : bool or None
        Every eigenvalue's real part below ``-tol`` (asymptotically stable); False when one is
        above ``tol``; None when the largest is within ``tol`` of zero (a fold or pitchfork, or
        an undamped system: decided at the next order).
    multipliers : ndarray of complex
        The Floquet multipliers it predicts, :math:`1 + \\varepsilon\\lambda`.
    """

    jacobian: np.ndarray = field(eq=False)
    eigenvalues: np.ndarray = field(eq=False)
    stable: bool | None
    multipliers: np.ndarray = field(eq=False)

    @property
    def fold(self) -> bool:
        """A real eigenvalue at zero: the branch turns (saddle-node) or another one crosses."""
        return self.stable is None


def slow_flow(
    equations: AmplitudeEquations,
    root: Mapping,
    values: Mapping,
    epsilon: float,
    order: int = 0,
) -> SlowFlow:
    """The slow flow's Jacobian at a root of the amplitude equations, and its stability.

    Parameters
    ----------
    equations : AmplitudeEquations
    root : mapping
        ``{amplitude symbol or name: value}`` (a root of ``equations``).
    values : mapping
        Values of the system's parameters (σ among them).
    epsilon : float
        ε, for the multipliers :math:`1 + \\varepsilon\\lambda` and for order > 1.
    order : int
        The state order whose displacement function is linearised (0: Malkin's first-order
        criterion, the Jacobian of the order-1 conditions).
    """
    rows = equations.displacement(order)
    symbols = equations.amplitudes
    subs = {s: float(_lookup(root, s)) for s in symbols}
    subs.update({p: float(_lookup(values, p)) for p in equations.system.parameters})
    subs[EPS] = float(epsilon)
    jac = np.array(
        [[float(sp.diff(r, a).xreplace(subs)) for a in symbols] for r in rows], dtype=float
    )
    if not np.all(np.isfinite(jac)):  # overflowed at these values: no stability to tell
        nan = np.full(len(symbols), complex(math.nan, math.nan))
        return SlowFlow(jac, nan, None, nan)
    eig = np.linalg.eigvals(jac) if jac.size else np.array([], dtype=complex)
    scale = max(float(np.max(np.abs(eig), initial=0.0)), math.ulp(1.0))
    top = float(np.max(eig.real, initial=-math.inf))
    stable = None if abs(top) <= SLOW_FLOW_ZERO * scale else top < 0
    multipliers = np.array([_exp(epsilon * complex(e)) for e in eig])
    return SlowFlow(jac, eig, stable, multipliers)


def _exp(z: complex) -> complex:
    """``cmath.exp(z)``, NaN where it is past the floats (eps = 1e308: no error, no number)."""
    try:
        return cmath.exp(z)
    except (OverflowError, ValueError):
        return complex(math.nan, math.nan)


def _lookup(mapping: Mapping, symbol: sp.Symbol):
    if symbol in mapping:
        return mapping[symbol]
    if symbol.name in mapping:
        return mapping[symbol.name]
    raise bad_value("values", dict(mapping), f"give a value for {symbol.name}", InvalidSystemError)
