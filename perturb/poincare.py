"""Poincaré's method for periodic solutions of quasilinear systems, order by order.

The construction works in the strained time :math:`s = \\Omega t` with
:math:`\\Omega = \\omega_{ref} + \\sum_{k\\ge1}\\varepsilon^k\\Omega_k`, so that the sought solution is
:math:`2\\pi`-periodic in ``s`` and the period correction of the classical write-up,
:math:`\\alpha = T - 2\\pi/\\omega_{ref}`, becomes the frequency correction. With
:math:`x_i = \\sum_k \\varepsilon^k x_{i,k}(s)` the equations

.. math:: \\Omega^2 x_i'' + \\omega_i^2 x_i = f_i(x, \\Omega x', \\varepsilon)

give at order ``k``:  :math:`\\omega_{ref}^2 x_{i,k}'' + \\omega_i^2 x_{i,k} = R_{i,k}(s)`.

* For a resonant coordinate (:math:`\\omega_i = m_i\\omega_{ref}`) the solution is
  :math:`x_{i,k} = \\beta_{i,k}^c\\cos m_i s + \\beta_{i,k}^s\\sin m_i s + g_{i,k}(s)` where
  :math:`g_{i,k}` is the quadrature :math:`\\frac{1}{m_i\\omega_{ref}^2}\\int_0^s R_{i,k}(u)\\sin m_i(s-u)\\,du`
  (zero initial data) and :math:`\\beta_{i,k}` are the Maclaurin coefficients of the initial-value
  deviations.  :math:`g_{i,k}` is :math:`2\\pi`-periodic iff the periodicity conditions
  :math:`g_{i,k}(2\\pi) = 0`, :math:`\\dot g_{i,k}(2\\pi) = 0` hold, i.e. iff the harmonic
  :math:`m_i` of :math:`R_{i,k}` vanishes.
* For a non-resonant coordinate the forced response is the unique periodic solution.

The conditions are polynomial in the unknowns (generating amplitudes, their corrections, the
:math:`\\Omega_k`).  Nonlinear ones — the amplitude equations of the first non-zero order — are solved
for all roots and a branch is chosen; after that every correction enters linearly.  Unknowns left free
by an order are carried symbolically and fixed by a later one (this covers isolated roots, continuous
families with a user-chosen amplitude, and degenerate branches whose deviations scale as a power of ε
fixed by the balance of orders).
"""

from __future__ import annotations

import multiprocessing
from collections.abc import Mapping

import sympy as sp
from attrs import field, frozen, validators

from perturb._defaults import (
    FFT_POINTS,
    FFT_TRIM,
    MAX_ORDER,
    NUMERIC_ZERO,
    PROBE_DIGITS,
    ROOT_MAX_DENOMINATOR,
    ROOT_RATIONAL_TOL,
    ROOT_RESIDUAL,
    SOLVE_SECONDS,
)
from perturb.cache import cached
from perturb.errors import InvalidSystemError, bad_value
from perturb.series import NotNumeric, TrigSeries, evaluate_analytic, evaluate_polynomial
from perturb.solution import PeriodicSolution, Status
from perturb.steps import Condition, GeneratingSolution, OrderStep
from perturb.system import EPS, QuasilinearSystem
from perturb.trig import TrigPoly

__all__ = ["PoincareMethod", "solve"]


def _check_order(instance, attribute, value):
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise bad_value("order", value, "pass an integer >= 1", InvalidSystemError)
    if value > MAX_ORDER:
        raise bad_value("order", value, f"pass an integer <= {MAX_ORDER}", InvalidSystemError)


def _as_mapping(value) -> dict:
    return dict(value or {})


