"""The disk's conditioned shooting on emulated machines: how often it is right, wrong or failed.

``python benchmarks/bench_true_orbit_noise.py [--machines N] [--ulps 1 4 16] [--state]`` runs
:func:`problems.rigid_body.true_orbit.conditioned_true_orbit` at the paper geometry (eps = 1e-4) on
``N`` emulated machines per noise level: the integrator's monodromy moved by up to ``ulps`` float64
spacings of each entry (``tests/oracle/noisy.py``, drawn per machine name ``m0``, ``m1``, ...),
and with ``--state`` the state by as many. Each result is compared with the two-route value
(``TRUE_PAPER`` of ``tests/rigid_body/test_disk_shooting.py``): *right* when both amplitudes are
within the orbit's claimed resolution (plus the pinned digits' rounding), *wrong* when not,
*failed* when it returned a failed status. It prints one row per noise level: the counts, the
worst error over what the result allowed itself, the median claimed resolution and the median CPU
seconds per orbit. Figures: ``bench_true_orbit_noise.md``.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

from perturb.oracle import Heyoka
from problems.rigid_body.true_orbit import conditioned_true_orbit, extended_type
from tests.oracle.noisy import NoisyIntegrator
from tests.rigid_body.test_disk_shooting import PAPER_EPS, TRUE_PAPER, TRUE_PAPER_DIGITS, disk


def _judge(orbit) -> tuple[str, float]:
    """('right' | 'wrong' | 'failed', the error over what the orbit allowed itself)."""
    if not orbit.success:
        return "failed", math.nan
    allowed = orbit.resolution * math.hypot(orbit.beta1, orbit.beta2) + TRUE_PAPER_DIGITS
    error = max(abs(orbit.beta1 - TRUE_PAPER[0]), abs(orbit.beta2 - TRUE_PAPER[1]))
    return ("right" if error <= allowed else "wrong"), error / allowed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--machines", type=int, default=24)
    parser.add_argument("--ulps", type=float, nargs="+", default=[1.0, 4.0, 16.0])
    parser.add_argument("--state", action="store_true", help="the same ulps on the state too")
    args = parser.parse_args()
    problem = disk(PAPER_EPS)
    problem.solve(1)  # the analytic seed, not timed
    conditioned_true_orbit(problem)  # the conditioned equations derived once, not timed
    print(
        f"{'ulps':>5s} {'state':>5s} {'machines':>8s} {'right':>5s} {'wrong':>5s} {'failed':>6s} "
        f"{'worst err/claim':>15s} {'median resolution':>17s} {'median CPU s':>12s}"
    )
    for ulps in args.ulps:
        counts = {"right": 0, "wrong": 0, "failed": 0}
        ratios, resolutions, seconds = [], [], []
        for k in range(args.machines):
            noisy = NoisyIntegrator(
                Heyoka(fp_type=extended_type()),
                ulps=ulps if args.state else 0.0,
                monodromy_ulps=ulps,
                machine=f"m{k}",
            )
            start = time.process_time()
            orbit = conditioned_true_orbit(problem, integrator=noisy)
            seconds.append(time.process_time() - start)
            verdict, ratio = _judge(orbit)
            counts[verdict] += 1
            if orbit.success:
                ratios.append(ratio)
                resolutions.append(orbit.resolution)
        worst = max(ratios, default=math.nan)
        median_resolution = statistics.median(resolutions) if resolutions else math.nan
        print(
            f"{ulps:5g} {'yes' if args.state else 'no':>5s} {args.machines:8d} "
            f"{counts['right']:5d} {counts['wrong']:5d} {counts['failed']:6d} {worst:15.2g} "
            f"{median_resolution:17.1e} {statistics.median(seconds):12.1f}",
            flush=True,
        )


if __name__ == "__main__":
    main()
