"""The map from a user's parameters to a system's symbols and its expansion parameter ε.

A problem is written in the parameters its user measures (Ω, a forcing level, a damping ratio, a
body's moments of inertia); its :class:`~perturb.QuasilinearSystem` is written in scaled symbols
(the detuning σ, the scaled damping ζ) and the small parameter ε. :class:`ParameterMap` declares
the bridge once, as sympy expressions — ``sigma = (Omega - 1)/eps``, the disk's
``epsilon = sqrt(M g l / C)/r0`` — so that every client (the response, a sweep, the order scan)
reads it instead of rediscovering it from samples:

* :meth:`ParameterMap.evaluate` — one point's symbol values and ε;
* :meth:`ParameterMap.columns` — many points at once, as numpy columns;
* :meth:`ParameterMap.solve_user` — a user parameter from a system value (a fold's σ back to Ω);
* :meth:`ParameterMap.with_epsilon` — the user values at another ε with every symbol kept;
* :meth:`ParameterMap.rate`, :meth:`ParameterMap.is_affine_in` — how a swept parameter moves them.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import EVAL_DIGITS, REAL_ROOT_TOL
from perturb.cache import cached
from perturb.errors import InvalidSystemError

__all__ = ["EPSILON_KEY", "ParameterMap"]

#: The key of ε in a declared map (``{"epsilon": "sqrt(M*g*l/C)/r0"}``); by default ε is the user
#: parameter ``eps`` when there is one.
EPSILON_KEY = "epsilon"
#: The user parameter that is ε itself when a map does not say otherwise.
DEFAULT_EPSILON_PARAMETER = "eps"


def _last_line(exc: BaseException) -> str:
    """The cause's last non-empty line (sympy's parse errors span several)."""
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return lines[-1] if lines else type(exc).__name__


def _declared_text(value) -> tuple[str, str]:
    """A declared right-hand side as text for a cache key: a string as written, anything else
    as the ``srepr`` of what sympy makes of it (its symbols' assumptions included)."""
    if value is None or isinstance(value, str):
        return type(value).__name__, str(value)
    try:
        return "sympy", sp.srepr(sp.sympify(value))
    except (sp.SympifyError, TypeError, ValueError):
        return type(value).__name__, repr(value)


def _as_expression(value, user: Mapping[str, sp.Symbol], where: str) -> sp.Expr:
    """A declared right-hand side (a sympy expression, a number or a string) in the user symbols."""
    if isinstance(value, str):
        try:
            expr = sp.sympify(value, locals=dict(user))
        except (sp.SympifyError, SyntaxError, TypeError) as exc:
            raise InvalidSystemError(
                f"`parameter_map[{where!r}]` = {value!r} is not an expression: write it in the "
                f"user parameters {sorted(user)} ({_last_line(exc)})"
            ) from None
    else:
        expr = sp.sympify(value)
    # a symbol named as a user parameter is that parameter, whatever assumptions it was made with
    by_name = {s: user[s.name] for s in expr.free_symbols if s.name in user}
    return expr.xreplace(by_name)


@frozen
class ParameterMap:
    """User parameters → a system's symbols and ε, as sympy expressions (checked once).

    Parameters
    ----------
    user : tuple of str
        The user parameters' names, in their order.
    symbols : tuple of (str, sympy.Expr)
        Each system symbol's name and its expression in the user parameters.
    epsilon : sympy.Expr or None
        ε in the user parameters (None: the system has no ε to set, e.g. a problem that gives its
        own).

    Examples
    --------
    A forced oscillator swept in Ω while its system is written in the detuning σ:

    >>> import sympy as sp
    >>> from perturb.case import ParameterMap
    >>> sigma, zeta = sp.symbols("sigma zeta")
    >>> mapping = ParameterMap.declare(
    ...     [sigma, zeta], ["eps", "zeta", "Omega"], {"sigma": "(Omega - 1)/eps"}
    ... )
    >>> mapping.evaluate({"eps": 0.05, "zeta": 0.1, "Omega": 1.1})
    ({'sigma': 2.0000000000000018, 'zeta': 0.1}, 0.05)
    >>> mapping.solve_user("Omega", "sigma", 3.0, {"eps": 0.05, "zeta": 0.1, "Omega": 1.1})
    1.15
    >>> mapping.with_epsilon({"eps": 0.05, "zeta": 0.1, "Omega": 1.1}, 0.025)
    {'eps': 0.025, 'zeta': 0.1, 'Omega': 1.05}
    """

    user: tuple = field(converter=tuple)
    symbols: tuple = field(converter=tuple)
    epsilon: sp.Expr | None = None
    _compiled: dict = field(factory=dict, init=False, eq=False, repr=False)

    def __getstate__(self) -> dict:
        """The map without its compiled functions: they are rebuilt where it is unpickled (a
        function lambdified for mpmath carries mpmath's whole namespace, whose objects a worker
        with another mpmath cannot read back)."""
        return {"user": self.user, "symbols": self.symbols, "epsilon": self.epsilon}

    def __setstate__(self, state: dict) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "_compiled", {})

    # ------------------------------------------------------------------ building and checking
    @classmethod
    def declare(
        cls, parameters, user, declared: Mapping | None = None, epsilon=None
    ) -> ParameterMap:
        """The map of a system's ``parameters`` from the ``user`` names.

        Parameters
        ----------
        parameters : sequence of sympy.Symbol
            The system's free symbols (its ``parameters``).
        user : sequence of str
            The user parameters.
        declared : mapping, optional
            ``{system symbol name: expression}`` and, under :data:`EPSILON_KEY`, ε's expression;
            a system symbol not declared is the user parameter of the same name.
        epsilon : optional
            ε's expression, if not under :data:`EPSILON_KEY` in ``declared``; default: the user
            parameter ``eps`` if there is one, else None.

        Raises
        ------
        perturb.errors.InvalidSystemError
            A system symbol that no declaration and no user parameter covers, a declaration for a
            symbol the system does not have, or an expression in names that are not user
            parameters — one line naming it and the fix.
        """
        names = tuple(str(u) for u in user)
        own = tuple(p.name for p in parameters)
        declared = dict(declared or {})
        # read back from the disk cache (kind ``parameter-map``) where this declaration was read
        # before: parsing its strings is most of a warm run's time in sympy's parser
        return cached(
            "parameter-map",
            lambda: (
                f"{cls.__module__}.{cls.__qualname__}",
                names,
                own,
                tuple((key, _declared_text(value)) for key, value in declared.items()),
                _declared_text(epsilon),
            ),
            lambda: cls._declare(own, names, dict(declared), epsilon),
        )

    @classmethod
    def _declare(cls, own: tuple, names: tuple, declared: dict, epsilon) -> ParameterMap:
        """:meth:`declare` of the system symbols named ``own`` (not cached)."""
        symbols = {n: sp.Symbol(n, real=True) for n in names}
        if EPSILON_KEY in declared:
            epsilon = declared.pop(EPSILON_KEY)
        unknown = sorted(set(declared) - set(own))
        if unknown:
            raise InvalidSystemError(
                f"`parameter_map` declares {unknown[0]!r}, which is not a symbol of the system: "
                f"declare its symbols {list(own)} (and {EPSILON_KEY!r} for ε)"
            )
        rows = []
        for name in own:
            if name in declared:
                rows.append((name, _as_expression(declared[name], symbols, name)))
            elif name in symbols:
                rows.append((name, symbols[name]))
            else:
                raise InvalidSystemError(
                    f"`parameter_map` does not cover the system symbol {name!r}: declare it in "
                    f"the user parameters {list(names)}, e.g. {{{name!r}: '...'}}, or add a "
                    f"parameter named {name!r}"
                )
        if epsilon is None and DEFAULT_EPSILON_PARAMETER in symbols:
            epsilon = symbols[DEFAULT_EPSILON_PARAMETER]
        eps = None if epsilon is None else _as_expression(epsilon, symbols, EPSILON_KEY)
        mapping = cls(names, tuple(rows), eps)
        mapping.check()
        return mapping

    def check(self) -> None:
        """Every expression is in the user parameters alone (raises InvalidSystemError)."""
        allowed = set(self.user)
        for name, expr in (*self.symbols, (EPSILON_KEY, self.epsilon)):
            if expr is None:
                continue
            stray = sorted(s.name for s in expr.free_symbols if s.name not in allowed)
            if stray:
                raise InvalidSystemError(
                    f"`parameter_map[{name!r}]` = {expr} uses {stray}, which are not user "
                    f"parameters: write it in {list(self.user)}"
                )

    # ------------------------------------------------------------------ reading
    @property
    def user_symbols(self) -> dict[str, sp.Symbol]:
        return {n: sp.Symbol(n, real=True) for n in self.user}

    def expression(self, name: str) -> sp.Expr:
        """The expression of the system symbol ``name`` (or of ε under :data:`EPSILON_KEY`)."""
        if name == EPSILON_KEY:
            return self.epsilon
        return dict(self.symbols)[name]

    def moved_by(self, user_name: str) -> tuple[str, ...]:
        """The system symbols (and :data:`EPSILON_KEY`) whose values change with ``user_name``."""
        symbol = self.user_symbols[user_name]
        rows = [*self.symbols, (EPSILON_KEY, self.epsilon)]
        return tuple(n for n, e in rows if e is not None and symbol in e.free_symbols)

    def set_by(self, name: str, verb: str = "set") -> str:
        """Advice for a user who names the system symbol ``name`` where a user parameter is due
        (``--sweep sigma=...`` where the map sets σ from Ω): which parameter sets it, through which
        expression, and what to ``verb`` instead; "" when ``name`` is not a mapped symbol.

        Examples
        --------
        >>> import sympy as sp
        >>> sigma, zeta = sp.symbols("sigma zeta")
        >>> mapping = ParameterMap.declare(
        ...     [sigma, zeta], ["eps", "zeta", "Omega"], {"sigma": "(Omega - 1)/eps"}
        ... )
        >>> mapping.set_by("sigma", "sweep")
        'sigma is set by Omega through the map sigma = (Omega - 1)/eps; sweep Omega'
        >>> mapping.set_by("zeta")
        ''
        """
        expression = dict(self.symbols).get(name)
        if expression is None or name in self.user or self.is_identity(name):
            return ""
        scale = set() if self.epsilon is None else {s.name for s in self.epsilon.free_symbols}
        names = [n for n in self.user if self.user_symbols[n] in expression.free_symbols]
        knobs = [n for n in names if n not in scale] or names
        if not knobs:
            return f"{name} is fixed by the map {name} = {expression}; it cannot be {verb}"
        which = " and ".join(knobs)
        return (
            f"{name} is set by {which} through the map {name} = {_plain(expression)}; "
            f"{verb} {which}"
        )

    def is_identity(self, name: str) -> bool:
        """Whether the system symbol ``name`` is the user parameter of the same name."""
        return dict(self.symbols).get(name) == self.user_symbols.get(name)

    def _function(self, key: str):
        if key not in self._compiled:
            from perturb._lambdify import numpy_lambdify

            exprs = [e for _, e in self.symbols]
            if self.epsilon is not None:
                exprs.append(self.epsilon)
            args = list(self.user_symbols.values())
            self._compiled[key] = numpy_lambdify(args, exprs)
        return self._compiled[key]

    def _precise(self):
        if "precise" not in self._compiled:
            exprs = [e for _, e in self.symbols]
            if self.epsilon is not None:
                exprs.append(self.epsilon)
            args = list(self.user_symbols.values())
            from perturb._lambdify import mpmath_lambdify

            self._compiled["precise"] = mpmath_lambdify(args, exprs)
        return self._compiled["precise"]

    def evaluate(self, values: Mapping[str, float]) -> tuple[dict[str, float], float | None]:
        """``(symbol values by name, ε)`` at one point of user ``values`` (ε None if unmapped).

        Each value is the double nearest the expression evaluated at the given doubles with
        :data:`EVAL_DIGITS` digits: the same bits on every machine, whatever the expression."""
        import mpmath

        with mpmath.workdps(EVAL_DIGITS):
            try:
                out = self._precise()(*(mpmath.mpf(float(values[n])) for n in self.user))
            except NameError as exc:  # a function with no numerical meaning in the map
                name = getattr(exc, "name", None) or str(exc)
                raise InvalidSystemError(
                    f"the parameter map uses {name}, which has no numerical value: write the "
                    "map with functions numpy and mpmath know (sqrt, exp, Heaviside, ...)"
                ) from None
            numbers = [_to_float(v) for v in out]
        symbols = {name: numbers[i] for i, (name, _) in enumerate(self.symbols)}
        return symbols, (numbers[-1] if self.epsilon is not None else None)

    def columns(
        self, values: Mapping[str, np.ndarray | float]
    ) -> tuple[dict[str, np.ndarray], np.ndarray | None]:
        """:meth:`evaluate` on columns: each user value a number or an array of one length."""
        arrays = [np.asarray(values[n], dtype=float) for n in self.user]
        shape = np.broadcast_shapes(*(a.shape for a in arrays)) if arrays else ()
        with np.errstate(all="ignore"):
            out = self._function("all")(*arrays)
        numbers = [np.broadcast_to(np.asarray(v, dtype=float), shape) for v in out]
        symbols = {name: numbers[i] for i, (name, _) in enumerate(self.symbols)}
        return symbols, (numbers[-1] if self.epsilon is not None else None)

    def is_affine_in(self, user_name: str) -> bool:
        """Whether every symbol and ε is affine in the user parameter ``user_name`` (the other
        parameters fixed): σ = (Ω − 1)/ε is affine in Ω, not in ε."""
        u = self.user_symbols[user_name]
        rows = [e for _, e in self.symbols] + ([self.epsilon] if self.epsilon is not None else [])
        return all(sp.simplify(sp.diff(e, u, 2)) == 0 for e in rows)

    def rate(self, user_name: str, values: Mapping[str, float]) -> tuple[dict, float | None]:
        """``(d symbol / d user_name by name, d ε / d user_name)`` at ``values``, exactly
        differentiated and evaluated as :meth:`evaluate` evaluates."""
        key = f"rate:{user_name}"
        if key not in self._compiled:
            u = self.user_symbols[user_name]
            symbols = tuple((n, _derivative(e, u)) for n, e in self.symbols)
            eps = None if self.epsilon is None else _derivative(self.epsilon, u)
            self._compiled[key] = ParameterMap(self.user, symbols, eps)
        return self._compiled[key].evaluate(values)

    # ------------------------------------------------------------------ inverting
    def solve_user(
        self, user_name: str, name: str, target: float, values: Mapping[str, float]
    ) -> float:
        """The value of the user parameter ``user_name`` at which the system symbol ``name`` (or
        ε) takes ``target``, the other user parameters at ``values``: the real root nearest to
        ``values[user_name]`` (NaN if there is none).

        Exact where it can be: the expression is solved once symbolically and the root evaluated,
        so a fold found in σ maps back to Ω without sampling.
        """
        found = self.user_roots(user_name, name, target, values)
        here = float(values[user_name])
        return min(found, key=lambda v: abs(v - here)) if found else math.nan

    def user_roots(
        self, user_name: str, name: str, target: float, values: Mapping[str, float]
    ) -> tuple[float, ...]:
        """Every real value of the user parameter ``user_name`` at which the system symbol
        ``name`` (or ε) takes ``target``, the others at ``values``, in increasing order (σ =
        (Ω² − 1)/(2ε) has two: ±Ω)."""
        return _real_roots(self.expression(name), self.user_symbols[user_name], target, values)

    def span(
        self, user_name: str, name: str, low: float, high: float, values: Mapping[str, float]
    ) -> tuple[float, float]:
        """``(min, max)`` of the system symbol ``name`` while the user parameter ``user_name``
        runs over [``low``, ``high``], the others at ``values``: its values at both ends and at
        every stationary point between (exact: the derivative's real roots)."""
        u = self.user_symbols[user_name]
        expr = self.expression(name)
        inside = [v for v in _real_roots(_derivative(expr, u), u, 0.0, values) if low < v < high]
        found = [self.evaluate({**values, user_name: v})[0][name] for v in (low, *inside, high)]
        return min(found), max(found)

    def with_epsilon(self, values: Mapping[str, float], eps: float) -> dict[str, float] | None:
        """The user values at which ε = ``eps`` and every system symbol keeps its value at
        ``values`` (None if the map has no such move).

        The user parameters moved are the fewest that do it: those ε depends on, plus, for each
        symbol they also move, one more parameter to restore it (Ω for σ = (Ω − 1)/ε). Where the
        move has several real solutions (ε = a² gives a = ±√ε) the one nearest ``values`` is
        taken: the point the move continues from.
        """
        if self.epsilon is None:
            return None
        symbols, _ = self.evaluate(values)
        known = {s: _exact(values[s.name]) for s in self.user_symbols.values()}
        known.update({_target_of(n): _exact(symbols[n]) for n, _ in self.symbols})
        known[_target_of(EPSILON_KEY)] = _exact(eps)
        for moving in self._moves():
            found = [
                moved
                for solved in _solve_move(self, moving)
                if (moved := _evaluated(solved, known)) is not None
            ]
            if found:
                nearest = min(found, key=lambda m: _distance(m, values))
                return {**values, **nearest}
        return None

    def _knob_rank(self, name: str) -> float:
        """How plainly ε follows the user parameter ``name``: 0 for ε ∝ name or 1/name, the
        distance of the power-law exponent from ±1 otherwise (the disk's r0 before its g)."""
        u = self.user_symbols[name]
        # cancel (a rational function's normal form) settles a power law, and a rational
        # function it leaves is no number; simplify, which loads sympy.physics.units on its
        # first call (0.3 s of a warm `perturb validate disk`), only for functions (exp, log...)
        exponent = sp.cancel(u * sp.diff(self.epsilon, u) / self.epsilon)
        if not exponent.is_number and exponent.atoms(sp.Function):
            exponent = sp.simplify(exponent)
        return abs(abs(float(exponent)) - 1) if exponent.is_number else math.inf

    def _moves(self) -> list[tuple[str, ...]]:
        """Candidate sets of user parameters to move for :meth:`with_epsilon`, fewest first.

        Found once per map (the order check moves ε several times) and kept on disk (kind
        ``parameter-moves``, keyed on the map's expressions): finding them differentiates ε
        by each parameter it depends on.
        """
        if "moves" not in self._compiled:
            self._compiled["moves"] = cached(
                "parameter-moves",
                lambda: (self.user, sp.srepr(self.symbols), sp.srepr(self.epsilon)),
                self._find_moves,
            )
        return list(self._compiled["moves"])

    def _find_moves(self) -> list[tuple[str, ...]]:
        eps_free = self.epsilon.free_symbols
        movers = [n for n in self.user if self.user_symbols[n] in eps_free]
        out = []
        for first in sorted(movers, key=self._knob_rank):
            moved = {k for k in self.moved_by(first) if k != EPSILON_KEY}
            if not moved:
                out.append((first,))
                continue
            # restore each symbol it moves with one other parameter of that symbol's expression
            others = []
            for name in sorted(moved):
                candidates = [
                    s.name
                    for s in self.expression(name).free_symbols
                    if s.name != first and s.name not in others
                ]
                if not candidates:
                    break
                others.append(sorted(candidates)[0])
            else:
                out.append((first, *others))
        return out


