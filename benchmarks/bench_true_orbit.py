"""The disk's true periodic orbit at the paper geometry by both routes, with timings.

``python benchmarks/bench_true_orbit.py`` prints beta1/eps, beta2/eps and (T - 2 pi)/eps**2 of
``perturb validate disk --set r0=30.2062`` from (1) the conditioned quadruple-precision heyoka
shooting (:func:`problems.rigid_body.true_orbit.conditioned_true_orbit`) and (2) the independent
40-digit mpmath Taylor shooting (:func:`problems.rigid_body.true_orbit_mp.mp_true_orbit`), both from
the parameters as exact rationals, and their relative disagreement.
"""

from __future__ import annotations

import time

from problems import get_problem
from problems.rigid_body.true_orbit import conditioned_true_orbit
from problems.rigid_body.true_orbit_mp import mp_true_orbit


def main() -> None:
    problem = get_problem("disk").create(r0=30.2062)
    problem.solve(1)  # the analytic seed, not timed
    start = time.perf_counter()
    fast = conditioned_true_orbit(problem)
    fast_s = time.perf_counter() - start
    start = time.perf_counter()
    slow = mp_true_orbit(problem)
    slow_s = time.perf_counter() - start
    rows = (
        ("quadruple (heyoka real128)", fast.beta1, fast.beta2, fast.alpha, fast_s),
        ("mpmath Taylor, 40 digits", slow.beta1, slow.beta2, float(slow.alpha), slow_s),
    )
    print(f"{'route':28s} {'beta1/eps':>14s} {'beta2/eps':>14s} {'(T-2pi)/eps^2':>16s} {'s':>7s}")
    for name, b1, b2, al, seconds in rows:
        print(f"{name:28s} {b1:14.10f} {b2:14.10f} {al:16.12f} {seconds:7.1f}")
    diff = max(abs(a / b - 1) for a, b in zip(rows[0][1:4], rows[1][1:4], strict=True))
    print(f"largest relative disagreement: {diff:.1e}")
    print(f"fast route: {fast.message}")


if __name__ == "__main__":
    main()
