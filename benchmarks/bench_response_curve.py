"""Benchmark: a 201-point order-3 response by continuation (issue 29), beside the route it replaced.

``perturb response forced-duffing --sweep Omega=0.95:1.2:201 --order 3 --format csv`` is run as a
fresh process in this tree: once cold (a fresh private cache: the amplitude equations derived,
compiled, the census solved) and ``--repeat`` times warm (the same cache: what a user re-running
or refining a sweep pays). With ``--before REV`` the same command runs in the tree of git revision
REV (``git archive``): the route of a certified first-order census and a Newton step at every grid
value. The table gives wall and CPU seconds (min and median of the warm runs), the import cost of
the CLI alone (``--help``, the floor of any command) and the load average, which on a shared
machine inflates the wall time. Run from the repository root::

    python benchmarks/bench_response_curve.py --before a86f06c --repeat 5
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _tree import export

ROOT = Path(__file__).resolve().parent.parent
COMMAND = ["-m", "perturb", "response", "forced-duffing", "--sweep", "Omega=0.95:1.2:201",
           "--order", "3", "--format", "csv"]  # fmt: skip
#: Give up one run after this many seconds (the replaced route took 86 s wall unloaded).
TIMEOUT = 900


def timed(tree: Path, args: list[str], cache: str) -> tuple[float, float, int]:
    """(wall s, CPU s, exit code) of ``python *args`` in ``tree`` with the cache ``cache``."""
    env = {**os.environ, "PYTHONPATH": str(tree), "PERTURB_CACHE_DIR": cache}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run([sys.executable, *args], cwd=tree, env=env, capture_output=True,
                         text=True, timeout=TIMEOUT)  # fmt: skip
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, out.returncode


def row(label: str, tree: Path, repeat: int) -> str:
    with tempfile.TemporaryDirectory() as cache:
        floor = timed(tree, ["-m", "perturb", "response", "--help"], cache)
        cold = timed(tree, COMMAND, cache)
        warm = [timed(tree, COMMAND, cache) for _ in range(repeat)]
    walls, cpus = [w for w, _, _ in warm], [c for _, c, _ in warm]
    codes = {code for _, _, code in [cold, *warm]}
    return (
        f"| {label} | {cold[0]:.2f} / {cold[1]:.2f} | {min(walls):.2f} / {min(cpus):.2f} | "
        f"{statistics.median(walls):.2f} / {statistics.median(cpus):.2f} | "
        f"{floor[0]:.2f} / {floor[1]:.2f} | {os.getloadavg()[0]:.1f} | {sorted(codes)} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="a git revision to measure beside this tree")
    parser.add_argument("--repeat", type=int, default=3, help="warm runs (default 3)")
    args = parser.parse_args()
    print("| tree | cold wall / CPU s | warm min wall / CPU s | warm median wall / CPU s | "
          "CLI import (--help) wall / CPU s | load avg | exit |")  # fmt: skip
    print("|---|---|---|---|---|---|---|")
    print(row("this tree", ROOT, args.repeat))
    if args.before:
        with tempfile.TemporaryDirectory() as folder:
            print(row(args.before, export(args.before, folder), max(1, min(args.repeat, 1))))


if __name__ == "__main__":
    main()
