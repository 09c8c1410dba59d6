"""Phase diagrams (issue 30, deliverable 3): the counts, the boundaries, the map, the command.

The coupled parametrons are HarmonicBalance.jl's example (its parameters at eps = 0.01): the
edges of the trivial state's tongues are checked against the exact Floquet multipliers of the
normal modes' Mathieu equations (scipy, rtol 1e-12), beside HarmonicBalance.jl's published
boundary lambda_bif(omega) = 2 sqrt((omega^2 - omega_s^2)^2 + gamma^2 omega^2).
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from perturb.report.phase import phase_as_dict, phase_as_table
from perturb.response.model import problem_response
from perturb.steady.singular import singular_points
from perturb.sweep.phase import FIRST_ORDER, ORDER_N, _assemble, _FirstOrder, phase_line
from problems import get_problem

#: C of the first-order tongue edges' error C eps^2 (in Omega): measured 0.55 (5.5e-5 at
#: eps = 0.01); the order-1 edges located on the continued curves: C eps^3, measured 4.
EDGE_FIRST, EDGE_ORDER_ONE = 2.0, 10.0


def _mathieu_edges(eps, zeta, kappa, h, near) -> list[float]:
    """Where the largest Floquet multiplier of q'' + 2 eps zeta q' + (1 -+ eps kappa - eps h
    cos(Omega t)) q = 0 crosses 1 (over two pump periods): the exact edges of the normal modes'
    tongues, the trivial state's boundaries; each sought within 10 eps^2 of a value in
    ``near``."""
    g, lam = 2 * eps * zeta, eps * h

    def excess(omega, ws2):
        period = 4 * math.pi / omega
        monodromy = np.zeros((2, 2))
        for k, y0 in enumerate(([1.0, 0.0], [0.0, 1.0])):
            solution = solve_ivp(
                lambda t, y: [y[1], -g * y[1] - (ws2 - lam * math.cos(omega * t)) * y[0]],
                (0.0, period), y0, rtol=1e-12, atol=1e-14, method="DOP853",
            )  # fmt: skip
            monodromy[:, k] = solution.y[:, -1]
        return float(np.max(np.abs(np.linalg.eigvals(monodromy)))) - 1.0

    edges = []
    width = 10 * eps**2
    for guess in near:  # the tongues overlap: the edge is the mode's whose multiplier crosses 1
        a, b = guess - width, guess + width
        modes = [w for w in (1 - eps * kappa, 1 + eps * kappa) if excess(a, w) * excess(b, w) < 0]
        edges += [brentq(excess, a, b, args=(w,), xtol=1e-12) for w in modes]
    return sorted(edges)


def _harmonic_balance_edges(eps, zeta, kappa, h) -> list[float]:
    """HarmonicBalance.jl's published boundary, solved for the pump frequency 2 omega."""
    g, lam = 2 * eps * zeta, eps * h
    edges = []
    for ws in (math.sqrt(1 - eps * kappa), math.sqrt(1 + eps * kappa)):

        def excess(w, ws=ws):
            return 2 * math.sqrt((w**2 - ws**2) ** 2 + g**2 * w**2) - lam

        edges += [2 * brentq(excess, ws - 0.05, ws), 2 * brentq(excess, ws, ws + 0.05)]
    return sorted(edges)


