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
from collections.abc import Iterator, Mapping

import attrs
import sympy as sp
from attrs import field, frozen

from perturb._defaults import MAX_RESTRICTIONS, PROBE_ORDERS, SOLVE_SECONDS
from perturb.errors import InvalidSystemError, UnknownNameError, bad_value
from perturb.method.components import Component, components_or_failed, solution_components
from perturb.method.conditions import ConditionSolver, OrderFailed, amplitude_pairs
from perturb.method.construction import OrderByOrder
from perturb.method.exact import is_zero
from perturb.method.family_names import name_families
from perturb.method.options import check_system
from perturb.method.poincare import PoincareMethod
from perturb.solution import PeriodicSolution, Status
from perturb.system import QuasilinearSystem

__all__ = ["Family", "FamilyList", "find_families"]

#: The two kinds of family, as reported to users.
ISOLATED, CONTINUUM = "isolated", "continuum"


@frozen
class Family:
    """One family of periodic solutions and its solution carried to the requested order.

    Parameters
    ----------
    name : str
        Stable user-facing name (see :mod:`perturb.method.family_names`).
    kind : {"isolated", "continuum"}
        ``isolated``: the amplitude equations fix every generating amplitude; ``continuum``: some
        stay free (named in ``free``), or the options fix them to a free parameter of the system.
    amplitudes : dict[str, sympy.Expr]
        The generating amplitudes that select the family: ``a_x`` (cosine amplitude of ``x``, i.e.
        x(0) at order 0), ``b_y`` (sine amplitude of ``y``); values may depend on the free ones.
    free : tuple of str
        The free amplitudes of a continuum, by their user-facing names (empty when isolated).
    solution : PeriodicSolution
        The family carried to the requested order (its ``status`` and ``message``). Free
        amplitudes are parameters of ``solution.system`` under their user-facing names.
    phase_coordinate : str
        The coordinate whose velocity vanishes at t = 0 on this family.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import find_families
    >>> family = find_families(vdp, order=2).families[0]
    >>> family.name, family.kind, family.amplitudes
    ('limit-cycle', 'isolated', {'a_x': 2})
    """

    name: str
    kind: str = field(validator=attrs.validators.in_((ISOLATED, CONTINUUM)))
    amplitudes: dict = field(converter=dict)
    free: tuple = field(converter=tuple)
    solution: PeriodicSolution = field(eq=False, repr=False)
    phase_coordinate: str = ""

    @property
    def status(self) -> Status:
        return self.solution.status

    @property
    def message(self) -> str:
        return self.solution.message or self.solution.status.value

    @property
    def frequency(self) -> tuple:
        """Ω₀, Ω₁, … as far as they are determined."""
        return self.solution.frequency


@frozen
class FamilyList:
    """Every family of periodic solutions of a system, in canonical order (see the module notes).

    Parameters
    ----------
    system : str
        The system's name.
    order : int
        The order each family was carried to.
    family_order : int or None
        The first order whose conditions select the families (None: the options fixed every
        generating amplitude, so there is one family, the given one).
    families : tuple of Family

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import find_families
    >>> families = find_families(vdp, order=2)
    >>> [family.name for family in families]
    ['limit-cycle']
    """

    system: str
    order: int
    family_order: int | None
    families: tuple = field(converter=tuple)

    def __iter__(self) -> Iterator[Family]:
        return iter(self.families)

    def __len__(self) -> int:
        return len(self.families)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.families)

    def get(self, name: str) -> Family:
        """The family called ``name``; :class:`UnknownNameError` listing the known names."""
        for family in self.families:
            if family.name == name:
                return family
        raise UnknownNameError(
            f"`family` = {name!r} is unknown for {self.system}: choose from {list(self.names)}"
        )


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
            k, eqs, unknowns, preference, self.seconds, amplitude_pairs(generating)
        )
        components = [c for c in found if self._admissible(c, generating, {**solved, **extra})]
        if not components:
            raise OrderFailed(
                Status.NO_ROOT,
                f"order {k}: the amplitude equations {eqs} have only the trivial root",
            )
        if len(components) == 1 and _passive(components[0], amplitudes & involved):
            return {**extra, **components[0].values}, ()
        raise _Found(k, _distinct(components, generating, {**solved, **extra}))

    def _admissible(self, component, generating, solved) -> bool:
        def value(a):
            return sp.sympify(a).xreplace(solved).xreplace(component.values)

        amplitudes = [value(a) for a in (*generating.cos_amplitudes, *generating.sin_amplitudes)]
        if all(is_zero(a) for a in amplitudes):
            return False  # the trivial equilibrium
        return self.phase_amplitude is None or not is_zero(value(self.phase_amplitude))


