"""Run the hostile corpus (tests/cli/hostile_corpus.py), each invocation in a fresh process and
folder, and print what each surface gave.

    python benchmarks/hostile_cli.py [--jobs 2] [--surface NAME] [--group NAME] [--tree PATH]
                                     [--match TEXT]

``--tree PATH`` runs another checkout's perturb (put first on PYTHONPATH), to compare a revision
with this one. Prints, per surface and class, and per group of the second corpus's classes
(tests/cli/hostile_classes.py: working folder, scene paths, report marker, sizes, user code,
overflow/JSON, valid input, outputs, stores), the invocations and how many broke a promise (a
traceback, an internal error, an exit code other than promised, a user's file removed or changed,
a file written outside the output — a planted module's marker among them —, a run past its bound,
JSON that is not JSON), then every broken invocation. Figures
recorded in benchmarks/hostile_cli.md.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from tests.cli.hostile_corpus import corpus, run_case  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--surface", default=None, help="only this surface's cases")
    parser.add_argument("--group", default=None, help="only this group's cases ('' the first)")
    parser.add_argument("--match", default=None, help="only cases whose command holds this text")
    parser.add_argument("--tree", default=None, help="run this checkout's perturb instead")
    args = parser.parse_args()
    cases = [c for c in corpus() if args.surface in (None, c.surface)]
    if args.group is not None:
        cases = [c for c in cases if c.group == args.group]
    if args.match:
        cases = [c for c in cases if args.match in c.name]
    cache = tempfile.mkdtemp(prefix="perturb-hostile-cache-")
    env = {
        "PERTURB_CACHE_DIR": cache,
        "PERTURB_CACHE_KEY_FILE": os.path.join(tempfile.mkdtemp(), "cache.key"),
        "PYTHONPATH": os.pathsep.join(
            [p for p in (args.tree, str(ROOT), os.environ.get("PYTHONPATH")) if p]
        ),
    }

    def one(case):
        with tempfile.TemporaryDirectory(prefix="perturb-hostile-") as folder:
            return case, run_case(case, Path(folder), env)

    table = collections.defaultdict(collections.Counter)
    groups = collections.defaultdict(collections.Counter)
    broken = []
    clock = time.perf_counter()
    with ThreadPoolExecutor(args.jobs) as pool:
        for case, outcome in pool.map(one, cases):
            key = (case.surface, case.expect)
            table[key]["cases"] += 1
            table[key]["broken"] += bool(outcome.broken)
            table[key]["seconds"] = max(table[key]["seconds"], outcome.seconds)
            group = groups[case.group or "(first corpus)"]
            group["cases"] += 1
            group["broken"] += bool(outcome.broken)
            group["seconds"] = max(group["seconds"], outcome.seconds)
            if outcome.broken:
                last = outcome.err.strip().splitlines()[-1:] if outcome.err else []
                broken.append((case, outcome, last))
            print(f"{'BROKEN' if outcome.broken else 'ok    '} {outcome.seconds:6.1f}s "
                  f"{case.name[:150]}", file=sys.stderr, flush=True)  # fmt: skip
    print(f"{'surface':12s}{'class':>8s}{'cases':>8s}{'broken':>8s}{'slowest s':>11s}")
    for (surface, expect), counts in sorted(table.items()):
        print(
            f"{surface:12s}{expect:>8s}{counts['cases']:8d}{counts['broken']:8d}"
            f"{counts['seconds']:11.1f}"
        )
    print(f"\n{'group':24s}{'cases':>8s}{'broken':>8s}{'slowest s':>11s}")
    for name, counts in sorted(groups.items()):
        print(f"{name:24s}{counts['cases']:8d}{counts['broken']:8d}{counts['seconds']:11.1f}")
    total = sum(c["cases"] for c in table.values())
    print(f"\n{total} invocations, {len(broken)} broke a promise, "
          f"{time.perf_counter() - clock:.0f} s with {args.jobs} jobs")  # fmt: skip
    for case, outcome, last in broken:
        print(f"  {case.name}\n      {'; '.join(outcome.broken)} | {' '.join(last)[:300]}")


if __name__ == "__main__":
    main()