@frozen
class PoincareMethod:
    r"""Poincaré's method (small or large parameter) for a :class:`QuasilinearSystem`.

    Parameters
    ----------
    order : int
        Highest power of ε kept in the solution (>= 1).
    amplitudes : mapping, optional
        Fixed initial values ``{coordinate name: x_i(0)}``.  Values may be numbers or expressions in the
        system's parameters, ε (``perturb.system.EPS``) and its ``initial_values`` symbols (a
        constraint such as a first integral).  A coordinate listed here has exactly this initial value
        at every order (a member of a continuous family chosen by the user); the generating amplitudes
        of the others are unknowns found from the periodicity conditions.
    phase_coordinate : str, optional
        The coordinate whose velocity vanishes at ``t = 0`` (fixes the phase of an autonomous system).
        Default: the only coordinate in ``amplitudes`` if there is one, else the first coordinate.
    quadrature : {"auto", "exact", "numeric"}
        How the forcing of each order is expanded in harmonics: ``exact`` linearises products of
        trigonometric polynomials (polynomial right-hand sides only); ``numeric`` computes Fourier
        coefficients by FFT quadrature (any analytic right-hand side, numeric parameters and fixed
        generating amplitudes needed); ``auto`` (default) uses exact where it can.
    dependent_condition : {"auto", "phase-sine", "none"}
        A first integral makes one periodicity condition a consequence of the others: the one for the
        position of the phase coordinate, :math:`g_{ref,k}(2\pi) = 0` (the integral fixes
        :math:`x_{ref}(T)` once the other components have returned). ``phase-sine`` does not impose it
        (its residual is kept in ``solution.dependent_residuals``); ``none`` imposes every condition;
        ``auto`` (default) drops it when the system declares first integrals. Dropping it matters for
        reduced systems truncated in ε, where the integral holds only to the truncation order and
        imposing the dependent condition at the highest orders would make the conditions inconsistent.
    solve_seconds : float
        Time budget of sympy's solver on the nonlinear amplitude equations (run in a child process
        where the platform can fork); past it the result has status ``NO_ROOT`` and says how to give
        the root instead. sympy's ``solve`` can run for hours on systems whose roots have no
        closed form.
    branch : mapping or int, optional
        Which root of the amplitude equations to follow: a mapping ``{symbol name: value}`` selects the
        root that has these values, and on a continuous family of roots fixes the generating
        amplitudes the family leaves free (``a_P0``: cosine amplitude of ``P`` at order 0, ``b_P0``:
        its sine amplitude); an integer indexes the admissible roots in the order listed in
        ``solution.steps[k].branches``.  Default: the isolated root with the largest phase amplitude.
    """

    order: int = field(default=1, validator=_check_order)
    amplitudes: dict = field(factory=dict, converter=_as_mapping)
    phase_coordinate: str | None = field(
        default=None, validator=validators.optional(validators.instance_of(str))
    )
    branch: object = None
    quadrature: str = field(default="auto", validator=validators.in_(("auto", "exact", "numeric")))
    dependent_condition: str = field(
        default="auto", validator=validators.in_(("auto", "phase-sine", "none"))
    )
    solve_seconds: float = field(default=SOLVE_SECONDS, eq=False, repr=False)

    # ------------------------------------------------------------------ public
    cache: bool = field(default=True, eq=False, repr=False)

    def solve(self, system: QuasilinearSystem) -> PeriodicSolution:
        """Construct the periodic solution of ``system``; see the module docstring.

        The result is read from / written to the disk cache (:mod:`perturb.cache`) unless
        ``cache=False``.
        """
        if not self.cache:
            return _Construction(self, system).run()
        return cached(
            "solution", self._cache_key(system), lambda: _Construction(self, system).run()
        )

    def _cache_key(self, system: QuasilinearSystem) -> tuple:
        def text(value):
            return (
                sp.srepr(sp.sympify(value))
                if isinstance(value, (sp.Basic, int, float))
                else repr(value)
            )

        fields = (
            system.coordinates,
            system.velocities,
            system.frequencies,
            system.rhs,
            system.parameter,
            system.parameters,
            system.initial_values,
            system.first_integrals,
        )
        amplitudes = sorted((k, text(v)) for k, v in self.amplitudes.items())
        branch = (
            sorted((str(k), text(v)) for k, v in self.branch.items())
            if isinstance(self.branch, Mapping)
            else repr(self.branch)
        )
        return (
            tuple(sp.srepr(f) for f in fields),
            system.regime.value,
            system.name,
            system.truncation,
            self.order,
            amplitudes,
            self.phase_coordinate,
            branch,
            self.quadrature,
            self.dependent_condition,
        )


def solve(system: QuasilinearSystem, order: int = 1, **options) -> PeriodicSolution:
    """Shortcut for ``PoincareMethod(order=order, **options).solve(system)``."""
    return PoincareMethod(order=order, **options).solve(system)


