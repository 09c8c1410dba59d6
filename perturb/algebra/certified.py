"""The front door of the real-root solvers: the system cut, each piece solved, the status honest."""

from __future__ import annotations

import time

import sympy as sp
from attrs import evolve

from perturb._defaults import EXACT_FIRST_SECONDS, LIFT_DIGITS, ON_DIGITS, PIVOT_GROWTH
from perturb.algebra.budget import solve_bounded
from perturb.algebra.msolve import INSTALL_HINT, msolve_binary, msolve_real_roots
from perturb.algebra.rootset import RootSet, RootStatus
from perturb.algebra.size import SystemSize
from perturb.algebra.split import BudgetSpent, Piece, cut, frequency_eliminants
from perturb.algebra.triangular import eliminate_linear, exact_real_roots

__all__ = ["BACKENDS", "certified_real_roots"]

#: The routes: ``auto`` is msolve when the extra is installed, else the exact sympy route.
BACKENDS = ("auto", "msolve", "sympy")


def _check(eqs, unknowns) -> None:
    from perturb.errors import InvalidSystemError, bad_value

    for e in eqs:
        stray = sp.sympify(e).free_symbols - set(unknowns)
        rational = (
            not stray
            and sp.sympify(e).is_polynomial(*unknowns)
            and all(c.is_Rational for c in sp.Poly(e, *unknowns).coeffs())
        )
        if not rational:
            raise bad_value(
                "eqs",
                e,
                "give polynomials in the unknowns with exact rational coefficients"
                + (f" (put in values for {sorted(map(str, stray))})" if stray else ""),
                InvalidSystemError,
            )


