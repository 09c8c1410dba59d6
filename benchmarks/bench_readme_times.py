"""Benchmark: every time the README states, measured on a clean copy of the tree.

The README promises figures a new user checks with a watch: the first ``perturb reproduce paper``
(CPU and wall), a warm one, the validated 21 x 21 disk map ("about a minute on 2 cores"), the
scene that "runs in seconds", the documentation build, the test suite. Each row here runs that
very command as a new process on a fresh export of the tree (``git archive``, so nothing of the
checkout's caches or build products is used) with a fresh, empty perturb cache — the clean clone
a new user has — and reports

* the CPU seconds of the process and every process it waited for (``getrusage`` of the
  children: the Dask workers of a sweep, the kernels of the docs build),
* the wall seconds,
* the load average of the machine before and after (``os.getloadavg``): on a machine shared with
  other work the wall time grows with it, and the CPU time less.

Rows: ``reproduce`` (cold, then warm), ``sweep`` (the README's validated 21 x 21 disk map, cold,
then ``--resume``-free warm run into a new store), ``scene`` (``examples/scenes/duffing.toml``);
with ``--docs`` the site's build (``sphinx -W -n``), with ``--suite`` the default test suite, with
``--large`` the 100 x 100 disk map. Run from the repository root::

    python benchmarks/bench_readme_times.py [--docs] [--suite] [--large] [--only WORDS] [--rev HEAD]

The installs (``pip install -e .``) are not measured: they need the network.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _tree import export

#: Give up a row after this many seconds (the suite on a loaded 2-core machine: about 30 min).
ROW_TIMEOUT = 3 * 3600

DISK_MAP = ["sweep", "disk", "--set", "R=0.123299", "--grid", "r0=0.5:1.0:{n}", "--grid",
            "gamma3_0=0.1:0.4:{n}", "--order", "2", "--validate", "--output", "{store}"]  # fmt: skip


def timed(argv: list[str], tree: Path, env: dict) -> dict:
    """Run ``argv`` in ``tree`` with ``env`` added: CPU and wall seconds, the loads, the exit."""
    load_before = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    clock = time.perf_counter()
    out = subprocess.run(
        argv, capture_output=True, text=True, cwd=tree, timeout=ROW_TIMEOUT,
        env={**os.environ, "PYTHONPATH": str(tree), **env},
    )  # fmt: skip
    wall = time.perf_counter() - clock
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {
        "cpu": cpu,
        "wall": wall,
        "load": (load_before, os.getloadavg()[0]),
        "code": out.returncode,
        "tail": (out.stdout + out.stderr).strip().splitlines()[-1:] or [""],
        "output": out.stdout + out.stderr,
    }


def perturb(*args: str) -> list[str]:
    return [sys.executable, "-m", "perturb", *args, "--quiet"]


def rows(options) -> list[tuple[str, str, list[str]]]:
    """``(row, the README's figure, argv)`` in the order they run (a warm row after its cold)."""
    out = [
        ("reproduce paper, first run", "15 s CPU, 38 s wall", perturb("reproduce", "paper")),
        ("reproduce paper, warm", "5 s CPU", perturb("reproduce", "paper")),
        ("validated 21 x 21 disk map, first run", "about a minute on 2 cores",
         perturb(*[a.format(n=21, store="map-1.zarr") for a in DISK_MAP])),
        ("validated 21 x 21 disk map, warm", "about a minute on 2 cores",
         perturb(*[a.format(n=21, store="map-2.zarr") for a in DISK_MAP])),
        ("scene examples/scenes/duffing.toml", "runs in seconds",
         perturb("report", "examples/scenes/duffing.toml", "--output", "duffing-report")),
    ]  # fmt: skip
    if options.large:
        out.append(("validated 100 x 100 disk map (warm)", "about 8 minutes",
                    perturb(*[a.format(n=100, store="map-3.zarr") for a in DISK_MAP])))  # fmt: skip
    if options.docs:
        out.append(("documentation build", "about two minutes (130 s from a clean clone)",
                    [sys.executable, "-m", "sphinx", "-W", "-n", "--keep-going", "-q", "-b",
                     "html", "docs", "docs/_build/html"]))  # fmt: skip
    if options.suite:
        out.append(("default test suite", "8 to 12 minutes on 2 cores",
                    [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"]))  # fmt: skip
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rev", default="HEAD", help="the git revision measured (default HEAD)")
    parser.add_argument("--docs", action="store_true", help="also the documentation build")
    parser.add_argument("--suite", action="store_true", help="also the default test suite")
    parser.add_argument("--large", action="store_true", help="also the 100 x 100 disk map")
    parser.add_argument(
        "--only", default=None, metavar="WORDS", help="only the rows whose name holds WORDS"
    )
    parser.add_argument(
        "--log", default=None, metavar="FILE", help="also write every row's whole output to FILE"
    )
    options = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="perturb-readme-") as scratch:
        tree = export(options.rev, tempfile.mkdtemp(dir=scratch))
        cache = Path(scratch) / "cache"
        env = {
            "PERTURB_CACHE_DIR": str(cache),
            "PERTURB_CACHE_KEY_FILE": str(Path(scratch) / "cache.key"),
        }
        print(f"{'row':40s} {'README':>40s} {'CPU s':>8s} {'wall s':>8s} {'load':>11s} exit")
        for name, promise, argv in rows(options):
            if options.only is not None and options.only not in name:
                continue
            result = timed(argv, tree, env)
            loads = f"{result['load'][0]:.1f}-{result['load'][1]:.1f}"
            print(f"{name:40s} {promise:>40s} {result['cpu']:8.1f} {result['wall']:8.1f} "
                  f"{loads:>11s} {result['code']}", flush=True)  # fmt: skip
            if result["code"] not in (0,):
                print(f"    {result['tail'][0][:200]}", flush=True)
            if options.log is not None:
                with open(options.log, "a", encoding="utf-8") as log:
                    log.write(f"===== {name}: {' '.join(argv)}\n{result['output']}\n")
        shutil.rmtree(tree, ignore_errors=True)
    print(f"({os.cpu_count()} cores; load: 1-minute load average before-after each row; "
          "a fresh export of the tree and a fresh cache)")  # fmt: skip


if __name__ == "__main__":
    main()
