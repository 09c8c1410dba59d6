"""Benchmark: sweeps on Dask — throughput, the Dask path against a plain loop, the validated disk map.

Issue 19 asks for evaluation-only sweeps at >= 1e5 points/s on 2 cores, a 100 x 100 validity map
of the fast-spin disk (r0 x gamma3_0, order 2, validated) in <= 10 min on 2 cores, and the
per-point overhead of the Dask path against a plain loop at 1 and 2 workers. Sections (each
prints a table; all by default):

``eval``      points/s of evaluation-only sweeps (Duffing order 2 on 1000 x 1000, van der Pol
              order 3 on 10^6 values of eps) on a LocalCluster of ``--workers``, into a Zarr store;
``overhead``  the same chunks run in a plain loop in this process, then on Dask with 1 and 2
              workers (evaluation and validation); the overhead per point is
              (workers x wall - loop) / points, the scheduling share (wall x workers - busy) / wall;
``point``     CPU of one validated point of the disk map (order 2, the symbolic solution), warm,
              in this tree and in ``--before REV`` (the same ``validate`` call through a model
              whose ``solve`` is ``solve(order, symbolic=True)``);
``ship``      shipping the derived solution to a worker (pickle, load, compile) against rebuilding
              it there (derive, warm disk cache and cold), fresh processes;
``disk``      the 100 x 100 validated map of the fast-spin disk, the whole ``perturb sweep``
              command timed (``--quick``: 20 x 20).

Wall times are measured on a machine that may be shared: rerun a section to see its spread. Run
from the repository root::

    python benchmarks/bench_sweep.py                       # everything (about 12 minutes)
    python benchmarks/bench_sweep.py --only overhead point --before main
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _tree import ROOT, export, run_child

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

#: The disk map of the issue: around the fast-spin point r0 = 0.755155, gamma3_0 = 0.25.
DISK_FIXED = {"R": 0.123299}
DISK_AXES = ("r0=0.5:1.0:{n}", "gamma3_0=0.1:0.4:{n}")
#: Give up a fresh-process run after this many seconds.
CHILD_TIMEOUT = 1800


def _job(problem, axes, **settings):
    from perturb.sweep.derive import plan
    from perturb.sweep.grid import parse_axis
    from perturb.sweep.spec import SweepJob, check_spec

    spec = check_spec(problem, [parse_axis(a) for a in axes], **settings)
    derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
    return SweepJob(spec, derivation, "bench")


def _sweep(problem, axes, workers: int, store: Path | None = None, client=None, **settings):
    import perturb

    clock = time.perf_counter()
    ds = perturb.sweep(
        problem, list(axes), workers=workers, output=store, client=client, **settings
    )
    return time.perf_counter() - clock, float(ds.attrs["seconds"]), ds


def section_eval(workers: int) -> None:
    from problems import get_problem

    print(f"\n## evaluation-only sweeps, LocalCluster of {workers} workers, Zarr store\n")
    print(
        "| sweep | points | sweep phase [s] | points/s (sweep phase) | points per task CPU-second "
        "| whole call [s] |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    cases = [
        ("duffing order 2, eps x amplitude 1000 x 1000", "duffing", ["eps=0.01:0.2:1000", "amplitude=0.5:1.5:1000"], 2),
        ("van der Pol order 3, eps 10^6 values", "van-der-pol", ["eps=0.01:0.5:1000000"], 3),
    ]  # fmt: skip
    for label, name, axes, order in cases:
        with tempfile.TemporaryDirectory() as folder:
            whole, phase, ds = _sweep(
                get_problem(name).create(), axes, workers, Path(folder) / "s.zarr", order=order
            )
            points = int(ds["status"].size)
            per_cpu = points / ds.attrs["task_cpu_seconds"]
            print(
                f"| {label} | {points:,} | {phase:.1f} | {points / phase:,.0f} | {per_cpu:,.0f} "
                f"| {whole:.1f} |"
            )


def _loop(job, chunking) -> tuple[float, float]:
    from perturb.sweep.task import run_chunk

    clock, cpu = time.perf_counter(), time.process_time()
    for number in chunking:
        run_chunk(job, chunking.indices(number))
    return time.perf_counter() - clock, time.process_time() - cpu


def section_overhead() -> None:
    from perturb.sweep.driver import Cluster, chunk_points, pilot_seconds, run_tasks
    from perturb.sweep.grid import Chunking
    from problems import get_problem

    print("\n## the Dask path against a plain loop (the same chunks, results kept in memory)\n")
    print(
        "CPU seconds are counted where the work runs (workers, and this process for the loop and"
        " the driver), so that they do not depend on what else the machine runs; the overhead per"
        " point is (tasks' CPU + driver's CPU - loop's CPU) / points.\n"
    )
    print(
        "| work | points | chunks | workers | loop wall [s] | loop CPU/point [ms] | Dask wall [s] "
        "| tasks CPU/point [ms] | driver CPU/point [ms] | overhead/point [ms] | overhead share |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    cases = [
        ("evaluation, duffing order 2", ["eps=0.01:0.2:500", "amplitude=0.5:1.5:400"], {"order": 2}),
        ("validation, duffing order 1", ["eps=0.02:0.2:16", "amplitude=0.6:1.4:12"], {"validate": True}),
    ]  # fmt: skip
    for label, axes, settings in cases:
        job = _job(get_problem("duffing").create(), axes, **settings)
        size = job.spec.grid.size
        seconds = pilot_seconds(job)
        for workers in (1, 2):
            chunking = Chunking.of(job.spec.grid.shape, chunk_points(seconds, size, workers))
            _loop(job, chunking)  # warm: every compiled integrator of the grid, in this process
            loop_wall, loop_cpu = _loop(job, chunking)
            with Cluster(workers) as cluster:
                cluster.client.wait_for_workers(workers)
                # warm every worker (imports, derivation, compiled integrators) as a long sweep does
                run_tasks(cluster, job, chunking, list(chunking), lambda n, r: None,
                          session=1, done=0, label="warm")  # fmt: skip
                clock, cpu = time.perf_counter(), time.process_time()
                stats = run_tasks(cluster, job, chunking, list(chunking), lambda n, r: None,
                                  session=1, done=0, label="timed")  # fmt: skip
                wall, driver = time.perf_counter() - clock, time.process_time() - cpu
            overhead = (stats.cpu + driver - loop_cpu) / size
            print(
                f"| {label} | {size:,} | {chunking.n_chunks} | {workers} | {loop_wall:.2f} | "
                f"{loop_cpu / size * 1e3:.4f} | {wall:.2f} | {stats.cpu / size * 1e3:.4f} | "
                f"{driver / size * 1e3:.4f} | {overhead * 1e3:.4f} | "
                f"{overhead * size / loop_cpu:.1%} |"
            )


_POINT = """
import json, sys, time
from problems import get_problem
from perturb.validation import Model, validate
cls = get_problem("disk")
base = dict(R=0.123299, r0=0.755155, gamma3_0=0.25)

