"""The oracle against bare heyoka on the rigid body, and the cost of one shooting (plain script).

Run from the repository root::

    python benchmarks/bench_oracle.py [--repeat 7]

Targets (issue 4 item 4):

1. ``perturb.oracle.Heyoka`` reaches a relative error <= 1e-10 over 100 periods of the fast-spin
   rigid body (problem ``rigid-body``, default parameters, started on the analytic solution) in at
   most 1.5x the time of a bare ``heyoka.taylor_adaptive`` run of the same equations and grid.
2. Shooting one periodic orbit of that body with heyoka (state + variational equations, the
   set-up :func:`perturb.validation.validate` uses) takes <= 50 ms once compiled.

Both sides are compiled before timing (JIT excluded, printed apart); times are medians of
``--repeat`` runs, interleaved so that machine load affects both alike.  The error reference is
heyoka in extended precision.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
import warnings

import numpy as np

from perturb.validation import original_equations

#: The brief's targets.
TARGET_ERROR = 1e-10
TARGET_RATIO = 1.5
TARGET_SHOOTING_SECONDS = 0.050
N_PERIODS = 100


def _bare_heyoka(symbols, exprs):
    import heyoka as hy

    from perturb.oracle import to_heyoka

    variables = hy.make_vars(*[f"y{i}" for i in range(len(symbols))])
    table = dict(zip(symbols, variables, strict=True))
    system = [(v, to_heyoka(e, table)) for v, e in zip(variables, exprs, strict=True)]
    return hy.taylor_adaptive(system, np.zeros(len(symbols)))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--periods", type=int, default=N_PERIODS)
    args = parser.parse_args(argv)
    n_periods = args.periods

    from perturb.oracle import Heyoka, SymbolicRHS, find_periodic_orbit, heyoka_available
    from perturb.validation.setup import derived_shooting_setup
    from problems import get_problem

    if not heyoka_available():
        print("heyoka is not installed: nothing to compare")
        return 1
    warnings.simplefilter("ignore")
    problem = get_problem("rigid-body").create()
    solution = problem.solve(1)
    names = problem.state_names()
    period = problem.period(solution)
    y0 = np.array([float(problem.state(solution, 0.0)[n]) for n in names])
    symbols, exprs = problem.original_symbolic()
    rhs = SymbolicRHS(symbols, exprs)
    t = np.linspace(0.0, n_periods * period, n_periods + 1)

    # compile both (timed apart)
    start = time.perf_counter()
    oracle = Heyoka()
    oracle.integrate(rhs, (0.0, period), y0)
    jit_oracle = time.perf_counter() - start
    start = time.perf_counter()
    bare = _bare_heyoka(symbols, exprs)
    jit_bare = time.perf_counter() - start

    reference = Heyoka(high_precision=True).integrate(rhs, (t[0], t[-1]), y0, t_eval=t)
    ref = np.asarray(reference.y, dtype=float)
    amp = np.max(np.abs(ref), axis=1)

    def run_oracle():
        return np.asarray(oracle.integrate(rhs, (t[0], t[-1]), y0, t_eval=t).y, dtype=float)

    def run_bare():
        ta = bare
        ta.time = 0.0
        ta.state[:] = y0
        return ta.propagate_grid(t)[-1].T

    times = {"oracle": [], "bare": []}
    results = {}
    for _ in range(args.repeat):
        for name, fn in (("oracle", run_oracle), ("bare", run_bare)):
            start = time.perf_counter()
            results[name] = fn()
            times[name].append(time.perf_counter() - start)
    med = {k: statistics.median(v) for k, v in times.items()}
    err = {k: float(np.max(np.abs(v - ref) / amp[:, None])) for k, v in results.items()}
    ratio = med["oracle"] / med["bare"]

    # shooting one orbit, as validate() sets it up
    equations = original_equations(problem, y0)
    samples = np.array(
        [[float(problem.state(solution, s)[n]) for s in np.linspace(0, period, 16)] for n in names]
    )
    setup = derived_shooting_setup(problem, equations, y0, 3, samples)
    kwargs = dict(
        section_index=setup.section_index,
        section_value=setup.section_value,
        fixed_indices=setup.fixed_indices,
        n_trivial=setup.n_trivial,
        integrator=Heyoka(),
    )
    start = time.perf_counter()
    orbit = find_periodic_orbit(rhs, y0, period, **kwargs)  # compiles the variational system
    jit_shoot = time.perf_counter() - start
    shoot_times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        orbit = find_periodic_orbit(rhs, y0, period, **kwargs)
        shoot_times.append(time.perf_counter() - start)
    shoot = statistics.median(shoot_times)

    print(f"# rigid-body (eps = {problem.epsilon():.4g}), {n_periods} periods of T = {period:.6g}")
    print(f"# reference: {reference.integrator}; medians of {args.repeat} interleaved runs")
    print(
        f"{'run':<34s} {'error':>10s} {'seconds':>10s} {'JIT [s]':>9s} {'target':>22s} {'ok':>4s}"
    )
    rows = [
        ("bare heyoka propagate_grid", err["bare"], med["bare"], jit_bare, "", None),
        (
            "perturb.oracle.Heyoka",
            err["oracle"],
            med["oracle"],
            jit_oracle,
            f"err<={TARGET_ERROR:g}, x{TARGET_RATIO} bare",
            err["oracle"] <= TARGET_ERROR and ratio <= TARGET_RATIO,
        ),
        (
            f"shooting ({orbit.iterations} Newton it., status {orbit.status.name})",
            orbit.residual,
            shoot,
            jit_shoot,
            f"<= {TARGET_SHOOTING_SECONDS * 1e3:g} ms",
            orbit.success and shoot <= TARGET_SHOOTING_SECONDS,
        ),
    ]
    for name, e, s, j, target, ok in rows:
        flag = "" if ok is None else ("yes" if ok else "NO")
        print(f"{name:<34s} {e:10.2e} {s:10.4f} {j:9.3f} {target:>22s} {flag:>4s}")
    print(
        f"oracle / bare time ratio: {ratio:.3f} (oracle overhead {med['oracle'] - med['bare']:.2e} s "
        "per call: argument checks and the Trajectory)"
    )
    ok = (
        err["oracle"] <= TARGET_ERROR and ratio <= TARGET_RATIO and shoot <= TARGET_SHOOTING_SECONDS
    )
    return 0 if ok and math.isfinite(ratio) else 1


if __name__ == "__main__":
    raise SystemExit(main())
