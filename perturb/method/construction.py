"""The order-by-order construction: the public template every Poincaré run follows.

:class:`OrderByOrder` is the working state of one run of :meth:`PoincareMethod.solve
<perturb.method.poincare.PoincareMethod.solve>` (the method's mathematics is in
:mod:`perturb.method.poincare`). It is a template in the sense of scipy's ``OdeSolver``: the
loop of :meth:`OrderByOrder.run` is written once, and what differs between kinds of run is a
numbered contract of hooks and strategies:

1. the frame — ``_setup_phase_and_harmonics`` (which coordinate fixes the phase, which are
   resonant), ``_phase_fixed_by``, ``_frequency_coefficient`` (the frequency unknown, or given);
   the free template here, the driven one in :mod:`perturb.method.given_period` (chosen by the
   system's :attr:`~perturb.QuasilinearSystem.frame`);
2. the condition strategy — ``solver``, made by ``_make_solver``: solve for one branch
   (:class:`~perturb.method.conditions.ConditionSolver`), enumerate every family (the family
   solver of :mod:`perturb.method.families`), or collect the equations unsolved (the amplitude
   equations of :mod:`perturb.method.driven`, which override ``_solve_conditions``);
3. :meth:`OrderByOrder.step` — one order: forcing, quadratures, conditions (a client that needs
   only some orders, as the amplitude equations do, calls it instead of :meth:`OrderByOrder.run`).
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp

from perturb.errors import InvalidSystemError, bad_value
from perturb.method.conditions import ConditionSolver, OrderFailed
from perturb.method.exact import vanishes_native
from perturb.method.expansion import GivenInitialValues, NotPolynomial, forcing
from perturb.method.kept import KeptSeries
from perturb.method.linear import solve_unique
from perturb.native import Converter, ring_for
from perturb.solution import PeriodicSolution, Status
from perturb.steps import GeneratingSolution, OrderStep, PeriodicityCondition
from perturb.system import EPS, QuasilinearSystem
from perturb.trig import SympyRing, TrigPoly

__all__ = ["OrderByOrder"]


class OrderByOrder(KeptSeries):
    """The working state of one run: the template of :meth:`PoincareMethod.solve`.

    Short-lived (the result is a frozen :class:`PeriodicSolution`; its ``steps`` record
    the construction). The steps of :meth:`run`:

    1. the generating solution (order 0), its unknown amplitudes;
    2. for ``k = 1, 2, ...``: the forcing :math:`R_{i,k}` (:func:`~perturb.method.expansion.forcing`),
       the quadratures and periodicity conditions (:meth:`_quadratures`), the conditions solved
       (:class:`~perturb.method.conditions.ConditionSolver`) and substituted everywhere;
    3. stop once order ``method.order`` is reached and no unknown of it is open; pack the result.
    """

    def __init__(self, method, system: QuasilinearSystem, ring: type | None = None):
        # method: the options, a perturb.method.poincare.PoincareMethod (which imports this module)
        self.method = method
        self.system = system
        self.n = system.n
        self.names = [c.name for c in system.coordinates]
        self._setup_phase_and_harmonics()
        self.conv = Converter(ring or self._ring())
        self._setup_unknowns()
        self.solver = self._make_solver()

    # ------------------------------------------------------------------ setup
    def _make_solver(self) -> ConditionSolver:
        """The solver of the periodicity conditions (hook: a driven system's knows the forcing
        fixes the phase)."""
        return ConditionSolver(self.method.branch, self.method.solve_seconds, self.phase)

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

    def _ring(self) -> type:
        """The coefficient ring of this run (:mod:`perturb.native`): native unless the right-hand
        side needs the numeric quadrature or an input holds a float (then sympy, as always)."""
        system = self.system
        variables = (*system.state_symbols, *system.initial_values)
        if self.method.quadrature == "numeric" or not all(
            sp.sympify(f).is_polynomial(*variables) for f in system.rhs
        ):
            return SympyRing
        return ring_for(
            *system.rhs, *system.frequencies, *map(sp.sympify, self.method.amplitudes.values())
        )

    def _setup_unknowns(self):
        self.unknowns: set[sp.Symbol] = set()
        self.created: set[str] = set()  # names of every unknown introduced (for `branch` keys)
        given: dict[int, sp.Expr] = {}
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
            given[i] = expr
        self.given = GivenInitialValues(self.system, given)
        # Native (self.conv's ring): omega, x, init_cos, pending. sympy: solved, steps, dependent.
        self.omega = [self.conv.to_native(self.w_ref)]
        # x_{i,k}(s) for each coordinate, order by order
        self.x: list[list] = [[] for _ in range(self.n)]
        self.init_cos: list[list] = [[] for _ in range(self.n)]
        self.solved: dict[sp.Symbol, sp.Expr] = {}
        self.steps: list[OrderStep] = []
        self.pending: list = []
        self.dependent: list[PeriodicityCondition] = []
        self.frequency_top: int | None = None  # the order whose Omega_k is the last one kept
        self.failure: OrderFailed | None = None  # why the run stopped, when it failed

    def _new(self, label: str) -> sp.Symbol:
        sym = sp.Symbol(label)
        self.unknowns.add(sym)
        self.created.add(label)
        return sym

    # ------------------------------------------------------------------ order 0
    def generating(self) -> GeneratingSolution:
        """Step 1 of the template: the generating solution (order 0), its amplitudes unknown
        where no option gives them."""
        conv, poly = self.conv, self.conv.poly
        cos_amp, sin_amp = [], []
        for i, name in enumerate(self.names):
            m = self.harmonics[i]
            if m is None:
                a = b = sp.S.Zero
            else:
                a = self._initial_cos(i, 0)
                b = sp.S.Zero if self._phase_fixed_by(i) else self._new(f"b_{name}0")
            cos_amp.append(a)
            sin_amp.append(b)
            self.x[i].append(
                poly.harmonic(m, conv.to_native(a), conv.to_native(b)) if m else poly()
            )
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
        if i not in self.given:
            value = self._new(f"a_{self.names[i]}{k}")
        else:
            value = self.given.coefficient(i, k, self._initial_value_series)
        self.init_cos[i].append(self.conv.to_native(value))
        return value

    def _initial_value_series(self, j: int, k: int) -> sp.Expr:
        """x_i(0) or xdot_i(0) as a polynomial in ε through order ``k`` (using what is known)."""
        coord, is_velocity = j % self.n, j >= self.n
        to_sympy = self.conv.to_sympy
        total = sp.S.Zero
        for order, term in enumerate(self.x[coord][: k + 1]):
            value = term.derivative().at_zero() if is_velocity else term.at_zero()
            total += EPS**order * to_sympy(value)
        if is_velocity:
            omega = sp.Add(*(EPS**q * to_sympy(w) for q, w in enumerate(self.omega)))
            total = sp.expand(total * omega)
        return total

    # ------------------------------------------------------------------ order k
    def _phase_fixed_by(self, i: int) -> bool:
        """Whether coordinate ``i``'s sine amplitudes vanish because its velocity fixes the phase
        (hook: the phase coordinate of an autonomous system; none of a driven one)."""
        return i == self.phase

    def _frequency_coefficient(self, k: int):
        """:math:`\\Omega_k` in the native ring: an unknown of order k (hook: a driven system's
        frequency is given)."""
        return self.conv.to_native(self._new(f"Omega{k}"))

    def _forcing(self, k: int) -> list[TrigPoly]:
        omega_new = self._frequency_coefficient(k)
        result = forcing(
            k,
            self.system,
            self.expansion,
            self.x,
            [*self.omega, omega_new],
            self.method.quadrature,
            self.conv,
        )
        self.omega.append(omega_new)
        return result

    def _quadratures(
        self, k: int, forcing: list[TrigPoly]
    ) -> tuple[dict, list[PeriodicityCondition]]:
        """Quadratures and periodicity conditions of order k (conditions returned unsolved)."""
        conv, poly = self.conv, self.conv.poly
        expand = poly.ring.expand
        w2 = self.w_ref**2
        w2_native, pi = conv.to_native(w2), conv.to_native(sp.pi)
        quadratures, conditions = {}, []
        for i, name in enumerate(self.names):
            r = forcing[i]
            m = self.harmonics[i]
            wi2 = self.system.frequencies[i] ** 2
            periodic = {}
            for j, (c, s) in r.terms.items():
                if m is not None and j == m:
                    continue
                den = conv.to_native(wi2 - j**2 * w2)
                periodic[j] = (expand(c / den), expand(s / den))
            part = poly(periodic)
            if m is None:
                quadratures[name] = conv.trig(part)
                self.x[i].append(part)
                continue
            rc, rs = r.coefficient(m)
            # g(2 pi) and dg/ds(2 pi) of the quadrature with zero initial data (paper's (16) form)
            for label, value, imposed in (
                (
                    f"g_{name},{k}(2pi)",
                    expand(-pi * rs / (m * w2_native)),
                    i != self.phase or not self.drop_phase_sine,
                ),
                (f"dg_{name},{k}/ds(2pi)", expand(pi * rc / w2_native), True),
            ):
                conditions.append(
                    PeriodicityCondition(label, conv.to_sympy(value), imposed=imposed)
                )
                if imposed:
                    self.pending.append(value)
            # zero initial data: subtract the periodic part's initial value and slope
            p0, dp0 = part.at_zero(), part.derivative().at_zero()
            g = part + poly.harmonic(m, -p0, -dp0 / m)
            quadratures[name] = conv.trig(g)
            self._initial_cos(i, k)
            a = self.init_cos[i][-1]
            b = (
                conv.ring.zero
                if self._phase_fixed_by(i)
                else conv.to_native(self._new(f"b_{name}{k}"))
            )
            self.x[i].append((g + poly.harmonic(m, a, b)).expand())
        return quadratures, conditions

    # ------------------------------------------------------------------ solving
    def _substitute(self, mapping: dict):
        if not mapping:
            return
        native = self.conv.mapping(mapping)
        expand = self.conv.ring.expand
        self.x = [[t.subs(native) for t in row] for row in self.x]
        self.omega = [expand(w.xreplace(native)) for w in self.omega]
        self.init_cos = [[expand(v.xreplace(native)) for v in row] for row in self.init_cos]
        self.solved = {s: sp.expand(v.xreplace(mapping)) for s, v in self.solved.items()}
        self.solved.update(mapping)
        self.pending = [expand(e.xreplace(native)) for e in self.pending]
        self.unknowns -= set(mapping)

    def _solve_conditions(self, k: int, generating: GeneratingSolution) -> tuple[dict, tuple]:
        expand, to_sympy = self.conv.ring.expand, self.conv.to_sympy
        native = [e for e in (expand(e) for e in self.pending) if e != 0]
        if not native:
            self.pending = []
            return {}, ()
        solution, branches = solve_unique(native, self.unknowns, self.conv), ()
        if solution is None:  # small, nonlinear or not unique: sympy's route
            eqs = [sp.expand(to_sympy(e)) for e in native]
            solution, branches = self.solver.solve(k, eqs, self.unknowns, generating, self.solved)
        # The solvers return solutions of the whole system (the free unknowns of a family left as
        # parameters), so every pending condition now holds identically. Proving it symbolically
        # means cancelling large rational functions; a numerical probe at a generic point (30 digits)
        # checks it at a fraction of the cost and still catches a solver that returned a bad root.
        pending = self.pending
        self._substitute(solution)
        for before, after in zip(pending, self.pending, strict=True):
            if after != 0 and not vanishes_native(after, self.conv):
                raise OrderFailed(
                    Status.INCONSISTENT,
                    f"order {k}: condition {to_sympy(before)} = 0 cannot hold",
                    (to_sympy(after),),
                )
        self.pending = []
        return solution, branches

    # ------------------------------------------------------------------ driver
    def step(self, k: int, generating: GeneratingSolution) -> OrderStep:
        """Order ``k``: the forcing, the quadratures and periodicity conditions, the conditions
        handed to the strategy (solved, or collected) and substituted everywhere."""
        forcing_k = self._forcing(k)
        quadratures, conditions = self._quadratures(k, forcing_k)  # extends self.pending
        self.dependent.extend(c for c in conditions if not c.imposed)
        solved, branches = self._solve_conditions(k, generating)
        return OrderStep(
            k,
            {n: self.conv.trig(f) for n, f in zip(self.names, forcing_k, strict=True)},
            quadratures,
            tuple(conditions),
            dict(solved),
            branches,
        )

    def run(self) -> PeriodicSolution:
        method, system = self.method, self.system
        lead = system.leading_order
        # the orders a run may take: order N's terms, the deeper ones of coordinates that start
        # at a power of eps (one lead more), and the corrections a degenerate family's
        # conditions fix only at twice its family order (Hénon–Heiles's lines: the correction
        # of order j at order j + 4; the bowed line along x, whose y starts at eps: N + 5)
        max_k = method.order + 3 * max(lead, 1) + 2
        self.expansion = system.expansion(max_k)
        generating = self.generating()
        status, message = Status.SUCCESS, ""
        k_done = 0
        try:
            for k in range(1, max_k + 1):
                if system.truncation is not None and k >= system.truncation:
                    raise OrderFailed(
                        Status.TRUNCATED,
                        f"order {method.order} needs the conditions of order {k}, but the system "
                        f"neglects epsilon^{system.truncation} and beyond "
                        f"(unknowns still open: {sorted(map(str, self._open_unknowns()))})",
                    )
                self.steps.append(self.step(k, generating))
                k_done = k
                if self.frequency_top is None and k >= method.order:
                    if not self._open_unknowns(uniform=True):
                        self.frequency_top = k
                if k >= max(self._depths()) and not self._open_unknowns():
                    break
        except NotPolynomial as exc:
            status, message = Status.NOT_POLYNOMIAL, str(exc)
        except OrderFailed as exc:
            status, message = exc.status, exc.message
            self.failure = exc
        if status is Status.SUCCESS and isinstance(method.branch, Mapping):
            stray = sorted({str(key) for key in method.branch} - self.created)
            if stray:
                raise bad_value(
                    "branch",
                    method.branch,
                    f"{stray} are not unknowns of this construction; "
                    f"name some of {sorted(self.created)}",
                    InvalidSystemError,
                )
        if status is Status.SUCCESS and self._open_unknowns():
            status = Status.UNDETERMINED
            message = f"unknowns {sorted(map(str, self._open_unknowns()))} are not fixed by orders up to {k_done}"
        return self.result(generating, status, message)