_TARGET = sp.Symbol("target_value_", real=True)


def _plain(expression: sp.Expr) -> str:
    """``(Omega - 1)/eps`` as a user writes it (sympy prints ``(Omega - 1)/eps`` too, but orders
    a sum by its own rules: kept when it reads as written)."""
    return str(sp.together(expression))


def _to_float(value) -> float:
    """An mpmath (or plain) number as a double; complex values (a square root of a negative
    number) and infinities become NaN, which the caller's checks report."""
    try:
        number = float(value)
    except TypeError:
        return math.nan
    return number if math.isfinite(number) else math.nan


def _exact(value: float) -> sp.Rational:
    """A double as the exact rational it is (the inverse is then evaluated without rounding)."""
    return sp.Rational(float(value))


def _target_of(name: str) -> sp.Symbol:
    return sp.Symbol(f"target_{name}_", real=True)


def _real_roots(
    expr: sp.Expr, unknown: sp.Symbol, target: float, values: Mapping[str, float]
) -> tuple[float, ...]:
    """The real solutions of ``expr = target`` for ``unknown``, the other symbols at ``values``
    (by name), evaluated with :data:`EVAL_DIGITS` digits from the exact inverse, increasing."""
    subs = (
        {s: _exact(values[s.name]) for s in expr.free_symbols if s != unknown}
        if expr is not None
        else {}
    )
    found = set()
    for root in _inverse(expr, unknown):
        try:
            number = complex(sp.N(root.xreplace({**subs, _TARGET: _exact(target)}), EVAL_DIGITS))
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if math.isfinite(number.real) and abs(number.imag) <= REAL_ROOT_TOL * max(1, abs(number)):
            found.add(number.real)
    return tuple(sorted(found))


