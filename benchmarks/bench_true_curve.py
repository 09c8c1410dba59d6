"""Benchmark: the true curve past the series (``perturb response --true``, issue 29 item 4).

Two tables:

1. **Cost** — for the shipped driven problems, the analytic response (order given) and then the
   true curves continued from it: curves, points, shots (integrations of the variational
   equations), special points, and the seconds (wall and process CPU) of the true part alone,
   the one-off compilation of the augmented field by heyoka included (its time is shown apart).
2. **Published values, two routes each** — the twin-well Duffing's period doubling against a
   brute-force stroboscopic scan, Mathieu's a_1(1) at the parametric tongue's edge, the forced van
   der Pol's Neimark-Sacker points against the oracle's forced shooting with Brent's method, the
   forced Duffing's folds against a minimally augmented system (``--published``; minutes).

Run from the repository root (``nice`` on a shared machine)::

    python benchmarks/bench_true_curve.py [--published]
"""

from __future__ import annotations

import argparse
import math
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

#: The sweeps: problem, overrides, swept parameter, grid, order.
SWEEPS = (
    ("forced-duffing", {}, "Omega", (0.95, 1.2, 51), 3),
    ("forced-duffing", {"gamma": -1.0}, "Omega", (0.8, 1.05, 51), 1),
    ("parametric-duffing", {}, "Omega", (1.9, 2.1, 41), 1),
    ("superharmonic-duffing", {}, "Omega", (0.3, 0.36, 31), 1),
    ("autoparametric-absorber", {}, "Omega", (1.9, 2.1, 21), 1),
)


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def cost_table() -> list[str]:
    from perturb.response.model import problem_response
    from perturb.response.true_curve import true_curves
    from problems import get_problem

    rows = [
        "| problem | sweep | order | curves | points | shots | special points | compile s | "
        "true curve wall s | CPU s | s per point |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, overrides, parameter, (lo, hi, n), order in SWEEPS:
        problem = get_problem(name).create(**overrides)
        result = problem_response(problem, parameter, np.linspace(lo, hi, n), order=order)
        wall, cpu = time.perf_counter(), _cpu()
        curves = true_curves(problem, parameter, result.response, result.branches, order)
        wall, cpu = time.perf_counter() - wall, _cpu() - cpu
        points = sum(len(c.points) for c in curves.curves)
        shots = sum(c.shots for c in curves.curves)
        kinds: dict[str, int] = {}
        for b in curves.bifurcations:
            kinds[b.kind] = kinds.get(b.kind, 0) + 1
        special = ", ".join(f"{k} {v}" for k, v in sorted(kinds.items())) or "none"
        compile_s = _compile_seconds(name, overrides, parameter, (lo, hi, n), order)
        label = name + "".join(f" {k}={v:g}" for k, v in overrides.items())
        rows.append(
            f"| {label} | {parameter}={lo:g}:{hi:g}:{n} | {order} | {len(curves.curves)} | "
            f"{points} | {shots} | {special} | {compile_s:.2f} | {wall:.2f} | {cpu:.2f} | "
            f"{wall / max(points, 1) * 1e3:.1f} ms |"
        )
        print(rows[-1], flush=True)
    return rows


def _compile_seconds(name: str, overrides: dict, parameter: str, grid, order: int) -> float:
    """The first shot of the augmented field in a fresh process (heyoka's JIT compilation; within
    one process heyoka keeps compiled code in memory)."""
    code = (
        "import time, numpy as np\n"
        "from problems import get_problem\n"
        "from perturb.response.true_family import TrueFamily\n"
        f"p = get_problem({name!r}).create(**{overrides!r})\n"
        f"s = TrueFamily(p, {parameter!r}, np.linspace(*{tuple(grid)!r}), {order})\n"
        f"lam = {float(grid[0])!r}\n"
        "t = time.perf_counter()\n"
        "s.family.shoot(np.zeros(s.family.state_size), s.values(lam), s.direction(lam))\n"
        "print(time.perf_counter() - t)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True
    )
    return float(out.stdout.strip().splitlines()[-1])


def published_table() -> list[str]:
    from scipy.special import mathieu_a

    from perturb.response.model import problem_response
    from problems import get_problem
    from tests.driven.published import (
        PUBLISHED_PERIOD_ONE,
        PUBLISHED_PERIOD_TWO,
        ForcedVanDerPol,
        TwinWell,
        brute_force_period_doubling,
        hill_edges,
        neimark_sacker_by_forced_shooting,
    )
    from tests.driven.test_true_curve_published import A1_AT_Q1, _fold_by_augmented_system

    rows = [
        "| case | published | true curve (heyoka, continuation) | second route | difference |",
        "|---|---|---|---|---|",
    ]

    twin = TwinWell.create()
    result = problem_response(twin, "Gamma", np.linspace(0.02, 0.4, 5), true=1000)
    pd = next(b for b in result.true_curve.bifurcations if b.kind == "period-doubling")
    scan = brute_force_period_doubling([0.2665, 0.267, 0.2675, 0.268, 0.269], periods=3000)
    rows.append(
        f"| twin-well Duffing x'' + 0.3x' - x + x^3 = G cos 1.2t, first period doubling | "
        f"period 1 at G = {PUBLISHED_PERIOD_ONE}, period 2 at {PUBLISHED_PERIOD_TWO} (Jordan & "
        f"Smith) | G = {pd.value:.9f} (multiplier {pd.multiplier.real:+.12f}) | brute-force "
        f"DOP853 stroboscopic scan, d^2 fit past the flip: {scan['gamma_pd']:.9f} | "
        f"{abs(pd.value - scan['gamma_pd']):.1e} |"
    )
    print(rows[-1], flush=True)

    exact = float(mathieu_a(1, 1.0))
    mathieu = get_problem("parametric-duffing").create(zeta=0.0, gamma=0.0, eps=0.5, h=2 / exact)
    result = problem_response(mathieu, "Omega", np.linspace(1.3, 1.6, 5), true=200)
    edge = min(
        (b for b in result.true_curve.bifurcations if b.kind == "branch-point"),
        key=lambda b: abs(b.value - 2 / math.sqrt(exact)),
    )
    a = 4 / edge.value**2
    hill = 4 / min(hill_edges(1 / exact)) ** 2
    rows.append(
        f"| Mathieu tongue edge at q = 1 (parametric-duffing, eps = 0.5) | a_1(1) = {A1_AT_Q1} "
        f"(A&S Table 20.1) | a = 4/Omega^2 = {a:.12f} | scipy {exact:.12f}, Hill determinant "
        f"{hill:.12f} | {abs(a - exact):.1e} |"
    )
    print(rows[-1], flush=True)

    vdp = ForcedVanDerPol.create()
    result = problem_response(vdp, "Omega", np.linspace(0.9, 1.1, 9), true=400)
    for b in (b for b in result.true_curve.bifurcations if b.kind == "neimark-sacker"):
        curve = next(c for c in result.true_curve.curves if b in c.bifurcations)
        near = min(curve.points, key=lambda p: abs(p.value - b.value))
        omega = neimark_sacker_by_forced_shooting(vdp, b.value - 0.005, b.value + 0.005, near.state)
        rows.append(
            f"| forced van der Pol (eps 0.05, F 2), Neimark-Sacker | slow-flow Hopf at "
            f"|x| = sqrt 2 (first order) | Omega = {b.value:.10f}, |x| = {b.norms['x']:.6f}, "
            f"|mu| = {abs(b.multiplier):.12f} | forced shooting (DOP853) + Brent on max|mu| = 1: "
            f"{omega:.10f} | {abs(omega - b.value):.1e} |"
        )
        print(rows[-1], flush=True)

    duffing = get_problem("forced-duffing").create()
    result = problem_response(duffing, "Omega", np.linspace(0.95, 1.3, 15), true=400)
    for b in (b for b in result.true_curve.bifurcations if b.kind == "fold"):
        curve = next(c for c in result.true_curve.curves if b in c.bifurcations)
        near = min(
            curve.points, key=lambda p: abs(p.value - b.value) + abs(p.norm() - b.norms["x"])
        )
        omega, _ = _fold_by_augmented_system(duffing, near.value, near.state)
        rows.append(
            f"| forced Duffing (README's sweep), fold | 1.0416 / 1.2629 (issue 29's independent "
            f"shooting) | Omega = {b.value:.10f} | minimally augmented system, DOP853 + fsolve: "
            f"{omega:.10f} | {abs(omega - b.value):.1e} |"
        )
        print(rows[-1], flush=True)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--published", action="store_true", help="also the published values")
    args = parser.parse_args()
    print("\n".join(cost_table()))
    if args.published:
        print()
        print("\n".join(published_table()))


if __name__ == "__main__":
    main()