def certified_real_roots(
    eqs, unknowns, *, seconds: float, backend: str = "auto", pairs=(), refine: bool = True
) -> RootSet:
    """Every real root of ``eqs = 0``, each certified by an isolating interval, within a budget.

    The system is first cut into disjoint pieces (:mod:`perturb.algebra.split`: linear pivots,
    factors read over the reals, sign symmetry); each piece is solved by msolve or the exact
    route, and the roots are put together. Each root's certificate names the cuts that led to
    its piece and the isolating box or interval that holds it.

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials in ``unknowns`` with exact rational coefficients.
    unknowns : sequence of sympy.Symbol
    seconds : float
        Time budget; when spent the status is ``BUDGET_EXCEEDED`` and the message gives the
        system's size.
    backend : {"auto", "msolve", "sympy"}
        ``msolve`` needs the extra ``roots``; ``sympy`` is the exact route of
        :mod:`perturb.algebra.triangular` (exact algebraic values); ``auto`` gives each piece
        :data:`EXACT_FIRST_SECONDS` on the exact route, then msolve when it is installed.
    pairs : sequence of (sympy.Symbol, sympy.Symbol), optional
        Amplitude equations: each coordinate's (cosine, sine) amplitudes, in the coordinates'
        order; the frequency-free combinations they give (:func:`~perturb.algebra.split.
        frequency_eliminants`) are used to cut the system.
    refine : bool
        Refine msolve's large roots to the digits a construction needs (default); False keeps
        the certified boxes' midpoints (for a caller that needs floats: a response's points).

    Returns
    -------
    RootSet

    Raises
    ------
    InvalidSystemError
        When an equation is not a polynomial with rational coefficients in ``unknowns``.
    MissingDependencyError
        ``backend="msolve"`` without the extra.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> found = certified_real_roots([x**3 - x, y - x**2], [x, y], seconds=30, backend="sympy")
    >>> found.status.name, [(r[x], r[y]) for r in found.exact]
    ('SOLVED', [(0, 0), (-1, 1), (1, 1)])
    """
    from perturb.errors import InvalidSystemError, MissingDependencyError, bad_value

    if backend not in BACKENDS:
        raise bad_value("backend", backend, f"use one of {list(BACKENDS)}", InvalidSystemError)
    unknowns = list(unknowns)
    eqs = [sp.expand(e) for e in eqs]
    _check(eqs, unknowns)
    binary = msolve_binary() if backend in ("auto", "msolve") else None
    if backend == "msolve" and binary is None:
        raise MissingDependencyError(f"`backend='msolve'` needs msolve: {INSTALL_HINT}")
    size = SystemSize.of(eqs, unknowns)
    route = "msolve" if binary is not None else "sympy"

    def failed(status, message, **extra):
        return RootSet(status, (), unknowns, message, size=size, backend=route, **extra)

    deadline = time.monotonic() + seconds
    members = frequency_eliminants(eqs, unknowns, pairs) if pairs else []
    try:
        leaves = cut(eqs, unknowns, members=members, deadline=deadline)
    except BudgetSpent:
        return failed(
            RootStatus.BUDGET_EXCEEDED, f"cutting the system ran past {seconds:g} s ({size})"
        )
    roots, certificates, dimensions, continua, closures = [], [], [], [], []
    answered: set = set()
    for leaf in leaves:
        found, leaf = _solve_leaf(
            leaf, binary, deadline - time.monotonic(), exact_first=backend == "auto", refine=refine
        )
        if found.status is RootStatus.BUDGET_EXCEEDED:
            return failed(
                RootStatus.BUDGET_EXCEEDED,
                f"the {route} route ran past {seconds:g} s on {size} (a piece: {found.size})",
            )
        if found.status is RootStatus.UNDECIDED:
            return failed(
                found.status,
                f"{found.message} (on the piece {'; '.join(leaf.path) or 'the whole system'})",
            )
        if found.status is RootStatus.POSITIVE_DIMENSIONAL:
            if found.dimension is None:  # msolve says only that it is not finite
                found = _dimension(leaf, deadline - time.monotonic()) or found
            free = [u for u in found.free if u in unknowns]
            continua.append((found.dimension, tuple(free), "; ".join(leaf.path)))
            closures.append(leaf)
            continue
        dimensions.append(found.dimension)
        answered.add(found.backend)
        for index in range(len(found.roots)):
            roots.append(_lift(leaf, found, index, unknowns))
            path = "; ".join(leaf.path)
            certificates.append(
                f"{path}: {found.certificates[index]}" if path else found.certificates[index]
            )
    if continua:  # a root of another piece on a continuum's closure is a point of it
        kept = [i for i, r in enumerate(roots) if not any(_on(leaf, r) for leaf in closures)]
        roots, certificates = [roots[i] for i in kept], [certificates[i] for i in kept]
        found = RootSet(RootStatus.POSITIVE_DIMENSIONAL, (), unknowns, continua=continua)
        return RootSet(
            RootStatus.POSITIVE_DIMENSIONAL,
            [{u: float(r[1][u]) for u in unknowns} for r in roots],
            unknowns,
            f"{len(continua)} continua ({found.describe_continua()}) and {len(roots)} isolated "
            f"real roots ({route} route)",
            exact=[r[0] for r in roots],
            approximations=[r[1] for r in roots],
            certificates=certificates,
            backend=route,
            dimension=max((d for d, _, _ in continua if d is not None), default=None),
            free=continua[0][1],
            size=size,
            continua=continua,
        )
    if not roots:
        dimension = -1 if all(d == -1 for d in dimensions) else 0
        how = f"{len(leaves)} pieces, none with a real root" if leaves else "every piece was empty"
        return failed(
            RootStatus.NO_REAL_ROOT, f"no real root ({how}; {route} route)", dimension=dimension
        )
    if _has_repeats(roots, unknowns):
        return failed(
            RootStatus.UNDECIDED, "two pieces gave the same root (the cut is not disjoint)"
        )
    route = "msolve" if "msolve" in answered else "sympy"  # the route that answered
    order = sorted(range(len(roots)), key=lambda i: [roots[i][1][u] for u in reversed(unknowns)])
    return RootSet(
        RootStatus.SOLVED,
        [{u: float(roots[i][1][u]) for u in unknowns} for i in order],
        unknowns,
        f"{len(roots)} real roots, isolated by the {route} route in {len(leaves)} pieces",
        exact=[roots[i][0] for i in order],
        approximations=[roots[i][1] for i in order],
        certificates=[certificates[i] for i in order],
        backend=route,
        dimension=0,
        size=size,
    )


