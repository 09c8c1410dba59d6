"""Benchmark (issue 30): every branch of many-mode systems, free and driven, against independent counts.

Two tables, one per kind of system; each row a size n, its time and its count by several routes.

``free``: the resonant chain ẍᵢ + xᵢ = −ε[(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³] (fixed ends) **typed without
an amplitude**, as a user types it: every family is a continuum in a_x1, found from the order-1
amplitude equations with a_x1 scaled out (the chart a_x1 = 1: :mod:`perturb.method.projective`).

* ``certified``: :func:`perturb.algebra.certified_real_roots` (msolve) on those equations: the
  proved count and its seconds;
* ``newton``: multi-start Newton on the homogeneous equations with the amplitudes on the unit
  sphere (``bench_chain.py``'s independent route, which knows nothing of the cuts): its roots off
  a_x1 = 0 that are one of the certified ones, and any other (a branch the certified route missed);
* ``families``: :func:`perturb.find_families` on the system with nothing fixed (every pass, every
  family carried to order 1): SUCCESS / families, seconds.

``forced``: the chain of Duffings ẍᵢ + xᵢ = ε[−2ζẋᵢ − γxᵢ³ + κ(xᵢ₋₁ − 2xᵢ + xᵢ₊₁) + Fδᵢ₁cos Ωt]
(``problems/forced_chain.py``: fixed ends, forced on x1) at one Ω:

* ``census``: the certified first-order count (distinct orbits) and its seconds;
* ``newton``: multi-start Newton on the same first-order equations from seeded starts in a box:
  the distinct real roots it finds, how many are certified ones, any other;
* ``order 2``: the branches of ``steady_state(2)`` (continued from the census) and their seconds;
* ``shot``: each order-2 branch shot (forced shooting of the true equations from its state): how
  many converge to distinct true orbits, how many agree in stability;
* ``response``: ``perturb response`` over Ω (order 1): seconds, points, failures.

Run from the repository root: ``python benchmarks/bench_coupled.py free --sizes 3 4 6 8`` and
``python benchmarks/bench_coupled.py forced --sizes 2 3 4``. Figures recorded in
``bench_coupled.md``.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import time
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from perturb import cache, find_families  # noqa: E402
from perturb.algebra import certified_real_roots  # noqa: E402
from perturb.algebra.budget import solve_bounded  # noqa: E402
from perturb.response import steady_state_of  # noqa: E402
from problems.forced_chain import forced_chain_of  # noqa: E402
from problems.resonant_chain import chain_system  # noqa: E402
from tests.algebra.chain_equations import amplitude_equations, pairs_of  # noqa: E402

#: Newton starts on the forced chain's first-order equations, the box of the starts (the largest
#: amplitude of a branch of the shipped chains at Omega = 1.1 is below 3), the seed.
FORCED_STARTS, FORCED_BOX, SEED = 4000, 4.0, 2030
#: Two Newton roots closer than this (relative) are one; a Newton point counts as a root below
#: this residual (the certified roots' boxes are far narrower than either).
SAME_ROOT, RESIDUAL = 1e-7, 1e-10


def _bench_chain():
    """``benchmarks/bench_chain.py`` as a module (its Newton on the sphere)."""
    spec = importlib.util.spec_from_file_location(
        "bench_chain", ROOT / "benchmarks" / "bench_chain.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _mirror(eqs, unknowns, n: int, sign: int, budget: float) -> str:
    """The standing waves with a_(n+1-i) = sign * a_i (the chain's reflection), certified: a
    sub-count that holds when the whole count runs past its budget."""
    amplitude = {i: sp.Integer(1) if i == 1 else sp.Symbol(f"a_x{i}0") for i in range(1, n + 1)}
    extra = [amplitude[n + 1 - i] - sign * amplitude[i] for i in range(1, n // 2 + 1)]
    extra += [sp.Symbol(f"b_x{i}0") for i in range(2, n + 1)]
    clock = time.perf_counter()
    found = certified_real_roots([*eqs, *extra], unknowns, seconds=budget, backend="msolve")
    return f"{found.status.name}, {len(found.roots)}, {time.perf_counter() - clock:.1f}"


def free_row(n: int, budget: float, newton: bool) -> str:
    chain = _bench_chain()
    eqs, unknowns = amplitude_equations(n)
    clock = time.perf_counter()
    found = certified_real_roots(eqs, unknowns, seconds=budget, pairs=pairs_of(n), backend="msolve")
    certified_seconds = time.perf_counter() - clock
    certified = f"{found.status.name}, {len(found.roots)}, {certified_seconds:.1f}"
    mirrored = " / ".join(_mirror(eqs, unknowns, n, sign, budget) for sign in (1, -1))
    newton_cell = "not run"
    if newton:
        clock = time.perf_counter()
        roots = chain.newton_roots(eqs, unknowns)
        mine = chain.certified_directions(found, unknowns) if found.roots else []
        amplitudes = chain.homogeneous(eqs, unknowns)[1][1:]
        matched = sum(any(chain.same_direction(r, c, amplitudes) for c in mine) for r in roots)
        near_zero = sum(1 for r in roots if abs(r[0]) < chain.X1_ZERO)
        other = len(roots) - matched - near_zero
        newton_cell = (
            f"{len(roots)}: {matched}, {near_zero}, {other}; {time.perf_counter() - clock:.1f}"
        )
    families_cell = "not run"
    if found.status.name == "SOLVED":

        def carried(eqs_, unknowns_):  # in a child process, under the budget
            with cache.bypassed():
                listing = find_families(chain_system(n), 1, solve_seconds=budget)
            return [f.status.name for f in listing]

        clock = time.perf_counter()
        try:
            statuses = solve_bounded([], [], budget, lambda *_: carried(None, None))
            ok = sum(s == "SUCCESS" for s in statuses)
            families_cell = f"{ok}/{len(statuses)}, {time.perf_counter() - clock:.1f}"
        except TimeoutError:
            families_cell = f"timeout, {time.perf_counter() - clock:.1f}"
    return f"| {n} | {len(unknowns)} | {certified} | {mirrored} | {newton_cell} | {families_cell} |"


def _first_order(problem):
    """The forced chain's first-order rows at the problem's values (pi divided out), their
    unknowns, and the parameter values."""
    from perturb.method.driven import amplitude_equations as driven_equations
    from perturb.steady.branches import exact_number
    from perturb.steady.roots import _primitive

    equations = driven_equations(problem.system(), 0)
    values = problem.symbol_values()
    fixed = {p: exact_number(values[p.name]) for p in equations.system.parameters}
    unknowns = list(equations.amplitudes)
    rows = [_primitive(sp.expand(e.xreplace(fixed)), unknowns) for e in equations.displacement(0)]
    return equations, rows, unknowns


def _newton(rows, unknowns, known) -> tuple[int, int, int]:
    """Distinct real roots by Newton from seeded starts in a box: (found, certified among them,
    other)."""
    from scipy.optimize import root

    f = sp.lambdify([unknowns], rows, "numpy")
    jac = sp.lambdify([unknowns], sp.Matrix(rows).jacobian(unknowns), "numpy")
    rng = np.random.default_rng(SEED)
    found: list[np.ndarray] = []
    for _ in range(FORCED_STARTS):
        start = rng.uniform(-FORCED_BOX, FORCED_BOX, len(unknowns))
        sol = root(lambda v: np.asarray(f(v), float), start,
                   jac=lambda v: np.asarray(jac(v), float))  # fmt: skip
        if not sol.success or np.max(np.abs(f(sol.x))) > RESIDUAL:
            continue
        size = max(1.0, float(np.max(np.abs(sol.x))))
        if not any(np.max(np.abs(sol.x - r)) <= SAME_ROOT * 1e3 * size for r in found):
            found.append(sol.x)
    matched = sum(
        any(np.max(np.abs(r - k)) <= 1e-6 * max(1.0, float(np.max(np.abs(k)))) for k in known)
        for r in found
    )
    return len(found), matched, len(found) - matched


def forced_row(n: int, omega: float, budget: float, shoot: bool, sweep: str) -> str:
    from perturb.response.model import problem_response
    from perturb.steady.census import distinct_orbits, shift_symmetry
    from tests.coupled.census import seeded

    problem = forced_chain_of(n).create(Omega=omega)
    equations, rows, unknowns = _first_order(problem)
    clock = time.perf_counter()
    with cache.bypassed():
        found = certified_real_roots(rows, unknowns, seconds=budget, backend="msolve",
                                     refine=False)  # fmt: skip
    seconds = time.perf_counter() - clock
    if found.status.name != "SOLVED":
        return f"| {n} | {len(unknowns)} | {found.status.name}, {seconds:.1f} | | | | |"
    roots = [np.array([r[u] for u in unknowns], dtype=float) for r in found.roots]
    group = problem.system().excitation.p * shift_symmetry(problem.system())
    count = len(distinct_orbits(roots, equations.harmonics, group))
    census_cell = f"{count}, {seconds:.1f}"
    clock = time.perf_counter()
    total, matched, other = _newton(rows, unknowns, roots)
    newton_cell = f"{total}: {matched}, {other}; {time.perf_counter() - clock:.1f}"
    clock = time.perf_counter()
    state = steady_state_of(problem, 2)
    order_cell = f"{len(state.points)}, {time.perf_counter() - clock:.1f}"
    shot_cell = "not run"
    if shoot:
        clock = time.perf_counter()
        shots = seeded(problem, 2)
        good = [(p, o) for _, p, o in shots if o.success]
        agree = sum(p.stable is bool(np.max(np.abs(o.floquet_multipliers)) < 1) for p, o in good)
        shot_cell = f"{len(good)}/{len(shots)}, {agree}; {time.perf_counter() - clock:.1f}"
    clock = time.perf_counter()
    name, low, high, points = sweep.replace("=", ":").split(":")
    response = problem_response(problem, name, np.linspace(float(low), float(high), int(points)),
                                order=1).response  # fmt: skip
    response_cell = (
        f"{time.perf_counter() - clock:.1f}, {len(response.points)}, {len(response.failures)}"
    )
    return (f"| {n} | {len(unknowns)} | {census_cell} | {newton_cell} | {order_cell} | "
            f"{shot_cell} | {response_cell} |")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=["free", "forced"])
    parser.add_argument("--sizes", type=int, nargs="+", default=[3, 4])
    parser.add_argument("--budget", type=float, default=600.0, help="seconds per solve")
    parser.add_argument("--no-newton", action="store_true", help="free: skip Newton on the sphere")
    parser.add_argument("--omega", type=float, default=1.1, help="forced: the excitation")
    parser.add_argument("--no-shoot", action="store_true", help="forced: skip the shootings")
    parser.add_argument("--sweep", default="Omega=0.95:1.15:21", help="forced: the response")
    args = parser.parse_args()
    if args.kind == "free":
        print("| n | unknowns | certified: status, roots, s | mirror-symmetric / antisymmetric "
              "standing waves, certified: status, roots, s | newton on the sphere: roots: "
              "certified, near a_x1 = 0, other; s | families typed without an amplitude: "
              "SUCCESS/families, s |")  # fmt: skip
        print("|---|---|---|---|---|---|")
        for n in args.sizes:
            print(free_row(n, args.budget, not args.no_newton), flush=True)
    else:
        print(f"| n | unknowns | census at Omega = {args.omega:g}: states, s | newton from "
              f"{FORCED_STARTS} starts: roots: certified, other; s | order 2: branches, s | shot: "
              f"true orbits, stability agreeing; s | response {args.sweep} (order 1): s, "
              "points, failures |")  # fmt: skip
        print("|---|---|---|---|---|---|---|")
        for n in args.sizes:
            print(forced_row(n, args.omega, args.budget, not args.no_shoot, args.sweep),
                  flush=True)  # fmt: skip
    print(f"\n(this process: {time.process_time():.0f} s of CPU)")


if __name__ == "__main__":
    main()
