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

The series arithmetic stays in one of sympy's sparse polynomial rings
(:mod:`problems.rigid_body._series_ring`) until the end; the sympy expressions of the result
(``F``, ``Phi``, ``system``, ``full_state`` ...) are built only when asked for. A reduction is kept in
memory and on disk (:func:`perturb.cache.cached`, kind ``reduction``). Orders that are solved for one
body's parameter values (:func:`specialised_disk_reduction`) put those values in *before* the
reduction: the same series, evaluated, at a fraction of the cost.

References
----------
.. [1] Reference derivation, ``shared/reference/derivation.md`` section (c).
.. [2] The seed paper, equations (1)–(7) (there written in :math:`\\mu^{-1} = \\varepsilon`).
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable, Mapping
from fractions import Fraction
from functools import cache, cached_property, lru_cache
from pathlib import Path

import numpy as np
import sympy as sp
from attrs import field, frozen
from sympy.polys.rings import PolyElement

from perturb._lambdify import numpy_lambdify
from perturb.cache import cached
from perturb.errors import InvalidParameterError, bad_value
from perturb.progress import stage
from perturb.system import EPS, QuasilinearSystem
from problems.rigid_body._elimination import (  # the symbols are public here
    DISK_PARAMETERS,
    G0,
    GENERAL_PARAMETERS,
    INITIAL_VALUES,
    LIGHT_SPECS,
    P0,
    REDUCED_STATE,
    VARIABLES,
    Builder,
    G,
    P,
    derived,
    dG,
    dG0,
    dP,
    dP0,
    gamma3_0,
)
from problems.rigid_body._inverse_map import PolynomialMap, compile_polynomials
from problems.rigid_body._series_ring import SeriesRing
from problems.rigid_body._stored import stored
from problems.rigid_body.equations import NONDIMENSIONAL_STATE, a, b, gamma1, p1

__all__ = [
    "DISK_PARAMETERS",
    "G",
    "G0",
    "P",
    "P0",
    "dG",
    "dG0",
    "dP",
    "dP0",
    "GENERAL_PARAMETERS",
    "INITIAL_VALUES",
    "REDUCED_STATE",
    "Reduction",
    "check_gamma3_0",
    "disk_reduction",
    "general_body_reduction",
    "gamma3_0",
    "specialised_disk_reduction",
    "specialised_general_body_reduction",
]

#: Highest reduction order accepted (symbolic disk, cold: order 3 ~0.2 s, 4 ~0.5 s, 5 ~2.5 s of
#: series arithmetic, plus the sympy expressions of what is asked for).
MAX_REDUCTION_ORDER = 6
#: Specialised reductions kept in memory (one per body and order; each is a few hundred kB).
SPECIALISED_CACHE_SIZE = 32
#: Inverse maps kept in the disk cache (kind ``inverse-map``), the most recently written: one per
#: body, order, parameter values and ε (a validation needs five: its point and the order check's
#: four), 10-50 kB each; a sweep makes new ones at every point.
INVERSE_MAP_CACHE_ENTRIES = 256