def _distinct(components: list, generating, solved: dict) -> list:
    """Drop components that are another one shifted by half a period.

    ``s -> s + pi`` changes the sign of every amplitude of odd harmonic: van der Pol's roots
    ``a_x = 2`` and ``a_x = -2`` are one limit cycle. On a continuum the free amplitudes change sign
    with their harmonic, which is a change of parameter. Of two such components the one whose
    phase amplitude is positive (else: whose amplitudes read first) is kept.
    """
    symbols = (*generating.cos_amplitudes, *generating.sin_amplitudes)
    signs = [(-1) ** (m or 0) for m in generating.harmonics] * 2

    def amplitudes(component, shift):
        flip = {}
        if shift:
            flip = {
                f: -f
                for f in component.free
                for sym, sign in zip(symbols, signs, strict=True)
                if sym == f and sign < 0
            }
        values = []
        for sym, sign in zip(symbols, signs, strict=True):
            value = sp.sympify(sym).xreplace(solved).xreplace(component.values).xreplace(flip)
            values.append(sign * value if shift else value)
        return values

    def same(first, second):
        return all(is_zero(a - b) for a, b in zip(first, second, strict=True))

    phase = generating.coordinates.index(generating.phase_coordinate)

    def key(component):
        lead = amplitudes(component, False)[phase]
        negative = lead.is_number and bool(lead < 0)
        return (negative, str(amplitudes(component, False)))

    ordered = sorted(components, key=key)
    kept: list = []
    for component in ordered:
        shifted = amplitudes(component, True)
        if not any(same(shifted, amplitudes(other, False)) for other in kept):
            kept.append(component)
    return kept


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
    """The family of ``component`` carried to ``order``: (amplitudes, free, solution, failure)."""
    passes = phase is not None
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
    solution = runner.run()
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
    for name, (amplitudes, free, solution) in zip(name_families(described), found, strict=True):
        families.append(
            Family(
                name=name,
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


def straight_orbit(solution: PeriodicSolution) -> bool | None:
    """Whether the orbit stays on the line of its generating amplitudes at every order computed.

    The generating solution of a line has cosine amplitudes only (a direction ``d`` in the
    coordinates); the orbit is straight when every term of every order and harmonic is parallel
    to ``d`` (exact zero tests of the 2 x 2 minors). None when the generating solution is not a
    line (sine amplitudes, non-resonant coordinates) or the solution failed.
    """
    if not solution.success:
        return None
    generating = solution.generating
    if any(m is None for m in generating.harmonics):
        return None
    if any(not is_zero(b) for b in generating.sin_amplitudes):
        return None
    direction = [sp.sympify(a) for a in generating.cos_amplitudes]
    rows = solution.terms
    top = max(len(row) for row in rows)
    for k in range(top):
        terms = [row[k] if k < len(row) else None for row in rows]
        harmonics = {j for t in terms if t is not None for j in t.terms}
        for j in harmonics:
            for part in (0, 1):
                values = [t.coefficient(j)[part] if t is not None else 0 for t in terms]
                for i in range(len(values)):
                    for m in range(i + 1, len(values)):
                        if not is_zero(
                            sp.expand(direction[m] * values[i] - direction[i] * values[m])
                        ):
                            return False
    return True


def _canonical_key(family: Family) -> tuple:
    return (family.kind != ISOLATED, family.name)
