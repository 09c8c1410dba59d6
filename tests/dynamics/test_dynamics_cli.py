"""``perturb basins``, ``perturb transient``, ``perturb ramp`` from the command line: tables,
valid JSON, plots, and bad input in one line (exit 2) or a failed run (exit 1)."""

from __future__ import annotations

import json

import pytest

from perturb.cli import main

BISTABLE = ["forced-duffing", "--set", "Omega=1.05"]


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_basins_prints_the_attractors_and_fractions(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "basins.png"
    code, out, err = run(capsys, "basins", *BISTABLE, "--grid", "x=-3:3:12", "--grid",
                         "xdot=-3:3:12", "--plot", str(plot), "--quiet")  # fmt: skip
    assert code == 0, err
    assert "lower" in out and "upper" in out and "middle" in out and "sampling error" in out
    assert plot.stat().st_size > 0


def test_basins_json_is_valid_and_complete(capsys):
    code, out, err = run(capsys, "basins", *BISTABLE, "--samples", "64", "--grid", "x=-3:3",
                         "--grid", "xdot=-3:3", "--format", "json", "--quiet")  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert data["mode"] == "samples" and data["status"] == "ok"
    assert [a["name"] for a in data["attractors"]] == ["lower", "upper"]
    assert [s["name"] for s in data["saddles"]] == ["middle"]
    assert sum(f["count"] for f in data["fractions"]) == 64
    assert data["outcomes"]["-1"] == "no convergence within the cap of periods"


def test_no_stable_state_is_a_failed_run_with_valid_json(capsys):
    code, out, err = run(capsys, "basins", "forced-duffing", "--set", "zeta=0", "--grid",
                         "x=-1:1:3", "--grid", "xdot=-1:1:3", "--format", "json")  # fmt: skip
    assert code == 1
    assert json.loads(out)["status"] == "no_stable_state"
    assert "no stable steady state" in err and "Traceback" not in err


def test_transient_table_csv_json(capsys, tmp_path):
    code, out, err = run(capsys, "transient", *BISTABLE, "--from", "x=2,xdot=0", "--periods",
                         "200")  # fmt: skip
    assert code == 0, err
    assert "settles on: upper" in out
    code, out, _ = run(capsys, "transient", *BISTABLE, "--from", "x=0", "--periods", "5",
                       "--format", "csv")  # fmt: skip
    assert code == 0 and out.splitlines()[0].startswith("t,x,xdot,envelope_x")
    code, out, _ = run(capsys, "transient", *BISTABLE, "--from", "x=0", "--periods", "5",
                       "--format", "json")  # fmt: skip
    data = json.loads(out)
    assert code == 0 and len(data["times"]) == 5 * 32 + 1
    # five periods are not enough to settle: said, as null
    assert data["settle_time"] is None and data["settled"].startswith("no convergence")


def test_ramp_json(capsys):
    code, out, err = run(capsys, "ramp", "forced-duffing", "--set", "eps=0.02", "--set", "F=0.5",
                         "--sweep", "Omega=0.99:1.06", "--rate", "1e-5", "--both-ways",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert [r["direction"] for r in data["runs"]] == ["up", "down"]
    assert len(data["folds"]) == 2


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["basins", *BISTABLE, "--grid", "x=-3:3:5"], "two coordinates of the state"),
        (["basins", *BISTABLE, "--grid", "x=-3:3:5", "--grid", "theta=0:1:5"], "not a coordinate"),
        (["basins", *BISTABLE, "--grid", "x=-3:3:5", "--grid", "xdot=-3:3:5", "--periods", "0"],
         "--periods 0"),
        (["basins", *BISTABLE, "--grid", "x=-3:3:5", "--grid", "xdot=-3:3:5", "--phase", "nan"],
         "--phase"),
        (["basins", *BISTABLE, "--grid", "x=-3:3:5", "--grid", "xdot=-3:3:5", "--resume"],
         "--output"),
        (["transient", *BISTABLE, "--from", "x=inf", "--periods", "5"], "finite"),
        (["transient", *BISTABLE, "--from", "q=1", "--periods", "5"], "not a coordinate"),
        (["transient", *BISTABLE, "--from", "x=1", "--periods", "0"], "--periods 0"),
        (["transient", *BISTABLE, "--periods", "5"], "--from"),
        (["ramp", *BISTABLE, "--sweep", "Omega=1:1.1", "--rate", "0"], "--rate"),
        (["ramp", "forced-duffing", "--sweep", "Omega=1:1", "--rate", "1e-4"], "does not move"),
        (["ramp", "forced-duffing", "--sweep", "F=1:2", "--rate", "1e-4"], "does not move"),
        (["ramp", "forced-duffing", "--sweep", "Omega=1", "--rate", "1e-4"], "START:STOP"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line_and_exit_2(capsys, argv, needle):
    code, _, err = run(capsys, *argv)
    assert code == 2, err
    assert needle in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["transient", *BISTABLE, "--from", "x=1", "--periods", "2000000"], "at most"),
        (["ramp", "forced-duffing", "--sweep", "Omega=0.9:1.1", "--rate", "1e-12"], "faster rate"),
        (["basins", *BISTABLE, "--grid", "x=-3:3:5", "--grid", "xdot=-3:3:5", "--periods",
          "100000000000"], "--yes"),
        (["basins", *BISTABLE, "--samples", "400000000", "--grid", "x=-3:3"], "--yes"),
    ],
)  # fmt: skip
def test_requests_past_the_cost_rule_are_refused_at_once(capsys, argv, needle):
    code, _, err = run(capsys, *argv)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_basins_without_xarray_names_the_extra_not_an_internal_error(capsys, monkeypatch):
    """A basin map is an xarray Dataset: without the extra sweep, one line naming it (exit 2),
    before any work; transient and ramp need no xarray and still run."""
    import sys

    for module in [m for m in sys.modules if m == "xarray" or m.startswith("xarray.")]:
        monkeypatch.setitem(sys.modules, module, None)
    monkeypatch.setitem(sys.modules, "xarray", None)
    code, out, err = run(capsys, "basins", *BISTABLE, "--grid", "x=-3:3:4", "--grid",
                         "xdot=-3:3:4", "--quiet")  # fmt: skip
    assert code == 2 and out == ""
    assert "xarray" in err and "perturb-poincare[sweep]" in err and "internal" not in err
    assert len(err.strip().splitlines()) == 1


def test_a_basin_store_with_a_folder_for_a_chunk_is_refused_in_one_line(capsys, tmp_path):
    """A folder where perturb writes a chunk: --resume refuses it in one line (exit 2), naming the
    place, before any cluster starts; nothing is removed."""
    pytest.importorskip("distributed")
    store = tmp_path / "b.zarr"
    grid = ["--grid", "x=-3:3:6", "--grid", "xdot=-3:3:6", "--output", str(store), "--workers",
            "1", "--quiet"]  # fmt: skip
    code, _, err = run(capsys, "basins", *BISTABLE, *grid)
    assert code == 0, err
    chunk = next(p for p in (store / "code" / "c").rglob("*") if p.is_file())
    chunk.unlink()
    chunk.mkdir()
    before = sorted(p.relative_to(store).as_posix() for p in store.rglob("*"))
    code, out, err = run(capsys, "basins", *BISTABLE, *grid[:-1], "--resume")  # not --quiet
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "there is not a chunk file" in err
    assert chunk.relative_to(store).as_posix() in err
    assert sorted(p.relative_to(store).as_posix() for p in store.rglob("*")) == before
