"""Where the order-N branches start: the certified first-order census, the exact first-order folds
on a line of parameters, and which responses are one orbit.

The first-order amplitude equations P₁ = 0 at exact rational parameter values have finitely many
real roots, each isolated with a certificate (:func:`perturb.steady.roots.real_roots`); on a line
of parameters p(λ) = p₀ + λ·dp the first-order folds are the real solutions of {P₁ = 0,
det ∂P₁/∂u = 0} in (u, λ), found by the same solver. Both are kept in the disk cache: a sweep
repeated costs no census.

A time shift that leaves the equations of motion unchanged maps a response onto another solution
that is the same motion: a shift by one forcing period (the response of p forcing periods), and
by a fraction 1/G of it when the forcing has that symmetry (a parametric term written as cos 2θ:
G = 2). In the strained time s = Ωt/p the harmonic-m amplitudes rotate by 2πkm/(pG):
:func:`orbit_images` lists them, :func:`distinct_orbits` keeps one of each.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import sympy as sp

from perturb._defaults import (
    CENSUS_SAME_ORBIT,
    FOLD_SECONDS,
    MAX_SHIFT_DIVISOR,
    ORDER_CENSUS_BEZOUT,
    ORDER_CENSUS_SECONDS,
    SYMMETRY_PROBES,
    SYMMETRY_SEED,
    SYMMETRY_TOL,
)
from perturb.cache import Uncached, cached
from perturb.steady.roots import RootStatus, real_roots

__all__ = [
    "census",
    "distinct_orbits",
    "line_folds",
    "orbit_images",
    "order_census",
    "shift_symmetry",
]


@lru_cache(maxsize=32)
def _shift_symmetry(rhs: tuple, state: tuple, phase: sp.Symbol, others: tuple) -> int:
    from perturb._lambdify import numpy_lambdify

    f = numpy_lambdify([*state, phase, *others], list(rhs))
    rng = np.random.default_rng(SYMMETRY_SEED)
    probes = rng.uniform(0.2, 0.6, size=(SYMMETRY_PROBES, len(state) + 1 + len(others)))
    theta = len(state)
    base = np.array([np.asarray(f(*p), dtype=float) for p in probes])
    scale = 1.0 + float(np.max(np.abs(base)))
    best = 1
    for g in range(2, MAX_SHIFT_DIVISOR + 1):
        shifted = probes.copy()
        shifted[:, theta] += 2 * math.pi / g
        values = np.array([np.asarray(f(*p), dtype=float) for p in shifted])
        if float(np.max(np.abs(values - base))) <= SYMMETRY_TOL * scale:
            best = g
    return best


def shift_symmetry(system) -> int:
    """G: the largest g such that shifting the forcing's phase θ by 2π/g leaves the equations of
    motion unchanged (1: only the forcing period itself), decided on the right-hand sides at
    ``SYMMETRY_PROBES`` points (a trigonometric polynomial in θ that is not invariant changes at
    almost every point by far more than ``SYMMETRY_TOL``)."""
    drive = system.excitation
    rhs = tuple(sp.sympify(f) for f in system.rhs)
    others = tuple(sorted(set().union(*(f.free_symbols for f in rhs))
                          - set(system.state_symbols) - {drive.phase}, key=str))  # fmt: skip
    state = tuple(system.state_symbols)
    return cached(
        "response-shift-symmetry",
        lambda: (sp.srepr((rhs, state, drive.phase, others)),),
        lambda: _shift_symmetry(rhs, state, drive.phase, others),
    )


def orbit_images(u: np.ndarray, harmonics, group: int) -> list[np.ndarray]:
    """The amplitudes ``u`` = (a₁, b₁, a₂, b₂, …) of the same motion shifted by k/group of the
    response's period, k = 1..group−1 (harmonic m rotated by 2πkm/group)."""
    out = []
    for k in range(1, group):
        image = np.array(u, dtype=float)
        for i, m in enumerate(harmonics):
            angle = 2 * math.pi * k * m / group
            c, s = math.cos(angle), math.sin(angle)
            a, b = u[2 * i], u[2 * i + 1]
            image[2 * i], image[2 * i + 1] = c * a + s * b, -s * a + c * b
        out.append(image)
    return out


def same_orbit(u, v, harmonics, group: int) -> bool:
    """Whether amplitudes ``u`` and ``v`` are one motion (equal, or one an image of the other)."""
    size = max(1.0, float(np.max(np.abs(u))), float(np.max(np.abs(v))))
    return any(
        float(np.max(np.abs(w - v))) <= CENSUS_SAME_ORBIT * size
        for w in [np.asarray(u, dtype=float), *orbit_images(u, harmonics, group)]
    )


