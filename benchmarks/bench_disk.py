"""Benchmark: the disk problem, before vs after (issue 12, the rigid-body half).

Every figure comes from a fresh interpreter (nothing imported or cached in memory); "cold" runs have
the disk cache off (``PERTURB_CACHE_DIR=off``), the warm ``perturb validate disk`` runs a filled
cache in a temporary folder. Times are the child's process CPU seconds (user + system), which a
loaded machine disturbs less than wall time; the table gives the median of ``--repeat`` runs.

Rows: disk orders 1/2/3 solved for one parameter set (the default path: orders above
``SYMBOLIC_MAX_ORDER`` specialised) and the first physical state; order 2 and (``--symbolic3``)
order 3 constructed symbolically in all the body's parameters; warm ``perturb validate disk``
(whole process); ``problem.state`` points per second at order 3.

``--before REV`` measures the same rows on the tree of git revision ``REV`` (exported with
``git archive`` into a temporary folder) right before the current tree, for a side-by-side table.
Run from the repository root::

    python benchmarks/bench_disk.py --before main --repeat 3
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _tree import export, run_child

ROOT = Path(__file__).resolve().parent.parent
#: Fresh-process repetitions of each row (medians are reported).
REPEATS = 3
#: Give up a row after this many seconds (symbolic order 3 can run for minutes).
ROW_TIMEOUT = 900
#: Sample points of the state-throughput row.
STATE_POINTS = 100_000

_SOLVE = """
import sys, time
from problems import get_problem
order = int(sys.argv[1])
problem = get_problem("disk").create(r0=30.2)
problem.state(problem.solve(order), [0.0])
"""

_SYMBOLIC = """
import sys
from perturb import PoincareMethod
from problems import get_problem
from problems.rigid_body._body import geometric_constraint
order = int(sys.argv[1])
disk = get_problem("disk")
reduction = disk.reduction_for(order)
options = disk.create().method_options()
options["amplitudes"] = {"G": geometric_constraint(reduction)}
solution = PoincareMethod(order=order, **options).solve(reduction.system)
assert solution.success, solution.message
"""

_STATE = """
import json, sys, time
import numpy as np
from problems import get_problem
problem = get_problem("disk").create(r0=30.2)
solution = problem.solve(3)
problem.state(solution, [0.0])
t = np.linspace(0.0, 10.0, int(sys.argv[1]))
best = float("inf")
for _ in range(5):
    start = time.perf_counter()
    problem.state(solution, t)
    best = min(best, time.perf_counter() - start)
print(json.dumps({"rate": t.size / best}))
"""


def _child(tree: Path, args: list[str], env: dict) -> tuple[float, str]:
    """(CPU seconds of the child, its stdout); CalledProcessError when it fails."""
    cpu, out = run_child(tree, args, env, ROW_TIMEOUT)
    out.check_returncode()
    return cpu, out.stdout


def measure(tree: Path, repeat: int, symbolic3: bool) -> dict[str, float | None]:
    cold = {"PERTURB_CACHE_DIR": "off"}
    rows: dict[str, float | None] = {}

    def median(label, args, env=cold):
        try:
            rows[label] = statistics.median(_child(tree, args, env)[0] for _ in range(repeat))
        except (subprocess.CalledProcessError, subprocess.TimeoutExpired) as exc:
            print(f"  {label}: {type(exc).__name__}", file=sys.stderr)
            rows[label] = None

    for order in (1, 2, 3):
        median(f"order {order} specialised, cold [s]", ["-c", _SOLVE, str(order)])
    median("order 2 symbolic, cold [s]", ["-c", _SYMBOLIC, "2"])
    if symbolic3:
        median("order 3 symbolic, cold [s]", ["-c", _SYMBOLIC, "3"])
    with tempfile.TemporaryDirectory() as folder:
        os.chmod(folder, 0o700)
        warm = {"PERTURB_CACHE_DIR": folder}
        validate = ["-m", "perturb", "validate", "disk"]
        _child(tree, validate, warm)  # fill the cache
        median("warm `perturb validate disk` [s]", validate, warm)
    rates = []
    for _ in range(repeat):
        rates.append(json.loads(_child(tree, ["-c", _STATE, str(STATE_POINTS)], cold)[1])["rate"])
    rows["state at order 3 [points/s]"] = statistics.median(rates)
    return rows


def _text(value: float | None) -> str:
    if value is None:
        return "-"
    return f"{value:.3g}" if value >= 1e4 else f"{value:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--before", metavar="REV", help="also measure git revision REV first")
    parser.add_argument("--repeat", type=int, default=REPEATS)
    parser.add_argument("--symbolic3", action="store_true", help="add order 3 symbolic (slow)")
    args = parser.parse_args()
    start = time.time()
    columns = {}
    with tempfile.TemporaryDirectory() as folder:
        if args.before:
            columns[f"before ({args.before})"] = measure(
                export(args.before, folder), args.repeat, args.symbolic3
            )
        columns["after (this tree)"] = measure(ROOT, args.repeat, args.symbolic3)
    labels = list(next(iter(columns.values())))
    print(f"{'row':<36}" + "".join(f"{name:>22}" for name in columns))
    for label in labels:
        print(f"{label:<36}" + "".join(f"{_text(c.get(label)):>22}" for c in columns.values()))
    print(
        f"(medians of {args.repeat} fresh processes, CPU seconds; {os.cpu_count()} cores, "
        f"load average {os.getloadavg()[0]:.1f}; {time.time() - start:.0f} s in all)"
    )


if __name__ == "__main__":
    main()
