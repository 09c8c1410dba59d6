"""Families of periodic solutions: every root of the amplitude equations, named and carried to order N.

A system's amplitude equations — the periodicity conditions of the first order that involves the
generating amplitudes — may have isolated roots (limit cycles), continua (the conservative
families: an amplitude stays free), and, in a system of several resonant coordinates, several of
each. :func:`find_families` finds them all, gives each a stable user-facing name
(:mod:`perturb.method.family_names`) and carries each to the requested order with the ordinary
construction, reporting its status (``SUCCESS``, ``INCONSISTENT`` at order k, ``UNDETERMINED``
with the unknowns left open).

How
---
1. **Passes over the phase coordinate.** The phase of an autonomous solution is fixed by making
   the velocity of the *phase coordinate* vanish at t = 0, which presumes that this coordinate
   oscillates. A family on which it is identically zero (Hénon–Heiles's y-axis orbit, x ≡ 0) leaves
   the phase unfixed, and one unknown stays open at every order. So, unless the options fix the
   phase coordinate (``phase_coordinate`` or ``amplitudes``), there is one pass per coordinate p:
   the generating amplitudes of the resonant coordinates before p are set to zero and p's own
   amplitude is required non-zero. Every family is found in exactly one pass: the one of its first
   oscillating coordinate.
2. **The family order.** The construction runs order by order. At each order whose conditions
   involve unknown generating amplitudes, every solution component is computed
   (:func:`~perturb.method.components.solution_components`: isolated roots and continua — sympy's
   ``solve`` alone loses continua). The trivial equilibrium and the components on which the phase
   amplitude vanishes are discarded. An order whose single component neither fixes an amplitude nor
   depends on one (Hénon–Heiles at order 1: Ω₁ = 0 for every amplitude) is solved and passed; the
   first other one is the family order, and each of its components is a family.
3. **Carrying a family.** The construction is run again in the same frame, with the family's
   root put in at the family order. Its free amplitudes become user-facing parameters (``a_x``:
   the cosine amplitude of ``x``, ``b_y``: the sine amplitude of ``y``, added to the system's
   ``parameters``) and their corrections at later orders are set to zero (a normalisation: a
   correction of a free amplitude is a change of the family member). Every later order is solved by
   the ordinary :class:`~perturb.method.conditions.ConditionSolver`.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

import attrs
import sympy as sp

from perturb._defaults import MAX_RESTRICTIONS, PROBE_ORDERS, SOLVE_SECONDS
from perturb.errors import InvalidSystemError, bad_value
from perturb.method.components import (
    Component,
    components_or_failed,
    same_component,
    solution_components,
)
from perturb.method.conditions import ConditionSolver, OrderFailed, amplitude_pairs
from perturb.method.construction import OrderByOrder
from perturb.method.exact import is_zero
from perturb.method.family import CONTINUUM, ISOLATED, Family, FamilyList
from perturb.method.family_names import name_families
from perturb.method.options import check_system
from perturb.method.poincare import PoincareMethod
from perturb.method.projective import (
    exact_modes,
    exact_or,
    is_exact,
    rescaled,
    scaling_degree,
)
from perturb.method.shifts import distinct_components
from perturb.method.straight import straight_orbit
from perturb.solution import PeriodicSolution, Status
from perturb.system import QuasilinearSystem

__all__ = ["Family", "FamilyList", "find_families"]


class _Found(Exception):
    """Raised by the probing solver at the family order (internal)."""

    def __init__(self, k: int, components: list[Component]):
        super().__init__(k)
        self.k, self.components = k, components


def _user_name(symbol: sp.Symbol) -> str:
    """``a_x0`` -> ``a_x``: the generating amplitude's user-facing name."""
    return symbol.name[:-1]


def _correction_of(symbol: sp.Symbol, free_names: set[str]) -> bool:
    """Whether ``symbol`` is a correction ``a_x1, a_x2, ...`` of a free amplitude ``a_x``."""
    for free in free_names:
        match = re.fullmatch(rf"{re.escape(free)}(\d+)", symbol.name)
        if match and int(match.group(1)) >= 1:
            return True
    return False


