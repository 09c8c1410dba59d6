"""Benchmark (issue 22): a numerical-homotopy count of the chain's real amplitude roots.

An independent count, beside the certified (msolve) one of ``bench_chain.py``: the order-1
amplitude equations of the chain ẍᵢ + xᵢ = −ε[(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³] (fixed ends, x1's
amplitude 1), exactly as the construction poses them (:func:`bench_chain.amplitude_equations`),
are solved by Bertini 2's zero-dimensional total-degree homotopy with the power-series endgame
in double precision (``ZeroDimPowerSeriesDoublePrecisionTotalDegree``). Every endpoint is
classified here, not by Bertini: finite (``FINITE``), real (``REAL``), one root
(``SAME_ROOT``), one of msolve's roots (``MATCH``).

Two steps, in two environments:

1. ``--dump``, in the project's venv (it needs perturb; msolve's roots are dumped too, from
   :func:`perturb.algebra.certified_real_roots` called as ``bench_chain.py`` calls it)::

       python benchmarks/bench_chain_homotopy.py --dump /tmp/chain_systems.json --sizes 3 4 6

2. the homotopy, in a scratch venv holding ``pybertini`` (it imports as ``bertini``). pybertini
   is never a dependency of perturb. Its cp311 wheel (1.0.9) bundles a Boost.Python built for
   Python 3.9 and fails on import (``SystemError: initialization of _pybertini failed``); the
   cp39 wheel works::

       python3.9 -m venv /work/venvs/chain-bertini39
       /work/venvs/chain-bertini39/bin/pip install pybertini==1.0.9
       /work/venvs/chain-bertini39/bin/python benchmarks/bench_chain_homotopy.py \\
           /tmp/chain_systems.json --sizes 3 4 6

It prints a markdown table: n, unknowns, paths (total degree), endpoints returned, finite
solutions (endpoints, distinct), real solutions (endpoints, distinct), how many distinct real
ones are msolve's roots, how many of msolve's roots were found (and reached by any endpoint,
whatever its size or residual), the gap in imaginary parts that ``REAL`` sits in, seconds. A
size whose path count times the measured seconds per path of a smaller size exceeds ``--limit``
is not run: its row gives the estimate. Each size runs in a child process, killed at
``--limit``. Single-threaded (Bertini 2's zero-dim algorithm is serial). ``--save FILE`` keeps
the endpoints, ``--endpoints FILE`` classifies saved ones without tracking, ``--max-norm`` sets
the endgame's security bound (Bertini's default 1e4), ``--verbose`` prints the real roots.

Measured (2 shared cores): 0.28 s/path (n = 3), 0.39 s/path (n = 4), so the 3^11 = 177147 paths
of n = 6 would take ~19 h; pybertini 1.0.9 exposes no other start system (only ``TotalDegree``:
no multihomogeneous, no polyhedral), so n = 6 is not run. n = 4 finds 6 of msolve's 8 roots
with Bertini's default endgame bound, 7 with ``--max-norm 1e8`` (the root with Omega = 5875); the
root with Omega = 1.3e6 (near x1 = 0, at infinity for double precision in the chart x1 = 1) is
reached by no endpoint.
"""

# The homotopy step runs under Python 3.9 (pybertini's working wheel): zip has no strict= there.
# ruff: noqa: B905

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import sys
import time
from pathlib import Path

import numpy as np

#: An endpoint is finite when its largest affine coordinate is below this: Bertini's own default
#: path-truncation threshold. Paths going to infinity stop, in double precision, at 1e4 to 1e6
#: (measured, n = 3), so a larger bound would let them in. msolve's roots of n = 4 reach 1.3e6
#: (Omega) and those of n = 6 reach 3.6e58: in the chart x1 = 1 they sit near infinity (they are
#: near x1 = 0), and a double-precision homotopy cannot tell them from points at infinity.
FINITE = 1e5
#: A finite endpoint is a solution when its residual, scaled by max(1, |x|)**3 (the equations are
#: cubics), is below this. Measured, n = 3: genuine endpoints <= 2e-11; failed endgames
#: (Bertini returns their last point too: its per-path metadata cannot be read from Python)
#: >= 5e-4 below |x| = 1e4, and >= 6e-9 for the paths toward infinity stopped at 1e4..1e5.
RESIDUAL = 1e-9
#: A solution is real when every imaginary part is below REAL * max(1, |x|). Measured: the real
#: roots land with imaginary parts <= 1.3e-12 (n = 3, all nonsingular) and <= 3.2e-7 (n = 4: the
#: two multiple roots, a2 = a3, where a double-precision endgame keeps only ~6 digits), the
#: complex solutions at >= 0.45 (n = 3) and >= 0.19 (n = 4): any tolerance in [3.2e-7, 0.19]
#: gives the same counts; 1e-4 sits near the middle of that gap on a log scale.
REAL = 1e-4
#: Two endpoints are one root when each coordinate agrees within SAME_ROOT * max(1, |point|):
#: the several paths that end at one multiple root agree only to that accuracy.
SAME_ROOT = 1e-4
#: A homotopy root is msolve's root when each coordinate agrees within MATCH * max(1, |root|).
MATCH = 1e-4
#: The Bertini 2 algorithm: total-degree start system, power-series endgame (singular
#: endpoints), double precision. The adaptive-precision Cauchy variant stops at once with
#: "CauchyEG Run time and point must be of matching precision. (20!=16)" in pybertini 1.0.9.
ALGORITHM = "ZeroDimPowerSeriesDoublePrecisionTotalDegree"


