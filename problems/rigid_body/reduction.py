"""Reduction of the fast-spin Euler–Poisson system to a quasilinear system, derived by code.

Disk (:math:`A + B = C`, :math:`z_0 = 0`)
    With :math:`P = p_1 - \\varepsilon x_0'\\gamma_0''/b` and :math:`G = \\gamma - \\varepsilon a\\gamma_0'' P`
    (the paper's :math:`p_2, \\gamma_2`),

    .. math::

        \\ddot P + P = \\varepsilon^2 F_2 + \\varepsilon^3 F_3 + \\dots, \\qquad
        \\ddot G + G = \\varepsilon^2 \\Phi_2 + \\varepsilon^3 \\Phi_3 + \\dots

General body, non-resonant fast spin
    :math:`P \\equiv p_1`, :math:`G \\equiv \\gamma`:
    :math:`\\ddot P + \\omega^2 P = \\varepsilon F_1 + \\dots`, :math:`\\ddot G + G = \\varepsilon\\Phi_1 + \\dots`
    with :math:`\\omega^2 = (C-A)(C-B)/(AB)`.

The full state :math:`(p_1, q_1, r_1, \\gamma, \\gamma', \\gamma'')` is rebuilt from the reduced state
:math:`(P, \\dot P, G, \\dot G)` by eliminating

* :math:`q_1` from the :math:`p_1`-equation (:math:`\\dot p_1 = \\dot P`),
* :math:`\\gamma'` from the :math:`\\gamma`-equation (:math:`\\dot\\gamma = \\dot G + s_G\\dot P`),
* :math:`\\gamma''` from the area integral, and
* :math:`r_1` from the energy integral,

each solved (with sympy) for its variable and then iterated as a truncated series in
:math:`\\varepsilon`. The constants of the integrals are their values at :math:`\\tau = 0`, where
:math:`r_1 = 1`, :math:`\\gamma'' = \\gamma_0''` and the reduced state is :math:`(P_0, \\dot P_0, G_0,
\\dot G_0)`. The forcing is then :math:`\\ddot P + \\omega^2 P` with
:math:`\\ddot P = \\nabla \\dot p_1 \\cdot f` evaluated on that series.

The series arithmetic uses sympy's sparse polynomial rings (coefficients in
:math:`\\mathbb{Q}(a, b)`), which keeps the order-3 disk reduction to about a second.

References
----------
.. [1] Reference derivation, ``shared/reference/derivation.md`` section (c).
.. [2] The seed paper, equations (1)–(7) (there written in :math:`\\mu^{-1} = \\varepsilon`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import cache, cached_property

import numpy as np
import sympy as sp
from attrs import field, frozen
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

from perturb.errors import InvalidParameterError, bad_value
from perturb.system import EPS, QuasilinearSystem
from problems.rigid_body.equations import (
    NONDIMENSIONAL_STATE,
    a,
    b,
    gamma1,
    gamma2,
    gamma3,
    inertia_ratio_values,
    k,
    nondimensional_equations,
    nondimensional_integrals,
    p1,
    q1,
    r1,
    x0p,
    y0p,
    z0p,
)

__all__ = [
    "DISK_PARAMETERS",
    "GENERAL_PARAMETERS",
    "INITIAL_VALUES",
    "REDUCED_STATE",
    "Reduction",
    "check_gamma3_0",
    "disk_reduction",
    "general_body_reduction",
    "gamma3_0",
]

# ---------------------------------------------------------------------------- symbols
P, G, dP, dG = sp.symbols("P G dP dG")
P0, G0, dP0, dG0 = sp.symbols("P0 G0 dP0 dG0")
#: Initial value of gamma'' (the paper's gamma0'').
gamma3_0 = sp.Symbol("gamma3_0")
#: Reduced state in the order (P, dP, G, dG).
REDUCED_STATE = (P, dP, G, dG)
#: Initial values in the engine's order: x(0)'s then xdot(0)'s.
INITIAL_VALUES = (P0, G0, dP0, dG0)
DISK_PARAMETERS = (a, b, k, x0p, y0p, gamma3_0)
GENERAL_PARAMETERS = (a, b, k, x0p, y0p, z0p, gamma3_0)

#: Placeholders for the constants of the energy and area integrals.
_H0, _K0 = sp.symbols("H_0 K_0")
#: Ring generators standing for 1/a and 1/b (polynomial mode of the series ring).
_INV_A, _INV_B = sp.symbols("inv_a inv_b")

#: Highest reduction order accepted (cold cost of the disk: order 3 ~2 s, 4 ~5 s, 5 ~15 s).
MAX_REDUCTION_ORDER = 5

_INITIAL_OF = {P: P0, dP: dP0, G: G0, dG: dG0}


# ---------------------------------------------------------------------------- truncated series
class _SeriesRing:
    """Polynomials in all symbols, truncated in epsilon at ``order``.

    With ``fraction_field=False`` the ratios a, b and their inverses ``1/a``, ``1/b`` are ring
    generators over QQ (fast; enough for the disk, whose only denominators are a and b); otherwise
    the coefficients live in QQ(a, b) (general body: 1/(1 - b) and the like appear).
    """

    def __init__(self, order: int, params: tuple[sp.Symbol, ...], fraction_field: bool):
        self.order = order
        self.fraction_field = fraction_field
        other = tuple(s for s in params if s not in (a, b))
        extra = () if fraction_field else (a, b, _INV_A, _INV_B)
        self.symbols = (
            EPS,
            *NONDIMENSIONAL_STATE,
            *REDUCED_STATE,
            *INITIAL_VALUES,
            _H0,
            _K0,
            *extra,
            *other,
        )
        domain = QQ.frac_field(a, b) if fraction_field else QQ
        self.ring, *_ = ring(self.symbols, domain)
        self.index = {s: i for i, s in enumerate(self.symbols)}

    def __call__(self, expr) -> PolyElement:
        expr = sp.expand(sp.sympify(expr))
        if not self.fraction_field:
            inverse = {a: _INV_A, b: _INV_B}
            expr = expr.replace(
                lambda e: e.is_Pow and e.base in inverse and e.exp.is_negative,
                lambda e: inverse[e.base] ** (-e.exp),
            )
            stray = expr.free_symbols - set(self.symbols)
            if stray or any(
                isinstance(d, sp.Pow) and d.exp.is_negative for d in sp.preorder_traversal(expr)
            ):
                raise AssertionError(f"cannot represent {expr} with inverse generators only")
        return self.ring.from_expr(expr)

    def gen(self, symbol: sp.Symbol) -> PolyElement:
        return self.ring.gens[self.index[symbol]]

    def trunc(self, poly: PolyElement) -> PolyElement:
        n = self.order
        return self.ring.from_dict({m: c for m, c in poly.items() if m[0] <= n})

    def _by_degree(self, poly: PolyElement) -> list[PolyElement]:
        parts: list[dict] = [{} for _ in range(self.order + 1)]
        for m, c in poly.items():
            if m[0] <= self.order:
                parts[m[0]][m] = c
        return [self.ring.from_dict(d) if d else None for d in parts]

    def mul(self, x: PolyElement, y: PolyElement) -> PolyElement:
        """Product truncated at eps**order (only the pairs of degrees that survive are multiplied)."""
        xs, ys = self._by_degree(x), self._by_degree(y)
        out = self.ring.zero
        for i, xi in enumerate(xs):
            if xi is None:
                continue
            for j in range(self.order + 1 - i):
                if ys[j] is not None:
                    out += xi * ys[j]
        return out

    def substitute(
        self, poly: PolyElement, mapping: Mapping[sp.Symbol, PolyElement]
    ) -> PolyElement:
        """Replace generators by series (truncated products)."""
        slots = [(self.index[s], v) for s, v in mapping.items()]
        powers: dict[tuple[int, int], PolyElement] = {}

        def power(i: int, value: PolyElement, e: int) -> PolyElement:
            key = (i, e)
            if key not in powers:
                powers[key] = value if e == 1 else self.mul(power(i, value, e - 1), value)
            return powers[key]

        result = self.ring.zero
        for monom, coeff in poly.items():
            rest = list(monom)
            factors = []
            for i, value in slots:
                if rest[i]:
                    factors.append(power(i, value, rest[i]))
                    rest[i] = 0
            term = self.ring.from_dict({tuple(rest): coeff})
            if term and rest[0] > self.order:
                continue
            for f in factors:
                term = self.mul(term, f)
            result += term
        return self.trunc(result)

    def _split_unit(self, s: PolyElement):
        """s = c0 * (1 + u) with c0 a constant and u = O(eps)."""
        lowest = {m: c for m, c in s.items() if m[0] == 0}
        if len(lowest) != 1 or any(next(iter(lowest))):
            raise AssertionError(f"series has no constant leading term: {s.as_expr()}")
        c0 = next(iter(lowest.values()))
        return c0, s * (1 / c0) - 1

    def inverse(self, s: PolyElement) -> PolyElement:
        c0, u = self._split_unit(s)
        out, term = self.ring.one, self.ring.one
        for _ in range(self.order):
            term = self.mul(term, -u)
            out += term
        return out * (1 / c0)

    def sqrt(self, s: PolyElement) -> PolyElement:
        c0, u = self._split_unit(s)
        if c0 != 1:
            raise AssertionError(f"sqrt of a series with leading term {c0} (expected 1)")
        out, term = self.ring.one, self.ring.one
        for n in range(1, self.order + 1):
            term = self.mul(term, u)
            out += self.ring.domain.convert(sp.binomial(sp.Rational(1, 2), n)) * term
        return out

    def to_expr(self, poly: PolyElement) -> sp.Expr:
        expr = poly.as_expr()
        if not self.fraction_field:
            expr = expr.subs({_INV_A: 1 / a, _INV_B: 1 / b})
        return sp.expand(expr)

    def coefficients(self, poly: PolyElement) -> tuple[sp.Expr, ...]:
        """Coefficients of eps**0 .. eps**order as expanded sympy expressions."""
        grouped: list[dict] = [{} for _ in range(self.order + 1)]
        for m, c in poly.items():
            grouped[m[0]][(0, *m[1:])] = c
        return tuple(self.to_expr(self.ring.from_dict(d)) if d else sp.S.Zero for d in grouped)


# ---------------------------------------------------------------------------- derivation
@frozen
class _Spec:
    """What distinguishes the disk from the general body."""

    equations: tuple[sp.Expr, ...]  # dimensionless rhs (p1, q1, r1, gamma1..3)
    energy: sp.Expr
    area: sp.Expr
    shift_p: sp.Expr  # p1 = P + shift_p
    shift_g: sp.Expr  # gamma = G + shift_g * P
    omega_sq: sp.Expr  # frequency squared of P
    params: tuple[sp.Symbol, ...]
    fraction_field: bool  # coefficients in QQ(a, b) (general) or a, b, 1/a, 1/b generators (disk)


def _solve_linear(equation: sp.Expr, unknown: sp.Symbol) -> tuple[sp.Expr, sp.Expr]:
    """Solve ``equation = 0``, linear in ``unknown``: return (numerator, denominator).

    ``equation = alpha * unknown + beta`` gives ``unknown = -beta / alpha``; both are polynomials,
    so the series evaluation needs one series inversion (of alpha).
    """
    equation = sp.expand(equation)
    alpha = sp.diff(equation, unknown)
    if alpha == 0 or sp.diff(alpha, unknown) != 0:
        raise AssertionError(f"{equation} = 0 is not linear in {unknown}")
    beta = sp.expand(equation.subs(unknown, 0))
    return -beta, alpha


@frozen
class _Eliminations:
    """Solved forms: each unknown as numerator/denominator (sympy), and r1**2 for the energy."""

    q1: tuple[sp.Expr, sp.Expr]
    gamma2: tuple[sp.Expr, sp.Expr]
    gamma3: tuple[sp.Expr, sp.Expr]
    r1_squared: tuple[sp.Expr, sp.Expr]


def _eliminations(spec: _Spec) -> _Eliminations:
    f_p, _, _, f_g, _, _ = spec.equations
    # p1 = P + const  =>  dp1/dtau = dP
    q_sol = _solve_linear(f_p - dP, q1)
    # gamma = G + s_G P  =>  dgamma/dtau = dG + s_G dP
    g2_sol = _solve_linear(f_g - dG - spec.shift_g * dP, gamma2)
    # area integral = its value at tau = 0
    g3_sol = _solve_linear(spec.area - _K0, gamma3)
    # energy: H = c2 r1**2 + H|_{r1=0} (no linear term), so r1**2 = (H0 - H|_{r1=0}) / c2
    poly = sp.Poly(spec.energy, r1)
    if poly.degree() != 2 or poly.coeff_monomial(r1) != 0:
        raise AssertionError("the energy integral is not of the form c2*r1**2 + rest")
    c2 = poly.coeff_monomial(r1**2)
    rest = poly.coeff_monomial(1)
    return _Eliminations(q_sol, g2_sol, g3_sol, (sp.expand(_H0 - rest), sp.expand(c2)))


class _Builder:
    """Runs the elimination as truncated series in one polynomial ring."""

    def __init__(self, spec: _Spec, order: int):
        self.spec = spec
        self.sr = _SeriesRing(order, spec.params, spec.fraction_field)
        self.elim = _eliminations(spec)
        conv = self.sr
        self.q_num, self.q_den = map(conv, self.elim.q1)
        self.g2_num, self.g2_den = map(conv, self.elim.gamma2)
        self.g3_num, self.g3_den = map(conv, self.elim.gamma3)
        self.rs_num, self.rs_den = map(conv, self.elim.r1_squared)

    def _ratio(self, num, den, mapping):
        return self.sr.mul(
            self.sr.substitute(num, mapping), self.sr.inverse(self.sr.substitute(den, mapping))
        )

    def _iterate(self, state: dict, reduced: Mapping, constants: Mapping | None) -> dict:
        """Fixed-point iteration; ``constants`` None means r1 = 1, gamma'' = gamma3_0 (tau = 0)."""
        sr = self.sr
        for _ in range(sr.order + 3):
            previous = dict(state)
            mapping = {**state, **reduced, **(constants or {})}
            state[q1] = self._ratio(self.q_num, self.q_den, mapping)
            mapping[q1] = state[q1]
            state[gamma2] = self._ratio(self.g2_num, self.g2_den, mapping)
            mapping[gamma2] = state[gamma2]
            if constants is not None:
                state[gamma3] = self._ratio(self.g3_num, self.g3_den, mapping)
                mapping[gamma3] = state[gamma3]
                r_sq = self._ratio(self.rs_num, self.rs_den, mapping)
                state[r1] = sr.sqrt(r_sq)
            if state == previous:
                return state
        raise AssertionError("the elimination series did not converge")

    def _start(self, reduced: Mapping[sp.Symbol, PolyElement]) -> dict:
        sr = self.sr
        shift_p = sr(self.spec.shift_p)
        shift_g = sr(self.spec.shift_g)
        p_val = reduced[P]
        return {
            p1: sr.trunc(p_val + shift_p),
            gamma1: sr.trunc(reduced[G] + sr.mul(shift_g, p_val)),
            r1: sr.ring.one,
            gamma3: sr(gamma3_0),
            q1: sr.ring.zero,
            gamma2: sr.ring.zero,
        }

    def run(self):
        sr = self.sr
        # --- tau = 0: r1 = 1, gamma'' = gamma3_0, reduced state = initial values
        initial_reduced = {s: sr.gen(_INITIAL_OF[s]) for s in REDUCED_STATE}
        initial = self._iterate(self._start(initial_reduced), initial_reduced, None)
        h0 = sr.substitute(sr(self.spec.energy), initial)
        k0 = sr.substitute(sr(self.spec.area), initial)
        # --- any tau
        reduced = {s: sr.gen(s) for s in REDUCED_STATE}
        state = self._iterate(self._start(reduced), reduced, {_H0: h0, _K0: k0})
        # --- accelerations along the flow: d/dtau of dp1/dtau and of dgamma/dtau
        f = self.spec.equations
        second = []
        for i in (0, 3):
            expr = sum(sp.diff(f[i], y) * fy for y, fy in zip(NONDIMENSIONAL_STATE, f, strict=True))
            second.append(sr.substitute(sr(sp.expand(expr)), state))
        ddp, ddgamma = second
        shift_g = sr(self.spec.shift_g)
        ddg = sr.trunc(ddgamma - sr.mul(shift_g, ddp))
        rhs_p = sr.trunc(ddp + sr(self.spec.omega_sq) * sr.gen(P))
        rhs_g = sr.trunc(ddg + sr.gen(G))
        geometric = sr.substitute(sr(gamma1**2 + gamma2**2 + gamma3**2), state)
        return state, initial, rhs_p, rhs_g, geometric, h0, k0


# ---------------------------------------------------------------------------- result
def _tuple_of_exprs(values) -> tuple[sp.Expr, ...]:
    return tuple(sp.sympify(v) for v in values)


@frozen
class Reduction:
    """A derived reduction: the quasilinear system and the maps between the two sets of variables.

    Attributes
    ----------
    system : perturb.system.QuasilinearSystem
        Coordinates (P, G), velocities (dP, dG), rhs in ``epsilon``.
    order : int
        Truncation order in epsilon of the rhs and of the maps.
    F, Phi : tuple of sympy.Expr
        ``F[n]`` is the coefficient of ``epsilon**n`` in the P-equation (``n = 0..order``), likewise
        ``Phi`` for the G-equation.
    full_state : tuple of sympy.Expr
        ``(p1, q1, r1, gamma1, gamma2, gamma3)`` as series in epsilon in the reduced state, the
        initial values and the parameters (the inverse map).
    initial_full_state : tuple of sympy.Expr
        The same at tau = 0, in the initial values only.
    reduced_state : tuple of sympy.Expr
        The exact forward map: ``(P, dP, G, dG)`` as functions of the full dimensionless state.
    reduced_accelerations : tuple of sympy.Expr
        ``(d2P, d2G)`` as exact functions of the full state (along the flow).
    geometric_integral : sympy.Expr
        :math:`|\\gamma|^2` in the reduced variables (a first integral, equal to 1).
    energy_constant, area_constant : sympy.Expr
        Values of the dimensionless energy and area integrals in terms of the initial values.
    parameters : tuple of sympy.Symbol
    """

    system: QuasilinearSystem
    order: int
    F: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    Phi: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    full_state: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    initial_full_state: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    reduced_state: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    reduced_accelerations: tuple[sp.Expr, ...] = field(converter=_tuple_of_exprs)
    geometric_integral: sp.Expr
    energy_constant: sp.Expr
    area_constant: sp.Expr
    parameters: tuple[sp.Symbol, ...]

    # ------------------------------------------------------------------ numeric versions
    def _args(self, values: Mapping, eps: float) -> tuple[float, ...]:
        by_name = {str(key): val for key, val in values.items()}
        missing = [s.name for s in self.parameters if s.name not in by_name]
        if missing:
            raise bad_value("values", dict(by_name), f"give values for {missing}")
        out = tuple(float(by_name[s.name]) for s in self.parameters)
        for s, value in zip(self.parameters, out, strict=True):
            if np.isnan(value) or np.isinf(value):
                raise bad_value(s.name, value, "give a finite real number")
        for name in ("a", "b"):
            if float(by_name[name]) <= 0:
                raise bad_value(name, float(by_name[name]), "moment ratios must be positive")
        if float(by_name["k"]) < 0:
            raise bad_value("k", float(by_name["k"]), "give k = 3C/(RMl) >= 0")
        check_gamma3_0(by_name["gamma3_0"])
        eps = float(eps)
        if not eps > 0 or np.isinf(eps):
            raise bad_value("eps", eps, "give a positive finite expansion parameter")
        return (*out, eps)

    def _lambdify(self, exprs, first, second) -> Callable:
        args = (*self.parameters, EPS)
        return sp.lambdify((first, second, args), list(exprs), "numpy", cse=True)

    @cached_property
    def _inverse_lambda(self) -> Callable:
        return self._lambdify(self.full_state, REDUCED_STATE, INITIAL_VALUES)

    @cached_property
    def _forward_lambda(self) -> Callable:
        return self._lambdify(
            self.reduced_state + self.reduced_accelerations, NONDIMENSIONAL_STATE, ()
        )

    @cached_property
    def _rhs_lambda(self) -> Callable:
        return self._lambdify(self.system.rhs, REDUCED_STATE, INITIAL_VALUES)

    def inverse_function(self, values: Mapping, eps: float) -> Callable[..., np.ndarray]:
        """Numeric inverse map ``(Z, Z0) -> (p1, q1, r1, gamma1, gamma2, gamma3)``.

        Parameters
        ----------
        values : Mapping
            Parameter name (or symbol) -> value, for every symbol of ``parameters``.
        eps : float
            The expansion parameter c/r0.

        Returns
        -------
        callable
            ``f(Z, Z0)`` with ``Z = (P, dP, G, dG)`` (scalars or arrays of one shape) and
            ``Z0 = (P0, G0, dP0, dG0)``; returns an array of shape (6, ...).
        """
        f = self._inverse_lambda
        args = self._args(values, eps)
        return lambda z, z0: np.array(np.broadcast_arrays(*f(tuple(z), tuple(z0), args)))

    def forward_function(self, values: Mapping, eps: float) -> Callable[[np.ndarray], np.ndarray]:
        """Numeric exact forward map ``y -> (P, dP, G, dG, d2P, d2G)``.

        ``y = (p1, q1, r1, gamma1, gamma2, gamma3)`` (shape (6,) or (6, n)); the derivatives are
        those along the full flow.
        """
        f = self._forward_lambda
        args = self._args(values, eps)
        return lambda y: np.array(np.broadcast_arrays(*f(tuple(y), (), args)))

    def rhs_function(self, values: Mapping, eps: float) -> Callable[..., np.ndarray]:
        """Numeric ``(Z, Z0) -> (rhs_P, rhs_G)`` of the reduced system (all orders kept)."""
        f = self._rhs_lambda
        args = self._args(values, eps)
        return lambda z, z0: np.array(np.broadcast_arrays(*f(tuple(z), tuple(z0), args)))


def _check_order(order: int) -> int:
    if (
        isinstance(order, bool)
        or not isinstance(order, int)
        or not 1 <= order <= MAX_REDUCTION_ORDER
    ):
        raise bad_value("order", order, f"give an integer between 1 and {MAX_REDUCTION_ORDER}")
    return order


def _build(spec: _Spec, order: int, name: str, frequencies) -> Reduction:
    builder = _Builder(spec, order)
    state, initial, rhs_p, rhs_g, geometric, h0, k0 = builder.run()
    sr = builder.sr
    F = sr.coefficients(rhs_p)
    Phi = sr.coefficients(rhs_g)
    rhs = [sp.Add(*[EPS**n * c for n, c in enumerate(coeffs)]) for coeffs in (F, Phi)]
    geometric_expr = sr.to_expr(geometric)
    system = QuasilinearSystem(
        coordinates=(P, G),
        velocities=(dP, dG),
        frequencies=frequencies,
        rhs=rhs,
        parameter=EPS,
        parameters=spec.params,
        initial_values=INITIAL_VALUES,
        first_integrals=(geometric_expr,),
        name=name,
        truncation=order + 1,
    )
    f = spec.equations
    shift_g = spec.shift_g
    reduced_state = (
        p1 - spec.shift_p,
        f[0],
        gamma1 - shift_g * (p1 - spec.shift_p),
        f[3] - shift_g * f[0],
    )
    dd = [
        sp.expand(sum(sp.diff(f[i], y) * fy for y, fy in zip(NONDIMENSIONAL_STATE, f, strict=True)))
        for i in (0, 3)
    ]
    accelerations = (dd[0], sp.expand(dd[1] - shift_g * dd[0]))
    return Reduction(
        system=system,
        order=order,
        F=F,
        Phi=Phi,
        full_state=[sr.to_expr(state[s]) for s in NONDIMENSIONAL_STATE],
        initial_full_state=[sr.to_expr(initial[s]) for s in NONDIMENSIONAL_STATE],
        reduced_state=reduced_state,
        reduced_accelerations=accelerations,
        geometric_integral=geometric_expr,
        energy_constant=sr.to_expr(h0),
        area_constant=sr.to_expr(k0),
        parameters=spec.params,
    )


@cache
def disk_reduction(order: int = 3) -> Reduction:
    """Reduce the disk (A + B = C, z0 = 0) to the quasilinear system in (P, G).

    Parameters
    ----------
    order : int
        Truncation order in epsilon (3 gives F2, F3, Phi2, Phi3; 4 adds F4, Phi4).

    Returns
    -------
    Reduction
        ``system.rhs`` is ``eps**2*F2 + eps**3*F3 + ...`` (F0 = F1 = 0 identically), parameters
        ``(a, b, k, x0p, y0p, gamma3_0)``, initial values ``(P0, G0, dP0, dG0)`` and the geometric
        integral as the first integral.

    Notes
    -----
    a and b are kept as separate symbols; a + b = 1 is used only through A1 = 1, B1 = -1,
    C1 = b - a (the reference's convention), so expressions are equal to other forms only modulo
    a + b = 1.
    """
    order = _check_order(order)
    ratios = inertia_ratio_values(disk=True)
    eqs = nondimensional_equations(True, ratios=True).subs(ratios).subs(z0p, 0)
    ints = nondimensional_integrals(True)
    spec = _Spec(
        equations=tuple(sp.expand(e) for e in eqs),
        energy=ints["energy"].subs(z0p, 0),
        area=ints["area"],
        shift_p=EPS * x0p * gamma3_0 / b,
        shift_g=EPS * a * gamma3_0,
        omega_sq=sp.S.One,
        params=DISK_PARAMETERS,
        fraction_field=False,
    )
    return _build(spec, order, "disk-newtonian-fast-spin", (1, 1))


@cache
def general_body_reduction(order: int = 2) -> Reduction:
    """The general body (any A, B, C, z0) at fast spin, non-resonant: P = p1, G = gamma.

    .. math::

        \\ddot P + \\omega^2 P = \\sum_{n\\ge1} \\varepsilon^n F_n, \\qquad
        \\ddot G + G = \\sum_{n\\ge1} \\varepsilon^n \\Phi_n, \\qquad
        \\omega^2 = -A_1 B_1 = \\frac{(1-a)(1-b)}{ab}.

    Valid for :math:`A_1 \\ne 0` (B != C, so that q1 can be eliminated) and away from the resonance
    :math:`\\omega = 1` (the disk), where the O(eps) forcing has a small divisor.
    """
    order = _check_order(order)
    ratios = inertia_ratio_values(disk=False)
    eqs = nondimensional_equations(True, ratios=True).subs(ratios)
    ints = nondimensional_integrals(True)
    omega_sq = sp.factor(-ratios[sp.Symbol("A1")] * ratios[sp.Symbol("B1")])
    spec = _Spec(
        equations=tuple(sp.expand(e) for e in eqs),
        energy=ints["energy"],
        area=ints["area"],
        shift_p=sp.S.Zero,
        shift_g=sp.S.Zero,
        omega_sq=omega_sq,
        params=GENERAL_PARAMETERS,
        fraction_field=True,
    )
    return _build(spec, order, "rigid-body-fast-spin", (sp.sqrt(omega_sq), 1))


def check_gamma3_0(value: float) -> float:
    """Validate an initial direction cosine gamma3_0 (|value| <= 1, not NaN)."""
    value = float(value)
    if np.isnan(value) or abs(value) > 1:
        raise InvalidParameterError(
            f"`gamma3_0` = {value!r} is invalid: a direction cosine needs |gamma3_0| <= 1"
        )
    return value
