"""Engine benchmark: derivation time per order, ``perturb --help`` start-up, evaluation throughput.

Run::

    python benchmarks/bench_engine.py                       # this tree only
    python benchmarks/bench_engine.py --before /tmp/old     # side by side with another checkout
    python benchmarks/bench_engine.py --fallback            # also this tree on the sympy backend
    python benchmarks/bench_engine.py --kernel              # single kernel operations, both backends

(``git worktree add /tmp/old <commit>`` makes the other checkout.) Prints tables, asserts nothing.

Every figure comes from a fresh process (cold: nothing derived yet, ``PERTURB_CACHE_DIR=off``), the
median of ``--repeats`` runs:

* derivation: process CPU seconds of ``PoincareMethod(order=k).solve`` for the resonant pair and
  van der Pol, ``k = 1..--max-order`` (the Groebner root search runs in a child process; its CPU
  time is added, from ``RUSAGE_CHILDREN``), and the wall time;
* ``perturb --help``: wall and CPU time of the whole process (median of 5);
* evaluation: state points per second of ``PeriodicSolution.evaluate`` at 10**6 times, best of
  ``EVALUATE_REPEATS`` calls in one process (wall and
  process CPU).

``--kernel`` prints instead the kernel's single operations (trigonometric-polynomial product,
ε-series of a cubic, a Taylor coefficient, the conversion back) on sympy and on symengine.

The machine is shared: run the trees back to back and compare the medians, not single runs.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent
N_POINTS = 1_000_000
#: In-process repetitions of the evaluation row (the best one is reported).
EVALUATE_REPEATS = 5
HELP_RUNS = 5
PROBLEMS = ("resonant-pair", "van-der-pol")


# ---------------------------------------------------------------------------------- workers
def _cpu() -> float:
    own = time.process_time()
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own + children.ru_utime + children.ru_stime


def _worker_derive(name: str, order: int) -> dict:
    from perturb import PoincareMethod
    from problems import get_problem

    problem = get_problem(name).create()
    system, options = problem.system(), problem.method_options()
    cpu, wall = _cpu(), time.perf_counter()
    solution = PoincareMethod(order=order, cache=False, **options).solve(system)
    cpu, wall = _cpu() - cpu, time.perf_counter() - wall
    assert solution.success, solution.message
    return {"cpu": cpu, "wall": wall}


def _worker_evaluate(name: str, order: int) -> dict:
    import numpy as np

    from perturb.validation.model import parameter_value_of
    from problems import get_problem

    problem = get_problem(name).create()
    solution = problem.solve(order)
    values, eps = problem.symbol_values(), parameter_value_of(problem)
    t = np.linspace(0.0, 100.0, N_POINTS)
    solution.evaluate(t[:10], eps, values)  # compile once
    # best of EVALUATE_REPEATS (as timeit does): a single 40 ms call varied 2x with the first
    # touch of its 10**6-point arrays and the machine's load
    cpu, wall = math.inf, math.inf
    for _ in range(EVALUATE_REPEATS):
        cpu0, wall0 = time.process_time(), time.perf_counter()
        solution.evaluate(t, eps, values)
        cpu = min(cpu, time.process_time() - cpu0)
        wall = min(wall, time.perf_counter() - wall0)
    return {"cpu": N_POINTS / cpu, "wall": N_POINTS / wall}


def _best(fn, repeats: int = 5) -> float:
    from sympy.core.cache import clear_cache

    times = []
    for _ in range(repeats):
        clear_cache()  # sympy memoises: every run starts cold
        start = time.process_time()
        fn()
        times.append(time.process_time() - start)
    return statistics.median(times)


def kernel_table() -> None:
    """The kernel's operations on sympy and on the native backend, in this process (CPU s)."""
    import sympy as sp

    from perturb import EPS, PoincareMethod, native
    from perturb.method.exact import taylor_coefficient
    from perturb.series import TrigSeries, evaluate_polynomial
    from perturb.trig import SympyRing
    from problems import get_problem

    if native.BACKEND != "symengine":
        print("kernel table: symengine is not installed")
        return
    problem = get_problem("resonant-pair").create()
    sol = PoincareMethod(order=6, cache=False, **problem.method_options()).solve(problem.system())
    x_terms = [t for t in sol.terms[0]]
    conv = native.Converter(native.SymengineRing)
    nx = [conv.native_poly(t) for t in x_terms]
    p, q = sol.steps[-1].forcing["x"], sol.steps[-2].forcing["y"]  # the largest polynomials
    np_, nq = conv.native_poly(p), conv.native_poly(q)
    x = sp.Symbol("x")
    cubic = -(x**3)
    series_s = {x: TrigSeries(x_terms)}
    series_n = {x: TrigSeries(nx)}
    g, c1, c2 = sp.symbols("gamma c1 c2")
    root = sp.sqrt(1 - (g + EPS * c1 + EPS**2 * c2) ** 2) * (c1 + EPS * c2) / (1 + EPS * g)

    def taylor_on(backend):
        def run():
            saved, native.BACKEND = native.BACKEND, backend
            try:
                taylor_coefficient(root, 4)
            finally:
                native.BACKEND = saved

        return run

    rows = [
        ("TrigPoly product R_x,7 * R_y,6 (res. pair)", lambda: p * q, lambda: np_ * nq),
        (
            "eps-series of -x^3 to eps^6",
            lambda: evaluate_polynomial(cubic, series_s, 6),
            lambda: evaluate_polynomial(cubic, series_n, 6, conv.to_native),
        ),
        ("Taylor coefficient eps^4 of a root", taylor_on("sympy"), taylor_on("symengine")),
    ]
    print("kernel operations, CPU s (median of 5, in process): sympy / native / ratio")
    for label, slow, fast in rows:
        a, b = _best(slow), _best(fast)
        print(f"{label:44s}{a:10.4f}{b:10.5f}{a / b:8.0f}x")
    product = np_ * nq
    back = _best(lambda: [conv.trig(product).terms])
    print(f"{'converting that product back to sympy':44s}{back:10.4f}")
    assert SympyRing is not native.SymengineRing


