"""The quasilinear autonomous system, the object every Poincaré construction starts from.

.. math::

    \\ddot x_i + \\omega_i^2 x_i = f_i(x, \\dot x, \\varepsilon), \\qquad f_i = \\sum_{k \\ge 1} \\varepsilon^k f_{i,k}(x, \\dot x)

In the large-parameter regime the right-hand side is written in a symbol :math:`\\mu` and expanded in
:math:`\\mu^{-1}` (:math:`\\varepsilon = 1/\\mu`).
"""

from __future__ import annotations

import enum
import hashlib
from collections.abc import Mapping, Sequence
from functools import cached_property

import attrs
import sympy as sp
from attrs import field, frozen

from perturb._checks import as_expression, as_mapping, check_count, known_keywords, real_number
from perturb._defaults import MAX_ORDER
from perturb._lambdify import numpy_lambdify
from perturb.analytic import maclaurin_coefficients, polynomial_coefficients
from perturb.errors import InvalidSystemError, bad_value
from perturb.excitation import TIME_NAMES, Excitation, time_forcing
from perturb.frame import DrivenFrame, Frame, FreeFrame

__all__ = ["QuasilinearSystem", "Regime"]

#: The canonical expansion symbol used inside the engine (the small parameter). Any symbol named
#: "epsilon" given to a system is replaced by this one.
EPS = sp.Symbol("epsilon", positive=True)


class Regime(enum.Enum):
    """Which way the system's parameter is small.

    Examples
    --------
    The same oscillator written in the large parameter μ = 1/ε:

    >>> import sympy as sp
    >>> from perturb import PoincareMethod, QuasilinearSystem, Regime
    >>> x, xdot, mu = sp.symbols("x xdot mu")
    >>> system = QuasilinearSystem([x], [xdot], [1], [(1 - x**2) * xdot / mu], parameter=mu,
    ...                            regime=Regime.LARGE)
    >>> PoincareMethod(order=2).solve(system).frequency_series()
    1 - 1/(16*mu**2)
    """

    SMALL = "small"  #: expansion in powers of the parameter itself, epsilon -> 0
    LARGE = "large"  #: expansion in powers of 1/mu, mu -> infinity (epsilon = 1/mu)


#: The memoised digest a pickled system carries with its fields (:attr:`content_digest`).
_DIGEST = "content_digest"


def _canonical(expr: sp.Expr) -> sp.Expr:
    """Replace any plain symbol named like the engine's ε by :data:`EPS` itself."""
    stray = {s: EPS for s in expr.free_symbols if s.name == EPS.name and s != EPS}
    return expr.xreplace(stray) if stray else expr


def _as_tuple_of_exprs(values, argument: str = "rhs") -> tuple[sp.Expr, ...]:
    if isinstance(values, (str, sp.Basic)) or not isinstance(values, Sequence):
        if values is None or isinstance(values, Mapping | set):
            raise bad_value(
                argument, values, "give a sequence of sympy expressions", InvalidSystemError
            )
        values = (values,)
    # frequencies: finite here, positive and real in _check_frequencies (which says so)
    check = as_expression if argument == "frequencies" else real_number
    return tuple(
        _canonical(check(f"{argument}[{i}]", v, InvalidSystemError)) for i, v in enumerate(values)
    )


def _as_symbol(argument: str, value) -> sp.Symbol:
    if isinstance(value, str):
        if not value or any(c.isspace() for c in value):
            raise bad_value(
                argument, value, "give a non-empty name without spaces", InvalidSystemError
            )
        value = sp.Symbol(value)
    if not isinstance(value, sp.Symbol):
        raise bad_value(argument, value, "give a sympy Symbol or a name", InvalidSystemError)
    return EPS if value.name == EPS.name else value


def _as_tuple_of_symbols(values, argument: str = "coordinates") -> tuple[sp.Symbol, ...]:
    if isinstance(values, (str, sp.Symbol)):
        values = (values,)
    if not isinstance(values, Sequence):
        raise bad_value(
            argument, values, "give a sequence of sympy Symbols or names", InvalidSystemError
        )
    return tuple(_as_symbol(f"{argument}[{i}]", v) for i, v in enumerate(values))