@functools.lru_cache(maxsize=256)
def _inverse(expr: sp.Expr, unknown: sp.Symbol) -> tuple[sp.Expr, ...]:
    """The solutions of ``expr = target`` for ``unknown`` (cached per expression)."""
    if expr is None or unknown not in expr.free_symbols:
        return ()
    try:
        return tuple(sp.solve(sp.Eq(expr, _TARGET), unknown, dict=False))
    except (NotImplementedError, TypeError):
        return ()


@functools.lru_cache(maxsize=256)
def _solve_move_cached(mapping_key, moving) -> tuple:
    """The solutions of a move, kept in memory and on disk (kind ``parameter-move``, keyed on
    the map's expressions and the moved names): solving costs sympy arithmetic every run."""
    rows, eps, user = mapping_key
    return cached(
        "parameter-move",
        lambda: (user, sp.srepr(rows), sp.srepr(eps), moving),
        lambda: _solve_move_exact(mapping_key, moving),
    )


def _solve_move_exact(mapping_key, moving) -> tuple:
    rows, eps, user = mapping_key
    symbols = {n: sp.Symbol(n, real=True) for n in user}
    unknowns = [symbols[n] for n in moving]
    equations = [sp.Eq(eps, _target_of(EPSILON_KEY))]
    for name, expr in rows:
        if any(u in expr.free_symbols for u in unknowns):
            equations.append(sp.Eq(expr, _target_of(name)))
    if len(equations) != len(unknowns):
        return ()
    if len(unknowns) == 1 and len(equations) == 1:
        power = _power_law(eps, unknowns[0])
        if power is not None:  # eps = rest * u**a: u = (target / rest)**(1/a), no sympy solve
            rest, exponent = power
            root = (_target_of(EPSILON_KEY) / rest) ** (1 / exponent)
            name = unknowns[0].name
            # an even power (u**2, u**(2/3)) has the two real roots ±root: the nearest is taken
            even = sp.Rational(exponent).p % 2 == 0 if exponent.is_rational else False
            return (((name, root),), ((name, -root),)) if even else (((name, root),),)
    try:
        found = sp.solve(equations, unknowns, dict=True)
    except (NotImplementedError, TypeError):
        return ()
    return tuple(tuple((u.name, f[u]) for u in unknowns if u in f) for f in found)


