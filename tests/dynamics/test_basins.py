"""Basin maps in this process: fractions against random sampling, the map against an independent
one by plain scipy, the separatrix drawn over the boundary, the Dataset's codes and meanings."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from perturb.dynamics.basins import BasinStatus, basins
from perturb.errors import InvalidParameterError
from problems import get_problem

#: Fractions from a grid and from random states agree within this many combined sampling errors
#: (binomial, sqrt(f(1 - f)/n) of each): 3 leaves a 0.3 % chance of a false alarm for independent
#: draws, and the seed is fixed.
SIGMAS = 3.0
GRID = ["x=-3:3:30", "xdot=-3:3:30"]


@pytest.fixture(scope="module")
def grid_map(bistable):
    return basins(bistable, GRID)


def test_the_map_is_a_dataset_of_codes_with_meanings(grid_map):
    ds = grid_map.dataset
    assert grid_map.status is BasinStatus.OK
    assert ds["code"].dims == ("xdot", "x") and ds.sizes == {"xdot": 30, "x": 30, "component": 2}
    meanings = json.loads(ds["code"].attrs["meanings"])
    assert meanings["0"].startswith("lower") and meanings["1"].startswith("upper")
    assert meanings["-1"] == "no convergence within the cap of periods"
    assert set(np.unique(ds["code"].values)) == {0, 1}
    decoded = grid_map.decoded()
    assert set(np.unique(decoded.values)) == {"lower", "upper"}
    assert [f.name for f in grid_map.fractions] == ["lower", "upper"]
    assert sum(f.count for f in grid_map.fractions) == 900
    lower = grid_map.fractions[0]
    assert lower.error == pytest.approx(math.sqrt(lower.fraction * (1 - lower.fraction) / 900))
    # the initial states are the grid's
    np.testing.assert_array_equal(
        ds["initial"].values[3, 5], [ds["x"].values[5], ds["xdot"].values[3]]
    )


def test_grid_fractions_agree_with_random_sampling(bistable, grid_map):
    sampled = basins(bistable, ["x=-3:3", "xdot=-3:3"], samples=900, seed=5)
    assert sampled.sampled and sampled.dataset.sizes["sample"] == 900
    by_grid = {f.name: f for f in grid_map.fractions}
    for f in sampled.fractions:
        g = by_grid[f.name]
        assert abs(f.fraction - g.fraction) <= SIGMAS * math.hypot(f.error, g.error), f.name


def _nearest_attractor(chart, y) -> int:
    return int(np.argmin([float(a.distance(y[None])[0]) for a in chart.attractors]))


def test_an_independent_map_by_plain_scipy_agrees_off_the_boundary(grid_map):
    """Points of the map integrated by scipy's DOP853 for the cap, the attractor nearest the
    end: the same code at every point whose grid neighbours share its code; points next to the
    boundary are named, not counted."""
    ds = grid_map.dataset
    codes = np.asarray(ds["code"].values)
    xs, vs = ds["x"].values, ds["xdot"].values
    padded = np.pad(codes, 1, mode="edge")
    interior = np.ones_like(codes, dtype=bool)
    for di, dj in ((0, 1), (2, 1), (1, 0), (1, 2)):
        interior &= padded[di : di + 30, dj : dj + 30] == codes
    rng = np.random.default_rng(2)
    picks = [
        tuple(p) for p in np.argwhere(interior)[rng.choice(int(interior.sum()), 8, replace=False)]
    ]
    near_boundary = [tuple(p) for p in np.argwhere(~interior)[::40][:2]]
    period = 2 * math.pi / 1.05

    def f(t, y):
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(1.05 * t)]

    disagree = []
    for i, j in picks + near_boundary:
        end = solve_ivp(f, (0, 250 * period), [xs[j], vs[i]], method="DOP853", rtol=1e-9,
                        atol=1e-11).y[:, -1]  # fmt: skip
        if _nearest_attractor(grid_map.catalogue, end) != codes[i, j]:
            disagree.append((i, j))
    assert not [p for p in disagree if p in picks], disagree
    assert len(near_boundary) == 2  # named: counted apart (they may go either way)


def test_the_separatrix_runs_along_the_basin_boundary(grid_map):
    """Every grid cell the separatrix crosses near the saddle holds both basins within a cell's
    reach: the first-order separatrix bounds the true basin to O(eps) there."""
    ds = grid_map.dataset
    codes = np.asarray(ds["code"].values)
    xs, vs = ds["x"].values, ds["xdot"].values
    assert len(grid_map.separatrix) == 2
    near = 0
    for curve in grid_map.separatrix:
        for x, v in curve[:40]:  # the stretch near the saddle
            if not (-3 < x < 3 and -3 < v < 3):
                continue
            j, i = int(np.argmin(np.abs(xs - x))), int(np.argmin(np.abs(vs - v)))
            block = codes[max(i - 2, 0) : i + 3, max(j - 2, 0) : j + 3]
            near += 1
            assert set(np.unique(block)) == {0, 1}, (x, v)
    assert near >= 10


def test_a_monostable_problem_is_one_basin():
    one = basins(get_problem("forced-duffing").create(), ["x=-2:2:6", "xdot=-2:2:6"])
    assert [(f.name, f.count) for f in one.fractions] == [("response", 36)]


def test_no_stable_state_is_a_failed_study():
    undamped = basins(get_problem("forced-duffing").create(zeta=0.0), ["x=-1:1:3", "xdot=-1:1:3"])
    assert undamped.status is BasinStatus.NO_STABLE_STATE and undamped.dataset is None
    assert "no stable steady state" in undamped.message


@pytest.mark.parametrize(
    ("grid", "kwargs", "match"),
    [
        (["x=-3:3:5"], {}, "two coordinates of the state"),
        (["x=-3:3:5", "theta=0:1:5"], {}, "not a coordinate of the state"),
        (["x=-3:3:5", "x=0:1:5"], {}, "twice"),
        (["x=-3:3:5", "xdot=-3:3:5"], {"periods": 0}, "periods"),
        (["x=-3:3:5", "xdot=-3:3:5"], {"phase": math.nan}, "phase"),
        (["x=-3:3:5", "xdot=-3:3:5"], {"base": {"x": math.inf}}, "finite"),
        (["x=3:-3", "xdot=-3:3"], {"samples": 10}, "LOW < HIGH"),
        (["x=-3:3", "xdot=-3:3"], {"samples": 0}, "samples"),
        (["x=-3:3:5", "xdot=-3:3:5"], {"resume": True}, "output"),
    ],
)
def test_bad_requests_are_refused_before_any_work(bistable, grid, kwargs, match):
    with pytest.raises(InvalidParameterError, match=match):
        basins(bistable, grid, **kwargs)


def test_a_parametric_response_of_two_drive_periods():
    """The parametric Duffing (response period 2 drive periods): its attractor has two points on
    the section; the state at rest is the unstable trivial response, and a grid through it says
    so, never a found attractor."""
    from perturb.dynamics.classify import Outcome

    result = basins(get_problem("parametric-duffing").create(), ["x=-1:1:5", "xdot=-1:1:5"])
    (response,) = result.catalogue.attractors
    assert response.period == 2 and [s.name for s in result.catalogue.saddles] == ["trivial"]
    codes = result.dataset["code"].values
    assert codes[2, 2] == Outcome.ON_SADDLE.code
    assert np.count_nonzero(codes == 0) == 24 and not result.catalogue.attractors[1:]


def test_basin_stability_in_four_dimensions():
    """Random states over all four coordinates of the 1:2 autoparametric absorber: every one
    classified, the states drawn inside the box, the same draws on every run (the seed)."""
    absorber = get_problem("autoparametric-absorber").create()
    box = ["x=-1:1", "y=-1:1", "xdot=-1:1", "ydot=-1:1"]
    first = basins(absorber, box, samples=40)
    again = basins(absorber, box, samples=40)
    initial = first.dataset["initial"].values
    assert initial.shape == (40, 4) and np.all(np.abs(initial) <= 1)
    np.testing.assert_array_equal(initial, again.dataset["initial"].values)
    assert sum(f.count for f in first.fractions) == 40
    assert all(f.code >= 0 for f in first.fractions)  # every state reached an attractor
