"""Sweep throughput: evaluation and validation, a plain loop against Dask at 1 and 2 workers.

    python benchmarks/bench_sweep.py [--quick]

Prints a table (wall seconds of the whole sweep, points per second, Dask's per-point overhead
against the plain loop). The plain loop is `evaluate_chunk` over all points in this process; the
Dask rows are `perturb.sweep.sweep` on a LocalCluster (its start-up timed apart).
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def main() -> None:
    from distributed import LocalCluster

    from perturb.sweep import Grid, sweep
    from perturb.sweep.points import evaluate_chunk
    from problems import get_problem

    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    duffing = get_problem("duffing").create()
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    cases = [
        ("duffing evaluate order 2", duffing,
         {"eps": np.linspace(0.01, 0.3, 1000), "amplitude": np.linspace(0.5, 2, 1000)}, 2, False),
        ("duffing validate order 1", duffing,
         {"eps": np.linspace(0.02, 0.3, 10), "amplitude": np.linspace(0.5, 1.5, 6)}, 1, True),
        ("disk evaluate order 2", disk,
         {"r0": np.linspace(0.6, 1.0, 5), "gamma3_0": np.linspace(0.2, 0.3, 4)}, 2, False),
        ("disk validate order 2", disk,
         {"r0": np.linspace(0.6, 1.0, 3), "gamma3_0": np.linspace(0.2, 0.3, 2)}, 2, True),
    ]  # fmt: skip
    if args.quick:
        cases = [cases[0], cases[1]]
    rows = []
    for label, problem, axes, order, validate in cases:
        grid = Grid.of(axes)
        names = tuple(f"amplitude_{n}" for n in problem.state_names())
        evaluate_chunk(problem, grid, np.arange(1), order, validate, names)  # warm caches
        start = time.perf_counter()
        evaluate_chunk(problem, grid, np.arange(grid.size), order, validate, names)
        rows.append((label, "plain loop", grid.size, time.perf_counter() - start))
        for workers in (1, 2):
            start = time.perf_counter()
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=":0")
            startup = time.perf_counter() - start
            with cluster:
                start = time.perf_counter()
                sweep(problem, grid, order=order, validate=validate,
                      scheduler=cluster.scheduler_address)  # fmt: skip
                wall = time.perf_counter() - start
            rows.append(
                (label, f"dask {workers} worker(s) (+{startup:.1f} s start)", grid.size, wall)
            )
    print(f"{'case':28s} {'run':34s} {'points':>8s} {'seconds':>9s} {'points/s':>10s}")
    for label, run, points, seconds in rows:
        print(f"{label:28s} {run:34s} {points:8d} {seconds:9.2f} {points / seconds:10.3g}")


if __name__ == "__main__":
    main()