class _Construction:
    """The mutable working state of one run (never escapes; results are frozen)."""

    def __init__(self, method: PoincareMethod, system: QuasilinearSystem):
        self.method = method
        self.system = system
        self.n = system.n
        self.names = [c.name for c in system.coordinates]
        self._setup_phase_and_harmonics()
        self._setup_unknowns()

    # ------------------------------------------------------------------ setup
    def _setup_phase_and_harmonics(self):
        method, names = self.method, self.names
        for key in method.amplitudes:
            if key not in names:
                raise bad_value(
                    "amplitudes",
                    {key: method.amplitudes[key]},
                    f"name a coordinate, one of {names}",
                    InvalidSystemError,
                )
        phase = method.phase_coordinate
        if phase is None:
            phase = next(iter(method.amplitudes)) if len(method.amplitudes) == 1 else names[0]
        if phase not in names:
            raise bad_value(
                "phase_coordinate", phase, f"name a coordinate, one of {names}", InvalidSystemError
            )
        self.phase = names.index(phase)
        dependent = self.method.dependent_condition
        if dependent == "auto":
            dependent = "phase-sine" if self.system.first_integrals else "none"
        self.drop_phase_sine = dependent == "phase-sine"
        self.w_ref = self.system.frequencies[self.phase]
        self.harmonics: list[int | None] = []
        for i, w in enumerate(self.system.frequencies):
            ratio = sp.nsimplify(sp.simplify(w / self.w_ref))
            m = int(ratio) if ratio.is_Integer and ratio > 0 else None
            self.harmonics.append(m)
            if m is None and names[i] in method.amplitudes:
                raise bad_value(
                    "amplitudes",
                    {names[i]: method.amplitudes[names[i]]},
                    f"{names[i]} is not resonant with the phase coordinate {phase} "
                    f"(omega ratio {ratio}); its generating amplitude vanishes, drop it",
                    InvalidSystemError,
                )

    def _setup_unknowns(self):
        self.unknowns: set[sp.Symbol] = set()
        self.given_series: dict[int, sp.Expr] = {}
        for name, value in self.method.amplitudes.items():
            i = self.names.index(name)
            expr = sp.sympify(value)
            allowed = set(self.system.parameters) | set(self.system.initial_values) | {EPS}
            stray = expr.free_symbols - allowed
            if stray:
                raise bad_value(
                    "amplitudes",
                    {name: value},
                    f"it depends on {sorted(map(str, stray))}; use only declared parameters, "
                    "initial-value symbols and epsilon",
                    InvalidSystemError,
                )
            self.given_series[i] = expr
        self.omega = [self.w_ref]
        # x_{i,k}(s) for each coordinate, order by order
        self.x: list[list[TrigPoly]] = [[] for _ in range(self.n)]
        self.init_cos: list[list[sp.Expr]] = [[] for _ in range(self.n)]
        self.solved: dict[sp.Symbol, sp.Expr] = {}
        self.steps: list[OrderStep] = []

    def _new(self, label: str) -> sp.Symbol:
        sym = sp.Symbol(label)
        self.unknowns.add(sym)
        return sym

    # ------------------------------------------------------------------ order 0
    def _generating(self) -> GeneratingSolution:
        cos_amp, sin_amp = [], []
        for i, name in enumerate(self.names):
            m = self.harmonics[i]
            if m is None:
                a = b = sp.S.Zero
            else:
                a = self._initial_cos(i, 0)
                b = sp.S.Zero if i == self.phase else self._new(f"b_{name}0")
            cos_amp.append(a)
            sin_amp.append(b)
            self.x[i].append(TrigPoly.harmonic(m, a, b) if m else TrigPoly())
        return GeneratingSolution(
            coordinates=tuple(self.names),
            harmonics=tuple(self.harmonics),
            cos_amplitudes=tuple(cos_amp),
            sin_amplitudes=tuple(sin_amp),
            phase_coordinate=self.names[self.phase],
            reference_frequency=self.w_ref,
        )

    def _initial_cos(self, i: int, k: int) -> sp.Expr:
        """x_{i,k}(0): given by ``amplitudes`` (expanded in ε) or a new unknown."""
        if i not in self.given_series:
            value = self._new(f"a_{self.names[i]}{k}")
        else:
            value = self._given_coefficient(i, k)
        self.init_cos[i].append(value)
        return value

    def _given_coefficient(self, i: int, k: int) -> sp.Expr:
        expr = self.given_series[i]
        if not (expr.free_symbols & set(self.system.initial_values)) and not expr.has(EPS):
            return expr if k == 0 else sp.S.Zero
        # The initial values are series sum_j eps^j c_j; expand once with placeholder symbols c_j
        # (cheap: small expressions), then put in what is known of the c_j at this order.
        placeholders = self._placeholders(i)
        subs = {}
        for j, sym in enumerate(self.system.initial_values):
            if not expr.has(sym):
                continue
            series = sp.Poly(self._initial_value_series(j, k), EPS)
            for q, c in enumerate(placeholders[sym][: k + 1]):
                subs[c] = series.coeff_monomial(EPS**q)
        return sp.expand(self._placeholder_taylor(i, k).xreplace(subs))

    def _placeholders(self, i: int) -> dict:
        if not hasattr(self, "_placeholder_cache"):
            self._placeholder_cache, self._taylor_cache = {}, {}
        if i not in self._placeholder_cache:
            expr = self.given_series[i]
            table = {}
            for j, sym in enumerate(self.system.initial_values):
                if expr.has(sym) and j % self.n == i:
                    raise bad_value(
                        "amplitudes",
                        {self.names[i]: expr},
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
            expr = self.given_series[i]
            subs = {
                sym: sp.Add(*(EPS**q * c for q, c in enumerate(cs[: k + 1])))
                for sym, cs in table.items()
                if expr.has(sym)
            }
            self._taylor_cache[key] = _taylor_coefficient(expr.xreplace(subs), k)
        return self._taylor_cache[key]

    def _initial_value_series(self, j: int, k: int) -> sp.Expr:
        """x_i(0) or xdot_i(0) as a polynomial in ε through order ``k`` (using what is known)."""
        coord, is_velocity = j % self.n, j >= self.n
        total = sp.S.Zero
        for order, term in enumerate(self.x[coord][: k + 1]):
            value = term.derivative().at_zero() if is_velocity else term.at_zero()
            total += EPS**order * value
        if is_velocity:
            total = sp.expand(total * sp.Add(*(EPS**q * w for q, w in enumerate(self.omega))))
        return total

    # ------------------------------------------------------------------ order k
    def _state_series(self, k: int) -> dict[sp.Symbol, TrigSeries]:
        """Series (to order k-1, padded to k) of the state and the initial values."""
        top = k - 1
        variables: dict[sp.Symbol, TrigSeries] = {}
        omega_series = TrigSeries([TrigPoly.constant(w) for w in self.omega[: top + 1]]).truncate(
            top
        )
        for i in range(self.n):
            xs = TrigSeries(self.x[i][: top + 1]).truncate(top)
            variables[self.system.coordinates[i]] = xs
            variables[self.system.velocities[i]] = (omega_series * xs.derivative()).truncate(top)
        for j, sym in enumerate(self.system.initial_values):
            value = variables[self.system.state_symbols[j]]
            variables[sym] = TrigSeries(
                [TrigPoly.constant(c.at_zero()) for c in value.coefficients]
            )
        return {sym: series.truncate(k) for sym, series in variables.items()}

    def _forcing(self, k: int) -> list[TrigPoly]:
        """R_{i,k}: order-k coefficient of f_i(x, Omega x') - (Omega^2 - w_ref^2) x_i''."""
        expansion = self.expansion
        variables = self._state_series(k)
        forcing = []
        omega_new = self._new(f"Omega{k}")
        omegas = self.omega + [omega_new]
        omega_sq = [
            sp.expand(sp.Add(*(omegas[a] * omegas[q - a] for a in range(q + 1))))
            for q in range(k + 1)
        ]
        for i in range(self.n):
            total = TrigPoly()
            for m in range(1, k + 1):
                f_m = expansion[i][m]
                if f_m == 0:
                    continue
                value = self._evaluate(f_m, variables, k - m)
                total = total + value.coefficients[k - m]
            for q in range(1, k + 1):  # -(Omega^2)_q x_{i,k-q}''
                if k - q < len(self.x[i]) and omega_sq[q] != 0:
                    total = total - self.x[i][k - q].derivative().derivative().scale(omega_sq[q])
            forcing.append(_chop(total.expand()))
        self.omega.append(omega_new)
        return forcing

    def _evaluate(self, expr: sp.Expr, variables, order: int) -> TrigSeries:
        """Series of ``expr`` on the state series: exact for polynomials, else numeric quadrature."""
        if self.method.quadrature != "numeric":
            try:
                return evaluate_polynomial(expr, variables, order)
            except sp.PolynomialError as exc:
                if self.method.quadrature == "exact":
                    raise _NotPolynomial(
                        f"{exc}; use quadrature='auto' with numeric parameters"
                    ) from None
        try:
            return evaluate_analytic(expr, variables, order, FFT_POINTS, FFT_TRIM)
        except NotNumeric as exc:
            raise _NotPolynomial(str(exc)) from None

    def _solve_order(self, k: int, forcing: list[TrigPoly]) -> tuple[dict, list[Condition]]:
        """Quadratures and periodicity conditions of order k (conditions returned unsolved)."""
        w2 = self.w_ref**2
        quadratures, conditions = {}, []
        for i, name in enumerate(self.names):
            r = forcing[i]
            m = self.harmonics[i]
            wi2 = self.system.frequencies[i] ** 2
            periodic = {}
            for j, (c, s) in r.terms.items():
                if m is not None and j == m:
                    continue
                den = wi2 - j**2 * w2
                periodic[j] = (sp.expand(c / den), sp.expand(s / den))
            part = TrigPoly(periodic)
            if m is None:
                quadratures[name] = part
                self.x[i].append(part)
                continue
            rc, rs = r.coefficient(m)
            # g(2 pi) and dg/ds(2 pi) of the quadrature with zero initial data (paper's (16) form)
            conditions.append(
                Condition(
                    f"g_{name},{k}(2pi)",
                    sp.expand(-sp.pi * rs / (m * w2)),
                    imposed=not (i == self.phase and self.drop_phase_sine),
                )
            )
            conditions.append(Condition(f"dg_{name},{k}/ds(2pi)", sp.expand(sp.pi * rc / w2)))
            # zero initial data: subtract the periodic part's initial value and slope
            p0, dp0 = part.at_zero(), part.derivative().at_zero()
            g = part + TrigPoly.harmonic(m, -p0, -dp0 / m)
            quadratures[name] = g
            a = self._initial_cos(i, k)
            b = sp.S.Zero if i == self.phase else self._new(f"b_{name}{k}")
            self.x[i].append((g + TrigPoly.harmonic(m, a, b)).expand())
        return quadratures, conditions

    # ------------------------------------------------------------------ solving
    def _substitute(self, mapping: dict):
        if not mapping:
            return
        self.x = [[t.subs(mapping) for t in row] for row in self.x]
        self.omega = [sp.expand(w.xreplace(mapping)) for w in self.omega]
        self.init_cos = [[sp.expand(v.xreplace(mapping)) for v in row] for row in self.init_cos]
        self.solved = {s: sp.expand(v.xreplace(mapping)) for s, v in self.solved.items()}
        self.solved.update(mapping)
        self.pending = [sp.expand(e.xreplace(mapping)) for e in self.pending]
        self.unknowns -= set(mapping)

    def _solve_conditions(self, k: int, generating: GeneratingSolution) -> tuple[dict, tuple]:
        eqs = [e for e in (sp.expand(e) for e in self.pending) if e != 0]
        if not eqs:
            self.pending = []
            return {}, ()
        unknowns = sorted(set().union(*(e.free_symbols for e in eqs)) & self.unknowns, key=str)
        if not unknowns:
            residual = [e for e in eqs if not _vanishes(e)]
            if residual:
                raise _Failure(
                    Status.INCONSISTENT, f"order {k}: conditions {residual} cannot vanish"
                )
            self.pending = []
            return {}, ()
        unknown_set = set(unknowns)
        linear = all(not (sp.diff(e, u).free_symbols & unknown_set) for e in eqs for u in unknowns)
        if linear:
            solution = self._solve_linear(eqs, unknowns, k)
            branches = ()
        else:
            solution, branches = self._solve_nonlinear(eqs, unknowns, k, generating)
        # The solvers return solutions of the whole system (the free unknowns of a family left as
        # parameters), so every pending condition now holds identically. Proving it symbolically
        # means cancelling large rational functions; a numerical probe at a generic point (30 digits)
        # checks it at a fraction of the cost and still catches a solver that returned a bad root.
        pending = self.pending
        self._substitute(solution)
        for before, after in zip(pending, self.pending, strict=True):
            if not _vanishes(after):
                raise _Failure(
                    Status.INCONSISTENT, f"order {k}: condition {before} = 0 cannot hold"
                )
        self.pending = []
        return solution, branches

    def _solve_linear(self, eqs, unknowns, k) -> dict:
        matrix, rhs = sp.linear_eq_to_matrix(eqs, unknowns)
        try:
            result = sp.linsolve((matrix, rhs), unknowns)
        except (NotImplementedError, ZeroDivisionError, ValueError) as exc:
            raise _Failure(
                Status.INCONSISTENT, f"order {k}: the linear periodicity conditions failed: {exc}"
            ) from None
        if result == sp.S.EmptySet:
            raise _Failure(
                Status.INCONSISTENT,
                f"order {k}: the linear periodicity conditions have no solution",
            )
        (values,) = tuple(result)
        solution = {}
        for sym, val in zip(unknowns, values, strict=True):
            val = sp.factor_terms(sp.cancel(val))
            if val.free_symbols & set(unknowns) == {sym}:
                continue
            if sym in val.free_symbols:
                continue
            solution[sym] = val
        return {s: sp.expand(v) if v.is_polynomial(*unknowns) else v for s, v in solution.items()}

    def _solve_nonlinear(self, eqs, unknowns, k, generating) -> tuple[dict, tuple]:
        numeric = self._numeric_system_roots(eqs, unknowns, generating)
        exact = numeric is not None and all(
            not v.has(sp.Float) for root in numeric for v in root.values()
        )
        try:
            if exact:
                roots = numeric
            else:
                try:
                    roots = _solve_bounded(eqs, unknowns, self.method.solve_seconds)
                except TimeoutError:
                    if not numeric:
                        raise
                    roots = numeric  # irrational roots sympy could not write in radicals
        except (NotImplementedError, sp.PolynomialError, ValueError) as exc:
            raise _Failure(
                Status.NO_ROOT,
                f"order {k}: sympy could not solve the amplitude equations {eqs}: {exc}",
            ) from None
        except TimeoutError:
            rescued = self._solve_with_branch_values(eqs, unknowns, k)
            if rescued is not None:
                return rescued, ()
            raise _Failure(
                Status.NO_ROOT,
                f"order {k}: sympy did not solve the amplitude equations {eqs} for {unknowns} within "
                f"{self.method.solve_seconds:g} s (PoincareMethod(solve_seconds=...)); if you know the "
                "root, give its generating amplitudes with `branch={name: value}`",
            ) from None
        if not roots:
            raise _Failure(Status.NO_ROOT, f"order {k}: amplitude equations {eqs} have no root")
        amplitude_syms = {
            s
            for s in (*generating.cos_amplitudes, *generating.sin_amplitudes)
            if isinstance(s, sp.Symbol)
        }
        admissible = []
        for root in roots:
            full = {s: root.get(s, s) for s in amplitude_syms}
            gen = [
                sp.sympify(a).xreplace(full)
                for a in (*generating.cos_amplitudes, *generating.sin_amplitudes)
            ]
            gen = [g.xreplace(self.solved) for g in gen]
            if all(_is_zero(g) for g in gen):
                continue  # trivial equilibrium
            if any(v.has(sp.I) and sp.simplify(sp.im(v)) != 0 for v in root.values()):
                continue
            admissible.append(root)
        if not admissible:
            raise _Failure(
                Status.NO_ROOT,
                f"order {k}: the amplitude equations {eqs} have only the trivial root",
            )
        chosen = self._choose_branch(admissible, unknowns, generating)
        return chosen, tuple(admissible)

    def _numeric_system_roots(self, eqs, unknowns, generating) -> list[dict] | None:
        """Roots by a Groebner basis when the coefficients are numbers (None: not applicable).

        Used as they are when every root is rational (exact); irrational roots come back as floats
        and are used only if sympy cannot write them in radicals within the time budget.

        The trivial equilibrium makes the system positive-dimensional (any frequency correction
        solves it there), so an unknown amplitude of the phase coordinate is required non-zero
        (Rabinowitsch: a new unknown w with w * amplitude = 1).
        """
        if any(e.free_symbols - set(unknowns) for e in eqs):
            return None
        if any(e.has(sp.Float) for e in eqs):
            return None
        system, variables = list(eqs), list(unknowns)
        phase_amplitude = generating.cos_amplitudes[self.phase]
        if isinstance(phase_amplitude, sp.Symbol) and phase_amplitude in unknowns:
            inverse = sp.Dummy("w")
            system.append(inverse * phase_amplitude - 1)
            variables = [inverse, *variables]
        try:
            roots = _solve_bounded(
                system, variables, self.method.solve_seconds, _groebner_real_roots
            )
        except (NotImplementedError, TimeoutError):
            return None
        return [{s: v for s, v in root.items() if s in unknowns} for root in roots]

    def _solve_with_branch_values(self, eqs, unknowns, k) -> dict | None:
        """When sympy cannot enumerate the roots, take the generating amplitudes from ``branch``.

        The amplitudes the user gives are put in, the remaining unknowns (frequency corrections)
        solved for, and every condition checked at the result; ``None`` if ``branch`` gives no
        amplitude of these equations.
        """
        selector = self.method.branch
        if not isinstance(selector, Mapping):
            return None
        given = {
            sp.Symbol(name) if isinstance(name, str) else name: sp.sympify(value)
            for name, value in selector.items()
        }
        given = {s: v for s, v in given.items() if s in unknowns}
        if not given:
            return None
        reduced = [e for e in (sp.expand(e.xreplace(given)) for e in eqs) if e != 0]
        rest = sorted(
            set().union(set(), *(e.free_symbols for e in reduced)) & set(unknowns), key=str
        )
        solution = dict(given)
        if rest:
            roots = _solve_bounded(reduced, rest, self.method.solve_seconds)
            if not roots:
                raise _Failure(
                    Status.INCONSISTENT,
                    f"order {k}: with the amplitudes of `branch` {selector} the conditions "
                    f"{reduced} have no solution",
                )
            solution.update(roots[0])
        residual = [e for e in eqs if not _vanishes(e.xreplace(solution))]
        if residual:
            raise _Failure(
                Status.INCONSISTENT,
                f"order {k}: the amplitudes of `branch` {selector} do not satisfy {residual}",
            )
        return solution

    def _choose_branch(self, roots, unknowns, generating) -> dict:
        selector = self.method.branch
        if isinstance(selector, int) and not isinstance(selector, bool):
            if not 0 <= selector < len(roots):
                raise bad_value(
                    "branch",
                    selector,
                    f"choose an index below {len(roots)}: {roots}",
                    InvalidSystemError,
                )
            return roots[selector]
        if isinstance(selector, Mapping):
            wanted = {
                sp.Symbol(k) if isinstance(k, str) else k: sp.sympify(v)
                for k, v in selector.items()
            }
            amplitude_syms = {
                s
                for s in (*generating.cos_amplitudes, *generating.sin_amplitudes)
                if isinstance(s, sp.Symbol)
            }
            for root in roots:
                # A root that fixes no generating amplitude leaves the choice to a later order. A root
                # that fixes some but leaves a wanted one free is a continuous family: the user's
                # value picks its member (only the generating amplitude: the corrections stay free
                # for the later orders to fix).
                extra = {}
                if amplitude_syms & set(root):
                    extra = {
                        s: v for s, v in wanted.items() if s in self.unknowns and s not in root
                    }
                candidate = {s: sp.sympify(v).xreplace(extra) for s, v in root.items()}
                candidate.update(extra)
                if all(
                    _is_zero(candidate[s] - v)
                    for s, v in wanted.items()
                    if s in unknowns and s in candidate
                ):
                    return candidate
            raise bad_value(
                "branch", selector, f"no root matches; the roots are {roots}", InvalidSystemError
            )
        isolated = [
            r
            for r in roots
            if not (set().union(*(sp.sympify(v).free_symbols for v in r.values())) & set(unknowns))
        ]
        pool = isolated or roots
        phase_amp = generating.cos_amplitudes[self.phase]

        def key(root):
            value = sp.sympify(phase_amp).xreplace(root)
            try:
                return -float(value.evalf(subs=_probe_values(value)))
            except (TypeError, ValueError):
                return 0.0

        return sorted(pool, key=key)[0]

    # ------------------------------------------------------------------ driver
    def run(self) -> PeriodicSolution:
        method, system = self.method, self.system
        lead = system.leading_order
        max_k = method.order + max(lead, 1) + 1
        self.expansion = system.expansion(max_k)
        self.pending: list[sp.Expr] = []
        self.dependent: list[Condition] = []
        generating = self._generating()
        status, message = Status.SUCCESS, ""
        k_done = 0
        try:
            for k in range(1, max_k + 1):
                if system.truncation is not None and k >= system.truncation:
                    raise _Failure(
                        Status.TRUNCATED,
                        f"order {method.order} needs the conditions of order {k}, but the system "
                        f"neglects epsilon^{system.truncation} and beyond "
                        f"(unknowns still open: {sorted(map(str, self._open_unknowns(method.order)))})",
                    )
                forcing = self._forcing(k)
                quadratures, conditions = self._solve_order(k, forcing)
                self.pending.extend(c.expression for c in conditions if c.imposed)
                self.dependent.extend(c for c in conditions if not c.imposed)
                solved, branches = self._solve_conditions(k, generating)
                self.steps.append(
                    OrderStep(
                        k,
                        {n: f for n, f in zip(self.names, forcing, strict=True)},
                        quadratures,
                        tuple(conditions),
                        dict(solved),
                        branches,
                    )
                )
                k_done = k
                if k >= method.order and not self._open_unknowns(method.order):
                    break
        except _NotPolynomial as exc:
            status, message = Status.NOT_POLYNOMIAL, str(exc)
        except _Failure as exc:
            status, message = exc.status, exc.message
        if status is Status.SUCCESS and self._open_unknowns(method.order):
            status = Status.UNDETERMINED
            message = f"unknowns {sorted(map(str, self._open_unknowns(method.order)))} are not fixed by orders up to {k_done}"
        return self._result(generating, status, message)

    def _open_unknowns(self, order: int) -> set:
        syms = set()
        for row in self.x:
            for term in row[: order + 1]:
                syms |= term.free_symbols()
        for w in self.omega[: order + 1]:
            syms |= w.free_symbols
        return syms & self.unknowns

    def _result(
        self, generating: GeneratingSolution, status: Status, message: str
    ) -> PeriodicSolution:
        order = self.method.order
        gen = GeneratingSolution(
            coordinates=generating.coordinates,
            harmonics=generating.harmonics,
            cos_amplitudes=tuple(
                sp.sympify(a).xreplace(self.solved) for a in generating.cos_amplitudes
            ),
            sin_amplitudes=tuple(
                sp.sympify(b).xreplace(self.solved) for b in generating.sin_amplitudes
            ),
            phase_coordinate=generating.phase_coordinate,
            reference_frequency=generating.reference_frequency,
        )
        terms = tuple(tuple(row[: order + 1]) for row in self.x)
        # keep every frequency coefficient that is fully determined
        frequency = []
        for w in self.omega:
            if w.free_symbols & self.unknowns:
                break
            frequency.append(w)
        deviations = {}
        for i, name in enumerate(self.names):
            if self.harmonics[i] is None:
                continue
            values = [t.at_zero() for t in terms[i]]
            deviations[name] = tuple(values[1:])
            slopes = [t.derivative().at_zero() for t in terms[i]]
            omega = self.omega[: len(frequency)]
            velocity = [
                sp.expand(sum(omega[a] * slopes[q - a] for a in range(q + 1) if a < len(omega)))
                for q in range(len(slopes))
            ]
            deviations[self.system.velocities[i].name] = tuple(velocity[1:])
        return PeriodicSolution(
            system=self.system,
            order=order,
            terms=terms,
            frequency=tuple(frequency),
            generating=gen,
            steps=tuple(self.steps),
            deviations=deviations,
            status=status,
            message=message,
            dependent_residuals={
                c.name: sp.expand(c.expression.xreplace(self.solved)) for c in self.dependent
            },
        )


def _sympy_roots(eqs, unknowns) -> list[dict]:
    return sp.solve(eqs, unknowns, dict=True, simplify=False)


def _solve_worker(solver, eqs, unknowns, connection) -> None:
    try:
        connection.send(("ok", solver(eqs, unknowns)))
    except Exception as exc:  # noqa: BLE001 - the parent re-raises it as a failed status
        connection.send(("error", exc))
    finally:
        connection.close()


def _solve_bounded(eqs, unknowns, seconds: float, solver=_sympy_roots) -> list[dict]:
    """``solver(eqs, unknowns)`` (default ``sympy.solve(..., dict=True)``) with a time budget.

    The solve runs in a forked child process, which is killed when the budget is spent
    (``TimeoutError``). Where the platform cannot fork, it runs in-process without a budget.
    """
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:  # pragma: no cover - platforms without fork
        return solver(eqs, unknowns)
    receiver, sender = context.Pipe(duplex=False)
    child = context.Process(target=_solve_worker, args=(solver, eqs, unknowns, sender), daemon=True)
    child.start()
    sender.close()
    try:
        if not receiver.poll(seconds):
            raise TimeoutError
        kind, value = receiver.recv()
    except EOFError:
        raise NotImplementedError("the solver process died") from None
    finally:
        if child.is_alive():
            child.kill()
        child.join()
        receiver.close()
    if kind == "error":
        raise (
            value
            if isinstance(value, (NotImplementedError, ValueError))
            else NotImplementedError(str(value))
        )
    return value


def _groebner_real_roots(eqs, unknowns) -> list[dict]:
    """Real roots of a zero-dimensional polynomial system with numeric coefficients.

    A lexicographic Groebner basis makes the system triangular; the last variable's polynomial is
    solved numerically (companion matrix), each root substituted back, variable by variable, keeping
    the roots every polynomial of that variable shares. Roots within ``ROOT_RATIONAL_TOL`` of a
    rational with a small denominator are returned exact. sympy's ``solve`` needs the roots in
    radicals and can run for hours where this takes a fraction of a second.

    Raises
    ------
    NotImplementedError
        If the system is not zero-dimensional (a family of roots) or a variable is left free.
    """
    import numpy as np

    basis = sp.groebner(eqs, *unknowns, order="lex")
    if list(basis.exprs) == [1]:
        return []
    if not basis.is_zero_dimensional:
        raise NotImplementedError("the amplitude equations have a continuum of roots")
    polys = list(basis.exprs)
    found: list[dict] = []

    def descend(index: int, assignment: dict) -> None:
        if index < 0:
            found.append(dict(assignment))
            return
        var = unknowns[index]
        candidates = []
        for poly in polys:
            expr = sp.expand(poly.xreplace(assignment))
            if expr.free_symbols == {var}:
                candidates.append(sp.Poly(expr, var))
            elif not expr.free_symbols and abs(complex(expr)) > ROOT_RESIDUAL:
                return
        if not candidates:
            raise NotImplementedError(f"{var} is left free by the amplitude equations")
        lowest = min(candidates, key=lambda q: q.degree())
        for z in np.roots([complex(c) for c in lowest.all_coeffs()]):
            if abs(z.imag) > ROOT_RESIDUAL * max(1.0, abs(z)):
                continue
            value = _exact_if_close(z.real)
            scale = lambda q: max(1.0, *(abs(complex(c)) for c in q.all_coeffs()))  # noqa: E731
            if all(abs(complex(q.eval(value))) <= ROOT_RESIDUAL * scale(q) for q in candidates):
                assignment[var] = value
                descend(index - 1, assignment)
                del assignment[var]

    descend(len(unknowns) - 1, {})
    return found


def _exact_if_close(value: float) -> sp.Expr:
    rational = sp.nsimplify(value, tolerance=ROOT_RATIONAL_TOL, rational=True)
    if rational.q <= ROOT_MAX_DENOMINATOR and abs(float(rational) - value) <= ROOT_RATIONAL_TOL:
        return rational
    return sp.Float(value, 17)


def _taylor_coefficient(expr: sp.Expr, k: int) -> sp.Expr:
    """Coefficient of ε^k in the Maclaurin expansion of ``expr`` (k-fold derivative at 0 over k!).

    Much faster than ``sympy.series`` on nested radicals of polynomials, the form first-integral
    constraints take.
    """
    if not expr.has(EPS):
        return sp.expand(expr) if k == 0 else sp.S.Zero
    if expr.is_polynomial(EPS):
        return sp.expand(sp.expand(expr).coeff(EPS, k))
    value = expr
    for _ in range(k):
        value = sp.diff(value, EPS)
    return sp.expand(value.subs(EPS, 0) / sp.factorial(k))


def _is_zero(expr) -> bool:
    """Cheap zero test: exact for symbolic expressions, round-off tolerant for floating numbers."""
    expr = sp.sympify(expr)
    if expr.is_number and expr.has(sp.Float):
        return abs(complex(expr)) < NUMERIC_ZERO
    return expr == 0 or sp.expand(expr) == 0 or sp.cancel(expr) == 0


def _vanishes(expr) -> bool:
    """Whether ``expr`` is zero: exactly when cheap, else by evaluation at a generic point.

    The generic point gives every symbol a distinct rational value in (0.5, 1) (where the
    square roots of first-integral constraints stay real); a non-zero rational function of the
    symbols that vanishes there to 30 digits would be a coincidence of measure zero.
    """
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    if expr.is_number:
        return _is_zero(expr)
    value = expr.evalf(PROBE_DIGITS, subs=_probe_values(expr))
    try:
        magnitude = abs(complex(value))
    except TypeError:  # evaluation left symbols behind (a function sympy cannot evaluate)
        return _is_zero(expr)
    return magnitude < NUMERIC_ZERO


def _chop(poly: TrigPoly) -> TrigPoly:
    """Drop floating-point round-off (|c| < NUMERIC_ZERO) from the coefficients of ``poly``."""

    def chop(expr: sp.Expr) -> sp.Expr:
        floats = {f: 0 for f in expr.atoms(sp.Float) if abs(f) < NUMERIC_ZERO}
        return sp.expand(expr.xreplace(floats)) if floats else expr

    return poly.map(chop)


def _probe_values(expr: sp.Expr) -> dict:
    """Deterministic generic values in (0.5, 1) for the free symbols of ``expr``.

    Distinct rationals with unrelated denominators (so no accidental cancellation), below 1 so that
    the square roots of first-integral constraints such as sqrt(1 - gamma**2) stay real.
    """
    symbols = sorted(expr.free_symbols, key=str)
    return {s: sp.Rational(1, 2) + sp.Rational(i + 1, 2 * (len(symbols) + 1)) - sp.Rational(1, 101 + 7 * i)
            for i, s in enumerate(symbols)}  # fmt: skip


class _Failure(Exception):
    def __init__(self, status: Status, message: str):
        super().__init__(message)
        self.status, self.message = status, message


class _NotPolynomial(Exception):
    pass