def test_the_tongue_edges_beside_harmonic_balance_and_the_exact_floquet_edges():
    problem = get_problem("coupled-parametrons").create(h=2.0)
    eps, zeta, kappa = (problem.values[k] for k in ("eps", "zeta", "kappa"))
    published = _harmonic_balance_edges(eps, zeta, kappa, 2.0)
    first = _FirstOrder(problem)
    system = first.equations.system
    sigma = sp.Symbol("sigma")
    fixed = {p: sp.Rational(repr(problem.symbol_values()[p.name]))
             for p in system.parameters if p != sigma}  # fmt: skip
    rows = [sp.expand(r.xreplace(fixed)) for r in first.equations.displacement(0)]
    found = singular_points(rows, first.equations.amplitudes, sigma, -3.0, 3.0,
                            first.equations.coordinates)  # fmt: skip
    at_rest = sorted(2 + eps * v for v, _, norms in found.branch_points
                     if all(n == 0 for n in norms.values()))  # fmt: skip
    assert len(at_rest) == len(published) == 4
    exact = _mathieu_edges(eps, zeta, kappa, 2.0, at_rest)
    assert len(exact) == 4
    for ours, true in zip(at_rest, exact, strict=True):
        assert abs(ours - true) <= EDGE_FIRST * eps**2
    response = problem_response(problem, "Omega", np.linspace(1.98, 2.02, 5), order=1).response
    continued = sorted(s.value for s in response.special if s.kind == "branch-point")
    for true in exact:  # each exact edge has an order-1 branch point beside it
        nearest = min(continued, key=lambda v: abs(v - true))
        assert abs(nearest - true) <= EDGE_ORDER_ONE * eps**3
        # HarmonicBalance.jl's formula is first-order accurate too: farther than order 1
        assert abs(nearest - true) < min(abs(p - true) for p in published)


def _duffing_states(problem, omega: float, force: float) -> int:
    """Positive roots a^2 of the forced Duffing's first-order response by numpy: [(s - 3 g
    a^2/8)^2 + z^2] a^2 = (F/2)^2 with s = (Omega - 1)/eps (a second route to the census)."""
    s = (omega - 1) / problem.values["eps"]
    g, z = problem.values["gamma"], problem.values["zeta"]
    k = 3 * g / 8
    roots = np.roots([k**2, -2 * s * k, s**2 + z**2, -((force / 2) ** 2)])
    return sum(1 for r in roots if abs(r.imag) < 1e-9 and r.real > 0)


def test_a_row_of_the_forced_duffing_counts_as_its_cubic():
    """Along Omega at F = 1: the certified count at every point equals numpy's count of the
    response cubic's positive roots, one or two of them stable (the middle one never); the
    continued order-1 response counts the same where no fold is within a grid step."""
    problem = get_problem("forced-duffing").create(F=1.0)
    omegas = np.linspace(0.98, 1.12, 8)
    line = phase_line(problem, "Omega", omegas, "F", 1.0, 1, True)
    by_hand = [_duffing_states(problem, w, 1.0) for w in omegas]
    assert line["first_order"] == by_hand and set(by_hand) == {1, 3}
    assert line["stable_first_order"] == [1 if n == 1 else 2 for n in by_hand]
    folds = [v for kind, v, order in line["special"] if kind == "fold" and order == FIRST_ORDER]
    assert len(folds) == sum(a != b for a, b in itertools.pairwise(by_hand))  # one per change
    step = omegas[1] - omegas[0]
    for w, n, m in zip(omegas, by_hand, line["states"], strict=True):
        if all(abs(w - f) > step for f in folds):
            assert m == n


def test_the_maps_and_their_report():
    """Two rows assembled: the maps, the special points with their kinds and orders, the table
    and the JSON (every count, -1 where not counted)."""
    problem = get_problem("forced-duffing").create()
    xs, ys = np.array([0.98, 1.05]), np.array([0.5, 1.0])
    rows = [
        {"states": [1, 3], "stable": [1, 2], "marginal": [0, 0], "first_order": [1, 3],
         "stable_first_order": [1, 2], "special": [("fold", 1.01, ORDER_N)], "failures": [],
         "seconds": 1.0},
        {"states": [1, -1], "stable": [1, -1], "marginal": [0, -1], "first_order": [1, 3],
         "stable_first_order": [1, 2], "special": [("fold", 1.02, FIRST_ORDER)],
         "failures": ["F = 1: not solved"], "seconds": 1.0},
    ]  # fmt: skip
    dataset = _assemble(problem, 1, ("Omega", xs), ("F", ys), rows, False, 2.0)
    assert dataset["n_stable"].dims == ("F", "Omega")
    assert dataset["n_stable"].values.tolist() == [[1, 2], [1, -1]]
    as_json = phase_as_dict(dataset)
    assert json.loads(json.dumps(as_json))["maps"]["n_first_order"] == [[1, 3], [1, 3]]
    assert [(p["kind"], p["first_order"]) for p in as_json["special"]] == [
        ("fold", False),
        ("fold", True),
    ]
    table = phase_as_table(dataset)
    assert "failed: F = 1: not solved" in table and "not counted: 1 points" in table


