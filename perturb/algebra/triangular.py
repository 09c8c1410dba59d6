"""Every real root of a polynomial system with rational coefficients, exact and certified (sympy).

The route, each step exact:

1. **Linear pivots.** An unknown that appears in some equation only linearly and with a constant
   coefficient (the frequency correction Ω₁ of an amplitude system) is solved for and put into
   the others; it is recovered at the end. Fewer unknowns make the Groebner basis far cheaper.
2. **Groebner basis** in grevlex (sympy's fastest order). ``{1}``: no complex root at all
   (proved). Not zero-dimensional: the dimension and a maximal set of free unknowns are read off
   the leading monomials (the largest set no leading monomial lives in).
3. **Lexicographic basis** by FGLM; its last polynomial is univariate in the last unknown and is
   factored over ℚ. For each irreducible factor f:

   * f linear: its rational root is put in and the smaller system solved the same way;
   * f of higher degree: its real roots are **isolated** (sympy's exact intervals: each holds
     exactly one root; a factor with none proves that no real root lies over it); the other
     unknowns on that component are polynomials in the root when the component's lex basis is in
     *shape position* ``{x_i − g_i(x_n)}``; if it is not, a separating linear form
     t = x_n + 2 x_{n−1} + … is adjoined and the shape sought in t.

Each real root is thus an exact algebraic number (a rational, a radical for a quadratic, or a
polynomial in a ``CRootOf``) with the isolating interval that certifies it.
"""

from __future__ import annotations

from itertools import combinations

import sympy as sp

from perturb._defaults import SEPARATING_FORMS, TRIANGULAR_DIGITS
from perturb.algebra.rootset import RootSet, RootStatus
from perturb.algebra.size import SystemSize

__all__ = ["eliminate_linear", "exact_real_roots", "ideal_dimension"]


class _Undecided(Exception):
    """A component whose lex basis is in shape position under no form tried."""


def eliminate_linear(polys: list, unknowns: list, growth: int | None = None) -> tuple[list, list]:
    """Solve for the unknowns that appear linearly with a constant coefficient; put them in.

    Returns the remaining polynomials and ``[(unknown, expression), ...]`` in elimination order
    (each expression in the unknowns still open when it was solved for). With ``growth`` an
    integer, a pivot is put in only when the largest total degree of the others grows by at most
    that much: the frequency correction of a free system (a cubic put into the products
    Ω₁·a: 3 -> 4) is, a driven system's forced amplitude (a cubic put into cubics: 3 -> 9,
    which makes msolve's work larger, not smaller) is not.

    Examples
    --------
    >>> import sympy as sp
    >>> w, x = sp.symbols("w x")
    >>> eliminate_linear([2*w - x**2, x**2 - w - 1], [w, x])
    ([x**2/2 - 1], [(w, x**2/2)])
    """
    polys = [sp.expand(p) for p in polys if sp.expand(p) != 0]
    open_ = list(unknowns)
    eliminated: list = []
    while True:
        best = None
        for index, poly in enumerate(polys):
            for var in open_:
                if sp.degree(poly, var) != 1:
                    continue
                coefficient = poly.coeff(var, 1)
                if coefficient.free_symbols & set(open_) or coefficient == 0:
                    continue
                rest = sp.expand(poly - coefficient * var)
                if growth is not None and _growth(polys, index, var, rest) > growth:
                    continue
                value = sp.expand(-rest / coefficient)
                cost = len(sp.Add.make_args(value))
                if best is None or cost < best[0]:
                    best = (cost, index, var, value)
        if best is None:
            return polys, eliminated
        _, index, var, value = best
        polys = [sp.expand(p.xreplace({var: value})) for i, p in enumerate(polys) if i != index]
        polys = [p for p in polys if p != 0]
        open_.remove(var)
        eliminated.append((var, value))


def _growth(polys: list, index: int, var, value) -> int:
    """How much ``var = value`` put into the polynomials other than ``polys[index]`` raises
    their largest total degree (a bound read off the degrees, nothing expanded)."""
    value_degree = sp.Poly(value, *value.free_symbols).total_degree() if value.free_symbols else 0
    before = after = 0
    for i, poly in enumerate(polys):
        if i == index:
            continue
        symbols = sorted(poly.free_symbols, key=str)
        p = sp.Poly(poly, *symbols)
        before = max(before, p.total_degree())
        if var not in symbols:
            after = max(after, p.total_degree())
            continue
        k = symbols.index(var)
        after = max([after, *(sum(m) - m[k] + m[k] * value_degree for m in p.monoms())])
    return after - before