# ---------------------------------------------------------------------------- result
@frozen
class Reduction:
    """A derived reduction: the quasilinear system and the maps between the two sets of variables.

    The series live in a polynomial ring; each sympy attribute below is built on first use.

    Attributes
    ----------
    kind : str
        ``"disk"`` or ``"general"``.
    order : int
        Truncation order in epsilon of the rhs and of the maps.
    parameters : tuple of sympy.Symbol
        The parameters the series are symbolic in (empty for a specialised reduction).
    values : tuple of (sympy.Symbol, sympy.Rational)
        The parameters put in before the reduction (empty for a symbolic one).
    system : perturb.system.QuasilinearSystem
        Coordinates (P, G), velocities (dP, dG), rhs in ``epsilon``. For a specialised reduction it
        equals ``symbolic.system.with_values(values)``.
    F, Phi : tuple of sympy.Expr
        ``F[n]`` is the coefficient of ``epsilon**n`` in the P-equation (``n = 0..order``), likewise
        ``Phi`` for the G-equation.
    full_state : tuple of sympy.Expr
        ``(p1, q1, r1, gamma1, gamma2, gamma3)`` as series in epsilon in the reduced state, the
        initial values and the parameters (the inverse map).
    initial_full_state : tuple of sympy.Expr
        The same at tau = 0, in the initial values only.
    reduced_state : tuple of sympy.Expr
        The exact forward map: ``(P, dP, G, dG)`` as functions of the full dimensionless state (in
        the body's parameters, also for a specialised reduction: it is exact, not a series).
    reduced_accelerations : tuple of sympy.Expr
        ``(d2P, d2G)`` as exact functions of the full state (along the flow).
    geometric_integral : sympy.Expr
        :math:`|\\gamma|^2` in the reduced variables (a first integral, equal to 1).
    energy_constant, area_constant : sympy.Expr
        Values of the dimensionless energy and area integrals in terms of the initial values.
    """

    kind: str
    order: int
    parameters: tuple[sp.Symbol, ...]
    values: tuple[tuple[sp.Symbol, sp.Rational], ...]
    _ring: SeriesRing = field(eq=False, repr=False)
    _series: Mapping[str, PolyElement] = field(eq=False, repr=False)

    # ------------------------------------------------------------------ sympy views
    @cached_property
    def F(self) -> tuple[sp.Expr, ...]:
        return self._ring.coefficients(self._series["rhs_p"])

    @cached_property
    def Phi(self) -> tuple[sp.Expr, ...]:
        return self._ring.coefficients(self._series["rhs_g"])

    @cached_property
    def full_state(self) -> tuple[sp.Expr, ...]:
        return tuple(self._expr(f"state:{s.name}") for s in NONDIMENSIONAL_STATE)

    @cached_property
    def initial_full_state(self) -> tuple[sp.Expr, ...]:
        return tuple(self._expr(f"initial:{s.name}") for s in NONDIMENSIONAL_STATE)

    @cached_property
    def geometric_integral(self) -> sp.Expr:
        return self._expr("geometric")

    @cached_property
    def energy_constant(self) -> sp.Expr:
        return self._expr("energy")

    @cached_property
    def area_constant(self) -> sp.Expr:
        return self._expr("area")

    def _expr(self, name: str) -> sp.Expr:
        return self._ring.to_expr(self._series[name])

    @cached_property
    def system(self) -> QuasilinearSystem:
        """The reduced system, kept on disk: building it from the ring series and checking it
        costs a warm ``perturb validate disk`` 0.3 s of CPU, reading it back 0.1 s."""
        parts = (
            self.kind,
            self.order,
            tuple((s.name, sp.srepr(v)) for s, v in self.values),
            tuple(p.name for p in self.parameters),
            _source_fingerprint(),
        )
        return cached("reduced-system", parts, self._built_system)

    def _built_system(self) -> QuasilinearSystem:
        spec = LIGHT_SPECS[self.kind]
        frequencies = spec["frequencies"]()
        if self.values:
            frequencies = tuple(sp.sympify(w).subs(dict(self.values)) for w in frequencies)
        rhs = [sp.Add(*[EPS**n * c for n, c in enumerate(coeffs)]) for coeffs in (self.F, self.Phi)]
        return QuasilinearSystem(
            coordinates=(P, G),
            velocities=(dP, dG),
            frequencies=frequencies,
            rhs=rhs,
            parameter=EPS,
            parameters=self.parameters,
            initial_values=INITIAL_VALUES,
            first_integrals=(self.geometric_integral,),
            name=spec["name"],
            truncation=self.order + 1,
        )

    @cached_property
    def reduced_state(self) -> tuple[sp.Expr, ...]:
        spec = derived(self.kind)[0]
        f, shift_g = spec.equations, spec.shift_g
        return (
            p1 - spec.shift_p,
            f[0],
            gamma1 - shift_g * (p1 - spec.shift_p),
            f[3] - shift_g * f[0],
        )

    @cached_property
    def reduced_accelerations(self) -> tuple[sp.Expr, ...]:
        spec, _, (ddp, ddgamma) = derived(self.kind)
        return (ddp, sp.expand(ddgamma - spec.shift_g * ddp))

    # ------------------------------------------------------------------ numeric versions
    @property
    def body_parameters(self) -> tuple[sp.Symbol, ...]:
        """Every parameter of the body (also those a specialised reduction has put in)."""
        return LIGHT_SPECS[self.kind]["params"]

    def _check(self, values: Mapping, eps: float) -> tuple[dict[str, float], float]:
        by_name = {str(key): val for key, val in values.items()}
        missing = [s.name for s in self.body_parameters if s.name not in by_name]
        if missing:
            raise bad_value("values", dict(by_name), f"give values for {missing}")
        out = {s.name: float(by_name[s.name]) for s in self.body_parameters}
        for name, value in out.items():
            if np.isnan(value) or np.isinf(value):
                raise bad_value(name, value, "give a finite real number")
        for name in ("a", "b"):
            if out[name] <= 0:
                raise bad_value(name, out[name], "moment ratios must be positive")
        if out["k"] < 0:
            raise bad_value("k", out["k"], "give k = 3C/(RMl) >= 0")
        check_gamma3_0(out["gamma3_0"])
        for symbol, fixed in self.values:
            if not math.isclose(out[symbol.name], float(fixed), rel_tol=1e-12, abs_tol=1e-15):
                raise bad_value(
                    symbol.name,
                    out[symbol.name],
                    f"this reduction was derived for {symbol.name} = {float(fixed)!r}; use the "
                    "reduction of these values",
                )
        eps = float(eps)
        if not eps > 0 or np.isinf(eps):
            raise bad_value("eps", eps, "give a positive finite expansion parameter")
        return out, eps

    def _lambdify(self, exprs, first, second, symbols) -> Callable:
        return numpy_lambdify((first, second, (*symbols, EPS)), list(exprs), cse=True)

    @cached_property
    def _forward_lambda(self) -> Callable:
        # the exact forward map needs the body's equations: kept on disk, it spares a warm run
        # (the true orbit's section) deriving them
        exprs = stored(
            "forward-map",
            ("reduction.py", "_elimination.py", "equations.py"),
            (self.kind,),
            lambda: self.reduced_state + self.reduced_accelerations,
        )
        return self._lambdify(exprs, NONDIMENSIONAL_STATE, (), self.body_parameters)

    @cached_property
    def _rhs_lambda(self) -> Callable:
        return self._lambdify(self.system.rhs, REDUCED_STATE, INITIAL_VALUES, self.parameters)

    @cached_property
    def _inverse_compiled(self) -> dict:
        return {}

    def _inverse_lambda(self, values: dict[str, float], eps: float) -> PolynomialMap:
        """The inverse map with the parameters and eps put in exactly (kept per values)."""
        key = (tuple(values[s.name] for s in self.parameters), eps)
        cache_ = self._inverse_compiled
        if key not in cache_:
            numbers = {s: Fraction(values[s.name]) for s in self.parameters}
            numbers[EPS] = Fraction(eps)
            polys = [self._series[f"state:{s.name}"] for s in NONDIMENSIONAL_STATE]
            if len(cache_) >= SPECIALISED_CACHE_SIZE:
                cache_.clear()
            cache_[key] = cached(
                "inverse-map",
                lambda: self._inverse_key(numbers),
                lambda: compile_polynomials(
                    self._ring, polys, numbers, REDUCED_STATE, INITIAL_VALUES
                ),
                keep=INVERSE_MAP_CACHE_ENTRIES,
            )
        return cache_[key]

    def _inverse_key(self, numbers: Mapping[sp.Symbol, Fraction]) -> tuple:
        """What the inverse map at ``numbers`` is kept on disk under: the reduction (kind, order,
        values, the sources that derive its series and compile them) and the exact numbers."""
        return (
            self.kind,
            self.order,
            tuple((s.name, sp.srepr(v)) for s, v in self.values),
            _source_fingerprint(),
            _inverse_map_fingerprint(),
            tuple((s.name, n.numerator, n.denominator) for s, n in numbers.items()),
        )

    def inverse_function(self, values: Mapping, eps: float) -> Callable[..., np.ndarray]:
        """Numeric inverse map ``(Z, Z0) -> (p1, q1, r1, gamma1, gamma2, gamma3)``.

        The parameters and ``eps`` are put in exactly (as the binary values of the floats) before
        the series are compiled, so the compiled map is a short polynomial in ``Z, Z0``.

        Parameters
        ----------
        values : Mapping
            Parameter name (or symbol) -> value, for every parameter of the body (a specialised
            reduction checks them against the values it was derived for).
        eps : float
            The expansion parameter c/r0.

        Returns
        -------
        callable
            ``f(Z, Z0)`` with ``Z = (P, dP, G, dG)`` (scalars or arrays of one shape) and
            ``Z0 = (P0, G0, dP0, dG0)``; returns an array of shape (6, ...).
        """
        checked, eps = self._check(values, eps)
        return self._inverse_lambda(checked, eps)

    def forward_function(self, values: Mapping, eps: float) -> Callable[[np.ndarray], np.ndarray]:
        """Numeric exact forward map ``y -> (P, dP, G, dG, d2P, d2G)``.

        ``y = (p1, q1, r1, gamma1, gamma2, gamma3)`` (shape (6,) or (6, n)); the derivatives are
        those along the full flow.
        """
        checked, eps = self._check(values, eps)
        f = self._forward_lambda
        args = (*(checked[s.name] for s in self.body_parameters), eps)
        return lambda y: np.array(np.broadcast_arrays(*f(tuple(y), (), args)))

    def rhs_function(self, values: Mapping, eps: float) -> Callable[..., np.ndarray]:
        """Numeric ``(Z, Z0) -> (rhs_P, rhs_G)`` of the reduced system (all orders kept)."""
        checked, eps = self._check(values, eps)
        f = self._rhs_lambda
        args = (*(checked[s.name] for s in self.parameters), eps)
        return lambda z, z0: np.array(np.broadcast_arrays(*f(tuple(z), tuple(z0), args)))


