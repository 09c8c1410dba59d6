"""Check: the disk's exact results are the very same expressions in this tree and in another one.

Runs the disk at orders 1-3 specialised (one parameter set, the default path) and order 2 symbolic in
all the body's parameters (``--symbolic3`` adds order 3, which an old tree may not reach in
``--timeout`` seconds) in fresh processes, once in this tree and once in ``--other``, cache off, and
compares ``srepr`` of every coefficient of the solution (terms, frequency, generating amplitudes,
initial-value deviations, the unknowns solved at each order, the dependent residuals). Prints a table
(identical / different, and the first items that differ). Run from the repository root::

    python benchmarks/check_disk_identical.py --other /work/main
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: Give up a case after this many seconds (an old tree's order 3 symbolic may run for an hour).
TIMEOUT = 1800

_DUMP = """
import json, sys
import sympy as sp
from perturb import PoincareMethod
from problems import get_problem
from problems.rigid_body._body import geometric_constraint
kind, order = sys.argv[1], int(sys.argv[2])
if kind == "specialised":
    solution = get_problem("disk").create(r0=30.2).solve(order)
else:
    disk = get_problem("disk")
    reduction = disk.reduction_for(order)
    options = disk.create().method_options()
    options["amplitudes"] = {"G": geometric_constraint(reduction)}
    solution = PoincareMethod(order=order, cache=False, **options).solve(reduction.system)
out = {"status": solution.status.name}
for i, row in enumerate(solution.terms):
    for k, term in enumerate(row):
        for j, (c, s) in sorted(term.terms.items()):
            out[f"x[{i}][{k}] cos {j}"] = sp.srepr(c)
            out[f"x[{i}][{k}] sin {j}"] = sp.srepr(s)
for k, w in enumerate(solution.frequency):
    out[f"omega[{k}]"] = sp.srepr(w)
gen = solution.generating
for i, (a, b) in enumerate(zip(gen.cos_amplitudes, gen.sin_amplitudes)):
    out[f"amplitude[{i}] cos"] = sp.srepr(sp.sympify(a))
    out[f"amplitude[{i}] sin"] = sp.srepr(sp.sympify(b))
for name, values in solution.deviations.items():
    for k, v in enumerate(values, start=1):
        out[f"deviation {name}[{k}]"] = sp.srepr(v)
for step in solution.steps:
    for sym, v in step.solved.items():
        out[f"order {step.order} solved {sym}"] = sp.srepr(v)
for name, v in solution.dependent_residuals.items():
    out[f"residual {name}"] = sp.srepr(v)
print(json.dumps(out))
"""


def dump(tree: Path, kind: str, order: int, timeout: float) -> tuple[dict | None, float]:
    """(srepr of every item, or None when the run failed or timed out; wall seconds)."""
    start = time.perf_counter()
    env = {**os.environ, "PYTHONPATH": str(tree), "PERTURB_CACHE_DIR": "off"}
    try:
        out = subprocess.run(
            [sys.executable, "-c", _DUMP, kind, str(order)],
            capture_output=True,
            text=True,
            check=True,
            cwd=tree,
            env=env,
            timeout=timeout,
        )
    except (subprocess.CalledProcessError, subprocess.TimeoutExpired) as exc:
        print(f"  {tree}: {kind} order {order}: {type(exc).__name__}", file=sys.stderr)
        return None, time.perf_counter() - start
    return json.loads(out.stdout.strip().splitlines()[-1]), time.perf_counter() - start


def compare(mine: dict | None, other: dict | None) -> tuple[str, list[str]]:
    """(verdict, names of the items that differ)."""
    if mine is None or other is None:
        return "not compared", []
    names = sorted(set(mine) | set(other))
    differ = [n for n in names if mine.get(n) != other.get(n)]
    return ("identical" if not differ else "DIFFERENT"), differ


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--other", required=True, type=Path, help="the other tree (e.g. /work/main)"
    )
    parser.add_argument("--symbolic3", action="store_true", help="add order 3 symbolic (slow)")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="seconds per run")
    args = parser.parse_args()
    cases = [("specialised", 1), ("specialised", 2), ("specialised", 3), ("symbolic", 2)]
    if args.symbolic3:
        cases.append(("symbolic", 3))
    print(f"{'case':<24}{'items':>7}{'this [s]':>10}{'other [s]':>11}  verdict")
    failed = False
    for kind, order in cases:
        mine, t_mine = dump(ROOT, kind, order, args.timeout)
        other, t_other = dump(args.other.resolve(), kind, order, args.timeout)
        verdict, differ = compare(mine, other)
        failed |= verdict == "DIFFERENT"
        items = len(mine) if mine is not None else 0
        print(
            f"{kind + ' order ' + str(order):<24}{items:>7}{t_mine:>10.1f}{t_other:>11.1f}  {verdict}"
        )
        for name in differ[:5]:
            print(f"    differs: {name}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
