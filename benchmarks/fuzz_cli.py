"""Run the whole CLI fuzz corpus (tests/cli/fuzz_corpus.py), each call in a fresh process.

    python benchmarks/fuzz_cli.py [--seconds 60] [--jobs 2]

Prints, per command, how many invocations exited 0/1/2 and how many broke a promise (traceback,
hang past the time limit, exit 2 without one error line, exit 0 printing NaN/inf or a negative
period), then every broken invocation.
"""

from __future__ import annotations

import argparse
import collections
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "cli"))
from fuzz_corpus import corpus, judge  # noqa: E402


def run_one(argv: list[str], seconds: float):
    start = time.perf_counter()
    try:
        with (
            tempfile.TemporaryDirectory() as folder
        ):  # whatever a call writes stays out of the tree
            proc = subprocess.run(
                [sys.executable, "-m", "perturb", *argv],
                capture_output=True,
                text=True,
                timeout=seconds,
                stdin=subprocess.DEVNULL,
                cwd=folder,
            )
        code, out, err = proc.returncode, proc.stdout, proc.stderr
    except subprocess.TimeoutExpired:
        code, out, err = None, "", ""
    return argv, code, out, err, time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=120.0, help="a call past this is a hang")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    cases = corpus()
    table = collections.defaultdict(collections.Counter)
    broken = []
    with ThreadPoolExecutor(args.jobs) as pool:
        for argv, code, out, err, _seconds in pool.map(lambda a: run_one(a, args.seconds), cases):
            command = argv[0] if argv else "(none)"
            table[command][f"exit {code}" if code is not None else "hang"] += 1
            problems = judge(argv, code, out, err)
            if problems:
                table[command]["broken"] += 1
                broken.append((argv, problems, err.strip().splitlines()[-1:] if err else []))
    columns = ["exit 0", "exit 1", "exit 2", "hang", "broken"]
    print(f"{'command':16s}" + "".join(f"{c:>9s}" for c in columns) + f"{'total':>9s}")
    for command, counts in sorted(table.items()):
        total = sum(v for k, v in counts.items() if k != "broken")
        print(f"{command:16s}" + "".join(f"{counts[c]:9d}" for c in columns) + f"{total:9d}")
    print(f"\n{len(cases)} invocations, {len(broken)} broke a promise")
    for argv, problems, last in broken:
        print(f"  {' '.join(repr(a) for a in argv)}: {', '.join(problems)} {last}")


if __name__ == "__main__":
    main()
