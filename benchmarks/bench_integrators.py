"""Error over 100 periods against wall time for the oracle's integrators (plain script, prints tables).

Run from the repository root::

    python benchmarks/bench_integrators.py [--quick]

Systems
-------
- Duffing x'' + x + x**3 = 0 from x = 1, x' = 0 (period 4 K(m)/sqrt(2), m = 1/4), 100 periods.
- Heavy rigid body about a fixed point (Euler-Poisson), A, B, C = 9, 11, 20 (dimensionless, M g = 1):
  I w' = (I w) x w + r_G x g,  g' = g x w  (g = downward vertical in body axes),
  with r_G = (0.1, 0.05, 0.5) and a fast spin about the C axis; "100 periods" = 100 * 2 pi.

The reference is heyoka in extended precision (long double or real128), cross-checked against a
second extended run (real128, or the elliptic-function solution for Duffing); its error is printed.
The error is the max-norm of the state difference at 101 points (one per period).  The heyoka time
excludes the one-off JIT compilation, printed separately.  "time to 1e-10" is the fastest setting
whose error is <= 1e-10.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import sympy as sp
from scipy.special import ellipj, ellipk

from perturb.oracle import (
    RK4,
    Heyoka,
    Scipy,
    SymbolicRHS,
    find_periodic_orbit,
    heyoka_available,
)

#: Target accuracy of the "time to" column (the brief's figure of merit).
TARGET_ERROR = 1e-10
N_PERIODS = 100


def duffing_problem():
    x, v = sp.symbols("x v")
    rhs = SymbolicRHS((x, v), (v, -x - x**3))
    m = 0.25  # beta A**2 / (2 (alpha + beta A**2)) with alpha = beta = A = 1
    period = 4 * ellipk(m) / math.sqrt(2.0)
    t = np.linspace(0.0, N_PERIODS * period, N_PERIODS + 1)
    sn, cn, dn, _ = ellipj(math.sqrt(2.0) * t, m)
    exact = np.array([cn, -math.sqrt(2.0) * sn * dn])
    return "Duffing x''+x+x^3=0, A=1", rhs, np.array([1.0, 0.0]), t, exact


def rigid_body_problem():
    p, q, r, g1, g2, g3 = sp.symbols("p q r gamma1 gamma2 gamma3")
    inertia = sp.diag(9, 11, 20)
    omega = sp.Matrix([p, q, r])
    gamma = sp.Matrix([g1, g2, g3])
    r_g = sp.Matrix([sp.Rational(1, 10), sp.Rational(1, 20), sp.Rational(1, 2)])
    omega_dot = inertia.inv() * ((inertia * omega).cross(omega) + r_g.cross(gamma))
    gamma_dot = gamma.cross(omega)
    rhs = SymbolicRHS((p, q, r, g1, g2, g3), tuple(omega_dot) + tuple(gamma_dot))
    theta = 0.3
    y0 = np.array([0.2, 0.1, 2.0, math.sin(theta), 0.0, math.cos(theta)])
    t = np.linspace(0.0, N_PERIODS * 2 * math.pi, N_PERIODS + 1)
    return "Heavy rigid body A,B,C=9,11,20 (6-D)", rhs, y0, t, None


def timed(integrator, rhs, y0, t, repeat=1):
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        trajectory = integrator.integrate(rhs, (t[0], t[-1]), y0, t_eval=t)
        best = min(best, time.perf_counter() - start)
    return trajectory, best


def run(problem, quick: bool):
    title, rhs, y0, t, exact = problem
    print(f"\n## {title}: {N_PERIODS} periods, t_end = {t[-1]:.2f}")
    reference = None
    if heyoka_available():
        start = time.perf_counter()
        reference = Heyoka(high_precision=True).integrate(rhs, (t[0], t[-1]), y0, t_eval=t)
        ref_time = time.perf_counter() - start
        ref = reference.y.astype(float)
        check_name, check = "elliptic functions", exact
        if check is None:
            check_name = "heyoka real128"
            check = Heyoka(fp_type="real128").integrate(rhs, (t[0], t[-1]), y0, t_eval=t).y
            check = np.array(check.astype(float))
        print(
            f"reference: {reference.integrator} ({ref_time:.2f} s); "
            f"difference from {check_name}: {np.max(np.abs(ref - check)):.1e}"
        )
    else:
        ref = exact if exact is not None else None
        if ref is None:
            ref = Scipy("DOP853", rtol=1e-14).integrate(rhs, (t[0], t[-1]), y0, t_eval=t).y
        print("reference: heyoka not installed; exact solution or DOP853 rtol=1e-14")

    rk4_steps = [50, 100, 200] if quick else [100, 200, 400, 800, 1600]
    # scipy clamps rtol below 100 * eps = 2.2e-14 (with a warning): 3e-14 is the tightest useful
    dop_rtols = [1e-8, 1e-10, 1e-12, 1e-13] if quick else [1e-8, 1e-10, 1e-11, 1e-12, 1e-13, 3e-14]
    hey_tols = [1e-8, 1e-10, 1e-12, 1e-15] if quick else [1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16]
    settings = [RK4(steps_per_unit=s) for s in rk4_steps]
    settings += [Scipy("DOP853", rtol=r) for r in dop_rtols]
    if heyoka_available():
        settings += [Heyoka(tol=tol) for tol in hey_tols]

    print(f"{'integrator':<44} {'max error':>10} {'time [s]':>9} {'nfev/steps':>11}")
    best: dict[str, tuple[float, str]] = {}
    for integrator in settings:
        if isinstance(integrator, Heyoka):
            start = time.perf_counter()
            integrator.integrate(rhs, (t[0], t[1]), y0)  # JIT compile once (cached)
            compile_time = time.perf_counter() - start
        repeat = 1 if quick or isinstance(integrator, RK4) else 3  # RK4 runs take seconds
        trajectory, elapsed = timed(integrator, rhs, y0, t, repeat=repeat)
        error = float(np.max(np.abs(trajectory.y.astype(float) - ref)))
        note = f"  (JIT {compile_time:.2f} s)" if isinstance(integrator, Heyoka) else ""
        print(f"{integrator.name:<44} {error:>10.1e} {elapsed:>9.4f} {trajectory.nfev:>11d}{note}")
        family = integrator.name.split(" (")[0]
        if error <= TARGET_ERROR and elapsed < best.get(family, (math.inf, ""))[0]:
            best[family] = (elapsed, integrator.name)
    print(f"time to reach error <= {TARGET_ERROR:g} over {N_PERIODS} periods:")
    for family in ("rk4", "scipy DOP853", "heyoka taylor_adaptive"):
        if family in best:
            print(f"  {family:<24} {best[family][0]:.4f} s  [{best[family][1]}]")
        else:
            print(f"  {family:<24} not reached by the settings above")


def shooting_benchmark():
    print("\n## Shooting (find_periodic_orbit)")
    x, v = sp.symbols("x v")
    eps = 0.1
    vdp = SymbolicRHS((x, v), (v, eps * (1 - x**2) * v - x))

    def vdp_numeric(y):
        return np.array([y[1], eps * (1 - y[0] ** 2) * y[1] - y[0]])

    def vdp_jac(y):
        return np.array([[0.0, 1.0], [-2 * eps * y[0] * y[1] - 1.0, eps * (1 - y[0] ** 2)]])

    duffing = SymbolicRHS((x, v), (v, -x - x**3))
    cases = [
        (
            "van der Pol eps=0.1, symbolic, default",
            lambda: find_periodic_orbit(vdp, [2.0, 0.0], 2 * math.pi, section_index=1),
        ),
        (
            "van der Pol eps=0.1, numeric + jac, DOP853 1e-13",
            lambda: find_periodic_orbit(
                vdp_numeric, [2.0, 0.0], 2 * math.pi, section_index=1, jac=vdp_jac
            ),
        ),
        (
            "van der Pol eps=0.1, numeric, FD jacobian",
            lambda: find_periodic_orbit(vdp_numeric, [2.0, 0.0], 2 * math.pi, section_index=1),
        ),
        (
            "Duffing A=1 pinned, symbolic, default",
            lambda: find_periodic_orbit(
                duffing, [1.0, 0.0], 5.0, section_index=1, fixed_indices=0, n_trivial=2
            ),
        ),
    ]
    print(f"{'case':<50} {'time [s]':>9} {'iter':>5} {'residual':>9} {'|mu-1|':>8}  period")
    for label, call in cases:
        call()  # warm-up: JIT compilation / lambdify caches
        start = time.perf_counter()
        orbit = call()
        elapsed = time.perf_counter() - start
        print(
            f"{label:<50} {elapsed:>9.4f} {orbit.iterations:>5d} {orbit.residual:>9.1e} "
            f"{orbit.trivial_multiplier_error:>8.1e}  {orbit.period:.15f}"
        )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer settings, no repeats")
    args = parser.parse_args()
    run(duffing_problem(), args.quick)
    run(rigid_body_problem(), args.quick)
    shooting_benchmark()


if __name__ == "__main__":
    main()
