"""Engine benchmark: time to derive orders 1-3, and evaluation throughput of a solution.

Run: ``python benchmarks/bench_engine.py`` (prints a table; no assertion: figures go in the notes).
Derivations run with the disk cache off, each in the same process after one warm-up import.
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from perturb import PoincareMethod
from problems import get_problem

REPEATS = 3
N_POINTS = 10_000_000


def derive_seconds(name: str, order: int) -> float:
    problem = get_problem(name).create()
    system = problem.system()
    options = problem.method_options()
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        sol = PoincareMethod(order=order, cache=False, **options).solve(system)
        times.append(time.perf_counter() - start)
        assert sol.success, sol.message
    return statistics.median(times)


def evaluation_rate(name: str, order: int) -> tuple[float, float]:
    problem = get_problem(name).create()
    sol = problem.solve(order)
    values = problem.symbol_values()
    eps = problem.parameter_value()
    t = np.linspace(0.0, 100.0, N_POINTS)
    sol.evaluate(t[:10], eps, values)  # compile once
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        sol.evaluate(t, eps, values)
        times.append(time.perf_counter() - start)
    harmonics = max(term.max_harmonic for row in sol.terms for term in row)
    return N_POINTS / statistics.median(times), harmonics


def main() -> None:
    print(
        f"{'problem':14s} {'order':>5s} {'derive [s]':>11s} {'eval [points/s]':>16s} {'harmonics':>9s}"
    )
    for name in ("duffing", "van-der-pol", "resonant-pair"):
        for order in (1, 2, 3):
            seconds = derive_seconds(name, order)
            rate, harmonics = evaluation_rate(name, order)
            print(f"{name:14s} {order:5d} {seconds:11.3f} {rate:16.3e} {harmonics:9d}")


if __name__ == "__main__":
    main()
