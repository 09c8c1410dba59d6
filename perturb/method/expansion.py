"""The forcing of each order and the ε-expansion of the initial values the user fixes.

At order ``k`` the state is known as series in ε to order ``k - 1`` (trigonometric polynomials in the
strained time ``s``); substituted into the right-hand side's coefficients :math:`f_{i,m}` they give

.. math:: R_{i,k}(s) = [\\varepsilon^k]\\Big(\\sum_{m\\ge1}\\varepsilon^m f_{i,m}(x, \\Omega x')\\Big)
          - \\sum_{q=1}^{k} (\\Omega^2)_q\\, x_{i,k-q}''(s),

the second sum being what the strained time adds. Products are linearised exactly for polynomial
right-hand sides, otherwise Fourier coefficients come from a numeric quadrature.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import sympy as sp

from perturb._defaults import FFT_POINTS, FFT_TRIM, MAX_ORDER
from perturb.errors import InvalidSystemError, bad_value
from perturb.method.exact import chop, taylor_coefficient
from perturb.series import NotNumeric, TrigSeries, evaluate_analytic, evaluate_polynomial
from perturb.system import EPS, QuasilinearSystem
from perturb.trig import TrigPoly

__all__ = ["GivenInitialValues", "NotPolynomial", "forcing", "state_series"]


class NotPolynomial(Exception):
    """The forcing cannot be expanded (not polynomial, and no numeric values for the quadrature)."""


def state_series(
    system: QuasilinearSystem,
    x: Sequence[Sequence[TrigPoly]],
    omega: Sequence[sp.Expr],
    k: int,
    poly: type = TrigPoly,
) -> dict[sp.Symbol, TrigSeries]:
    """Series (to order ``k - 1``, padded to ``k``) of the state and of the initial values.

    ``x[i][q]`` is :math:`x_{i,q}(s)`, ``omega[q]`` is :math:`\\Omega_q`; velocities are
    :math:`\\Omega\\, dx/ds`. ``poly`` is the class of the ``x[i][q]`` (sympy's
    :class:`TrigPoly` or the engine's native one) and the ``omega[q]`` are in its ring.
    """
    top = k - 1
    variables: dict[sp.Symbol, TrigSeries] = {}
    omega_series = TrigSeries([poly.constant(w) for w in omega[: top + 1]], poly).truncate(top)
    for i in range(system.n):
        xs = TrigSeries(x[i][: top + 1], poly).truncate(top)
        variables[system.coordinates[i]] = xs
        variables[system.velocities[i]] = (omega_series * xs.derivative()).truncate(top)
    for j, sym in enumerate(system.initial_values):
        value = variables[system.state_symbols[j]]
        variables[sym] = TrigSeries([poly.constant(c.at_zero()) for c in value.coefficients], poly)
    drive = system.excitation
    if drive is not None:  # theta = Omega t = p s: cos(theta), sin(theta) are harmonic p in s
        one, zero = poly.ring.coerce(1), poly.ring.zero
        variables[drive.cos_symbol] = TrigSeries([poly.harmonic(drive.p, one, zero)], poly)
        variables[drive.sin_symbol] = TrigSeries([poly.harmonic(drive.p, zero, one)], poly)
    return {sym: series.truncate(k) for sym, series in variables.items()}


def forcing(
    k: int,
    system: QuasilinearSystem,
    expansion: Sequence[Sequence[sp.Expr]],
    x: Sequence[Sequence[TrigPoly]],
    omega: Sequence[sp.Expr],
    quadrature: str,
    converter=None,
) -> list[TrigPoly]:
    """:math:`R_{i,k}`: order-``k`` coefficient of :math:`f_i(x, \\Omega x') - (\\Omega^2 - \\omega_{ref}^2) x_i''`.

    Parameters
    ----------
    k : int
        The order.
    system : QuasilinearSystem
    expansion : sequence
        ``expansion[i][m]`` is :math:`f_{i,m}` (see :meth:`QuasilinearSystem.expansion`).
    x : sequence
        ``x[i][q]``, the solution's coefficients known so far (``q < k``).
    omega : sequence
        :math:`\\Omega_0, \\dots, \\Omega_k` (the last one still an unknown).
    quadrature : {"auto", "exact", "numeric"}
        See :class:`~perturb.method.poincare.PoincareMethod`.
    converter : perturb.native.Converter, optional
        When given, ``x`` and ``omega`` (and the result) are in its native ring; ``expansion``
        stays sympy.

    Raises
    ------
    NotPolynomial
        When a term can be expanded neither exactly nor numerically.
    """
    poly = converter.poly if converter is not None else TrigPoly
    ring = poly.ring
    variables = state_series(system, x, omega[:k], k, poly)
    omega_sq = [
        ring.expand(ring.add(omega[a] * omega[q - a] for a in range(q + 1))) for q in range(k + 1)
    ]
    out = []
    for i in range(system.n):
        total = poly()
        for m in range(1, k + 1):
            f_m = expansion[i][m]
            if f_m == 0:
                continue
            value = _evaluate(f_m, variables, k - m, quadrature, converter)
            total = total + value.coefficients[k - m]
        for q in range(1, k + 1):  # -(Omega^2)_q x_{i,k-q}''
            if k - q < len(x[i]) and omega_sq[q] != 0:
                total = total - x[i][k - q].derivative().derivative().scale(omega_sq[q])
        out.append(chop(total.expand()))
    return out


def _evaluate(expr: sp.Expr, variables, order: int, quadrature: str, converter) -> TrigSeries:
    """Series of ``expr`` on the state series: exact for polynomials, else numeric quadrature."""
    if quadrature != "numeric":
        try:
            convert = converter.to_native if converter is not None else None
            return evaluate_polynomial(expr, variables, order, convert)
        except sp.PolynomialError as exc:
            if quadrature == "exact":
                raise NotPolynomial(
                    f"{exc}; use quadrature='auto' with numeric parameters"
                ) from None
    try:
        if converter is None or not converter.native:
            return evaluate_analytic(expr, variables, order, FFT_POINTS, FFT_TRIM)
        # the quadrature works on sympy coefficients: over and back (the engine runs numeric
        # right-hand sides in sympy, see perturb.native.ring_for; this is the safety net)
        plain = {
            sym: TrigSeries([converter.trig(c) for c in series.coefficients], TrigPoly)
            for sym, series in variables.items()
        }
        value = evaluate_analytic(expr, plain, order, FFT_POINTS, FFT_TRIM)
        return TrigSeries([converter.native_poly(c) for c in value.coefficients], converter.poly)
    except NotNumeric as exc:
        raise NotPolynomial(str(exc)) from None


class GivenInitialValues:
    """The initial values the user fixes (``amplitudes=``), expanded in ε order by order.

    A value may depend on ε and on the system's ``initial_values`` symbols (a constraint such as a
    first integral); those are themselves series :math:`\\sum_j \\varepsilon^j c_j` known order by
    order. Each value is expanded once with placeholder symbols for the :math:`c_j` (cheap: small
    expressions), and what is known of the :math:`c_j` is put in at each order.

    Parameters
    ----------
    system : QuasilinearSystem
    values : dict
        ``{coordinate index: expression}``.
    """

    def __init__(self, system: QuasilinearSystem, values: dict[int, sp.Expr]):
        self.system = system
        self.values = values
        self._placeholder_cache: dict = {}
        self._taylor_cache: dict = {}

    def __contains__(self, i: int) -> bool:
        return i in self.values

    def coefficient(self, i: int, k: int, initial_series: Callable[[int, int], sp.Expr]) -> sp.Expr:
        """The ε^k coefficient of coordinate ``i``'s given initial value.

        ``initial_series(j, k)`` is the ``j``-th initial value (``x_1(0) .. xdot_n(0)``) as a
        polynomial in ε through order ``k``, from what the construction knows so far.
        """
        expr = self.values[i]
        if not (expr.free_symbols & set(self.system.initial_values)) and not expr.has(EPS):
            return expr if k == 0 else sp.S.Zero
        placeholders = self._placeholders(i)
        subs = {}
        for j, sym in enumerate(self.system.initial_values):
            if not expr.has(sym):
                continue
            series = sp.Poly(initial_series(j, k), EPS)
            for q, c in enumerate(placeholders[sym][: k + 1]):
                subs[c] = series.coeff_monomial(EPS**q)
        return sp.expand(self._placeholder_taylor(i, k).xreplace(subs))

    def _placeholders(self, i: int) -> dict:
        if i not in self._placeholder_cache:
            expr = self.values[i]
            names = [c.name for c in self.system.coordinates]
            table = {}
            for j, sym in enumerate(self.system.initial_values):
                if expr.has(sym) and j % self.system.n == i:
                    raise bad_value(
                        "amplitudes",
                        {names[i]: expr},
                        "the initial value of a coordinate cannot depend on itself",
                        InvalidSystemError,
                    )
                table[sym] = [sp.Dummy(f"{sym.name}_{q}") for q in range(MAX_ORDER + 4)]
            self._placeholder_cache[i] = table
        return self._placeholder_cache[i]

    def _placeholder_taylor(self, i: int, k: int) -> sp.Expr:
        key = (i, k)
        if key not in self._taylor_cache:
            table = self._placeholders(i)
            expr = self.values[i]
            subs = {
                sym: sp.Add(*(EPS**q * c for q, c in enumerate(cs[: k + 1])))
                for sym, cs in table.items()
                if expr.has(sym)
            }
            self._taylor_cache[key] = taylor_coefficient(expr.xreplace(subs), k)
        return self._taylor_cache[key]
