"""perturb beside OSCILATE (multiple scales, sympy) on OSCILATE's own examples: the Duffing
oscillator's backbone and the time to derive the forced and parametric responses.

    python -m venv /tmp/osc && /tmp/osc/bin/pip install oscilate
    python benchmarks/bench_oscilate.py --oscilate-python /tmp/osc/bin/python

OSCILATE runs in its own venv (never a dependency); its script is ``_oscilate_side.py`` (its
examples ``Duffing_direct.py`` and ``Duffing_parametric.py`` without the plots). The backbone is
compared as a function of the peak amplitude max|x| with the exact frequency of
x'' + x + 0.2 x^3 = 0 (an elliptic integral, a third route).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import time
from pathlib import Path

import numpy as np
import sympy as sp
from scipy.special import ellipk

GAMMA = 0.2
AMPLITUDES = (0.2, 0.6, 1.0)


def exact_frequency(amplitude: float) -> float:
    omega = np.sqrt(1 + GAMMA * amplitude**2)
    m = GAMMA * amplitude**2 / (2 * omega**2)
    return float(2 * np.pi / (4 * ellipk(m) / omega))


def main() -> None:
    from perturb import EPS, PoincareMethod, QuasilinearSystem, amplitude_equations
    from perturb.cache import bypassed
    from problems import get_problem

    parser = argparse.ArgumentParser()
    parser.add_argument("--oscilate-python", default=None)
    args = parser.parse_args()
    x, v, a = sp.symbols("x xdot A", positive=True)
    rows = []
    with bypassed():
        start = time.perf_counter()
        free = PoincareMethod(order=3, amplitudes={"x": a}, cache=False).solve(
            QuasilinearSystem([x], [v], [1], [-EPS * x**3], parameters=[a])
        )
        rows.append(("perturb: free Duffing backbone, order 3", time.perf_counter() - start))
        for name, order in (("forced-duffing", 3), ("parametric-duffing", 1)):
            start = time.perf_counter()
            amplitude_equations(get_problem(name).system(), order)
            rows.append(
                (f"perturb: {name} response equations, order {order}", time.perf_counter() - start)
            )
    osc = {}
    if args.oscilate_python:
        side = Path(__file__).with_name("_oscilate_side.py")
        for which, order in (("direct", 3), ("parametric", 1)):
            out = subprocess.run(
                [args.oscilate_python, str(side), which, str(order)],
                capture_output=True, text=True, timeout=3600,
            )  # fmt: skip
            line = next((s for s in out.stdout.splitlines() if s.startswith("JSON")), None)
            if line is None:
                rows.append(
                    (f"OSCILATE {which} Ne={order}: failed: {out.stderr[-200:]}", float("nan"))
                )
                continue
            data = json.loads(line[4:])
            osc[which] = data
            rows.append(
                (
                    f"OSCILATE: Duffing {which}, Ne = {order} (whole pipeline)",
                    data["derive_seconds"],
                )
            )
    print(f"{'derivation':58s} {'seconds':>8s}")
    for label, seconds in rows:
        print(f"{label:58s} {seconds:8.2f}")
    print()
    print(f"backbone of x'' + x + {GAMMA} x^3 = 0 against the exact frequency, by peak amplitude")
    print(
        f"{'max|x|':>7s} {'exact':>16s} {'perturb (order 3)':>18s} {'error':>8s} {'OSCILATE (Ne 3)':>16s} {'error':>8s}"
    )
    backbone = {b["xmax"]: b["omega"] for b in osc.get("direct", {}).get("backbone", [])}
    for amplitude in AMPLITUDES:
        exact = exact_frequency(amplitude)
        ours = float(free.frequency_expr.subs({EPS: GAMMA, a: amplitude}))
        theirs = backbone.get(amplitude, float("nan"))
        print(f"{amplitude:7.2f} {exact:16.12f} {ours:18.12f} {abs(ours - exact):8.1e} "
              f"{theirs:16.12f} {abs(theirs - exact):8.1e}")  # fmt: skip


if __name__ == "__main__":
    main()
