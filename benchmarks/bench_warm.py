"""Benchmark: a warm ``perturb validate disk`` (cache filled), whole process, phase by phase.

Issue 12 asks for a warm ``perturb validate disk`` in at most 1 s of CPU for the whole process and
``perturb --help`` in at most 0.3 s. Each figure is the process CPU time (user + system) of a fresh
interpreter, read from ``getrusage`` of the child; the median of ``--repeat`` runs is shown. The
cache is a fresh private folder (and signing key), filled by one run before the timed ones.

Rows: ``perturb --help``; warm ``perturb validate disk`` at the paper's parameters (eps = 232: the
series breaks down, no shooting) and at ``r0 = 30.2`` (eps = 1e-4: the conditioned true-orbit
shooting runs); the breakdown of the first into interpreter start, the command's imports, the
command itself (problem, ``validate``, report) and the interpreter's exit.

``--before REV`` measures the tree of git revision ``REV`` too (``git archive`` into a temporary
folder), for a side-by-side table. Run from the repository root::

    python benchmarks/bench_warm.py --before main --repeat 5
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
import time
from pathlib import Path

from _tree import export, run_child

ROOT = Path(__file__).resolve().parent.parent
#: Fresh-process repetitions of each row (medians are reported).
REPEATS = 5
#: Give up a fresh-process run after this many seconds.
CHILD_TIMEOUT = 600

#: The CLI as a program, with CPU marks: the command's own start-up (where the tree has one), its
#: imports, the command, and the end of ``main`` (what follows is the interpreter's exit).
_PHASES = """
import json, sys, time
marks = {"start": time.process_time()}
from perturb.cli import _main
getattr(_main, "_as_a_program", lambda: None)()  # what the tree's CLI does before any import
import perturb.cli._commands, perturb.report, perturb.validation, problems
marks["imported"] = time.process_time()
sys.argv = ["perturb", *sys.argv[1:]]
code = _main.main()
marks["done"] = time.process_time()
sys.stderr.write("MARKS " + json.dumps(marks) + "\\n")
sys.exit(code)
"""


def _child(tree: Path, args: list[str], env: dict) -> tuple[float, str]:
    """(CPU seconds of the child, its stderr); exit codes 0 and 1 (a verdict) are runs."""
    cpu, out = run_child(tree, args, env, CHILD_TIMEOUT)
    if out.returncode not in (0, 1):
        raise RuntimeError(f"{args}: exit {out.returncode}: {out.stderr[-500:]}")
    return cpu, out.stderr


def measure(tree: Path, repeat: int) -> dict[str, float]:
    rows: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as folder:
        os.chmod(folder, 0o700)
        env = {
            "PERTURB_CACHE_DIR": str(Path(folder) / "cache"),
            "PERTURB_CACHE_KEY_FILE": str(Path(folder) / "key" / "cache.key"),
        }
        rows["`perturb --help`"] = statistics.median(
            _child(tree, ["-m", "perturb", "--help"], env)[0] for _ in range(repeat)
        )
        for label, extra in (("", []), (" r0=30.2", ["--set", "r0=30.2"])):
            command = ["-m", "perturb", "validate", "disk", *extra]
            _child(tree, command, env)  # fill the cache
            rows[f"warm `validate disk{label}`"] = statistics.median(
                _child(tree, command, env)[0] for _ in range(repeat)
            )
        start = statistics.median(_child(tree, ["-c", "pass"], env)[0] for _ in range(repeat))
        phases = []
        for _ in range(repeat):
            total, err = _child(tree, ["-c", _PHASES, "validate", "disk"], env)
            marks = json.loads(err.rsplit("MARKS ", 1)[1])
            phases.append(
                {
                    "imports": marks["imported"] - marks["start"],
                    "command": marks["done"] - marks["imported"],
                    "exit": total - marks["done"],
                }
            )
        rows["  interpreter start"] = start
        for name in ("imports", "command", "exit"):
            rows[f"  {name}"] = statistics.median(p[name] for p in phases)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--before", metavar="REV", help="also measure git revision REV first")
    parser.add_argument("--repeat", type=int, default=REPEATS)
    args = parser.parse_args()
    began = time.time()
    columns = {}
    with tempfile.TemporaryDirectory() as folder:
        if args.before:
            columns[f"before ({args.before})"] = measure(export(args.before, folder), args.repeat)
        columns["after (this tree)"] = measure(ROOT, args.repeat)
    labels = list(next(iter(columns.values())))
    print(f"{'CPU seconds':<32}" + "".join(f"{name:>22}" for name in columns))
    for label in labels:
        print(f"{label:<32}" + "".join(f"{c[label]:>22.2f}" for c in columns.values()))
    threads = {n: os.environ.get(n, "unset") for n in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    print(
        f"(medians of {args.repeat} fresh processes; {os.cpu_count()} cores, load average "
        f"{os.getloadavg()[0]:.1f}; {threads}; {time.time() - began:.0f} s in all)"
    )


if __name__ == "__main__":
    main()