@attrs.define
class _FamilySolver:
    """The construction's condition solver, probing for the families (or carrying one).

    Before the family order it solves the conditions as the ordinary solver would, except that the
    generating amplitudes of ``zeros`` vanish; at the family order it raises :class:`_Found` with every
    admissible component, or, carrying ``target``, puts that component in; after it, the
    corrections of the free amplitudes are set to zero and the ordinary solver does the rest.
    """

    inner: ConditionSolver
    zeros: dict
    phase_amplitude: object
    seconds: float
    target: Component | None = None
    family_order: int | None = None
    system: object = None
    renames: dict = attrs.Factory(dict)

    def solve(self, k, eqs, open_unknowns, generating, solved):
        extra = {s: v for s, v in self.zeros.items() if s in open_unknowns}
        if self.family_order is not None and k > self.family_order:
            names = {s.name for s in self.renames.values()}
            extra.update({u: sp.S.Zero for u in open_unknowns if _correction_of(u, names)})
        eqs = [e for e in (sp.expand(e.xreplace(extra)) for e in eqs) if e != 0]
        open_now = set(open_unknowns) - set(extra)
        amplitudes = _amplitude_symbols(generating) & open_now
        involved = set().union(set(), *(e.free_symbols for e in eqs)) & open_now
        if not eqs:
            return extra, ()
        if self.target is not None and k == self.family_order:
            values = {
                s: sp.sympify(v).xreplace(self.renames) for s, v in self.target.values.items()
            }
            return {**extra, **values, **self.renames}, ()
        if not involved & amplitudes:
            solution, branches = self.inner.solve(k, eqs, open_now, generating, solved)
            return {**extra, **solution}, branches
        unknowns = sorted(involved, key=str)
        preference = _preference(generating, involved)
        found = components_or_failed(
            k, eqs, unknowns, preference, self.seconds, amplitude_pairs(generating),
            scale=self.phase_amplitude, amplitudes=_amplitude_symbols(generating),
        )  # fmt: skip
        known = {**solved, **extra}
        modes = exact_modes(self.system, generating, known, self.phase_amplitude, unknowns, eqs,
                            self.seconds) if self.system is not None else []  # fmt: skip
        found = [*found, *(m for m in modes if not any(same_component(m, c) for c in found))]
        components = [c for c in found if self._admissible(c, generating, known)]
        if not components:
            raise OrderFailed(
                Status.NO_ROOT,
                f"order {k}: the amplitude equations {eqs} have only the trivial root",
            )
        if len(components) == 1 and _passive(components[0], amplitudes & involved):
            return {**extra, **components[0].values}, ()
        raise _Found(k, distinct_components(components, generating, {**solved, **extra}))

    def _admissible(self, component, generating, solved) -> bool:
        def value(a):
            return sp.sympify(a).xreplace(solved).xreplace(component.values)

        amplitudes = [value(a) for a in (*generating.cos_amplitudes, *generating.sin_amplitudes)]
        if all(is_zero(a) for a in amplitudes):
            return False  # the trivial equilibrium
        return self.phase_amplitude is None or not is_zero(value(self.phase_amplitude))


def _passive(component: Component, amplitudes: set) -> bool:
    """A component that neither fixes an amplitude nor depends on one (order passed)."""
    if not amplitudes <= set(component.free):
        return False
    return not any(sp.sympify(v).free_symbols & amplitudes for v in component.values.values())


def _amplitude_symbols(generating) -> set:
    return {
        s
        for s in (*generating.cos_amplitudes, *generating.sin_amplitudes)
        if isinstance(s, sp.Symbol)
    }


def _preference(generating, involved: set) -> list:
    """Which amplitudes stay free on a continuum: the phase amplitude, cosines, then sines."""
    phase = generating.coordinates.index(generating.phase_coordinate)
    cosines = list(generating.cos_amplitudes)
    ordered = [cosines[phase], *cosines[:phase], *cosines[phase + 1 :], *generating.sin_amplitudes]
    return [s for s in ordered if isinstance(s, sp.Symbol) and s in involved]


def _method(order: int, options: Mapping, phase: str | None) -> PoincareMethod:
    opts = dict(options)
    if phase is not None:
        opts["phase_coordinate"] = phase
    return PoincareMethod(order=order, cache=False, **opts)


def _runner(
    method: PoincareMethod, system: QuasilinearSystem, passes: bool, **solver_options
) -> OrderByOrder:
    runner = OrderByOrder(method, system)
    zeros, phase_amplitude = _frame(runner, passes)
    runner.solver = _FamilySolver(
        inner=runner.solver,
        zeros=zeros,
        phase_amplitude=phase_amplitude,
        seconds=method.solve_seconds,
        system=system,
        **solver_options,
    )
    return runner


def _frame(runner: OrderByOrder, passes: bool) -> tuple[dict, object]:
    """Generating amplitudes forced to zero (resonant coordinates before the phase coordinate,
    in a pass over the phase coordinates) and the phase amplitude's symbol (None when given)."""
    zeros = {}
    if passes:
        for i in range(runner.phase):
            if runner.harmonics[i] is not None:
                name = runner.names[i]
                zeros.update(
                    {sp.Symbol(f"a_{name}0"): sp.S.Zero, sp.Symbol(f"b_{name}0"): sp.S.Zero}
                )
    phase_amplitude = (
        None if runner.phase in runner.given else sp.Symbol(f"a_{runner.names[runner.phase]}0")
    )
    return zeros, phase_amplitude


