"""Benchmark: basin maps — the forced Duffing at 200 x 200 and 1000 x 1000, against a solve_ivp loop.

The basin study (``perturb basins``) is asked for a 200 x 200 map of the shipped forced Duffing at
its defaults in <= 30 s on 2 cores and 1000 x 1000 in <= 10 min, side by side with what a user
writes without perturb (a ``solve_ivp`` loop over the grid) on a sample of the same points, with
the cost per initial condition and its scaling with the grid and with Dask workers. Sections
(each prints a table; all by default):

``map``      200 x 200 of the defaults (Omega = 1, one attractor) and of the bistable Omega = 1.05,
             on a LocalCluster of 2 workers, the whole ``basins()`` call timed (the catalogue, the
             cluster's start, the chunks) and its compute part;
``scaling``  the defaults at 50^2, 100^2, 200^2 in this process (CPU per initial condition), and
             200^2 on 1 and 2 workers;
``scipy``    a plain ``solve_ivp`` loop (DOP853, rtol 1e-9, every state followed for the cap the
             map needed at most, the nearest attractor at the end) on a random sample of the
             bistable 200 x 200 grid: seconds per initial condition, and its codes against the
             map's (a disagreement next to the basin boundary is counted apart);
``large``    1000 x 1000 of the defaults on 2 workers into a Zarr store.

Wall times are measured on a machine that may be shared (the load average is printed): rerun a
section to see its spread. Run from the repository root::

    python benchmarks/bench_basins.py                 # everything (about 5 minutes)
    python benchmarks/bench_basins.py --only map scipy
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import tempfile
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: The defaults' grid, and the bistable case's.
BOX = "-3:3"
SAMPLE = 100


def _grid(n: int) -> list[str]:
    return [f"x={BOX}:{n}", f"xdot={BOX}:{n}"]


def _problem(**values):
    from problems import get_problem

    return get_problem("forced-duffing").create(**values)


def _load() -> str:
    return "load average " + " ".join(f"{v:.1f}" for v in os.getloadavg())


def _timed(problem, n: int, **kwargs):
    from perturb.dynamics.basins import basins

    clock, cpu = time.perf_counter(), time.process_time()
    result = basins(problem, _grid(n), **kwargs)
    return result, time.perf_counter() - clock, time.process_time() - cpu


def section_map() -> None:
    print(f"\n## 200 x 200 on 2 workers ({_load()})")
    print(f"{'case':<28s} {'wall s':>8s} {'compute s':>10s} {'worker CPU per IC ms':>21s}  "
          "fractions")  # fmt: skip
    for label, values in (("defaults (Omega = 1)", {}), ("bistable (Omega = 1.05)",
                                                          {"Omega": 1.05})):  # fmt: skip
        result, wall, _ = _timed(_problem(**values), 200, workers=2)
        compute = float(result.dataset.attrs["seconds"])
        fractions = ", ".join(f"{f.name} {f.fraction:.4f}±{f.error:.4f}" for f in result.fractions)
        per = float(result.dataset.attrs["task_cpu_seconds"]) / 40000
        print(f"{label:<28s} {wall:>8.1f} {compute:>10.1f} {per * 1e3:>21.3f}  {fractions}")


def section_scaling() -> None:
    print(f"\n## scaling with the grid (this process) and with workers ({_load()})")
    print(f"{'grid':>9s} {'workers':>8s} {'wall s':>8s} {'CPU s':>11s} {'CPU per IC ms':>14s} "
          f"{'mean periods':>13s}")  # fmt: skip
    problem = _problem()
    _timed(problem, 10, workers=0)  # the catalogue and the compiled integrator, once
    for n in (50, 100, 200):
        result, wall, cpu = _timed(problem, n, workers=0)
        periods = float(np.mean(result.dataset["periods"].values))
        print(f"{n:>4d}^2    {0:>8d} {wall:>8.2f} {cpu:>11.2f} {cpu / n**2 * 1e3:>14.3f} "
              f"{periods:>13.1f}")  # fmt: skip
    for workers in (1, 2):
        result, wall, _ = _timed(problem, 200, workers=workers)
        compute = float(result.dataset.attrs["seconds"])
        cpu = float(result.dataset.attrs["task_cpu_seconds"])
        print(
            f"{200:>4d}^2    {workers:>8d} {wall:>8.2f} {cpu:>11.2f} {cpu / 200**2 * 1e3:>14.3f} "
            f"{'':>13s}  (compute wall {compute:.2f} s)"
        )


def section_scipy() -> None:
    from scipy.integrate import solve_ivp

    print(f"\n## a solve_ivp loop on {SAMPLE} points of the bistable 200 x 200 grid ({_load()})")
    problem = _problem(Omega=1.05)
    result, _, cpu = _timed(problem, 200, workers=0)
    ds = result.dataset
    codes = np.asarray(ds["code"].values)
    cap = int(np.max(ds["periods"].values))
    xs, vs = ds["x"].values, ds["xdot"].values
    chart = result.catalogue
    rng = np.random.default_rng(0)
    picks = rng.integers(0, 200, size=(SAMPLE, 2))
    omega = 1.05
    period = 2 * math.pi / omega

    def f(t, y):  # what a user writes: the equation at the defaults, by hand
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(omega * t)]

    clock = time.process_time()
    disagree, near = 0, 0
    for i, j in picks:
        end = solve_ivp(f, (0, cap * period), [xs[j], vs[i]], method="DOP853", rtol=1e-9,
                        atol=1e-11).y[:, -1]  # fmt: skip
        code = int(np.argmin([float(a.distance(end[None])[0]) for a in chart.attractors]))
        if code != codes[i, j]:
            block = codes[max(i - 1, 0) : i + 2, max(j - 1, 0) : j + 2]
            near += len(np.unique(block)) > 1
            disagree += 1
    loop = (time.process_time() - clock) / SAMPLE
    per = cpu / 200**2
    print(f"{'route':<40s} {'CPU per IC ms':>14s} {'200 x 200 (1 core)':>19s}")
    print(f"{'perturb basins (heyoka batch, capture)':<40s} {per * 1e3:>14.3f} {cpu:>17.1f} s")
    print(f"{'solve_ivp loop (DOP853, ' + str(cap) + ' periods)':<40s} {loop * 1e3:>14.1f} "
          f"{loop * 200**2 / 60:>15.1f} min")  # fmt: skip
    print(
        f"speed-up {loop / per:.0f}x; codes that differ: {disagree} of {SAMPLE} "
        f"({near} next to the basin boundary)"
    )


def section_large() -> None:
    from perturb.dynamics.basins import basins

    print(f"\n## 1000 x 1000 of the defaults on 2 workers into a store ({_load()})")
    folder = tempfile.mkdtemp(prefix="bench-basins-")
    try:
        clock = time.perf_counter()
        result = basins(_problem(), _grid(1000), workers=2, output=f"{folder}/map.zarr")
        wall = time.perf_counter() - clock
        compute = float(result.dataset.attrs["seconds"])
        cpu = float(result.dataset.attrs["task_cpu_seconds"])
        print(
            f"wall {wall:.0f} s (compute {compute:.0f} s), worker CPU {cpu:.0f} s = "
            f"{cpu / 1e6 * 1e3:.3f} ms per IC, {result.status.value}; "
            + ", ".join(f"{f.name} {f.count}" for f in result.fractions)
        )
    finally:
        shutil.rmtree(folder, ignore_errors=True)


SECTIONS = {"map": section_map, "scaling": section_scaling, "scipy": section_scipy,
            "large": section_large}  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", choices=sorted(SECTIONS), default=list(SECTIONS))
    args = parser.parse_args()
    print(f"# bench_basins ({os.cpu_count()} cores, {_load()})")
    for name in args.only:
        SECTIONS[name]()


if __name__ == "__main__":
    main()