def _run_worker(tree: Path, args: list[str], env_extra: dict | None = None) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree), PERTURB_CACHE_DIR="off", **(env_extra or {}))
    done = subprocess.run(
        [sys.executable, str(Path(__file__).resolve()), "--worker", *args],
        env=env,
        cwd=tree,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def _help_times(tree: Path, env_extra: dict | None = None) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree), PERTURB_CACHE_DIR="off", **(env_extra or {}))
    walls, cpus = [], []
    for _ in range(HELP_RUNS):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "perturb", "--help"],
            env=env,
            cwd=tree,
            capture_output=True,
            check=True,
        )
        walls.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return {"wall": statistics.median(walls), "cpu": statistics.median(cpus)}


def _median(runs: list[dict]) -> dict:
    return {key: statistics.median(r[key] for r in runs) for key in runs[0]}


# ---------------------------------------------------------------------------------- tables
def measure(trees: dict[str, tuple[Path, dict]], max_order: int, repeats: int) -> dict:
    """Every figure for every tree, the trees interleaved run by run (the machine's load then
    weighs on all columns alike)."""
    out = {label: {"help": None, "derive": {}, "evaluate": {}} for label in trees}

    def each(args: list[str]) -> dict[str, dict]:
        runs: dict[str, list] = {label: [] for label in trees}
        for _ in range(repeats):
            for label, (tree, env) in trees.items():
                runs[label].append(_run_worker(tree, args, env))
        return {label: _median(r) for label, r in runs.items()}

    for label, (tree, env) in trees.items():
        out[label]["help"] = _help_times(tree, env)
    for name in PROBLEMS:
        for order in range(1, max_order + 1):
            for label, value in each(["derive", name, str(order)]).items():
                out[label]["derive"][(name, order)] = value
            print(f"  {name} order {order} done", file=sys.stderr)
        for label, value in each(["evaluate", name, "3"]).items():
            out[label]["evaluate"][name] = value
    return out


def _print_tables(columns: dict[str, dict], max_order: int) -> None:
    labels = list(columns)
    width = max(14, *(len(label) + 2 for label in labels))
    head = "".join(f"{label:>{width}s}" for label in labels)
    print("perturb --help (fresh process, median of 5) [s], wall / CPU")
    print(f"{'':24s}{head}")
    print(
        f"{'--help':24s}"
        + "".join(
            f"{c['help']['wall']:>{width - 7}.3f} /{c['help']['cpu']:5.3f}"
            for c in columns.values()
        )
    )
    print()
    print("derivation, cache off, fresh process (median) [s]: CPU (own + children) / wall")
    print(f"{'problem':16s}{'order':>8s}{head}")
    for name in PROBLEMS:
        for order in range(1, max_order + 1):
            cells = "".join(
                f"{c['derive'][(name, order)]['cpu']:>{width - 8}.3f} /{c['derive'][(name, order)]['wall']:6.2f}"
                for c in columns.values()
            )
            print(f"{name:16s}{order:8d}{cells}")
    print()
    print(f"evaluate, order 3, {N_POINTS:.0e} points [points/s]: per CPU second / per wall second")
    for name in PROBLEMS:
        cells = "".join(
            f"{c['evaluate'][name]['cpu']:>{width - 10}.2e} /{c['evaluate'][name]['wall']:8.2e}"
            for c in columns.values()
        )
        print(f"{name:24s}{cells}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, help="another checkout to measure first")
    parser.add_argument("--fallback", action="store_true", help="also PERTURB_BACKEND=sympy")
    parser.add_argument("--max-order", type=int, default=12)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--kernel", action="store_true", help="only the kernel operations table")
    parser.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:
        kind, name, order = args.worker
        worker = _worker_derive if kind == "derive" else _worker_evaluate
        print(json.dumps(worker(name, int(order))))
        return
    if args.kernel:
        kernel_table()
        return
    from perturb.native import BACKEND  # this tree's backend, for the label

    trees: dict[str, tuple[Path, dict]] = {}
    if args.before is not None:
        trees[f"before ({args.before.name})"] = (args.before.resolve(), {})
    trees[f"this tree ({BACKEND})"] = (HERE, {})
    if args.fallback:
        trees["this tree (sympy)"] = (HERE, {"PERTURB_BACKEND": "sympy"})
    columns = measure(trees, args.max_order, args.repeats)
    _print_tables(columns, args.max_order)


if __name__ == "__main__":
    main()