@cache
def _inverse_map_fingerprint() -> str:
    """Hash of the source that compiles the inverse map's polynomials to numbers."""
    source = (Path(__file__).parent / "_inverse_map.py").read_bytes()
    return hashlib.sha256(source).hexdigest()[:16]


@cache
def _source_fingerprint() -> str:
    """Hash of the sources the reduction is derived by: an edit invalidates the disk cache."""
    here = Path(__file__).parent
    digest = hashlib.sha256()
    for name in ("reduction.py", "_elimination.py", "_series_ring.py", "equations.py"):
        digest.update(name.encode() + b"\0" + (here / name).read_bytes())
    return digest.hexdigest()[:16]


def _reduce(kind: str, order: int, values: tuple[tuple[sp.Symbol, sp.Rational], ...]) -> Reduction:
    light = LIGHT_SPECS[kind]
    params = light["params"]
    sr = SeriesRing(order, VARIABLES, params, (a, b), light["fraction_field"], dict(values))
    label = f"reducing the {kind} equations to order {order}"
    if sr.fraction_field:  # coefficients in QQ(a, b): computed, not kept on disk
        with stage(label):
            series = Builder(kind, sr).run()
    else:
        parts = (
            kind,
            order,
            tuple((s.name, sp.srepr(v)) for s, v in values),
            _source_fingerprint(),
        )

        def compute() -> dict:
            with stage(label):
                return {name: sr.export(poly) for name, poly in Builder(kind, sr).run().items()}

        series = {name: sr.load(data) for name, data in cached("reduction", parts, compute).items()}
    return Reduction(
        kind=kind,
        order=order,
        parameters=() if values else params,
        values=values,
        ring=sr,
        series=series,
    )