def _symbols_of(argument: str):
    return lambda values: _as_tuple_of_symbols(values, argument)


def _exprs_of(argument: str):
    return lambda values: _as_tuple_of_exprs(values, argument)


def _as_parameter(value) -> sp.Symbol:
    if isinstance(value, Sequence) and not isinstance(value, str) and len(value) == 1:
        value = value[0]
    return _as_symbol("parameter", value)


def _as_regime(value) -> Regime:
    try:
        return Regime(value)
    except ValueError:
        raise bad_value(
            "regime",
            value,
            f"use one of {[r.value for r in Regime]} (or perturb.Regime)",
            InvalidSystemError,
        ) from None


def _check_excitation(instance, attribute, value) -> None:
    if value is not None and not isinstance(value, Excitation):
        raise bad_value(
            "excitation", value, "give a perturb.Excitation or None", InvalidSystemError
        )


def _check_name(instance, attribute, value) -> None:
    if not isinstance(value, str):
        raise bad_value("name", value, "give a string label", InvalidSystemError)


@known_keywords
@frozen
class QuasilinearSystem:
    """A quasilinear autonomous system of ``n`` coupled oscillators.

    Parameters
    ----------
    coordinates : sequence of sympy.Symbol or str
        The coordinates :math:`x_i`.
    velocities : sequence of sympy.Symbol or str
        Symbols standing for :math:`\\dot x_i` in the right-hand sides, same length as ``coordinates``.
    frequencies : sequence of sympy expressions
        The generating frequencies :math:`\\omega_i` (positive; may depend on declared ``parameters``).
    rhs : sequence of sympy expressions
        The right-hand sides :math:`f_i(x, \\dot x, \\varepsilon)` of
        :math:`\\ddot x_i + \\omega_i^2 x_i = f_i`; each must vanish when the parameter does
        (lowest power of ε positive). They may start at any power (the disk starts at ε²).
    parameter : sympy.Symbol or str
        The expansion parameter as it appears in ``rhs``: ε (regime ``SMALL``) or μ (regime ``LARGE``).
    regime : Regime
        ``SMALL``: expand in powers of ``parameter``. ``LARGE``: expand in powers of ``1/parameter``.
    parameters : sequence of sympy.Symbol or str
        Symbolic constants allowed in ``rhs`` and ``frequencies`` besides the state and the parameter.
    initial_values : sequence of sympy.Symbol or str, optional
        Symbols that stand for the initial state, in the order
        ``x_1(0), ..., x_n(0), xdot_1(0), ..., xdot_n(0)``. Reduced systems obtained by eliminating
        variables through first integrals depend on the initial state this way.
    first_integrals : sequence of sympy expressions, optional
        Known first integrals (functions of the state, the parameter and the initial values).
    name : str
        A label used in reports.
    truncation : int, optional
        For right-hand sides that are themselves truncated series (reduced systems): the first power
        of ε that was neglected. The construction then refuses any order that would need it, rather
        than return coefficients computed from a missing term.
    excitation : Excitation, optional
        Makes the system driven: the right-hand sides may hold ``excitation.phase`` (standing for
        :math:`\\Omega t`) through cos/sin of its integer multiples, and the construction looks for
        the response with the forcing's period (:mod:`perturb.method.driven`). None (default): a
        free, autonomous system.

    Raises
    ------
    InvalidSystemError
        For mismatched lengths, non-positive or non-real frequencies, undeclared symbols, or a
        right-hand side that does not vanish with the parameter.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> vdp.state_names
    ('x', 'xdot')
    >>> PoincareMethod(order=1).solve(vdp).success
    True
    """

    coordinates: tuple[sp.Symbol, ...] = field(converter=_symbols_of("coordinates"))
    velocities: tuple[sp.Symbol, ...] = field(converter=_symbols_of("velocities"))
    frequencies: tuple[sp.Expr, ...] = field(converter=_exprs_of("frequencies"))
    rhs: tuple[sp.Expr, ...] = field(converter=_exprs_of("rhs"))
    parameter: sp.Symbol = field(default="epsilon", converter=_as_parameter)
    regime: Regime = field(default=Regime.SMALL, converter=_as_regime)
    parameters: tuple[sp.Symbol, ...] = field(default=(), converter=_symbols_of("parameters"))
    initial_values: tuple[sp.Symbol, ...] = field(
        default=(), converter=_symbols_of("initial_values")
    )
    first_integrals: tuple[sp.Expr, ...] = field(default=(), converter=_exprs_of("first_integrals"))
    name: str = field(default="system", validator=_check_name)
    truncation: int | None = None
    excitation: Excitation | None = field(default=None, validator=_check_excitation)

    def __attrs_post_init__(self):
        n = len(self.coordinates)
        if n < 1:
            raise InvalidSystemError("`coordinates` is empty: give at least one coordinate")
        for label, seq in (
            ("velocities", self.velocities),
            ("frequencies", self.frequencies),
            ("rhs", self.rhs),
        ):
            if len(seq) != n:
                raise InvalidSystemError(
                    f"`{label}` has {len(seq)} entries but there are {n} coordinates: give one per coordinate"
                )
        if self.initial_values and len(self.initial_values) != 2 * n:
            raise InvalidSystemError(
                f"`initial_values` has {len(self.initial_values)} symbols: give 2n = {2 * n} "
                "(x_1(0)..x_n(0), xdot_1(0)..xdot_n(0)) or none"
            )
        roles = [
            *((s.name, "coordinates") for s in self.coordinates),
            *((s.name, "velocities") for s in self.velocities),
            (self.parameter.name, "parameter"),
            *((s.name, "parameters") for s in self.parameters),
            *((s.name, "initial_values") for s in self.initial_values),
            *((s.name, role) for s, role in self.frame.extra_symbols()),
        ]
        names = [name for name, _ in roles]
        duplicates = sorted({n_ for n_ in names if names.count(n_) > 1})
        if duplicates:
            where = sorted({f"`{role}`" for name, role in roles if name in duplicates})
            raise InvalidSystemError(
                f"symbol names {duplicates} are used twice (in {', '.join(where)}): give each "
                "symbol one role"
            )
        if self.truncation is not None and (
            isinstance(self.truncation, bool)
            or not isinstance(self.truncation, int)
            or self.truncation < 2
        ):
            raise InvalidSystemError(
                f"`truncation` = {self.truncation!r} is invalid: give the first neglected power of "
                "epsilon, an integer >= 2, or None"
            )
        self._check_frequencies()
        self._check_excitation()
        self._check_symbols()
        self._check_real()
        self._check_vanishing()

    # ------------------------------------------------------------------ validation
    def _check_frequencies(self):
        allowed = set(self.parameters)
        for i, w in enumerate(self.frequencies):
            stray = w.free_symbols - allowed
            if stray:
                raise InvalidSystemError(
                    f"`frequencies[{i}]` = {w} depends on {sorted(map(str, stray))}: "
                    "declare them in `parameters` (frequencies may not depend on the state or the parameter)"
                )
            if w.is_number:
                value = complex(w.evalf())
                if abs(value.imag) > 0 or not value.real > 0:
                    raise InvalidSystemError(
                        f"`frequencies[{i}]` = {w} is not a positive real number: give omega_{i + 1} > 0"
                    )
            elif w.is_positive is False or w.is_real is False:
                raise InvalidSystemError(
                    f"`frequencies[{i}]` = {w} cannot be positive: give a positive frequency"
                )

    def _check_excitation(self):
        self.frame.check(self)

    @cached_property
    def frame(self) -> Frame:
        """:class:`~perturb.frame.FreeFrame`, or :class:`~perturb.frame.DrivenFrame` with an
        excitation: what free vs driven decides (the one place that tests ``excitation``)."""
        return FreeFrame() if self.excitation is None else DrivenFrame(self.excitation)

    @cached_property
    def content_digest(self) -> str:
        """SHA-256 (hex) of the ``srepr`` of the system's symbols and expressions (coordinates,
        velocities, frequencies, right-hand sides, parameter, parameters, initial values, first
        integrals): what a cache keys a result of these equations on.

        Computed once and kept when the system is pickled, so a system read back from the disk
        cache (:mod:`perturb.cache`, whose entries are signed) is not printed again to key what is
        derived from it.
        """
        parts = (
            self.coordinates,
            self.velocities,
            self.frequencies,
            self.rhs,
            self.parameter,
            self.parameters,
            self.initial_values,
            self.first_integrals,
        )
        text = repr(tuple(sp.srepr(part) for part in parts))
        return hashlib.sha256(text.encode()).hexdigest()

    def __getstate__(self) -> dict:
        """The fields and the :attr:`content_digest` (computed now if it was not)."""
        state = {a.name: getattr(self, a.name) for a in attrs.fields(type(self))}
        state[_DIGEST] = self.content_digest
        return state

    def __setstate__(self, state: dict) -> None:
        for name in (*(a.name for a in attrs.fields(type(self))), _DIGEST):
            if name in state:
                object.__setattr__(self, name, state[name])

    @property
    def reference_index(self) -> int:
        """The coordinate whose frequency the excitation's ratio refers to (driven systems)."""
        return self.frame.reference_index(self)

    def _check_real(self):
        """A right-hand side holding the imaginary unit must still be real for real arguments."""
        real = {s: sp.Dummy(s.name, real=True) for s in self._all_symbols()}
        for i, f in enumerate(self.rhs):
            if f.has(sp.I) and sp.simplify(sp.im(f.xreplace(real))) != 0:
                raise bad_value(
                    f"rhs[{i}]",
                    f,
                    "give a real right-hand side (it holds the imaginary unit)",
                    InvalidSystemError,
                )

    def _all_symbols(self) -> set:
        return {*self.state_symbols, *self.parameters, *self.initial_values, self.parameter}

    def _check_symbols(self):
        allowed = set(self.state_symbols) | set(self.parameters) | set(self.initial_values)
        allowed.add(self.parameter)
        allowed.update(s for s, _ in self.frame.extra_symbols())
        timed = {s for s in self.parameters if s.name in TIME_NAMES}
        for i, f in enumerate(self.rhs):
            stray = f.free_symbols - allowed
            advice = time_forcing(f, stray | timed, declared=timed) if (stray or timed) else ""
            if advice:  # F*cos(Omega*t): the time, which a driven system's phase stands for
                raise InvalidSystemError(f"`rhs[{i}]`: {advice}")
            if stray:
                raise InvalidSystemError(
                    f"`rhs[{i}]` depends on undeclared symbols {sorted(map(str, stray))}: "
                    "declare them in `parameters` (or `initial_values`)"
                )

    def _check_vanishing(self):
        for i in range(self.n):
            if i in self._analytic_rhs:  # not polynomial in ε: its Maclaurin series (or a refusal)
                lowest = self._analytic_leading_order(i)
                at_zero = sp.simplify(self._maclaurin(i, 0)[0]) if lowest == 0 else sp.S.Zero
            else:
                at_zero = sp.simplify(self._polynomial_rhs[i][0])
            if at_zero != 0:
                raise InvalidSystemError(
                    f"`rhs[{i}]` does not vanish as the expansion parameter tends to its limit "
                    f"(leftover {at_zero}): the lowest power of epsilon must be positive; move the "
                    "O(1) part into the frequency or the generating system"
                )

    # ------------------------------------------------------------------ derived data
    @property
    def n(self) -> int:
        """Number of degrees of freedom."""
        return len(self.coordinates)

    @property
    def state_symbols(self) -> tuple[sp.Symbol, ...]:
        """``(x_1, ..., x_n, xdot_1, ..., xdot_n)``."""
        return self.coordinates + self.velocities

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.state_symbols)

    @cached_property
    def rhs_in_epsilon(self) -> tuple[sp.Expr, ...]:
        """The right-hand sides written in the engine's small parameter ε (ε = 1/μ when LARGE);
        a driven system's excitation as a polynomial in cos θ and sin θ
        (:meth:`Excitation.polynomial_form`)."""
        rhs = tuple(self.frame.polynomial_rhs(f) for f in self.rhs)
        if self.regime is Regime.LARGE:
            return tuple(sp.expand(f.subs(self.parameter, 1 / EPS)) for f in rhs)
        return tuple(f.subs(self.parameter, EPS) for f in rhs)

    def expansion(self, order: int) -> tuple[tuple[sp.Expr, ...], ...]:
        """Coefficients :math:`f_{i,k}` for ``k = 0..order``: ``result[i][k]``.

        Right-hand sides polynomial in ε have their coefficients read off; any other dependence
        analytic at ε = 0 (rational, elementary functions, removable singularities; in the
        large-parameter regime the same in 1/μ) is expanded by ``sympy.series`` to ``order``, once per
        expression and order (:mod:`perturb.analytic`).

        Raises
        ------
        InvalidSystemError
            When a right-hand side has no Maclaurin series in ε (a pole at ε = 0, a branch point).
        """
        check_count("order", order, 0, InvalidSystemError)
        out = []
        for i in range(self.n):
            if i in self._analytic_rhs:
                out.append(self._maclaurin(i, order))
                continue
            coefficients = self._polynomial_rhs[i]
            out.append(
                tuple(
                    coefficients[k] if k < len(coefficients) else sp.S.Zero
                    for k in range(order + 1)
                )
            )
        return tuple(out)

    @cached_property
    def _analytic_rhs(self) -> dict[int, sp.Expr]:
        """The right-hand sides not polynomial in ε, by index, in the form handed to ``series``.

        Polynomial ones keep the fast path (coefficients read off a ``Poly``); these are expanded
        by :func:`perturb.analytic.maclaurin_coefficients` (memoised per expression and order).
        """
        return {
            i: sp.together(f) if self.regime is Regime.LARGE else f
            for i, f in enumerate(self.rhs_in_epsilon)
            if i not in self._polynomial_rhs
        }

    @cached_property
    def _polynomial_rhs(self) -> dict[int, tuple[sp.Expr, ...]]:
        """The right-hand sides polynomial in ε, by index: their coefficients (expanded) to the degree."""
        out = {}
        for i, f in enumerate(self.rhs_in_epsilon):
            coefficients = polynomial_coefficients(f, EPS)
            if coefficients is not None:
                out[i] = coefficients
        return out

    def _maclaurin(self, i: int, order: int) -> tuple[sp.Expr, ...]:
        label = (
            f"rhs[{i}]"
            if self.regime is Regime.SMALL
            else f"rhs[{i}] (in epsilon = 1/{self.parameter})"
        )
        return maclaurin_coefficients(self._analytic_rhs[i], EPS, order, label)

    @property
    def leading_order(self) -> int:
        """The lowest power of ε present in any right-hand side (the first non-zero forcing)."""
        best = None
        for i in range(self.n):
            if i in self._analytic_rhs:
                k = self._analytic_leading_order(i)
                if k is None:
                    continue
            else:
                nonzero = [k for k, c in enumerate(self._polynomial_rhs[i]) if c != 0]
                if not nonzero:
                    continue
                k = nonzero[0]
            best = k if best is None else min(best, k)
        return best if best is not None else 0

    def _analytic_leading_order(self, i: int) -> int | None:
        """Lowest power of ε in the Maclaurin series of a non-polynomial right-hand side.

        Searched through ``MAX_ORDER`` (no construction can use a higher one); a non-zero
        expression whose series vanishes that far is flat at ε = 0 (``exp(-1/eps)``), not analytic.
        """
        for order in sorted({min(2**j, MAX_ORDER) for j in range(1, MAX_ORDER.bit_length() + 1)}):
            coefficients = self._maclaurin(i, order)  # short series first: they are the common case
            for k, c in enumerate(coefficients):
                if c != 0:
                    return k
        if sp.simplify(self._analytic_rhs[i]) == 0:
            return None
        raise InvalidSystemError(
            f"`rhs[{i}]` = {self.rhs[i]} is invalid: its Maclaurin series in epsilon vanishes through "
            f"epsilon**{MAX_ORDER} although it is not zero (an essential singularity at epsilon = 0, "
            "e.g. exp(-1/epsilon)); the right-hand side must be analytic in the expansion parameter"
        )

    def with_values(self, values: Mapping) -> QuasilinearSystem:
        """A copy with some declared parameters replaced by numbers (or expressions)."""
        values = as_mapping("values", values, InvalidSystemError)
        subs = {
            self._symbol(k): real_number(f"values[{k!r}]", v, InvalidSystemError)
            for k, v in values.items()
        }
        return attrs.evolve(
            self,
            frequencies=tuple(w.subs(subs) for w in self.frequencies),
            rhs=tuple(f.subs(subs) for f in self.rhs),
            parameters=tuple(p for p in self.parameters if p not in subs),
            first_integrals=tuple(h.subs(subs) for h in self.first_integrals),
            excitation=self.frame.excitation_with(subs),
        )

    def _symbol(self, key) -> sp.Symbol:
        for p in self.parameters:
            if p == key or p.name == key:
                return p
        raise InvalidSystemError(
            f"`values` names {key!r}, which is not a declared parameter: choose from "
            f"{[p.name for p in self.parameters]}"
        )

    def as_large_parameter(self, mu: str | sp.Symbol = "mu") -> QuasilinearSystem:
        """The same system written in the large parameter μ = 1/ε (regime ``LARGE``)."""
        mu = _as_symbol("mu", mu)
        taken = {s.name for s in self._all_symbols() - {self.parameter}}
        if mu.name in taken:
            raise bad_value(
                "mu",
                mu,
                f"it already names a symbol of the system; avoid {sorted(taken)}",
                InvalidSystemError,
            )
        return attrs.evolve(
            self,
            rhs=tuple(sp.expand(f.subs(EPS, 1 / mu)) for f in self.rhs_in_epsilon),
            parameter=mu,
            regime=Regime.LARGE,
            first_integrals=tuple(h.subs(self.parameter, 1 / mu) for h in self.first_integrals)
            if self.regime is Regime.SMALL
            else self.first_integrals,
        )

    def vector_field(
        self, parameter_value: float, values: Mapping | None = None, initial_state=None
    ):
        """Numeric first-order form ``y' = F(t, y)`` of the system, ``y = (x, xdot)``.

        Parameters
        ----------
        parameter_value : float
            ε (or μ in the large-parameter regime).
        values : mapping, optional
            Values of the declared parameters.
        initial_state : array_like, optional
            Needed when the right-hand sides depend on ``initial_values``.

        Returns
        -------
        callable
            ``F(t, y)`` returning a numpy array, compiled once with common subexpressions.
        """
        import numpy as np

        from perturb._checks import as_real_array

        values = as_mapping("values", values, InvalidSystemError)
        parameter_value = float(as_real_array(self.parameter.name, parameter_value))
        for key, value in values.items():
            self._symbol(key)
            values[key] = float(as_real_array(f"values[{key!r}]", value))
        values = {getattr(k, "name", k): v for k, v in values.items()}
        subs = {p: values[p.name] for p in self.parameters if p.name in values}
        missing = [p.name for p in self.parameters if p.name not in values]
        if missing:
            raise InvalidSystemError(
                f"`values` lacks {missing}: give every declared parameter a value"
            )
        if self.initial_values:
            if initial_state is None:
                raise InvalidSystemError(
                    "`initial_state` is None but the right-hand sides depend on the initial values: pass it"
                )
            subs.update(zip(self.initial_values, map(float, initial_state), strict=True))
        subs[self.parameter] = parameter_value
        w2 = [float((w**2).subs(subs)) for w in self.frequencies]
        exprs = [f.subs(subs) for f in self.rhs]
        fn = numpy_lambdify([self.state_symbols], exprs, cse=True)
        n = self.n

        def rhs(t, y):
            f = fn(y)
            out = np.empty(2 * n)
            out[:n] = y[n:]
            for i in range(n):
                out[n + i] = f[i] - w2[i] * y[i]
            return out

        return rhs