def dump(path: str, sizes, forced: float | None = None) -> None:
    """Write each size's equations (integer coefficients, denominators cleared: the same roots)
    and msolve's certified real roots to ``path``. Needs perturb (the project's venv). With
    ``forced``: the forced chain of n (``problems/forced_chain.py``) at Omega = ``forced``, its
    first-order response equations (issue 30, ``bench_coupled.py``)."""
    import sympy as sp

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_chain import amplitude_equations, pairs_of

    from perturb.algebra import certified_real_roots

    out = {}
    for n in sizes:
        if forced is not None:
            from bench_coupled import _first_order

            from problems.forced_chain import forced_chain_of

            _, eqs, unknowns = _first_order(forced_chain_of(n).create(Omega=forced))
            pairs_of = lambda n: ()  # noqa: E731 - a forced system has no frequency correction
        else:
            eqs, unknowns = amplitude_equations(n)
        terms = []
        for e in eqs:
            poly = sp.Poly(e, *unknowns)
            den = sp.ilcm(*[c.q for c in poly.coeffs()])
            terms.append([[str(int(c * den)), list(m)] for m, c in poly.terms()])
        found = certified_real_roots(
            eqs, unknowns, seconds=600, backend="msolve", pairs=pairs_of(n)
        )
        out[str(n)] = {
            "unknowns": [str(u) for u in unknowns],
            "equations": terms,
            "msolve_status": found.status.name,
            "msolve_roots": [[repr(float(r[u])) for u in unknowns] for r in found.roots],
        }
    Path(path).write_text(json.dumps(out))
    print(f"wrote {path}: sizes {list(sizes)}")


def evaluate(terms, point) -> np.ndarray:
    """The equations at a (complex) point, from their term lists."""
    return np.array(
        [sum(int(c) * np.prod(np.power(point, m)) for c, m in eq) for eq in terms], complex
    )


def track(system: dict, queue, max_norm=None) -> None:
    """Child process: solve with Bertini 2, send back each endpoint (homogeneous and affine)."""
    import bertini as pb

    variables = [pb.Variable(s) for s in system["unknowns"]]
    sys_ = pb.System()
    for eq in system["equations"]:
        f = None
        for c, m in eq:
            term = int(c)
            for v, e in zip(variables, m):
                if e:
                    term = term * (v**e if e > 1 else v)
            f = term if f is None else f + term
        sys_.add_function(f)
    sys_.add_variable_group(pb.VariableGroup(variables))
    sys_.homogenize()
    sys_.auto_patch()
    solver = getattr(pb.nag_algorithm, ALGORITHM)(sys_)
    if max_norm is not None:  # the endgame's "security": a path past this norm is given up
        endgame = solver.get_endgame()  # a reference: the setting sticks
        security = endgame.get_security_settings()
        security.max_norm = max_norm
        endgame.set_security_settings(security)
    start = time.perf_counter()
    solver.solve()
    seconds = time.perf_counter() - start
    endpoints = []
    for p in solver.solutions():
        if len(p) == 0:  # a failed path
            endpoints.append(None)
            continue
        hom = [complex(x) for x in p]
        aff = [complex(x) for x in sys_.dehomogenize_point(p)]
        endpoints.append(([(z.real, z.imag) for z in hom], [(z.real, z.imag) for z in aff]))
    queue.put((seconds, endpoints))


def run(system: dict, limit: float, max_norm=None):
    """Track in a child process; ``None`` when it is not done within ``limit`` seconds."""
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    child = ctx.Process(target=track, args=(system, queue, max_norm))
    child.start()
    try:
        return queue.get(timeout=limit)
    except Exception:
        return None
    finally:
        child.join(timeout=5)
        if child.is_alive():
            child.kill()
            child.join()


def close(p, q, tol) -> bool:
    return bool(np.all(np.abs(p - q) <= tol * max(1.0, float(np.max(np.abs(q))))))


