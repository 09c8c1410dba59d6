"""Benchmark: ``perturb response`` on the shipped driven problems, this tree against another.

Issue 22 (item 5) sends the response equations through the certified solver of the free systems.
For each driven problem a sweep across its resonance is run as a fresh ``perturb response ...
--format json`` process in this tree and, with ``--before REV``, in the tree of git revision REV
(``git archive``); the table gives the process CPU seconds, the points with at least one branch, the
branches in all, the folds, and the points that failed. A run past ``--timeout`` is shown as such.
The cache is a fresh private folder per run (cold: the amplitude equations are derived each time).
Run from the repository root::

    python benchmarks/bench_response.py --before 62fa1a6
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
from pathlib import Path

from _tree import export, run_child

ROOT = Path(__file__).resolve().parent.parent
#: Give up one sweep after this many seconds (the absorber's folds ran past 300 s before).
TIMEOUT = 300
#: The sweeps: problem, swept parameter, range across its resonance, points.
SWEEPS = (
    ("forced-duffing", "Omega=0.95:1.2:51"),
    ("parametric-duffing", "Omega=1.9:2.1:41"),
    ("superharmonic-duffing", "Omega=0.3:0.36:31"),
    ("autoparametric-absorber", "Omega=1.9:2.1:21"),
)


def run(tree: Path, problem: str, sweep: str, timeout: float) -> str:
    """One row's figures: CPU s, points with a branch / points, branches, folds, failures."""
    with tempfile.TemporaryDirectory() as cache:
        args = ["-m", "perturb", "response", problem, "--sweep", sweep, "--format", "json"]
        try:
            cpu, out = run_child(tree, args, {"PERTURB_CACHE_DIR": cache}, timeout)
        except subprocess.TimeoutExpired:
            return f"past {timeout:g} s | | | |"
    if out.returncode != 0:
        return f"exit {out.returncode}: {out.stderr.strip()[-60:]} | | | |"
    data = json.loads(out.stdout)
    points = data.get("points", [])
    values = sorted({p["value"] for p in points})
    grid = int(sweep.rsplit(":", 1)[1])
    return (
        f"{cpu:.1f} | {len(values)}/{grid} | {len(points)} | {len(data.get('folds', []))} | "
        f"{len(data.get('failures', []))}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="a git revision to measure beside this tree")
    parser.add_argument("--timeout", type=float, default=TIMEOUT)
    args = parser.parse_args()
    trees = [("this tree", ROOT)]
    with tempfile.TemporaryDirectory() as folder:
        if args.before:
            trees.append((args.before, export(args.before, folder)))
        print(
            "| problem | sweep | tree | CPU s | points with a branch | branches | folds | failed |"
        )
        print("|---|---|---|---|---|---|---|---|")
        for problem, sweep in SWEEPS:
            for label, tree in trees:
                print(
                    f"| {problem} | {sweep} | {label} | {run(tree, problem, sweep, args.timeout)} |"
                )


if __name__ == "__main__":
    main()
