"""Benchmark (issue 22): every branch of the resonant chain's amplitude equations, by several routes.

The chain ẍᵢ + xᵢ = −ε[(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³], fixed ends, x1's amplitude 1. For each size
the amplitude equations of order 1 are taken from the construction and solved by

* ``msolve``: :func:`perturb.algebra.certified_real_roots` with the extra ``roots`` (the system
  cut by :mod:`perturb.algebra.split`, each piece isolated by msolve) — the count is proved;
* ``exact``: the same cuts, each piece by the exact sympy route (Groebner, FGLM, isolation);
* ``sympy.solve``: plain ``sympy.solve`` on the whole system, in a child process, under the budget;
* ``newton``: an independent numeric count on the whole system, which knows nothing of the cuts
  (multi-start Newton from seeded random starts spread over five decades, roots deduplicated on
  their cosine amplitudes) — a lower bound, never a proof; ``in certified`` counts how many of
  its roots are one of msolve's.

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

from perturb import cache, find_families, solve  # noqa: E402
from perturb.algebra import certified_real_roots, msolve_binary, solve_bounded  # noqa: E402
from perturb.method import conditions  # noqa: E402
from problems.resonant_chain import chain_system  # noqa: E402

#: Newton starts per size and the seed (the count must not change from run to run).
STARTS, SEED = 2000, 2024
#: Cosine amplitudes closer than this (relative, and absolute for small ones) are one root.
SAME_ROOT = 1e-5


def amplitude_equations(n: int):
    """The order-1 amplitude equations of the chain of ``n``, as the construction poses them."""
    captured = {}
    original = conditions.ConditionSolver._solve_nonlinear

    def capture(self, eqs, unknowns, *args):
        captured["eqs"] = [sp.expand(e / sp.pi) for e in eqs]
        captured["unknowns"] = list(unknowns)
        raise KeyboardInterrupt  # stop the construction here

    conditions.ConditionSolver._solve_nonlinear = capture
    try:
        solve(chain_system(n), order=1, amplitudes={"x1": 1}, cache=False)
    except KeyboardInterrupt:
        pass
    finally:
        conditions.ConditionSolver._solve_nonlinear = original
    return captured["eqs"], captured["unknowns"]


def pairs_of(n: int):
    """Each coordinate's (cosine, sine) generating amplitudes (x1's put in: 1 and 0)."""
    return [(sp.Integer(1), sp.Integer(0))] + [
        (sp.Symbol(f"a_x{j}0"), sp.Symbol(f"b_x{j}0")) for j in range(2, n + 1)
    ]


def newton_roots(eqs, unknowns) -> list[np.ndarray]:
    """Distinct real roots found by Newton from seeded random starts (a lower bound)."""
    from scipy.optimize import root

    f = sp.lambdify([unknowns], eqs, "numpy")
    jac = sp.lambdify([unknowns], sp.Matrix(eqs).jacobian(unknowns), "numpy")
    cosines = [i for i, u in enumerate(unknowns) if str(u).startswith("a_")]
    rng = np.random.default_rng(SEED)
    found: list[np.ndarray] = []
    for _ in range(STARTS):
        start = rng.choice([-1, 1], len(unknowns)) * 10 ** rng.uniform(-2, 3, len(unknowns))
        sol = root(
            lambda v: np.asarray(f(v), float), start, jac=lambda v: np.asarray(jac(v), float)
        )
        if not sol.success or np.max(np.abs(f(sol.x))) > 1e-8 * max(1, np.max(np.abs(sol.x))):
            continue
        # the standing waves are multiple roots in the sine amplitudes: Newton creeps there,
        # so roots are told apart by their cosine amplitudes only
        a = sol.x[cosines]
        if not any(np.allclose(a, r, rtol=SAME_ROOT, atol=SAME_ROOT) for r in found):
            found.append(a)
    return found


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
        + " | sympy.solve: real roots, s | newton: roots (in certified), s"
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
            cosines = [u for u in unknowns if str(u).startswith("a_")]
            inside = (
                sum(
                    any(
                        np.allclose(r, [c[u] for u in cosines], rtol=SAME_ROOT, atol=SAME_ROOT)
                        for c in reference.roots
                    )
                    for r in numeric
                )
                if reference is not None
                else "-"
            )
            plain_cell = f"{plain}, {t_plain:.1f}"
            newton_cell = f"{len(numeric)} ({inside}), {t_newton:.1f}"
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