def classify(system: dict, endpoints):
    """Counts of the endpoints: tracked, finite, real, distinct real roots, matched to msolve."""
    ok = [e for e in endpoints if e is not None]
    affine = [np.array([complex(*z) for z in aff]) for _, aff in ok]
    affine = [x for x in affine if np.all(np.isfinite(x))]
    size = [max(1.0, float(np.max(np.abs(x)))) for x in affine]
    residual = [
        float(np.max(np.abs(evaluate(system["equations"], x)))) / s**3 for x, s in zip(affine, size)
    ]
    imag = [float(np.max(np.abs(x.imag))) / s for x, s in zip(affine, size)]
    solution = [s < FINITE and r <= RESIDUAL for s, r in zip(size, residual)]
    finite = [x for x, ok_ in zip(affine, solution) if ok_]
    distinct: list[np.ndarray] = []
    for x in finite:
        if not any(close(x, r, SAME_ROOT) for r in distinct):
            distinct.append(x)
    real = [x.real for x, ok_, i in zip(affine, solution, imag) if ok_ and i <= REAL]
    roots: list[np.ndarray] = []
    for x in real:
        if not any(close(x, r, SAME_ROOT) for r in roots):
            roots.append(x)
    certified = [np.array([float(v) for v in r]) for r in system["msolve_roots"]]
    matched = sum(any(close(r, c, MATCH) for c in certified) for r in roots)
    found = sum(any(close(r, c, MATCH) for r in roots) for c in certified)
    # msolve's roots that some endpoint reaches, whatever its size or residual
    anywhere = [x.real for x, i in zip(affine, imag) if i <= REAL]
    reached = sum(any(close(x, c, MATCH) for x in anywhere) for c in certified)
    solution_imag = [i for i, ok_ in zip(imag, solution) if ok_]
    gap = (
        max((i for i in solution_imag if i <= REAL), default=float("nan")),
        min((i for i in solution_imag if i > REAL), default=float("nan")),
    )
    return {
        "tracked": len(ok),
        "failed": len(endpoints) - len(ok),
        "finite": len(finite),
        "finite_distinct": len(distinct),
        "reached": reached,
        "rejected": sorted(
            (r, s) for r, s in zip(residual, size) if not (s < FINITE and r <= RESIDUAL)
        ),
        "real": len(real),
        "roots": len(roots),
        "matched": matched,
        "found": found,
        "certified": len(certified),
        "residual": max(
            (r for r, ok_, i in zip(residual, solution, imag) if ok_ and i <= REAL),
            default=float("nan"),
        ),
        "gap": gap,
        "real_points": roots,
    }


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", help="the file written by --dump")
    parser.add_argument("--dump", action="store_true", help="write the JSON (project's venv)")
    parser.add_argument("--forced", type=float, help="--dump the forced chains at this Omega")
    parser.add_argument("--sizes", type=int, nargs="+", default=[3, 4, 6])
    parser.add_argument("--limit", type=float, default=1200.0, help="seconds per size")
    parser.add_argument("--verbose", action="store_true", help="print each real root")
    parser.add_argument("--save", help="write every size's endpoints to this JSON file")
    parser.add_argument(
        "--max-norm",
        type=float,
        help="the endgame's security max_norm (Bertini's default 1e4): paths past it are given up",
    )
    parser.add_argument("--endpoints", help="classify endpoints saved by --save, track nothing")
    args = parser.parse_args(argv)
    if args.dump:
        dump(args.json, args.sizes, args.forced)
        return
    data = json.loads(Path(args.json).read_text())
    done = json.loads(Path(args.endpoints).read_text()) if args.endpoints else {}
    print(
        f"| n | unknowns | paths (total degree) | endpoints (failed) "
        f"| finite solutions (|x| < {FINITE:.0e}, residual <= {RESIDUAL:.0e}): endpoints, distinct "
        f"| real (Im <= {REAL:.0e}·max(1,|x|)): endpoints, distinct "
        f"| distinct real that are msolve's / msolve's found of msolve's / reached by any endpoint "
        f"| largest Im of a real, smallest of a non-real | s |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    rate, saved = None, {}
    for n in args.sizes:
        system = data[str(n)]
        k = len(system["unknowns"])
        paths = math.prod(max(sum(m) for _, m in eq) for eq in system["equations"])
        head = f"| {n} | {k} | {paths} |"
        if str(n) in done:
            result = done[str(n)]["seconds"], done[str(n)]["endpoints"]
        elif args.endpoints or (rate is not None and rate * paths > args.limit):
            estimate = f"~{rate * paths:.0f} s at {rate:.2f} s/path" if rate else "no estimate"
            print(f"{head} not run: {estimate} | | | | | |")
            continue
        else:
            start = time.perf_counter()
            result = run(system, args.limit, args.max_norm)
            if result is None:
                print(f"{head} timeout | | | | | {time.perf_counter() - start:.0f} |")
                continue
        seconds, endpoints = result
        rate = seconds / paths
        if args.save:
            saved[str(n)] = {"seconds": seconds, "endpoints": endpoints}
            Path(args.save).write_text(json.dumps(saved))
        c = classify(system, endpoints)
        print(
            f"{head} {c['tracked']} ({c['failed']}) | {c['finite']}, {c['finite_distinct']} "
            f"| {c['real']}, {c['roots']} "
            f"| {c['matched']} / {c['found']} of {c['certified']} / {c['reached']} "
            f"| {c['gap'][0]:.1e}, {c['gap'][1]:.1e} | {seconds:.0f} |",
            flush=True,
        )
        if args.verbose:
            for r in c["real_points"]:
                print("    ", np.array2string(r, precision=6, max_line_width=200))
            print(f"     largest scaled residual of a real solution: {c['residual']:.1e}")
            small = [(f"{r:.0e}", f"{x:.0e}") for r, x in c["rejected"][:8]]
            print(f"     rejected endpoints, smallest residuals (residual, |x|): {small}")


if __name__ == "__main__":
    main()