def _member_choices(system: QuasilinearSystem, options: Mapping) -> dict[str, sp.Expr]:
    """Given amplitudes that are a free parameter of the system: a member of a continuum."""
    amplitudes = dict(options.get("amplitudes") or {})
    return {
        f"a_{name}": sp.sympify(v)
        for name, v in amplitudes.items()
        if isinstance(sp.sympify(v), sp.Symbol) and sp.sympify(v) in system.parameters
    }


def _readable(value) -> sp.Expr:
    """An amplitude as users read it: simplified (a root in radicals can come back unsimplified)."""
    value = sp.sympify(value)
    return value if value.is_Atom else sp.simplify(value)


def _describe(solution: PeriodicSolution, free_names: tuple, members: dict) -> tuple[dict, tuple]:
    """User-facing amplitudes of a carried family and the names of its free ones."""
    generating = solution.generating
    amplitudes = {}
    for i, name in enumerate(generating.coordinates):
        if generating.harmonics[i] is None:
            continue
        amplitudes[f"a_{name}"] = _readable(generating.cos_amplitudes[i])
        if name != generating.phase_coordinate:
            amplitudes[f"b_{name}"] = _readable(generating.sin_amplitudes[i])
    free = tuple(free_names) + tuple(n for n in members if n not in free_names)
    return amplitudes, free


def _carry(system, order, options, phase, k, component, members) -> tuple:
    """The family of ``component`` carried to ``order``: (amplitudes, free, solution, failure).

    A continuum in the phase amplitude alone of a system that scales with its amplitude
    (:func:`perturb.method.projective.scaling_degree`) is carried at amplitude 1 and rescaled:
    the same series, exactly, at the cost of one numeric amplitude."""
    passes = phase is not None
    degree = scaling_degree(system) if passes else None
    if degree is not None and len(component.free) == 1:
        scale = component.free[0]
        user = sp.Symbol(_user_name(scale))
        if scale == sp.Symbol(f"{user.name}0") and user.name == f"a_{phase}":
            at_one = {u: sp.sympify(v).xreplace({scale: 1}) for u, v in component.values.items()}
            fixed = {**options, "amplitudes": {phase: 1}}
            runner = _runner(
                _method(order, fixed, phase), system, passes, target=Component(at_one, ()),
                family_order=k,
            )  # fmt: skip
            note = (
                f"derived at {user} = 1 and scaled (the system is homogeneous of degree {degree})"
            )
            solution = rescaled(exact_or(runner.run(), system, order), user, degree, note)
            amplitudes, free = _describe(solution, (user.name,), members)
            return amplitudes, free, solution, runner.failure
    renames = {s: sp.Symbol(_user_name(s)) for s in component.free}
    carried_system = attrs.evolve(system, parameters=(*system.parameters, *renames.values()))
    runner = _runner(
        _method(order, options, phase),
        carried_system,
        passes,
        target=component,
        family_order=k,
        renames=renames,
    )
    solution = exact_or(runner.run(), system, order)
    names = tuple(s.name for s in renames.values())
    amplitudes, free = _describe(solution, names, members)
    return amplitudes, free, solution, runner.failure


def _restriction(solution, failure, component) -> tuple:
    """The conditions a later order puts on a continuum's free amplitudes (empty: none)."""
    if not component.free or solution.status is not Status.INCONSISTENT or failure is None:
        return ()
    names = {sp.Symbol(_user_name(s)) for s in component.free}
    return tuple(c for c in failure.residual_conditions if c.free_symbols & names)


def _restricted(component: Component, conditions: tuple, phase_amplitude, seconds) -> list:
    """The components of a continuum that meet ``conditions`` (in the free amplitudes' user
    names): each with fewer free amplitudes, the phase amplitude kept free and non-zero."""
    user = {sp.Symbol(_user_name(s)): s for s in component.free}
    unknowns = sorted(user, key=lambda u: (user[u] != phase_amplitude, u.name))
    try:
        parts = solution_components(list(conditions), unknowns, unknowns, seconds)
    except (TimeoutError, sp.PolynomialError, NotImplementedError, ValueError):
        return []
    out = []
    for part in parts:
        values = {user[u]: sp.sympify(v).xreplace(user) for u, v in part.values.items()}
        if phase_amplitude in values and is_zero(values[phase_amplitude]):
            continue  # the phase coordinate at rest: another pass's family
        if all(is_zero(v) for v in values.values()) and not part.free:
            continue  # the trivial equilibrium
        merged = {u: sp.sympify(v).xreplace(values) for u, v in component.values.items()}
        merged.update(values)
        free = tuple(user[u] for u in part.free if u in user)
        out.append(Component(merged, free))
    return out