def test_the_map_draws_counts_and_boundaries():
    pytest.importorskip("matplotlib")
    from perturb.report.plots import plot_phase_diagram

    x, y = np.linspace(0.0, 1.0, 4), np.linspace(0.0, 1.0, 3)
    counts = np.array([[1, 1, 2, 2], [1, 2, 2, 3], [-1, 2, 3, 3]])
    special = [(0.5, 0.2, "fold"), (0.6, 0.4, "branch-point"), (0.1, 0.9, "neimark-sacker")]
    figure = plot_phase_diagram(x, y, counts, special, xname="Omega", yname="h")
    ax = figure.axes[0]
    assert len(ax.collections) == 1 + 3  # the map, then one marker set per kind
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "fold",
        "branch point",
        "neimark sacker",
    ]
    with pytest.raises(ValueError, match="counts"):
        plot_phase_diagram(x, y, counts.T, xname="Omega", yname="h")


@pytest.mark.slow
def test_the_command_on_a_local_cluster_writes_the_store_and_the_map(tmp_path, capsys):
    """A real LocalCluster of one worker, a real Zarr store, the picture; the store's certified
    counts against numpy's."""
    pytest.importorskip("matplotlib")
    pytest.importorskip("dask")
    from perturb.cli import main

    store, picture = tmp_path / "map.zarr", tmp_path / "map.png"
    code = main([
        "phase-diagram", "forced-duffing", "--grid", "Omega=0.98:1.1:4", "--grid", "F=0.5:1:2",
        "--rows-only", "--workers", "1", "--output", str(store), "--plot", str(picture),
    ])  # fmt: skip
    out, err = capsys.readouterr()
    assert code == 0, err
    assert picture.stat().st_size > 0 and "stable steady states" in out
    import xarray as xr

    dataset = xr.open_zarr(str(store))
    problem = get_problem("forced-duffing").create()
    by_hand = [[_duffing_states(problem, w, f) for w in dataset["Omega"].values]
               for f in dataset["F"].values]  # fmt: skip
    assert dataset["n_first_order"].values.tolist() == by_hand


def test_bad_input_is_one_line_and_exit_2(capsys):
    from perturb.cli import main

    for argv, fragment in (
        (["--grid", "Omega=0.9:1.1:3"], "give two"),
        (["--grid", "Omega=0.9:1.1:3", "--grid", "Omega=1:2:3"], "twice"),
        (["--grid", "Omega=0.9:1.1:3", "--grid", "nope=1:2:3"], "nope"),
        (["--grid", "Omega=0.9:1.1:5000", "--grid", "F=0.5:1.5:4000"], "--yes"),
    ):
        code = main(["phase-diagram", "forced-duffing", *argv])
        _, err = capsys.readouterr()
        assert code == 2 and fragment in err and len(err.strip().splitlines()) == 1, err


def test_a_store_or_a_plot_in_the_way_is_refused_before_any_work(capsys, tmp_path):
    from perturb.cli import main

    store, plot = tmp_path / "mine.zarr", tmp_path / "mine.png"
    store.mkdir()
    plot.write_bytes(b"a user's picture")
    grids = ["--grid", "Omega=0.98:1.1:3", "--grid", "F=0.5:1:2"]
    for extra, fragment in (
        (["--output", str(store)], "exists"),
        (["--plot", str(plot)], "--plot"),
    ):
        code = main(["phase-diagram", "forced-duffing", *grids, *extra])
        _, err = capsys.readouterr()
        assert code == 2 and fragment in err and len(err.strip().splitlines()) == 1, err
    assert plot.read_bytes() == b"a user's picture" and not any(store.iterdir())