def _solve_leaf(
    leaf: Piece,
    binary: str | None,
    seconds: float,
    exact_first: bool = False,
    refine: bool = True,
) -> tuple[RootSet, Piece]:
    """The real roots of one piece (its remaining linear pivots put in first, its non-zero
    conditions imposed by one more unknown), and the piece as solved."""
    growth = PIVOT_GROWTH if binary is not None else None
    polys, eliminated = eliminate_linear(list(leaf.polys), list(leaf.unknowns), growth)
    nonzero = list(leaf.nonzero)
    for var, value in eliminated:
        nonzero = [sp.expand(q.xreplace({var: value})) for q in nonzero]
    leaf = evolve(
        leaf,
        polys=polys,
        unknowns=[u for u in leaf.unknowns if u not in dict(eliminated)],
        nonzero=[q for q in nonzero if not q.is_number],
        eliminated=[*leaf.eliminated, *eliminated],
    )
    polys, variables = list(leaf.polys), list(leaf.unknowns)
    if any(q == 0 for q in nonzero) or any(p.is_number for p in polys):
        return RootSet(RootStatus.NO_REAL_ROOT, (), variables, "empty", dimension=-1), leaf
    if leaf.nonzero:
        inverse = sp.Dummy("nonzero")
        polys.append(sp.expand(inverse * sp.Mul(*leaf.nonzero) - 1))
        variables.append(inverse)
    if seconds <= 0:
        return RootSet(
            RootStatus.BUDGET_EXCEEDED, (), variables, size=SystemSize.of(polys, variables)
        ), leaf
    if not leaf.unknowns:  # everything was put in: one root, the checks done by the cut
        found = RootSet(
            RootStatus.SOLVED,
            [{}],
            [],
            exact=[{}],
            approximations=[{}],
            certificates=["exact"],
            dimension=0,
        )
        return found, leaf
    if not leaf.polys:
        found = RootSet(
            RootStatus.POSITIVE_DIMENSIONAL,
            (),
            variables,
            f"{list(leaf.unknowns)} appear in no equation",
            dimension=len(leaf.unknowns),
            free=leaf.unknowns,
        )
        return found, leaf
    if binary is not None:
        if exact_first and _can_bound():  # exact values (radicals) where the route is quick
            try:
                slice_ = min(EXACT_FIRST_SECONDS, seconds / 4)
                return solve_bounded(polys, variables, slice_, exact_real_roots), leaf
            except (TimeoutError, NotImplementedError, ValueError):
                pass
        return msolve_real_roots(polys, variables, seconds, binary, refine=refine), leaf
    try:
        return solve_bounded(polys, variables, seconds, exact_real_roots), leaf
    except TimeoutError:
        return RootSet(
            RootStatus.BUDGET_EXCEEDED, (), variables, size=SystemSize.of(polys, variables)
        ), leaf


def _can_bound() -> bool:
    """Whether a solve can be given a budget here: not in a daemonic process (a Dask worker, a
    pool's), where :func:`~perturb.algebra.budget.solve_bounded` runs without one — the exact
    route's first slice would then be unbounded (a phase diagram's census hung on it)."""
    import multiprocessing

    return not multiprocessing.current_process().daemon


def _dimension(leaf: Piece, seconds: float) -> RootSet | None:
    """The dimension and free unknowns of a positive-dimensional piece, by the exact route's
    Groebner basis within ``seconds`` (None when it does not finish)."""
    if seconds <= 0:
        return None
    try:
        return solve_bounded(list(leaf.polys), list(leaf.unknowns), seconds, exact_real_roots)
    except (TimeoutError, NotImplementedError, ValueError):
        return None


def _on(leaf: Piece, root: tuple) -> bool:
    """Whether a root (exact, approximation) satisfies a piece's equations and cuts (its
    non-zero conditions aside): exactly when its values are exact, else to ON_DIGITS digits."""
    exact, approx = root
    values = exact if all(u in exact for u in approx) else approx
    residuals = [sp.expand(p.xreplace(values)) for p in leaf.polys]
    residuals += [
        sp.expand(var - expr.xreplace(values)).xreplace(values) for var, expr in leaf.eliminated
    ]
    if values is exact:
        return all(sp.simplify(r) == 0 for r in residuals)
    scale = max([1, *(abs(float(v)) for v in approx.values())])
    return all(abs(float(r)) <= 10.0**-ON_DIGITS * scale**3 for r in residuals)


def _lift(leaf: Piece, found: RootSet, index: int, unknowns: list) -> tuple[dict, dict]:
    """A leaf's root as ``(exact, approximation)`` in every unknown (the eliminated put back)."""
    exact = dict(found.exact[index]) if found.exact else {}
    approx = dict(found.approximations[index]) if found.approximations else {}
    for u, value in exact.items():
        approx.setdefault(
            u, value if value.is_Rational else sp.Float(sp.N(value, LIFT_DIGITS), LIFT_DIGITS)
        )
    for u, value in found.roots[index].items():
        approx.setdefault(u, sp.Float(value))
    for var, expr in reversed(leaf.eliminated):
        if expr.free_symbols <= set(exact):
            exact[var] = sp.expand(expr.xreplace(exact))
        approx[var] = sp.expand(expr.xreplace(approx))
    keep = set(unknowns)
    return {u: v for u, v in exact.items() if u in keep}, {
        u: v for u, v in approx.items() if u in keep
    }


def _has_repeats(roots: list, unknowns: list) -> bool:
    """Whether two roots coincide (the pieces are disjoint by construction: a bug if so)."""
    points = [tuple(sp.Float(r[1][u], 25) for u in unknowns) for r in roots]
    return len(set(points)) < len(points)