def _power_law(expr: sp.Expr, unknown: sp.Symbol) -> tuple[sp.Expr, sp.Expr] | None:
    """``(rest, a)`` when ``expr`` is ``rest * unknown**a`` (a a non-zero number, ``rest`` free
    of ``unknown``), else None: the inverse is then written down, where sympy's ``solve`` costs
    0.3 s the first time (it loads sympy.physics.units) — the disk's ε = c/r0."""
    exponent = sp.cancel(unknown * sp.diff(expr, unknown) / expr)
    if not exponent.is_number or exponent == 0:
        return None
    rest = sp.powsimp(expr * unknown ** (-exponent))
    if unknown in rest.free_symbols:
        return None
    return rest, exponent


def _solve_move(mapping: ParameterMap, moving: tuple[str, ...]) -> list[dict[str, sp.Expr]]:
    """Every symbolic solution of the move of the user parameters ``moving`` (may be none)."""
    solved = _solve_move_cached((mapping.symbols, mapping.epsilon, mapping.user), moving)
    return [dict(s) for s in solved if len(s) == len(moving)]


def _evaluated(solved: dict[str, sp.Expr], known: dict) -> dict[str, float] | None:
    """One solution of a move at the ``known`` values, or None where it is not real and finite."""
    out = {}
    for name, expr in solved.items():
        try:
            number = complex(sp.N(expr.xreplace(known), EVAL_DIGITS))
        except (TypeError, ValueError, ZeroDivisionError):
            return None
        if not math.isfinite(number.real) or abs(number.imag) > REAL_ROOT_TOL * max(1, abs(number)):
            return None
        out[name] = number.real
    return out


def _distance(moved: dict[str, float], values: Mapping[str, float]) -> float:
    """How far a move takes the user values (the largest relative change)."""
    return max(abs(v - values[n]) / max(abs(values[n]), 1.0) for n, v in moved.items())


def _derivative(expr: sp.Expr, symbol: sp.Symbol) -> sp.Expr:
    """``d expr / d symbol`` almost everywhere: the DiracDelta a Heaviside step (or a sign, an
    absolute value) differentiates to is 0 off its jump, where the rate of a map is read (at the
    jump itself the map has no rate; numerically a point falls on it with probability 0)."""
    rate = sp.diff(expr, symbol)
    if rate.has(sp.DiracDelta):
        rate = rate.replace(sp.DiracDelta, lambda *args: sp.S.Zero)
    return rate
