"""Validity maps (plain arrays in, a Figure out) and ``[sweep]`` sections of scenes."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from perturb.errors import InvalidParameterError, SceneError  # noqa: E402
from perturb.report.plots import (  # noqa: E402
    plot_error_map,
    plot_period_map,
    plot_slope_map,
    plot_verdict_map,
)
from perturb.scene import check_sweep_names, parse_scene  # noqa: E402

X = np.linspace(0.5, 1.0, 6)
Y = np.geomspace(0.01, 1.0, 5)
LABELS = {-1: "not_computed", 0: "valid", 1: "invalid", 2: "undecided", 3: "lower_order"}


def _codes():
    codes = np.zeros((X.size, Y.size), dtype=int)
    codes[3:, :] = 1
    codes[0, 0] = -1
    return codes


def test_verdict_regions_with_a_legend_of_the_verdicts_present():
    fig = plot_verdict_map(X, Y, _codes(), LABELS, xname="r0", yname="eps")
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["not computed", "valid", "invalid"]
    assert ax.get_yscale() == "log" and ax.get_xscale() == "linear"  # geometric y: log axis
    mesh = ax.collections[0]
    assert mesh.get_array().size == X.size * Y.size


def test_error_map_draws_the_tolerance_contour():
    error = np.outer(np.geomspace(1e-4, 1, X.size), np.ones(Y.size))
    error[0, 0] = np.nan
    fig = plot_error_map(X, Y, error, tol=0.01, xname="r0", yname="eps")
    ax = fig.axes[0]
    contour = [c for c in ax.collections if hasattr(c, "levels")]
    assert contour and contour[0].levels.tolist() == [pytest.approx(-2.0)]
    values = ax.collections[0].get_array()
    assert np.ma.is_masked(values) or np.isnan(values).any()  # the missing point stays blank


def test_slope_and_period_maps():
    slope = np.full((X.size, Y.size), 2.0)
    slope[:2] = 1.2
    fig = plot_slope_map(X, Y, slope, expected=2.0, band=0.5, xname="r0", yname="eps")
    norm = fig.axes[0].collections[0].norm
    assert norm.vcenter == 2.0
    period = np.outer(X, 1 + Y)
    fig = plot_period_map(X, Y, period, xname="r0", yname="eps", unit="s")
    assert "period [s]" in fig.axes[1].get_ylabel()


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: plot_verdict_map(X, Y, _codes()[:2], LABELS, xname="a", yname="b"), "codes"),
        (lambda: plot_verdict_map(X, Y, _codes() + 7, LABELS, xname="a", yname="b"), "codes"),
        (
            lambda: plot_error_map(
                X[::-1][[0, 2, 1, 3, 4, 5]], Y, np.ones((6, 5)), tol=0.1, xname="a", yname="b"
            ),
            "x",
        ),
        (lambda: plot_error_map(X, Y, np.ones((6, 5)), tol=0, xname="a", yname="b"), "tol"),
        (
            lambda: plot_slope_map(X, Y, np.ones((6, 5)), expected=np.nan, xname="a", yname="b"),
            "expected",
        ),
        (lambda: plot_period_map(X, Y, np.ones((6, 5)), xname="", yname="b"), "xname"),
    ],
)
def test_bad_input_names_the_argument(call, name):
    with pytest.raises(InvalidParameterError, match=f"`{name}`"):
        call()


SCENE = """
[problem]
name = "duffing"
[sweep]
grid = ["eps=0.05:0.15:3", "amplitude=0.8,1.2"]
{extra}
[outputs]
{outputs}
"""


@pytest.mark.parametrize(
    ("extra", "outputs", "words"),
    [
        ("", 'plots = ["error_map"]', "needs validate = true"),
        ("validate = true\ncolour = 1", "sweep = true", "unknown key 'colour' in [sweep]"),
        ("workers = 0", "sweep = true", "[sweep] workers = 0"),
        ('derive = "never"', "sweep = true", "derive"),
        ("times = [0, nan]", "sweep = true", "times"),
    ],
)
def test_bad_sweep_sections(extra, outputs, words):
    with pytest.raises(SceneError) as info:
        parse_scene(SCENE.format(extra=extra, outputs=outputs), "s.toml")
    assert words in str(info.value) and "\n" not in str(info.value)


def test_a_map_needs_a_sweep_over_two_axes():
    with pytest.raises(SceneError, match="needs a \\[sweep\\] section"):
        parse_scene('[problem]\nname = "duffing"\n[outputs]\nplots = ["period_map"]')
    one_axis = '[problem]\nname = "duffing"\n[sweep]\ngrid = ["eps=0.1:0.2:3"]\n[outputs]\nplots = ["period_map"]'
    with pytest.raises(SceneError, match="two axes, not 1"):
        parse_scene(one_axis)
    bad_axis = (
        '[problem]\nname = "duffing"\n[sweep]\ngrid = ["eps=0.1:0.2:0"]\n[outputs]\nsweep = true'
    )
    with pytest.raises(
        SceneError, match="line 4: \\[sweep\\] grid = 'eps=0.1:0.2:0' is invalid: N = 0"
    ):
        parse_scene(bad_axis, "s.toml")


def test_sweep_names_are_checked_against_the_problem():
    scene = parse_scene(
        SCENE.format(extra="", outputs="sweep = true").replace("amplitude=", "amplitud="), "s.toml"
    )
    with pytest.raises(SceneError, match="did you mean 'amplitude'"):
        check_sweep_names(scene, ["eps", "amplitude"], "duffing")


def test_a_scene_with_a_sweep_writes_its_store_table_and_maps(tmp_path, capsys):
    pytest.importorskip("distributed")
    import xarray as xr

    from perturb.cli import main

    scene = tmp_path / "scene.toml"
    scene.write_text(
        SCENE.format(
            extra="workers = 1\ntimes = [0.0, 0.5]", outputs='sweep = true\nplots = ["period_map"]'
        )
    )
    folder = tmp_path / "report"
    assert main(["report", str(scene), "--output", str(folder)]) == 0
    summary = capsys.readouterr().out
    assert "sweep: 6 points over eps (3) × amplitude (2): ok 6" in summary
    ds = xr.open_zarr(folder / "sweep.zarr")
    assert ds.sizes["eps"] == 3 and list(ds["time"].values) == [0.0, 0.5]
    rows = (folder / "sweep.csv").read_text().splitlines()
    assert len(rows) == 7 and rows[0].startswith("eps,amplitude,status")
    assert (folder / "period_map.png").stat().st_size > 0
    assert json.loads(ds.attrs["settings"])["times"] == [0.0, 0.5]
    # a second report without the sweep removes the report's own store, nothing else
    (folder / "mine.txt").write_text("keep")
    scene.write_text('[problem]\nname = "duffing"\n[outputs]\ntable = true\n')
    assert main(["report", str(scene), "--output", str(folder)]) == 0
    assert not (folder / "sweep.zarr").exists() and (folder / "mine.txt").read_text() == "keep"


def test_the_example_map_scene_is_valid():
    from pathlib import Path

    from perturb.scene import read_scene

    root = Path(__file__).resolve().parents[2]
    scene = read_scene(root / "examples" / "scenes" / "disk-validity-map.toml")
    from problems import get_problem

    check_sweep_names(scene, [p.name for p in get_problem("disk").parameter_specs], "disk")
    assert scene.sweep.validate and scene.outputs.needs_sweep and len(scene.sweep.grid) == 2
