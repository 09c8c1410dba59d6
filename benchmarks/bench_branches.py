"""Benchmark: the whole diagram of the true responses (``perturb response --true
[--max-period K]``): every branch born at a branch point or a period doubling, followed.

The issue's example: x'' + 0.1 x' + x + x^3 = F cos 1.2 t (``forced-duffing`` typed with eps = 1,
zeta = 0.05, Omega = 1.2), continued in F from 0.01 to 60 with ``--true``: the symmetric branch,
the asymmetric pair born at each pitchfork, and the doubled orbits born on them (``--max-period``
1, 2, 4). For each: the branches (records), their points and shots, the special points by kind,
and the wall and CPU seconds of the whole command (series, true curves, heyoka's compilation).
A second table: each pitchfork and period doubling of the K = 2 run against a route that shares
nothing with perturb (scipy DOP853 at rtol 1e-12, Newton on the period or half-period map at each
F, Brent on F for the zero of det(J + I)).

Run from the repository root (``nice`` on a shared machine)::

    python benchmarks/bench_branches.py [--quick]
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

OMEGA, DAMPING = 1.2, 0.1


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def run(max_period: int, high: float):
    from perturb.response.model import problem_response
    from problems import get_problem

    problem = get_problem("forced-duffing").create(eps=1.0, zeta=0.05, Omega=OMEGA)
    grid = np.linspace(0.01, high, 61)
    wall, cpu = time.perf_counter(), _cpu()
    result = problem_response(problem, "F", grid, order=1, true=1000, max_period=max_period)
    return result.true_curve, time.perf_counter() - wall, _cpu() - cpu


def _field(force):
    from math import cos

    def f(t, y):
        x, v = y[0], y[1]
        m = y[2:].reshape(2, 2)
        jac = np.array([[0.0, 1.0], [-1.0 - 3 * x * x, -DAMPING]])
        return [v, -DAMPING * v - x - x**3 + force * cos(OMEGA * t), *(jac @ m).ravel()]

    return f


def _map(y, force, half, periods=1):
    from scipy.integrate import solve_ivp

    span = (math.pi if half else 2 * math.pi * periods) / OMEGA
    sol = solve_ivp(_field(force), (0.0, span), [*y, 1.0, 0.0, 0.0, 1.0], method="DOP853",
                    rtol=1e-12, atol=1e-14)  # fmt: skip
    end, mono = sol.y[:2, -1], sol.y[2:, -1].reshape(2, 2)
    return (-end, -mono) if half else (end, mono)


def reference(value, state, half, periods=1):
    from scipy.optimize import brentq

    y = np.array(state, dtype=float)

    def test(force):
        nonlocal y
        for _ in range(30):
            image, jac = _map(y, force, half, periods)
            step = np.linalg.solve(jac - np.eye(2), -(image - y))
            y = y + step
            if float(np.max(np.abs(step))) < 1e-12 * max(1.0, float(np.max(np.abs(y)))):
                break
        return float(np.linalg.det(_map(y, force, half, periods)[1] + np.eye(2)))

    return brentq(test, value - 1e-4, value + 1e-4, xtol=1e-13, rtol=1e-15)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="F up to 26 only, K = 1 and 2")
    args = parser.parse_args()
    high = 26.0 if args.quick else 60.0
    periods = (1, 2) if args.quick else (1, 2, 4)
    print(f"# cores: {os.cpu_count()}, load average {os.getloadavg()[0]:.2f}")
    print("| max period | branches (by period) | points | shots | special points | wall s | "
          "CPU s |")  # fmt: skip
    print("|---|---|---|---|---|---|---|")
    kept = None
    for k in periods:
        curves, wall, cpu = run(k, high)
        by_period = Counter(c.period for c in curves.curves)
        kinds = Counter(b.kind for c in curves.curves for b in c.bifurcations
                        if b.kind != "crossing")  # fmt: skip
        points = sum(len(c.points) for c in curves.curves)
        shots = sum(c.shots for c in curves.curves)
        print(f"| {k} | {len(curves.curves)} ({', '.join(f'{n} of period {p}' for p, n in sorted(by_period.items()))}) "
              f"| {points} | {shots} | {', '.join(f'{n} {kind}' for kind, n in sorted(kinds.items()))} "
              f"| {wall:.1f} | {cpu:.1f} |")  # fmt: skip
        if k == 2:
            kept = curves
    print()
    print("| kind | curve (period) | F (perturb) | F (scipy DOP853 + Newton + Brent) | "
          "difference |")  # fmt: skip
    print("|---|---|---|---|---|")
    seen = set()
    worst = 0.0
    for index, curve in enumerate(kept.curves):
        for b in curve.bifurcations:
            key = (b.kind, round(b.value, 7))
            if b.kind not in ("branch-point", "period-doubling") or key in seen:
                continue
            seen.add(key)
            half = b.kind == "branch-point" and curve.parent is None
            if b.kind == "branch-point" and not half:
                continue
            ref = reference(b.value, b.state, half, curve.period)
            worst = max(worst, abs(b.value - ref))
            print(f"| {b.kind} | {index + 1} ({curve.period}) | {b.value:.12f} | {ref:.12f} | "
                  f"{abs(b.value - ref):.1e} |")  # fmt: skip
    print(f"\nlargest difference: {worst:.1e}")


if __name__ == "__main__":
    main()
