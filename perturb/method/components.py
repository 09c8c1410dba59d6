"""Every solution of the amplitude equations: isolated roots and positive-dimensional components.

sympy's ``solve`` loses components of under-determined polynomial systems (on
``[Ω₁a, Ω₁c, Ω₁d]`` it returns only ``a = c = d = 0``, not the plane ``Ω₁ = 0``), which hides the
continuous families of conservative systems. This module splits the solution set first:

1. a Groebner basis of the equations; any basis polynomial that factors splits the set into one
   part per factor (recursively), so each part is given by irreducible polynomials;
2. parts contained in another part are dropped (ideal membership);
3. each part's dimension and free amplitudes come from a maximal independent set of the
   generating amplitudes (no polynomial of the part's ideal involves only them), chosen in the
   caller's order of preference;
4. the part is solved by sympy ``solve`` for the other unknowns, the free ones kept as parameters
   (within a time budget); every root is checked against the original equations.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from perturb._defaults import NUMERIC_ZERO, PROBE_DIGITS
from perturb.algebra.budget import solve_bounded
from perturb.algebra.certified import certified_real_roots
from perturb.algebra.msolve import install_advice
from perturb.algebra.rootset import RootStatus
from perturb.errors import InvalidSystemError
from perturb.method.component import Component
from perturb.method.exact import probe_values, rational_form, vanishes

__all__ = [
    "Component",
    "ContinuumUnwritten",
    "components_or_failed",
    "same_component",
    "solution_components",
]


def _factors(poly: sp.Expr, unknowns: Sequence[sp.Symbol]) -> list[sp.Expr]:
    """The distinct non-constant irreducible factors of ``poly`` in ``unknowns``."""
    _, factors = sp.factor_list(poly, *unknowns)
    wanted = set(unknowns)
    return [f for f, _ in factors if f.free_symbols & wanted]


def _split(eqs: list, unknowns: list, depth: int = 0) -> list[list]:
    """Generators of the irreducible parts of ``eqs = 0`` (possibly with redundant parts)."""
    basis = sp.groebner(eqs, *unknowns, order="grevlex")
    if list(basis.exprs) == [1]:
        return []
    generators = list(basis.exprs)
    for index, poly in enumerate(generators):
        factors = _factors(poly, unknowns)
        if len(factors) > 1 and depth < len(unknowns) * 4:
            parts = []
            for factor in factors:
                parts.extend(_split([*generators, factor], unknowns, depth + 1))
            return parts
        if len(factors) == 1 and sp.expand(factors[0] - poly) != 0:
            generators[index] = factors[0]  # the radical: drop constants and multiplicities
    return [generators]


def _contains(outer: list, inner_basis, unknowns) -> bool:
    """Whether the variety of ``inner_basis`` lies inside the variety of ``outer``."""
    inner = list(inner_basis.exprs)
    return all(sp.expand(sp.reduced(g, inner, *unknowns, order="grevlex")[1]) == 0 for g in outer)


def _independent(basis_exprs: list, unknowns: list, subset: list) -> bool:
    """No polynomial of the ideal involves only ``subset`` (lex elimination with subset last)."""
    rest = [u for u in unknowns if u not in subset]
    lex = sp.groebner(basis_exprs, *rest, *subset, order="lex")
    chosen = set(subset)
    return not any(
        (sp.sympify(g).free_symbols & set(unknowns)) <= chosen
        for g in lex.exprs
        if sp.sympify(g) != 0
    )


def _is_real(value: sp.Expr) -> bool:
    """Whether ``value`` is real at the generic point of :func:`probe_values` (30 digits)."""
    value = sp.sympify(value)
    if value.is_real:
        return True
    number = sp.N(value.xreplace(probe_values(value)), PROBE_DIGITS)
    try:
        return abs(complex(number).imag) <= NUMERIC_ZERO * max(1.0, abs(complex(number)))
    except TypeError:  # a function sympy cannot evaluate: keep the root
        return True


def solution_components(
    eqs: list, unknowns: list, preference: list, seconds: float, pairs=()
) -> list[Component]:
    """Every root of ``eqs = 0``: isolated ones and positive-dimensional parts.

    Parameters
    ----------
    eqs : list of sympy expressions
        Polynomials in ``unknowns`` (other symbols are parameters).
    unknowns : list of sympy.Symbol
        What to solve for.
    preference : list of sympy.Symbol
        The amplitudes that may stay free, most preferred first (a part of dimension d keeps the
        first d of them that are independent on it).
    seconds : float
        Time budget of each sympy ``solve``.
    pairs : sequence of (sympy.Symbol, sympy.Symbol), optional
        Each coordinate's (cosine, sine) amplitudes, handed to the certified solver.

    Returns
    -------
    list of Component
        Real roots (at generic positive parameter values) that satisfy every equation, in the
        order found.

    Raises
    ------
    TimeoutError
        When sympy (or the certified solver) cannot solve a part within ``seconds``.
    """
    unknowns = list(unknowns)
    # Numeric coefficients: the certified solver first (every real root, or a proof there is
    # none); a continuum or a system with parameters goes on to the Groebner parts below.
    try:
        isolated = _certified(eqs, unknowns, seconds, pairs)
    except _Continuum as continuum:
        try:
            return _grouped(eqs, unknowns, preference, seconds)
        except TimeoutError:
            raise ContinuumUnwritten(continuum.found.describe_continua()) from None
    if isolated is not None:
        return [Component(values=root, free=()) for root in isolated]
    return _grouped(eqs, unknowns, preference, seconds)


def components_or_failed(
    k, eqs, unknowns, preference, seconds, pairs=(), scale=None, amplitudes=()
) -> list[Component]:
    """:func:`solution_components` for the order-by-order template: what stops it becomes an
    :class:`~perturb.method.conditions.OrderFailed` whose status says what happened.

    ``scale``: an amplitude known not to vanish on the roots wanted (the phase amplitude of a
    pass), ``amplitudes`` the generating amplitudes: weighted-homogeneous equations are then
    solved with ``scale`` = 1 and every root is a continuum in it
    (:func:`perturb.method.projective.projective_components`)."""
    from perturb.algebra.size import SystemSize
    from perturb.method.conditions import OrderFailed
    from perturb.method.projective import Partial, projective_components
    from perturb.solution import Status

    try:
        found = None
        if scale is not None:
            found = projective_components(eqs, unknowns, scale, amplitudes, seconds, pairs)
            if found is not None and not isinstance(found, Partial):
                return found
        others = solution_components(eqs, unknowns, preference, seconds, pairs)
        if not found:
            return others
        return [*found, *(c for c in others if not any(same_component(c, f) for f in found))]
    except ContinuumUnwritten as exc:
        raise OrderFailed(
            Status.UNDETERMINED,
            f"order {k}: the amplitude equations have a continuum of roots (proved: {exc}) "
            f"that was not written within {seconds:g} s: raise solve_seconds=... or fix its "
            "free amplitudes with `amplitudes=`",
        ) from None
    except TimeoutError:
        size = SystemSize.of([rational_form(e) for e in eqs], unknowns)
        raise OrderFailed(
            Status.SOLVER_BUDGET,
            f"order {k}: the amplitude equations ({size}) could not be solved within "
            f"{seconds:g} s: raise it with solve_seconds=...{install_advice()}",
        ) from None
    except (sp.PolynomialError, NotImplementedError, ValueError) as exc:
        raise OrderFailed(
            Status.NO_ROOT,
            f"order {k}: the amplitude equations {eqs} could not be split into their "
            f"components ({type(exc).__name__}: {exc})",
        ) from None


def same_component(first: Component, second: Component) -> bool:
    """Whether two components are the same root (the same free amplitudes and values)."""
    if set(first.free) != set(second.free) or set(first.values) != set(second.values):
        return False
    return all(vanishes(sp.expand(first.values[u] - second.values[u])) for u in first.values)


def _grouped(eqs, unknowns, preference, seconds) -> list[Component]:
    """The components by Groebner parts, each solved with its free amplitudes as parameters."""
    polys, back = _polynomial_form(eqs, set(unknowns))
    components = [
        Component(
            values={s: sp.sympify(v).xreplace(back) for s, v in c.values.items()}, free=c.free
        )
        for c in _components(polys, unknowns, preference, seconds)
    ]
    return [c for c in components if all(vanishes(sp.expand(e.xreplace(c.values))) for e in eqs)]


class _Continuum(Exception):  # noqa: N818 - a signal between two functions, not an error
    def __init__(self, found):
        super().__init__(found.message)
        self.found = found


class ContinuumUnwritten(TimeoutError):
    """The certified solver proved a continuum (its dimension and free amplitudes are the
    message) but the Groebner parts did not write it within the budget."""


def _polynomial_form(eqs: list, unknowns: set) -> tuple[list, dict]:
    """Numerators of ``eqs`` with every non-polynomial constant (``sqrt(1 - g**2)``, ``pi``) named.

    Groebner bases need polynomials over a field of rational functions of the parameters; radicals of
    the parameters are replaced by new symbols (``back`` maps them back).
    """
    atoms = set()
    for e in eqs:
        for atom in sp.sympify(e).atoms(sp.Pow, sp.Function, sp.NumberSymbol):
            if atom.free_symbols & unknowns:
                continue
            if atom.is_Pow and atom.exp.is_Integer:
                continue
            atoms.add(atom)
    names = {atom: sp.Dummy(f"c{i}") for i, atom in enumerate(sorted(atoms, key=str))}
    polys = []
    for e in eqs:
        numerator, _ = sp.fraction(sp.together(sp.sympify(e).xreplace(names)))
        polys.append(sp.expand(numerator))
    return polys, {d: atom for atom, d in names.items()}


def _certified(part: list, targets: list, seconds: float, pairs=()) -> list[dict] | None:
    """The real roots of a part with numeric coefficients, certified (None: not that, or not
    decided). Exact where they are rationals or radicals, else 30-digit floats."""
    part = [rational_form(g) for g in part]
    if any(sp.sympify(g).free_symbols - set(targets) for g in part):
        return None
    try:
        found = certified_real_roots(part, targets, seconds=seconds, pairs=pairs)
    except InvalidSystemError:  # irrational coefficients: the Groebner parts take it
        return None
    if found.status is RootStatus.NO_REAL_ROOT:
        return []
    if found.status is RootStatus.BUDGET_EXCEEDED:
        raise TimeoutError(found.message)
    if found.status is RootStatus.POSITIVE_DIMENSIONAL:
        raise _Continuum(found)
    if found.status is not RootStatus.SOLVED:
        return None
    return found.numbers()


def _components(eqs, unknowns, preference, seconds) -> list[Component]:
    parts = _split(eqs, unknowns)
    unique: list[tuple[list, object]] = []
    seen = set()
    for basis in (sp.groebner(p, *unknowns, order="grevlex") for p in parts):
        key = tuple(sorted(str(g) for g in basis.exprs))
        if key not in seen:
            seen.add(key)
            unique.append((list(basis.exprs), basis))
    maximal = [
        (part, basis)
        for i, (part, basis) in enumerate(unique)
        if not any(
            j != i and _contains(other, basis, unknowns) and not _contains(part, b2, unknowns)
            for j, (other, b2) in enumerate(unique)
        )
    ]
    components = []
    for part, _ in maximal:
        free: list = []
        for candidate in preference:
            if candidate in unknowns and _independent(part, unknowns, [*free, candidate]):
                free.append(candidate)
        targets = [u for u in unknowns if u not in free]
        try:
            roots = _certified(part, targets, seconds) if targets and not free else None
        except _Continuum:  # the part's free unknowns were not all found: sympy below
            roots = None
        if roots is None:
            roots = solve_bounded(part, targets, seconds) if targets else [{}]
        for root in roots:
            root = {s: v for s, v in root.items() if s in targets}
            if not all(_is_real(v) for v in root.values()):
                continue
            components.append(Component(values=root, free=tuple(free)))
    return components