def distinct_orbits(points, harmonics, group: int) -> list[int]:
    """Indices of ``points`` (amplitude arrays) that are distinct motions, first kept."""
    kept: list[int] = []
    for i, u in enumerate(points):
        if not any(same_orbit(points[j], u, harmonics, group) for j in kept):
            kept.append(i)
    return kept


def _first_rows(equations, fixed: dict) -> list[sp.Expr]:
    return [sp.expand(e.xreplace(fixed)) for e in equations.displacement(0)]


def _kept_unless_spent(found, value):
    """``value``, not kept in the disk cache when the solve behind it ran out of its time budget
    (a faster or idler machine finishes it: the cache must not make one machine's budget law)."""
    return Uncached(value) if found.status is RootStatus.BUDGET_EXCEEDED else value


def census(equations, fixed: dict) -> tuple[list[np.ndarray], str]:
    """Every real root of the first-order equations at the exact parameter values ``fixed``
    (``{symbol: Rational}``): ``(roots as amplitude arrays, "")`` or ``([], why)``.

    Kept in the disk cache under the exact equations.
    """
    rows = _first_rows(equations, fixed)
    unknowns = list(equations.amplitudes)

    def solve():
        found = real_roots(rows, unknowns)
        if not found.status.success:
            return _kept_unless_spent(found, ([], f"{found.status.value} ({found.message})"))
        return [np.array([float(r[u]) for u in unknowns]) for r in found.roots], ""

    return cached("response-census", lambda: (sp.srepr(tuple(rows)),), solve)


def order_census(equations, order: int, fixed: dict) -> tuple[list[np.ndarray], str]:
    """Every real root of the order-``order`` equations D_N = 0 at the exact values ``fixed``
    (``{symbol: Rational}``, ε among them): ``(roots, "")``, or ``([], why)`` when they are not
    polynomial, too large to solve (Bezout bound above ``ORDER_CENSUS_BEZOUT``) or the budget
    ``ORDER_CENSUS_SECONDS`` was spent.

    Most roots of the truncated series are not motions (large amplitudes where its terms do not
    decrease): the caller keeps those the series describes. Kept in the disk cache.
    """
    unknowns = list(equations.amplitudes)
    rows = [sp.expand(e.xreplace(fixed)) for e in equations.displacement(order)]
    try:
        degrees = [sp.Poly(r, *unknowns).total_degree() for r in rows]
    except sp.PolynomialError:
        return [], "the order-N equations are not polynomial in the amplitudes"
    if math.prod(max(d, 1) for d in degrees) > ORDER_CENSUS_BEZOUT:
        return [], f"the order-N equations are too large (degrees {degrees})"

    def solve():
        try:
            found = real_roots(rows, unknowns, seconds=ORDER_CENSUS_SECONDS, floats=True)
        except (ValueError, TypeError, sp.PolynomialError) as exc:  # not over the rationals
            return [], f"the order-N equations could not be solved exactly ({exc})"
        if found.status is RootStatus.NO_REAL_ROOT:
            return [], ""
        if not found.status.success:
            return _kept_unless_spent(found, ([], f"{found.status.value} ({found.message})"))
        return [np.array([float(r[u]) for u in unknowns]) for r in found.roots], ""

    return cached("response-order-census", lambda: (sp.srepr(tuple(rows)),), solve)


def line_folds(equations, base: dict, slope: dict, lam: sp.Symbol) -> tuple[list[np.ndarray], str]:
    """The first-order folds on the line p = base + lam·slope (exact rationals by symbol): the
    real roots (u, lam) of {P₁ = 0, det ∂P₁/∂u = 0}, as arrays; or ([], why)."""
    line = {s: base[s] + lam * slope.get(s, 0) for s in base}
    rows = _first_rows(equations, line)
    unknowns = list(equations.amplitudes)
    if not any(r.has(lam) for r in rows):
        return [], ""

    def solve():
        jac = sp.Matrix([[sp.diff(r, u) for u in unknowns] for r in rows])
        det = sp.expand(jac.det(method="berkowitz"))
        found = real_roots([*rows, det], [*unknowns, lam], seconds=FOLD_SECONDS)
        if found.status is not RootStatus.SOLVED:
            if found.status is RootStatus.NO_REAL_ROOT:
                return [], ""
            return _kept_unless_spent(found, ([], f"{found.status.value} ({found.message})"))
        return [np.array([float(r[v]) for v in (*unknowns, lam)]) for r in found.roots], ""

    return cached("response-line-folds", lambda: (sp.srepr(tuple(rows)), lam.name), solve)
