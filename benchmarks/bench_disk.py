"""Benchmark: the disk reduction and its first-order Poincaré solution, cold and cached.

Cold figures come from a fresh interpreter per repetition (nothing imported or cached); cached
figures repeat the same calls in one process (``functools.cache`` on the reduction, the problem
solution cache). Run from the repository root::

    python benchmarks/bench_disk.py
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

#: Fresh-process repetitions (each pays imports, the reduction and the solve).
COLD_REPEATS = 3
#: In-process repetitions of the cached calls.
WARM_REPEATS = 20

_COLD_SCRIPT = """
import json, time
t0 = time.perf_counter()
from problems.rigid_body.reduction import disk_reduction
from problems import get_problem
t1 = time.perf_counter()
disk_reduction(3)
t2 = time.perf_counter()
problem = get_problem("disk").create(r0=30.2)
solution = problem.solve(1)
t3 = time.perf_counter()
problem.state(solution, [0.0, 0.1])
t4 = time.perf_counter()
print(json.dumps({"import": t1 - t0, "reduction": t2 - t1, "solve": t3 - t2, "first state": t4 - t3}))
"""


def cold() -> dict[str, list[float]]:
    runs: dict[str, list[float]] = {}
    for _ in range(COLD_REPEATS):
        out = subprocess.run(
            [sys.executable, "-c", _COLD_SCRIPT], capture_output=True, text=True, check=True
        )
        for key, value in json.loads(out.stdout.strip().splitlines()[-1]).items():
            runs.setdefault(key, []).append(value)
    return runs


def warm() -> dict[str, list[float]]:
    import numpy as np

    from problems import get_problem
    from problems.rigid_body.reduction import disk_reduction

    problem = get_problem("disk").create(r0=30.2)
    problem.state(problem.solve(1), [0.0])  # fill the caches
    t = np.linspace(0.0, 10.0, 1001)
    runs: dict[str, list[float]] = {}
    for _ in range(WARM_REPEATS):
        for label, call in (
            ("reduction", lambda: disk_reduction(3)),
            ("solve", lambda: problem.solve(1)),
            ("state, 1001 times", lambda: problem.state(problem.solve(1), t)),
        ):
            start = time.perf_counter()
            call()
            runs.setdefault(label, []).append(time.perf_counter() - start)
    return runs


def main() -> None:
    print(f"{'stage':<22}{'cold (fresh process) s':>26}{'cached (in process) s':>26}")
    cold_runs, warm_runs = cold(), warm()
    for key in ("import", "reduction", "solve", "first state", "state, 1001 times"):
        c = cold_runs.get(key)
        w = warm_runs.get(key)
        c_txt = f"{statistics.median(c):.3f}" if c else "-"
        w_txt = f"{statistics.median(w):.2e}" if w else "-"
        print(f"{key:<22}{c_txt:>26}{w_txt:>26}")


if __name__ == "__main__":
    main()