def _check_order(order: int) -> int:
    if (
        isinstance(order, bool)
        or not isinstance(order, int)
        or not 1 <= order <= MAX_REDUCTION_ORDER
    ):
        raise bad_value("order", order, f"give an integer between 1 and {MAX_REDUCTION_ORDER}")
    return order


def _exact_values(kind: str, values: Mapping) -> tuple[tuple[sp.Symbol, sp.Rational], ...]:
    """``values`` (name or symbol -> number) as exact rationals for every parameter of ``kind``."""
    by_name = {str(key): val for key, val in values.items()}
    params = LIGHT_SPECS[kind]["params"]
    missing = [s.name for s in params if s.name not in by_name]
    if missing:
        raise bad_value("values", dict(by_name), f"give values for {missing}")
    out = []
    for s in params:
        value = sp.sympify(by_name[s.name])
        if not value.is_Rational:
            raise bad_value(s.name, by_name[s.name], "give an exact rational (sympy Rational)")
        out.append((s, value))
    return tuple(out)


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
    return _reduce("disk", _check_order(order), ())


def specialised_disk_reduction(order: int, values: Mapping) -> Reduction:
    """:func:`disk_reduction` for one body: the parameters put in (exactly) before the reduction.

    Parameters
    ----------
    order : int
        Truncation order in epsilon.
    values : Mapping
        Parameter name (or symbol) -> sympy Rational, for each of ``(a, b, k, x0p, y0p, gamma3_0)``.

    Returns
    -------
    Reduction
        With no free parameters; its ``system`` equals ``disk_reduction(order).system
        .with_values(values)`` and its series are those of :func:`disk_reduction` evaluated at
        ``values`` (evaluation commutes with every step of the reduction).
    """
    return _specialised("disk", _check_order(order), _exact_values("disk", values))


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
    return _reduce("general", _check_order(order), ())


def specialised_general_body_reduction(order: int, values: Mapping) -> Reduction:
    """:func:`general_body_reduction` with the parameters put in first (see
    :func:`specialised_disk_reduction`); ``values`` covers ``(a, b, k, x0p, y0p, z0p, gamma3_0)``."""
    return _specialised("general", _check_order(order), _exact_values("general", values))


@lru_cache(maxsize=SPECIALISED_CACHE_SIZE)
def _specialised(kind: str, order: int, values: tuple) -> Reduction:
    return _reduce(kind, order, values)


def check_gamma3_0(value: float) -> float:
    """Validate an initial direction cosine gamma3_0 (|value| <= 1, not NaN)."""
    value = float(value)
    if np.isnan(value) or abs(value) > 1:
        raise InvalidParameterError(
            f"`gamma3_0` = {value!r} is invalid: a direction cosine needs |gamma3_0| <= 1"
        )
    return value
