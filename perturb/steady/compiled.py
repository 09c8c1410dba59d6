"""The order-N response compiled once: the displacement function, the series' harmonics, the
Jacobian of the equations of motion — evaluated at any point without deriving anything again.

* :func:`compiled_displacement`: the rows of :math:`D_N`
  (:meth:`perturb.method.driven.AmplitudeEquations.displacement`) as polynomials in (amplitudes,
  system parameters, ε), with their gradients
  (:class:`~perturb.steady.polynomial.CompiledPolynomials`, kept in the disk cache);
* :func:`compiled_series`: the cosine and sine coefficients of every harmonic of every coordinate
  of the order-N series, summed over the orders, as polynomials in the same variables;
* :func:`compiled_motion`: the Jacobian of the first-order equations of motion of the driven
  system, (ẋ, ẍ) = (v, −ω²x + f(x, v, θ)), with respect to the state, as numpy functions of
  (state, θ, parameters, ε), for the variational equation along the series
  (:mod:`perturb.steady.floquet`).

Rows that are not polynomial in these variables (a parameter under a square root) are lambdified
instead, behind the same two methods.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._lambdify import numpy_lambdify
from perturb.cache import cached
from perturb.steady.polynomial import CompiledPolynomials, compile_polynomials
from perturb.system import EPS

__all__ = ["Motion", "Series", "compiled_displacement", "compiled_motion", "compiled_series"]


def variables(equations) -> list[sp.Symbol]:
    """The variables of the compiled rows: the amplitudes, the system's parameters, ε."""
    return [*equations.amplitudes, *equations.system.parameters, EPS]


@frozen
class Lambdified:
    """Rows that are not polynomial, lambdified: the interface of CompiledPolynomials."""

    names: tuple = field(converter=tuple)
    rows: object = field(eq=False)
    gradient: object = field(eq=False)

    def values(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        out = np.array(self.rows(*np.moveaxis(x, -1, 0)), dtype=float)
        return np.moveaxis(np.broadcast_to(out, (out.shape[0], *x.shape[:-1])), 0, -1)

    def values_and_gradient(self, x):
        x = np.asarray(x, dtype=float)
        return (
            np.asarray(self.rows(*x), dtype=float),
            np.asarray(self.gradient(*x), dtype=float),
        )

    def specialized(self, fixed: dict, moving: dict, name: str = "lam"):
        return None  # the caller evaluates the full rows along the line


def _compile(key, rows, symbols, lambdified_gradient: bool = True):
    """The rows compiled to polynomials (disk-cached under ``key``), else lambdified."""
    compiled = cached("compiled-response", key, lambda: compile_polynomials(rows(), symbols))
    if compiled is not None:
        return compiled
    exprs = rows()
    fn = numpy_lambdify(symbols, exprs, cse=True)
    grad = (
        numpy_lambdify(symbols, [[sp.diff(r, s) for s in symbols] for r in exprs], cse=True)
        if lambdified_gradient
        else None
    )
    return Lambdified(tuple(s.name for s in symbols), fn, grad)


def _key(equations, what: str, order: int) -> tuple:
    from perturb.method.poincare import PoincareMethod

    method = PoincareMethod(order=1, cache=False)
    return ("compiled-response", what, method.cache_key(equations.system), order)


def compiled_displacement(equations, order: int) -> CompiledPolynomials | Lambdified:
    """:math:`D_{order}` of ``equations`` in :func:`variables` (disk-cached when polynomial)."""
    return _compile(
        lambda: _key(equations, "displacement", order),
        lambda: list(equations.displacement(order)),
        variables(equations),
    )


@frozen
class Series:
    """The order-N series' harmonics as compiled rows.

    ``rows`` evaluates to ``(n_coordinates, 2, H + 1)`` numbers per point (cos and sin of
    harmonics 0..H, summed over the orders); ``frequency`` the frequency ν of the strained time
    (s = νt) as a row too (the last one).
    """

    coordinates: tuple = field(converter=tuple)
    harmonics: int
    rows: object = field(eq=False)

    def evaluate(self, x) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(nu, cos, sin)`` at points ``x`` (shape (P, k)): (P,), (P, n, H + 1) twice."""
        values = self.rows.values(np.atleast_2d(x))
        n, h = len(self.coordinates), self.harmonics + 1
        coefficients = values[:, :-1].reshape(-1, n, 2, h)
        return values[:, -1], coefficients[:, :, 0, :], coefficients[:, :, 1, :]


def compiled_series(equations) -> Series:
    """The series of ``equations.solution`` (state to its order) as :class:`Series`."""
    solution = equations.solution
    symbols = variables(equations)
    h = max((t.max_harmonic for row in solution.terms for t in row), default=0)
    names = tuple(c.name for c in solution.system.coordinates)

    def rows():
        out = []
        for row in solution.terms:
            for which in (0, 1):
                for j in range(h + 1):
                    out.append(
                        sp.Add(*(EPS**k * t.coefficient(j)[which] for k, t in enumerate(row)))
                    )
        out.append(solution.frequency_expr)
        return out

    key = lambda: _key(equations, "series", equations.order)  # noqa: E731
    compiled = _compile(key, rows, symbols, lambdified_gradient=False)
    return Series(names, h, compiled)


@frozen
class Motion:
    """The driven system's equations of motion, ready for the variational equation.

    ``jacobian(state (..., 2n), theta (...), params (..., m), eps (...))`` is the Jacobian of
    (v, −ω²x + f) with respect to (x, v), shape (..., 2n, 2n); ``divergence`` its trace.
    ``p`` the excitation's numerator (θ = p s in the strained time s).
    """

    n: int
    p: int
    function: object = field(eq=False)

    def jacobian(self, state, theta, params, eps) -> np.ndarray:
        state = np.asarray(state, dtype=float)
        shape = state.shape[:-1]
        args = [*np.moveaxis(state, -1, 0), theta, *np.moveaxis(params, -1, 0), eps]
        blocks = self.function(*args)  # [[d f_i / d x_j] .., [d f_i / d v_j] ..] and -omega^2
        n = self.n
        out = np.zeros((*shape, 2 * n, 2 * n))
        out[..., :n, n:] = np.eye(n)
        for i in range(n):
            for j in range(2 * n):
                out[..., n + i, j] = np.broadcast_to(blocks[i][j], shape)
        return out


def compiled_motion(system) -> Motion:
    """The Jacobian of the driven ``system``'s first-order equations (see :class:`Motion`)."""
    n = system.n
    coords, velocities = system.coordinates, system.velocities
    rhs = [sp.sympify(f).subs(system.parameter, EPS) for f in system.rhs]
    rows = []
    for i in range(n):
        accel = rhs[i] - sp.sympify(system.frequencies[i]) ** 2 * coords[i]
        rows.append([sp.diff(accel, s) for s in (*coords, *velocities)])
    args = [*coords, *velocities, system.excitation.phase, *system.parameters, EPS]
    return Motion(n, system.excitation.p, numpy_lambdify(args, rows, cse=True))