def _carry_restricted(system, order, options, phase, k, component, members, depth=0) -> list:
    """:func:`_carry`, and a continuum that later orders restrict split into what survives.

    A continuum with several free amplitudes (Hénon–Heiles's lines in every direction at order 2)
    can be a degenerate family: the conditions of a later order (there 4) hold only for some
    directions. The conditions that fail are solved for the free amplitudes (every real
    component) and each surviving family is carried on its own; a continuum carried to ``order``
    with more than one free amplitude is probed up to :data:`PROBE_ORDERS` orders further, so
    that the low orders a user asks for never report a direction that no periodic orbit has.
    """
    amplitudes, free, solution, failure = _carry(
        system, order, options, phase, k, component, members
    )
    conditions = _restriction(solution, failure, component)
    if not conditions and solution.success and len(component.free) > 1:
        for probe in range(order + 1, order + PROBE_ORDERS + 1):
            _, _, probed, probe_failure = _carry(
                system, probe, options, phase, k, component, members
            )
            conditions = _restriction(probed, probe_failure, component)
            if conditions or not probed.success:
                break
    if not conditions or depth >= MAX_RESTRICTIONS:
        return [(amplitudes, free, solution)]
    phase_amplitude = sp.Symbol(f"a_{solution.generating.phase_coordinate}0")
    seconds = options.get("solve_seconds", SOLVE_SECONDS)
    survivors = _restricted(component, conditions, phase_amplitude, seconds)
    if not survivors:
        return [(amplitudes, free, solution)]
    out = []
    for restricted in survivors:
        out += _carry_restricted(system, order, options, phase, k, restricted, members, depth + 1)
    return out


def find_families(system: QuasilinearSystem, order: int = 1, **options) -> FamilyList:
    """Every family of periodic solutions of ``system``, each carried to ``order``.

    Parameters
    ----------
    system : QuasilinearSystem
    order : int
        The order each family's solution is carried to.
    **options
        Options of :class:`~perturb.method.poincare.PoincareMethod` that define the frame
        (``amplitudes``, ``phase_coordinate``, ``quadrature``, ``dependent_condition``,
        ``solve_seconds``); not ``branch``: the families are the branches.

    Returns
    -------
    FamilyList
        The families in canonical order with their names; empty when no non-trivial root exists.

    Raises
    ------
    InvalidSystemError
        On a bad option (as :class:`PoincareMethod` raises it), or when ``branch`` is given.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import find_families
    >>> families = find_families(vdp, order=2)
    >>> len(families.families), families.families[0].name
    (1, 'limit-cycle')
    """
    check_system(system)
    if "branch" in options:
        raise bad_value(
            "branch",
            options["branch"],
            "drop it: find_families follows every branch; select a family by its name",
            InvalidSystemError,
        )
    fixed = options.get("phase_coordinate") is not None or bool(options.get("amplitudes"))
    phases = [None] if fixed else [c.name for c in system.coordinates]
    members = _member_choices(system, options)
    found: list[tuple] = []
    family_order = None
    for phase in phases:
        method = _method(order, options, phase)
        runner = _runner(method, system, phase is not None)
        try:
            solution = runner.run()
        except _Found as exc:
            family_order = exc.k if family_order is None else min(family_order, exc.k)
            for component in exc.components:
                found += _carry_restricted(system, order, options, phase, exc.k, component, members)
            continue
        if solution.status is Status.NO_ROOT and not fixed:
            continue  # no family oscillates in this coordinate first
        amplitudes, free = _describe(solution, (), members)
        if any(not is_zero(v) for v in amplitudes.values()):
            found.append((amplitudes, free, solution))
    families = []
    described = [(a, f, straight_orbit(solution)) for a, f, solution in found]
    state = system.state_symbols
    nonlinear = any(
        not sp.sympify(f).is_polynomial(*state) or sp.Poly(f, *state).total_degree() > 1
        for f in system.rhs
    )
    for name, (amplitudes, free, solution) in zip(name_families(described), found, strict=True):
        families.append(
            Family(
                name=f"{name}-exact" if nonlinear and is_exact(solution) else name,
                kind=CONTINUUM if free else ISOLATED,
                amplitudes=amplitudes,
                free=free,
                solution=solution,
                phase_coordinate=solution.generating.phase_coordinate,
            )
        )
    families.sort(key=lambda f: _canonical_key(f))
    return FamilyList(
        system=system.name or "system",
        order=order,
        family_order=family_order,
        families=tuple(families),
    )


def _canonical_key(family: Family) -> tuple:
    return (family.kind != ISOLATED, family.name)
