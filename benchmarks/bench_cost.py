"""The figures behind perturb.cost's estimate (the rule for expensive requests): CPU seconds of a
response of the shipped driven problems against its order, its grid values, its shots and its
true curves, with the disk cache off (every derivation made afresh).

    PERTURB_CACHE_DIR=off python benchmarks/bench_cost.py [--problems forced-duffing ...]

Prints one row per run: the problem, what was asked, the CPU seconds measured and the seconds
perturb.cost estimates for it. Recorded in benchmarks/hostile_cli.md.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

from perturb.cost import response_cost
from problems import get_problem

DRIVEN = (
    "forced-duffing",
    "parametric-duffing",
    "superharmonic-duffing",
    "autoparametric-absorber",
)

#: (order, grid values, shots per branch, true-curve points) of each run.
RUNS = ((1, 20, 0, 0), (3, 20, 0, 0), (3, 200, 0, 0), (5, 20, 0, 0), (7, 20, 0, 0),
        (3, 20, 5, 0), (3, 20, 0, 50))  # fmt: skip


def main() -> None:
    from perturb.response.model import problem_response

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problems", nargs="*", default=list(DRIVEN))
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print(f"{'problem':26s}{'order':>6s}{'values':>8s}{'shots':>7s}{'true':>6s}"
          f"{'cpu s':>9s}{'estimate s':>12s}")  # fmt: skip
    for name in args.problems:
        problem = get_problem(name).create()
        omega = problem.values["Omega"]
        for order, values, shots, true in RUNS:
            grid = np.linspace(0.97 * omega, 1.03 * omega, values)
            clock = time.process_time()
            problem_response(problem, "Omega", grid, order=order, validate=shots, true=true)
            cpu = time.process_time() - clock
            estimate = response_cost(values, order, shots, true).seconds
            print(f"{name:26s}{order:6d}{values:8d}{shots:7d}{true:6d}{cpu:9.1f}{estimate:12.1f}",
                  flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
