"""The amplitude equations of a driven system, prepared once for every parameter point.

A response curve or a phase diagram solves the same amplitude equations at many parameter
values. What does not depend on the values is done once per :class:`~perturb.method.driven.
AmplitudeEquations` and order (:func:`compiled`):

* the first-order rows as polynomials in the amplitudes whose coefficients are expressions in the
  parameters, the common factor π taken out (every periodicity condition is π times a Fourier
  coefficient of the forcing, rational for a polynomial right-hand side): putting exact values in
  is then a few small substitutions, and the rows handed to the certified solver are the exact
  ones (:meth:`CompiledEquations.first_order`);
* the displacement function :math:`D_N` and its Jacobian in the amplitudes as numpy functions of
  (amplitudes, parameters, ε): the order-N continuation of a root and its slow flow cost a few
  function calls, not a symbolic substitution per root.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._lambdify import numpy_lambdify
from perturb.method.driven import AmplitudeEquations, SlowFlow
from perturb.system import EPS

__all__ = ["CompiledEquations", "compiled"]

#: Compiled equations kept per process (each holds numpy functions of a few kB).
_CACHE: dict[tuple[int, int], tuple[AmplitudeEquations, CompiledEquations]] = {}
_LOCK = threading.Lock()
#: At most this many are kept (the oldest dropped): a process sweeps one or two systems.
CACHE_SIZE = 16


@frozen
class CompiledEquations:
    """The amplitude equations of one driven system to one order, ready for many points.

    Attributes
    ----------
    equations : AmplitudeEquations
    order : int
        The order N of the displacement function compiled (0: the first-order equations).
    parameters : tuple of sympy.Symbol
        The system's parameters, in the order the numeric functions take them.
    first_terms : tuple
        Per first-order row, ``((monomial, coefficient), ...)``: the exponents of the amplitudes
        and the coefficient, an expression in the parameters.
    """

    equations: AmplitudeEquations = field(eq=False)
    order: int
    parameters: tuple
    first_terms: tuple = field(eq=False, repr=False)
    _rows: object = field(eq=False, repr=False, alias="rows")
    _jacobian: object = field(eq=False, repr=False, alias="jacobian")
    _first_jacobian: object = field(eq=False, repr=False, alias="first_jacobian")

    @classmethod
    def of(cls, equations: AmplitudeEquations, order: int) -> CompiledEquations:
        """Prepare ``equations`` to ``order`` (see the module notes)."""
        amplitudes = list(equations.amplitudes)
        parameters = tuple(equations.system.parameters)
        args = [*amplitudes, *parameters, EPS]
        first = [sp.expand(r) for r in equations.displacement(0)]
        terms = []
        for row in first:
            scaled = sp.expand(row / sp.pi)
            if scaled.has(sp.pi):  # not a common factor: the row as it is
                scaled = row
            poly = sp.Poly(scaled, *amplitudes)
            terms.append(tuple(poly.terms()))
        rows = [sp.expand(r) for r in equations.displacement(order)] if order else first
        jacobian = [[sp.diff(r, a) for a in amplitudes] for r in rows]
        first_jacobian = (
            jacobian if not order else [[sp.diff(r, a) for a in amplitudes] for r in first]
        )
        return cls(
            equations=equations,
            order=order,
            parameters=parameters,
            first_terms=tuple(terms),
            rows=numpy_lambdify(args, rows),
            jacobian=numpy_lambdify(args, jacobian),
            first_jacobian=numpy_lambdify(args, first_jacobian),
        )

    def first_order(self, fixed: Mapping) -> list[sp.Expr]:
        """The first-order rows at the exact parameter values ``fixed`` ({symbol: rational}),
        as polynomials in the amplitudes (π taken out where it is a common factor)."""
        amplitudes = self.equations.amplitudes
        out = []
        for terms in self.first_terms:
            coefficients = {}
            for monomial, coefficient in terms:
                value = sp.sympify(coefficient).xreplace(fixed)
                if value != 0:
                    coefficients[monomial] = value
            if not coefficients:
                out.append(sp.S.Zero)
                continue
            out.append(sp.Poly.from_dict(coefficients, *amplitudes).as_expr())
        return out

    def _args(self, amplitudes, values: Mapping, epsilon: float) -> list[float]:
        return [
            *(float(a) for a in amplitudes),
            *(float(values[p.name]) for p in self.parameters),
            float(epsilon),
        ]

    def residual(self, amplitudes, values: Mapping, epsilon: float) -> np.ndarray:
        """:math:`D_N` at ``amplitudes`` (in the order of ``equations.amplitudes``)."""
        return np.asarray(self._rows(*self._args(amplitudes, values, epsilon)), dtype=float)

    def jacobian(self, amplitudes, values: Mapping, epsilon: float, first: bool = False):
        """:math:`\\partial D_N/\\partial(a, b)` (``first``: of the first-order rows)."""
        function = self._first_jacobian if first else self._jacobian
        return np.asarray(function(*self._args(amplitudes, values, epsilon)), dtype=float)

    def slow_flow(self, amplitudes, values: Mapping, epsilon: float, first: bool) -> SlowFlow:
        """The slow flow at a root (as :func:`perturb.method.driven.slow_flow`): of the
        first-order rows (``first``) or of :math:`D_N`."""
        matrix = self.jacobian(amplitudes, values, epsilon, first=first or not self.order)
        return SlowFlow.of(matrix, float(epsilon))


def compiled(equations: AmplitudeEquations, order: int) -> CompiledEquations:
    """:class:`CompiledEquations` of ``equations`` to ``order``, prepared once per process.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem, amplitude_equations
    >>> x, v, th, s, F = sp.symbols("x v theta sigma F")
    >>> duffing = QuasilinearSystem([x], [v], [1], [EPS * (F * sp.cos(th) - x**3 - v)],
    ...     parameters=[s, F], excitation=Excitation(th, 1, s))
    >>> ready = compiled(amplitude_equations(duffing, 1), 1)
    >>> ready.first_order({s: sp.Integer(0), F: sp.Integer(2)})
    [3*a_x**2*b_x/4 - a_x + 3*b_x**3/4, -3*a_x**3/4 - 3*a_x*b_x**2/4 - b_x + 2]
    """
    key = (id(equations), int(order))
    with _LOCK:
        hit = _CACHE.get(key)
        if hit is not None and hit[0] is equations:
            return hit[1]
    ready = CompiledEquations.of(equations, int(order))
    with _LOCK:
        if len(_CACHE) >= CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = (equations, ready)
    return ready
