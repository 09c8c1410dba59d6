"""Benchmark (issue 22): every branch of the resonant chain's amplitude equations, by several routes.

The chain ẍᵢ + xᵢ = −ε[(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³], fixed ends, x1's amplitude 1. For each size
the amplitude equations of order 1 are taken from the construction and solved by

* ``msolve``: :func:`perturb.algebra.certified_real_roots` with the extra ``roots`` (the system
  cut by :mod:`perturb.algebra.split`, each piece isolated by msolve) — the count is proved;
* ``exact``: the same cuts, each piece by the exact sympy route (Groebner, FGLM, isolation);
* ``sympy.solve``: plain ``sympy.solve`` on the whole system, in a child process, under the budget;
* ``newton``: an independent numeric count on the whole system, which knows nothing of the cuts:
  multi-start Newton on the homogeneous equations (x1's amplitude put back as an unknown) with
  the amplitudes on the unit sphere, roots told apart as directions — a lower bound, never a
  proof; its roots are split into those that are one of msolve's, those near x1 = 0 (not
  branches, see ``X1_ZERO``) and any other (a branch the certified route would have missed).

``construction`` is ``find_families`` at the order given (every branch carried to that order),
cache bypassed. Run from the repository root:
``python benchmarks/bench_chain.py [--budget 60] [--sizes 3 4 6] [--order2 3]``.
A numerical homotopy (``pybertini``) was tried in a scratch venv: see ``bench_chain.md``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from perturb import cache, find_families  # noqa: E402
from perturb.algebra import certified_real_roots, msolve_binary, solve_bounded  # noqa: E402
from problems.resonant_chain import chain_system  # noqa: E402
from tests.algebra.chain_equations import amplitude_equations, pairs_of  # noqa: E402, F401

#: Newton starts per size and the seed (the count must not change from run to run).
STARTS, SEED = 3000, 2024
#: Directions on the unit sphere closer than this are one root; the standing waves are multiple
#: roots of the whole system in the sine amplitudes, where Newton converges only linearly.
SAME_ROOT = 1e-5
#: Largest residual of a Newton point on the sphere that counts as a root.
RESIDUAL = 1e-10
#: Sine parts of two Newton points closer than this are one root: at the standing waves the
#: residual grows like b**3, so Newton stops with |b| up to (1e-10)**(1/3) ~ 5e-4.
SINE_CREEP = 1e-2
#: A direction with |x1| below this is taken as near x1 = 0: there the dropped sine condition of
#: x1 is not implied and every phase of a standing wave of x2..xn solves the rest (a continuum;
#: Newton lands within 1e-6 of it with residuals below RESIDUAL). No branch is missed there that
#: the chart x1 = 1 could hold: its directions have |x1| = 1/|amplitudes|.
X1_ZERO = 1e-4


def homogeneous(eqs, unknowns):
    """The amplitude equations with x1's amplitude ``a1`` put back: each monomial of the
    frequency correction times amplitudes of degree 1, every other monomial of degree 3."""
    omega, amplitudes = unknowns[0], list(unknowns[1:])
    a1 = sp.Symbol("a1")
    out = []
    for e in eqs:
        total = sp.S.Zero
        for (k, *powers), c in sp.Poly(sp.expand(e), omega, *amplitudes).terms():
            missing = (1 if k else 3) - sum(powers)
            total += (
                c
                * omega**k
                * a1**missing
                * sp.Mul(*(v**p for v, p in zip(amplitudes, powers, strict=True)))
            )
        out.append(total)
    return out, [omega, a1, *amplitudes]


def sphere(values) -> np.ndarray:
    """A direction of amplitudes on the unit sphere, its sign fixed (first clear entry > 0)."""
    v = np.asarray(values, float) / np.linalg.norm(values)
    first = next(x for x in v if abs(x) > SAME_ROOT)
    return v if first > 0 else -v


def newton_roots(eqs, unknowns) -> list[np.ndarray]:
    """Distinct real roots, as directions on the unit sphere of amplitudes, found by Newton from
    seeded random starts on the homogeneous equations with |amplitudes| = 1 (a lower bound).

    Every branch is a direction, whatever its size in the chart x1 = 1 (the chain of 6 has roots
    with amplitudes up to 1e29 there, which starts in a box would never reach)."""
    from scipy.optimize import root

    system, variables = homogeneous(eqs, unknowns)
    system.append(sum(v**2 for v in variables[1:]) - 1)
    f = sp.lambdify([variables], system, "numpy")
    jac = sp.lambdify([variables], sp.Matrix(system).jacobian(variables), "numpy")
    rng = np.random.default_rng(SEED)
    found: list[np.ndarray] = []
    for _ in range(STARTS):
        z = rng.normal(size=len(variables) - 1)
        start = np.concatenate([[rng.uniform(0, 3)], z / np.linalg.norm(z)])
        sol = root(
            lambda v: np.asarray(f(v), float), start, jac=lambda v: np.asarray(jac(v), float)
        )
        if not sol.success or np.max(np.abs(f(sol.x))) > RESIDUAL:
            continue
        direction = sphere(sol.x[1:])
        if not any(same_direction(direction, r, variables[1:]) for r in found):
            found.append(direction)
    return found


def same_direction(p, q, amplitudes) -> bool:
    """One root: cosine parts within SAME_ROOT, sine parts within SINE_CREEP."""
    sine = np.array([str(u).startswith("b_") for u in amplitudes])
    return bool(
        np.all(np.abs(p - q)[~sine] <= SAME_ROOT) and np.all(np.abs(p - q)[sine] <= SINE_CREEP)
    )


def certified_directions(found, unknowns) -> list[np.ndarray]:
    """The certified roots (chart x1 = 1) as directions on the sphere, like :func:`newton_roots`."""
    return [sphere([1.0, *(root[u] for u in unknowns[1:])]) for root in found.roots]


def timed(fn):
    start = time.perf_counter()
    try:
        return fn(), time.perf_counter() - start
    except TimeoutError:
        return "timeout", time.perf_counter() - start


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=60.0)
    parser.add_argument("--sizes", type=int, nargs="+", default=[3, 4, 6])
    parser.add_argument("--order2", type=int, default=3, help="size carried to order 2 (0: none)")
    args = parser.parse_args(argv)
    routes = (["msolve"] if msolve_binary() else []) + ["sympy"]
    print(
        "| n | order | unknowns | "
        + " | ".join(
            f"certified {'msolve' if r == 'msolve' else 'exact'}: status, roots, s" for r in routes
        )
        + " | sympy.solve: real roots, s | newton on the sphere: roots: certified, near x1 = 0, other; s"
        " | construction: SUCCESS/families, s |"
    )
    print("|---|---|---|" + "---|" * len(routes) + "---|---|---|")
    cases = [(n, 1) for n in args.sizes] + ([(args.order2, 2)] if args.order2 else [])
    for n, order in cases:
        eqs, unknowns = amplitude_equations(n)
        cells, reference = [], None
        for route in routes:
            found, seconds = timed(
                lambda route=route, eqs=eqs, unknowns=unknowns, n=n: certified_real_roots(
                    eqs, unknowns, seconds=args.budget, backend=route, pairs=pairs_of(n)
                )
            )
            cells.append(f"{found.status.name}, {len(found.roots)}, {seconds:.1f}")
            if route == routes[0] and found.status.name == "SOLVED":
                reference = found
        if order == 1:
            plain, t_plain = timed(lambda e=eqs, u=unknowns: solve_bounded(e, u, args.budget))
            if plain != "timeout":
                plain = sum(all(sp.im(sp.N(v)) == 0 for v in r.values()) for r in plain)
            numeric, t_newton = timed(lambda e=eqs, u=unknowns: newton_roots(e, u))
            proved = certified_directions(reference, unknowns) if reference is not None else []
            amplitudes = homogeneous(eqs, unknowns)[1][1:]
            matched = [any(same_direction(r, c, amplitudes) for c in proved) for r in numeric]
            inside = sum(matched)
            on_x1_zero = sum(
                abs(r[0]) < X1_ZERO for r, m in zip(numeric, matched, strict=True) if not m
            )
            missed = len(numeric) - inside - on_x1_zero
            plain_cell = f"{plain}, {t_plain:.1f}"
            newton_cell = f"{len(numeric)}: {inside}, {on_x1_zero}, {missed}, {t_newton:.1f}"
        else:
            plain_cell = newton_cell = "same system as order 1"
        with cache.bypassed():
            families, t_build = timed(
                lambda n=n, order=order: find_families(
                    chain_system(n), order=order, amplitudes={"x1": 1}, solve_seconds=args.budget
                )
            )
        ok = sum(f.status.ok for f in families)
        print(
            f"| {n} | {order} | {len(unknowns)} | {' | '.join(cells)} | {plain_cell} | "
            f"{newton_cell} | {ok}/{len(families)}, {t_build:.1f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