def ideal_dimension(basis_exprs: list, unknowns: list) -> tuple[int, tuple]:
    """Dimension of the solution set of a Groebner basis (grevlex), and a maximal free set.

    The dimension is the size of the largest set of unknowns that contains the variables of no
    leading monomial; the first such set (in the order of ``unknowns``) is returned.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y, z = sp.symbols("x y z")
    >>> basis = sp.groebner([x*y, x*z], x, y, z, order="grevlex")
    >>> ideal_dimension(list(basis.exprs), [x, y, z])
    (2, (y, z))
    """
    leading = []
    for g in basis_exprs:
        monomial = sp.Poly(g, *unknowns).monoms(order="grevlex")[0]
        leading.append({u for u, e in zip(unknowns, monomial, strict=True) if e})
    if any(not support for support in leading):
        return -1, ()
    for d in range(len(unknowns), -1, -1):
        for subset in combinations(unknowns, d):
            chosen = set(subset)
            if not any(support <= chosen for support in leading):
                return d, subset
    return 0, ()  # pragma: no cover - the empty set always qualifies


def _is_shape(lex: list, unknowns: list) -> bool:
    """Whether a lex basis is ``{x_i − g_i(x_n) for i < n} ∪ {f(x_n)}``."""
    if len(lex) != len(unknowns):
        return False
    last = unknowns[-1]
    for poly, var in zip(lex[:-1], unknowns[:-1], strict=True):
        rest = sp.expand(poly - poly.coeff(var, 1) * var)
        if not poly.coeff(var, 1).is_number or rest.free_symbols - {last}:
            return False
    return lex[-1].free_symbols <= {last}


def _real_roots_of(factor: sp.Expr, var: sp.Symbol) -> list[tuple]:
    """``(exact root, certificate)`` for each real root of an irreducible ``factor``."""
    poly = sp.Poly(factor, var)
    intervals = poly.intervals()
    if not intervals:
        return []
    if poly.degree() == 2:  # radicals: matched to the intervals by their order
        values = sorted((r for r in sp.roots(poly, var) if r.is_real), key=lambda r: float(r))
    else:
        values = [sp.CRootOf(poly, i) for i in range(len(intervals))]
    return [
        (value, f"{var} = root {i} of {poly.as_expr()} in [{lo}, {hi}] (exactly one root)")
        for i, (value, ((lo, hi), _)) in enumerate(zip(values, intervals, strict=True))
    ]


def _shape_roots(lex: list, unknowns: list, var: sp.Symbol, factor: sp.Expr) -> list[tuple]:
    """Roots of a shape-position component: ``var`` a root of ``factor``, the rest ``g_i(var)``."""
    out = []
    others = list(zip(lex[:-1], unknowns[:-1], strict=True))
    for value, certificate in _real_roots_of(factor, var):
        root = {}
        for poly, u in others:
            g = sp.expand(-(poly - poly.coeff(u, 1) * u) / poly.coeff(u, 1))
            g = sp.rem(g, factor, var) if sp.degree(factor, var) > 1 else g
            root[u] = sp.expand(sp.sympify(g).xreplace({var: value}))
        if var in unknowns:
            root[var] = value
        out.append((root, certificate))
    return out


def _component_roots(basis: list, unknowns: list, factor: sp.Expr) -> list[tuple]:
    """The real roots of ``basis = 0, factor(x_n) = 0``, f irreducible of degree >= 2."""
    last = unknowns[-1]
    if not sp.Poly(factor, last).intervals():
        return []  # no real value of x_n: proved by isolation
    ideal = [*basis, factor]
    lex = list(sp.groebner(ideal, *unknowns, order="grevlex").fglm("lex").exprs)
    if _is_shape(lex, unknowns):
        return _shape_roots(lex, unknowns, last, lex[-1])
    t = sp.Dummy("t")
    for k in range(2, 2 + SEPARATING_FORMS):
        form = sum(k**j * u for j, u in enumerate(reversed(unknowns)))
        variables = [*unknowns, t]
        lex = list(sp.groebner([*ideal, t - form], *variables, order="grevlex").fglm("lex").exprs)
        if not _is_shape(lex, variables):
            continue
        out = []
        _, factors = sp.factor_list(lex[-1], t)
        for f, _ in factors:
            out.extend(_shape_roots([*lex[:-1], f], variables, t, f))
        return [({u: v for u, v in root.items() if u in unknowns}, c) for root, c in out]
    raise _Undecided(f"the component over {factor} = 0 is in shape position under no form tried")


