"""Solving the periodicity conditions of one order: linear, nonlinear, Groebner, time budget, branches.

The conditions of an order are polynomial in the open unknowns (generating amplitudes, their
corrections, the frequency corrections :math:`\\Omega_k`). Linear ones are solved by ``linsolve``,
free unknowns left as parameters for a later order. Nonlinear ones (the amplitude equations of the
first non-zero order) are solved for all roots and one branch is chosen:

1. with numeric coefficients, by the certified real-root solver of :mod:`perturb.algebra`
   (msolve where the extra ``roots`` is installed, else the exact sympy route): every real root,
   each isolated; ``NO_ROOT`` only when it is proved that none exists;
2. else by sympy's ``solve`` in a forked child process under a time budget
   (:func:`perturb.algebra.budget.solve_bounded`); a spent budget is ``SOLVER_BUDGET``, with the
   size of the system and the option that raises the budget;
3. when no root can be enumerated in time, from the generating amplitudes the user gives in
   ``branch`` (the frequency corrections are then solved for and every condition checked).
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from attrs import frozen

from perturb._defaults import ROOT_RESIDUAL
from perturb.algebra.budget import solve_bounded
from perturb.algebra.certified import certified_real_roots
from perturb.algebra.msolve import install_advice
from perturb.algebra.rootset import RootStatus
from perturb.algebra.size import SystemSize
from perturb.errors import InvalidSystemError, bad_value
from perturb.method.exact import exact_if_close, is_zero, probe_values, rational_form, vanishes
from perturb.solution import Status
from perturb.steps import GeneratingSolution

__all__ = [
    "ConditionSolver",
    "OrderFailed",
    "compatibility_conditions",
    "groebner_real_roots",
]


class OrderFailed(Exception):
    """The construction cannot go on at some order; carries the result's status and the reason.

    Internal to :mod:`perturb.method`: :meth:`PoincareMethod.solve` turns it into a failed
    :class:`~perturb.solution.PeriodicSolution`, never lets it escape.
    """

    def __init__(self, status: Status, message: str, residual_conditions: tuple = ()):
        super().__init__(message)
        self.status, self.message = status, message
        #: For INCONSISTENT: polynomials free of the order's unknowns that would have to vanish
        #: for the conditions to hold (they restrict a family's free amplitudes; see
        #: :func:`compatibility_conditions`).
        self.residual_conditions = tuple(residual_conditions)


@frozen
class ConditionSolver:
    """Solves the periodicity conditions of one order and chooses the branch.

    Parameters
    ----------
    branch : mapping, int or None
        The user's branch selector (see :class:`~perturb.method.poincare.PoincareMethod`).
    solve_seconds : float
        Time budget of one sympy ``solve`` (and of one Groebner root search).
    phase : int
        Index of the phase coordinate (its amplitude orders the default branch choice).

    A driven system's template gives its own subclass
    (:class:`perturb.method.given_period.ForcedConditions`): there the forcing fixes the phase.
    """

    branch: object
    solve_seconds: float
    phase: int

    def phase_amplitude_nonzero(self) -> bool:
        """Whether the phase coordinate's cosine amplitude must not vanish (a Rabinowitsch
        condition): it fixes the phase of a free motion."""
        return True

    def size(self, generating: GeneratingSolution) -> sp.Expr:
        """What orders the default branch (largest first): the phase coordinate's cosine
        amplitude."""
        return generating.cos_amplitudes[self.phase]

    def solve(
        self,
        k: int,
        eqs: list,
        open_unknowns: set,
        generating: GeneratingSolution,
        solved: Mapping,
    ) -> tuple[dict, tuple]:
        """Solve ``eqs = 0`` (non-zero, expanded) for the unknowns they contain.

        Parameters
        ----------
        k : int
            The order (for messages).
        eqs : list of sympy expressions
            The pending conditions.
        open_unknowns : set of sympy.Symbol
            Every unknown of the construction not yet solved for.
        generating : GeneratingSolution
            The generating solution with its unknown amplitudes.
        solved : mapping
            The unknowns solved at lower orders (to judge whether a root is trivial).

        Returns
        -------
        (dict, tuple)
            ``{unknown: value}`` (a solution of the whole system, free unknowns of a family left as
            parameters) and every admissible root when the conditions were nonlinear.

        Raises
        ------
        OrderFailed
            When the conditions are inconsistent or no admissible root is found.
        """
        unknowns = sorted(set().union(*(e.free_symbols for e in eqs)) & open_unknowns, key=str)
        if not unknowns:
            residual = [e for e in eqs if not vanishes(e)]
            if residual:
                raise OrderFailed(
                    Status.INCONSISTENT,
                    f"order {k}: conditions {residual} cannot vanish",
                    tuple(residual),
                )
            return {}, ()
        unknown_set = set(unknowns)
        linear = all(not (sp.diff(e, u).free_symbols & unknown_set) for e in eqs for u in unknowns)
        if linear:
            return _solve_linear(eqs, unknowns, k), ()
        return self._solve_nonlinear(eqs, unknowns, k, generating, solved, open_unknowns)

    # ------------------------------------------------------------------ nonlinear
    def _solve_nonlinear(self, eqs, unknowns, k, generating, solved, open_unknowns):
        numeric, found = self._numeric_system_roots(eqs, unknowns, generating)
        if numeric == []:
            raise OrderFailed(
                Status.NO_ROOT,
                f"order {k}: the amplitude equations have no admissible real root (proved: "
                f"{found.message}; {found.backend} route)",
            )
        exact = numeric is not None and all(
            not v.has(sp.Float) for root in numeric for v in root.values()
        )
        certified = numeric is not None and found is not None
        try:
            if exact or certified:
                roots = numeric
            else:
                try:
                    roots = solve_bounded(eqs, unknowns, self.solve_seconds)
                except TimeoutError:
                    if not numeric:
                        raise
                    roots = numeric  # irrational roots sympy could not write in radicals
        except (NotImplementedError, sp.PolynomialError, ValueError) as exc:
            raise OrderFailed(
                Status.NO_ROOT,
                f"order {k}: sympy could not solve the amplitude equations {eqs}: {exc}",
            ) from None
        except TimeoutError:
            rescued = self._solve_with_branch_values(eqs, unknowns, k)
            if rescued is not None:
                return rescued, ()
            if found is not None and found.status is RootStatus.POSITIVE_DIMENSIONAL:
                raise OrderFailed(
                    Status.UNDETERMINED,
                    f"order {k}: the amplitude equations have a continuum of roots (proved by "
                    f"the certified solver: {found.describe_continua()}); sympy did not write it "
                    f"within {self.solve_seconds:g} s: list it with `perturb families` "
                    "(find_families) or fix its free amplitudes with `amplitudes=`",
                ) from None
            size = SystemSize.of([rational_form(e) for e in eqs], unknowns)
            tried = f"; the certified solver: {found.status.name}" if found is not None else ""
            raise OrderFailed(
                Status.SOLVER_BUDGET,
                f"order {k}: the amplitude equations ({size}) in {unknowns} were not solved "
                f"within the budget of {self.solve_seconds:g} s{tried} — raise it with "
                f"PoincareMethod(solve_seconds=...){install_advice()}; if you know the root, give "
                "its generating amplitudes with `branch={name: value}`",
            ) from None
        if not roots:
            raise OrderFailed(Status.NO_ROOT, f"order {k}: amplitude equations {eqs} have no root")
        amplitude_syms = _amplitude_symbols(generating)
        admissible = []
        for root in roots:
            full = {s: root.get(s, s) for s in amplitude_syms}
            gen = [
                sp.sympify(a).xreplace(full)
                for a in (*generating.cos_amplitudes, *generating.sin_amplitudes)
            ]
            gen = [g.xreplace(solved) for g in gen]
            if all(is_zero(g) for g in gen):
                continue  # trivial equilibrium
            if any(v.has(sp.I) and sp.simplify(sp.im(v)) != 0 for v in root.values()):
                continue
            admissible.append(root)
        if not admissible:
            raise OrderFailed(
                Status.NO_ROOT,
                f"order {k}: the amplitude equations {eqs} have only the trivial root",
            )
        chosen = self._choose_branch(admissible, unknowns, generating, open_unknowns)
        return chosen, tuple(admissible)

    def _numeric_system_roots(self, eqs, unknowns, generating):
        """Every real root by the certified solver when the coefficients are numbers.

        Returns ``(roots, found)``: the roots (None: not applicable or not decided) and the
        :class:`~perturb.algebra.RootSet` (None when not applicable). Exact values are kept exact
        (rationals and radicals); any other root is a 30-digit float (:meth:`RootSet.numbers`).

        The trivial equilibrium makes the system positive-dimensional (any frequency correction
        solves it there), so an unknown amplitude of the phase coordinate is required non-zero
        (Rabinowitsch: a new unknown w with w * amplitude = 1).
        """
        if any(e.free_symbols - set(unknowns) for e in eqs):
            return None, None
        if any(e.has(sp.Float) for e in eqs):
            return None, None
        system, variables = [rational_form(e) for e in eqs], list(unknowns)
        phase_amplitude = generating.cos_amplitudes[self.phase]
        if (
            self.phase_amplitude_nonzero()
            and isinstance(phase_amplitude, sp.Symbol)
            and phase_amplitude in unknowns
        ):
            inverse = sp.Dummy("w")
            system.append(inverse * phase_amplitude - 1)
            variables = [inverse, *variables]
        try:
            found = certified_real_roots(
                system, variables, seconds=self.solve_seconds, pairs=amplitude_pairs(generating)
            )
        except InvalidSystemError:
            return None, None
        if found.status is not RootStatus.SOLVED:
            return ([] if found.status is RootStatus.NO_REAL_ROOT else None), found
        roots = [{s: root[s] for s in unknowns} for root in found.numbers()]
        # Largest values first, the last unknown deciding first (the order of the former
        # numeric route: in-phase before anti-phase when the phase amplitudes tie).
        roots.sort(key=lambda r: [-float(r[s]) for s in reversed(unknowns)])
        return roots, found

    def _given_branch_values(self, unknowns) -> dict:
        selector = self.branch
        if not isinstance(selector, Mapping):
            return {}
        given = {
            sp.Symbol(name) if isinstance(name, str) else name: sp.sympify(value)
            for name, value in selector.items()
        }
        return {s: v for s, v in given.items() if s in unknowns}

    def _solve_with_branch_values(self, eqs, unknowns, k) -> dict | None:
        """When sympy cannot enumerate the roots, take the generating amplitudes from ``branch``.

        The amplitudes the user gives are put in, the remaining unknowns (frequency corrections)
        solved for, and every condition checked at the result; ``None`` if ``branch`` gives no
        amplitude of these equations.
        """
        given = self._given_branch_values(unknowns)
        if not given:
            return None
        reduced = [e for e in (sp.expand(e.xreplace(given)) for e in eqs) if e != 0]
        rest = sorted(
            set().union(set(), *(e.free_symbols for e in reduced)) & set(unknowns), key=str
        )
        solution = dict(given)
        if rest:
            roots = solve_bounded(reduced, rest, self.solve_seconds)
            if not roots:
                raise OrderFailed(
                    Status.INCONSISTENT,
                    f"order {k}: with the amplitudes of `branch` {self.branch} the conditions "
                    f"{reduced} have no solution",
                )
            solution.update(roots[0])
        residual = [e for e in eqs if not vanishes(e.xreplace(solution))]
        if residual:
            raise OrderFailed(
                Status.INCONSISTENT,
                f"order {k}: the amplitudes of `branch` {self.branch} do not satisfy {residual}",
            )
        return solution

    # ------------------------------------------------------------------ branch choice
    def _choose_branch(self, roots, unknowns, generating, open_unknowns) -> dict:
        selector = self.branch
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
            amplitude_syms = _amplitude_symbols(generating)
            for root in roots:
                # A root that fixes no generating amplitude leaves the choice to a later order. A root
                # that fixes some but leaves a wanted one free is a continuous family: the user's
                # value picks its member (only the generating amplitude: the corrections stay free
                # for the later orders to fix).
                extra = {}
                if amplitude_syms & set(root):
                    extra = {
                        s: v for s, v in wanted.items() if s in open_unknowns and s not in root
                    }
                candidate = {s: sp.sympify(v).xreplace(extra) for s, v in root.items()}
                candidate.update(extra)
                if all(
                    is_zero(candidate[s] - v)
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
        phase_amp = self.size(generating)

        def key(root):
            value = sp.sympify(phase_amp).xreplace(root)
            try:
                return -float(value.evalf(subs=probe_values(value)))
            except (TypeError, ValueError):
                return 0.0

        return sorted(pool, key=key)[0]


def amplitude_pairs(generating: GeneratingSolution) -> tuple:
    """Each coordinate's (cosine, sine) generating amplitudes, in the coordinates' order: the
    certified solver cuts the amplitude equations with their frequency-free combinations."""
    return tuple(zip(generating.cos_amplitudes, generating.sin_amplitudes, strict=True))


def _amplitude_symbols(generating: GeneratingSolution) -> set:
    return {
        s
        for s in (*generating.cos_amplitudes, *generating.sin_amplitudes)
        if isinstance(s, sp.Symbol)
    }


def _solve_linear(eqs, unknowns, k) -> dict:
    matrix, rhs = sp.linear_eq_to_matrix(eqs, unknowns)
    try:
        result = sp.linsolve((matrix, rhs), unknowns)
    except (NotImplementedError, ZeroDivisionError, ValueError) as exc:
        raise OrderFailed(
            Status.INCONSISTENT, f"order {k}: the linear periodicity conditions failed: {exc}"
        ) from None
    if result == sp.S.EmptySet:
        raise OrderFailed(
            Status.INCONSISTENT,
            f"order {k}: the linear periodicity conditions have no solution",
            compatibility_conditions(matrix, rhs),
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


def compatibility_conditions(matrix: sp.Matrix, rhs: sp.Matrix) -> tuple:
    """What the parameters must satisfy for ``matrix @ u = rhs`` to have a solution.

    For each vector ``y`` of the left null space of ``matrix`` (over the rational functions of
    its parameters), ``y . rhs`` must vanish: the numerator of each non-zero one, as a factored
    polynomial without constant factors. Empty when the system is solvable for generic
    parameters. These are the conditions a degenerate family's free amplitudes must meet (the
    directions of Hénon–Heiles's straight and bowed orbits, selected at order 4).
    """
    out = []
    for y in matrix.T.nullspace():
        value = sp.together(sp.expand((y.T * rhs)[0]))
        numerator = sp.numer(value)
        if numerator == 0:
            continue
        _, factors = sp.factor_list(sp.expand(numerator))
        poly = sp.Mul(*(f for f, _ in factors if f.free_symbols))
        if poly != 1 and poly.free_symbols:
            out.append(poly)
    return tuple(out)


# ---------------------------------------------------------------------- root finders
def groebner_real_roots(eqs, unknowns) -> list[dict]:
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
            value = exact_if_close(z.real)
            scale = lambda q: max([1.0, *(abs(complex(c)) for c in q.all_coeffs())])  # noqa: E731
            if all(abs(complex(q.eval(value))) <= ROOT_RESIDUAL * scale(q) for q in candidates):
                assignment[var] = value
                descend(index - 1, assignment)
                del assignment[var]

    descend(len(unknowns) - 1, {})
    return found
