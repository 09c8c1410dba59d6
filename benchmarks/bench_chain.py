"""Benchmark (issue 22): every branch of the resonant chain's amplitude equations, three routes.

The chain ẍᵢ + xᵢ = −ε[(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³], fixed ends, x1's amplitude 1. For each size
the amplitude equations of order 1 are taken from the construction and solved by

* ``certified``: :func:`perturb.algebra.certified_real_roots` (msolve when the extra ``roots`` is
  installed, else the exact sympy route) — the count is proved;
* ``sympy``: plain ``sympy.solve`` under the same budget;
* ``newton``: an independent numeric count (multi-start Newton from seeded random starts spread
  over five decades, roots deduplicated) — a lower bound, never a proof.

``construction`` is ``find_families`` at the order given (every branch carried to that order).
Run from the repository root: ``python benchmarks/bench_chain.py [--budget 60] [--sizes 3 4 6]``.
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
from perturb.algebra import certified_real_roots, solve_bounded  # noqa: E402
from perturb.method import conditions  # noqa: E402
from problems.resonant_chain import chain_system  # noqa: E402

#: Newton starts per size and the seed (the count must not change from run to run).
STARTS, SEED = 2000, 2024


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


def newton_count(eqs, unknowns) -> int:
    """Distinct real roots found by Newton from seeded random starts (a lower bound)."""
    from scipy.optimize import root

    f = sp.lambdify([unknowns], eqs, "numpy")
    jac = sp.lambdify([unknowns], sp.Matrix(eqs).jacobian(unknowns), "numpy")
    rng = np.random.default_rng(SEED)
    found: list[np.ndarray] = []
    for _ in range(STARTS):
        start = rng.choice([-1, 1], len(unknowns)) * 10 ** rng.uniform(-2, 3, len(unknowns))
        sol = root(
            lambda v: np.asarray(f(v), float), start, jac=lambda v: np.asarray(jac(v), float)
        )
        if not sol.success or np.max(np.abs(f(sol.x))) > 1e-8 * max(1, np.max(np.abs(sol.x))):
            continue
        if not any(np.allclose(sol.x, r, rtol=1e-5, atol=1e-3) for r in found):  # slow b -> 0
            found.append(sol.x)
    return len(found)


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
    parser.add_argument("--backend", default="auto")
    args = parser.parse_args(argv)
    print(
        "| n | order | unknowns | certified: status, real roots, s | sympy.solve: roots, s |"
        " newton (lower bound), s | construction: families, s |"
    )
    print("|---|---|---|---|---|---|---|")
    cases = [(n, 1) for n in args.sizes] + ([(args.order2, 2)] if args.order2 else [])
    for n, order in cases:
        eqs, unknowns = amplitude_equations(n)
        found, t_cert = timed(
            lambda: certified_real_roots(eqs, unknowns, seconds=args.budget, backend=args.backend)
        )
        cert = f"{found.status.name} ({found.backend}), {len(found.roots)}, {t_cert:.1f}"
        plain, t_plain = timed(lambda: solve_bounded(eqs, unknowns, args.budget))
        if plain != "timeout":
            plain = sum(all(sp.im(sp.N(v)) == 0 for v in r.values()) for r in plain)
        count, t_newton = timed(lambda: newton_count(eqs, unknowns))
        with cache.bypassed():
            families, t_build = timed(
                lambda: find_families(
                    chain_system(n), order=order, amplitudes={"x1": 1}, solve_seconds=args.budget
                )
            )
        ok = sum(f.status.ok for f in families)
        print(
            f"| {n} | {order} | {len(unknowns)} | {cert} | {plain}, {t_plain:.1f} | "
            f"{count}, {t_newton:.1f} | {ok}/{len(families)} SUCCESS, {t_build:.1f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