def _solve(polys: list, unknowns: list) -> list[tuple]:
    """Every real root of a zero-dimensional system: ``[(exact dict, [certificates]), ...]``."""
    polys = [p for p in (sp.expand(q) for q in polys) if p != 0]
    if not unknowns:
        return [] if polys else [({}, [])]
    if not polys:
        raise _Undecided(f"{unknowns} left free")
    basis = sp.groebner(polys, *unknowns, order="grevlex")
    if list(basis.exprs) == [1]:
        return []
    if not basis.is_zero_dimensional:
        raise _Undecided(f"a specialisation left {unknowns} with a continuum")
    lex = list(basis.fglm("lex").exprs)
    last = unknowns[-1]
    _, factors = sp.factor_list(lex[-1], last)
    found = []
    for factor, _ in factors:
        if sp.degree(factor, last) == 1:
            value = sp.solve(factor, last)[0]
            rest = [q.xreplace({last: value}) for q in lex[:-1]]
            for root, certificates in _solve(rest, unknowns[:-1]):
                found.append(({**root, last: value}, certificates))
        else:
            found.extend((root, [c]) for root, c in _component_roots(lex[:-1], unknowns, factor))
    return found


def exact_real_roots(eqs, unknowns) -> RootSet:
    """Every real root of ``eqs = 0`` (rational coefficients), exact, each one certified.

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials in ``unknowns`` with rational coefficients.
    unknowns : sequence of sympy.Symbol

    Returns
    -------
    RootSet
        SOLVED with the roots (``exact`` and floats), NO_REAL_ROOT (proved),
        POSITIVE_DIMENSIONAL (with ``dimension`` and ``free``) or UNDECIDED.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> found = exact_real_roots([x**2 + y**2 - 1, x - y], [x, y])
    >>> found.status.name, [root[x] for root in found.exact]
    ('SOLVED', [-sqrt(2)/2, sqrt(2)/2])
    >>> exact_real_roots([x**2 + 1], [x]).status.name
    'NO_REAL_ROOT'
    """
    unknowns = list(unknowns)
    size = SystemSize.of(eqs, unknowns)
    polys, eliminated = eliminate_linear(list(eqs), unknowns)
    remaining = [u for u in unknowns if u not in dict(eliminated)]

    def result(status, message="", **extra):
        return RootSet(status, (), unknowns, message, size=size, backend="sympy", **extra)

    if remaining and polys:
        basis = sp.groebner(polys, *remaining, order="grevlex")
        if list(basis.exprs) == [1]:
            return result(
                RootStatus.NO_REAL_ROOT, "no complex root at all: the basis is {1}", dimension=-1
            )
        if not basis.is_zero_dimensional:
            dimension, free = ideal_dimension(list(basis.exprs), remaining)
            return result(
                RootStatus.POSITIVE_DIMENSIONAL,
                f"a component of dimension {dimension}; free unknowns {list(free)}",
                dimension=dimension,
                free=free,
            )
    elif remaining:
        return result(
            RootStatus.POSITIVE_DIMENSIONAL,
            f"{remaining} appear in no equation",
            dimension=len(remaining),
            free=remaining,
        )
    try:
        found = _solve(polys, remaining)
    except _Undecided as exc:
        return result(RootStatus.UNDECIDED, str(exc))
    exact, certificates = [], []
    for root, certificate in found:
        for var, value in reversed(eliminated):
            root[var] = sp.expand(value.xreplace(root))
        exact.append({u: root[u] for u in unknowns})
        certificates.append("; ".join(certificate) or "rational root")
    order = sorted(
        range(len(exact)), key=lambda i: [float(exact[i][u]) for u in reversed(unknowns)]
    )
    exact = [exact[i] for i in order]
    certificates = [certificates[i] for i in order]
    floats = [{u: float(sp.N(v, TRIANGULAR_DIGITS)) for u, v in root.items()} for root in exact]
    if not exact:
        return result(
            RootStatus.NO_REAL_ROOT, "every root is complex (isolation found none)", dimension=0
        )
    return RootSet(
        RootStatus.SOLVED,
        floats,
        unknowns,
        f"{len(exact)} real roots, isolated exactly",
        exact=exact,
        certificates=certificates,
        backend="sympy",
        dimension=0,
        size=size,
    )