SYMBOLIC = sys.argv[1] == "symbolic"
class Symbolic(Model):  # a sweep's derivations: solve(order, symbolic=True), or the problem's own
    def __init__(self, p): self.p = p
    def solve(self, order=1):
        return self.p.solve(order, symbolic=True) if SYMBOLIC else self.p.solve(order)
    def with_epsilon(self, eps):
        q = self.p.with_epsilon(eps)
        return None if q is None else Symbolic(q)
for name in ["state_names", "state", "period", "epsilon", "system", "symbol_values",
             "label", "case", "method_options",
             "original_equations", "integrals_of_motion", "validity_estimates", "true_orbit",
             "shooting_setup", "euler_angles"]:
    setattr(Symbolic, name, (lambda n: lambda self, *a, **k: getattr(self.p, n)(*a, **k))(name))
Symbolic.__abstractmethods__ = frozenset()
r0s = [0.5 + 0.5 * i / 19 for i in range(20)]
points = [(r, g) for g in (0.25, 0.3) for r in r0s]  # per point: one derivation per gamma3_0
for r, g in points[:3] + points[20:23]:  # warm: derivations, compiled integrators
    validate(Symbolic(cls.create(**{**base, "r0": r, "gamma3_0": g})), order=2)
timed = points[3:20] + points[23:]
clock = time.process_time()
for r, g in timed:
    validate(Symbolic(cls.create(**{**base, "r0": r, "gamma3_0": g})), order=2)
print(json.dumps({"cpu_per_point": (time.process_time() - clock) / len(timed)}))
"""


def section_point(before: str | None) -> None:
    print("\n## one validated point of the disk map (order 2, warm: derivations made), CPU\n")
    print("| tree | derivation | CPU per point [s] |")
    print("|---|---|---:|")
    trees = [("this tree", ROOT)]
    tmp = None
    if before:
        tmp = tempfile.mkdtemp(prefix="bench-sweep-")
        trees.append((f"before ({before})", export(before, tmp)))
    try:
        for label, tree in trees:
            for mode in ("symbolic", "per point"):
                with tempfile.TemporaryDirectory() as cache:
                    env = {"PERTURB_CACHE_DIR": cache}
                    _, out = run_child(tree, ["-c", _POINT, mode.split()[0]], env, CHILD_TIMEOUT)
                if out.returncode != 0:
                    print(f"| {label} | {mode} | failed: {out.stderr.strip().splitlines()[-1]} |")
                    continue
                cpu = json.loads(out.stdout.strip().splitlines()[-1])["cpu_per_point"]
                print(f"| {label} | {mode} | {cpu:.3f} |")
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)


_DERIVE = """
import json, pickle, sys, time
from problems import get_problem
disk = get_problem("disk").create(R=0.123299, r0=0.755155, gamma3_0=0.25)
clock = time.process_time()
solution = disk.solve(2, symbolic=True)
derive = time.process_time() - clock
clock = time.process_time()
solution._compiled
compile_ = time.process_time() - clock
if len(sys.argv) > 1:
    open(sys.argv[1], "wb").write(pickle.dumps(solution))
print(json.dumps({"derive": derive, "compile": compile_}))
"""
_LOAD = """
import json, pickle, sys, time
import perturb.solution, problems
clock = time.process_time()
solution = pickle.loads(open(sys.argv[1], "rb").read())
load = time.process_time() - clock
clock = time.process_time()
solution._compiled
print(json.dumps({"load": load, "compile": time.process_time() - clock}))
"""


def section_ship() -> None:
    print("\n## the derivation on a worker: shipped (pickled) or rebuilt (disk order 2 symbolic)\n")
    print("| route | what | CPU [s] |")
    print("|---|---|---:|")
    with tempfile.TemporaryDirectory() as folder:
        blob = Path(folder) / "solution.pkl"
        cache = Path(folder) / "cache"
        cache.mkdir(mode=0o700)
        env = {"PERTURB_CACHE_DIR": str(cache)}
        _, cold = run_child(ROOT, ["-c", _DERIVE, str(blob)], env, CHILD_TIMEOUT)
        cold = json.loads(cold.stdout.splitlines()[-1])
        _, warm = run_child(ROOT, ["-c", _DERIVE], env, CHILD_TIMEOUT)
        warm = json.loads(warm.stdout.splitlines()[-1])
        _, load = run_child(ROOT, ["-c", _LOAD, str(blob)], env, CHILD_TIMEOUT)
        load = json.loads(load.stdout.splitlines()[-1])
        size = blob.stat().st_size
        print(
            f"| rebuild, cold (no disk cache) | derive + compile | {cold['derive'] + cold['compile']:.2f} |"
        )
        print(
            f"| rebuild, warm disk cache | derive + compile | {warm['derive'] + warm['compile']:.2f} |"
        )
        print(
            f"| ship ({size / 1e3:.0f} kB pickle) | load + compile | {load['load'] + load['compile']:.2f} |"
        )


def section_disk(quick: bool, workers: int) -> None:
    n = 20 if quick else 100
    print(f"\n## the validated disk map {n} x {n}, order 2, {workers} workers (whole command)\n")
    print("| grid | points | wall [s] | sweep phase [s] | verdicts |")
    print("|---|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as folder:
        store = Path(folder) / "disk.zarr"
        argv = [sys.executable, "-m", "perturb", "sweep", "disk", "--order", "2", "--validate",
                "--workers", str(workers), "--output", str(store), "--quiet"]  # fmt: skip
        for name, value in DISK_FIXED.items():
            argv += ["--set", f"{name}={value}"]
        for axis in DISK_AXES:
            argv += ["--grid", axis.format(n=n)]
        clock = time.perf_counter()
        out = subprocess.run(argv, capture_output=True, text=True, cwd=ROOT, timeout=CHILD_TIMEOUT)
        wall = time.perf_counter() - clock
        if out.returncode != 0:
            print(f"| {n} x {n} | failed: {out.stderr.strip()[-300:]} |")
            return
        summary = out.stdout.splitlines()
        phase = summary[0].split("), ")[1].split(" s;")[0]
        verdicts = next((line for line in summary if line.startswith("verdicts")), "")
        print(
            f"| {' x '.join(DISK_AXES).format(n=n)} | {n * n:,} | {wall:.0f} | {phase} | {verdicts} |"
        )


def _spin(n: int) -> float:
    clock = time.perf_counter()
    total = 0
    for i in range(n):
        total += i * i
    return time.perf_counter() - clock


def _parallelism(n: int = 5_000_000) -> float:
    """Work done by two processes at once, in units of one alone (2 on two free cores)."""
    from concurrent.futures import ProcessPoolExecutor

    alone = _spin(n)
    with ProcessPoolExecutor(2) as pool:
        pool.submit(_spin, 1000).result()  # started
        clock = time.perf_counter()
        list(pool.map(_spin, [n, n]))
        together = time.perf_counter() - clock
    return 2 * alone / together


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="+", default=["eval", "overhead", "point", "ship", "disk"])
    parser.add_argument("--before", default=None, metavar="REV", help="also time this revision")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="a 20 x 20 disk map")
    args = parser.parse_args()
    sections = {
        "eval": lambda: section_eval(args.workers),
        "overhead": section_overhead,
        "point": lambda: section_point(args.before),
        "ship": section_ship,
        "disk": lambda: section_disk(args.quick, args.workers),
    }
    print(f"# bench_sweep ({os.cpu_count()} cores, Python {sys.version.split()[0]})")
    print(
        f"\nparallelism of this machine now: {_parallelism():.2f} (2 processes of pure Python "
        "against one; 2.00 = two free cores)"
    )
    for name in args.only:
        sections[name]()


if __name__ == "__main__":
    main()
