"""Sweeps on Dask (issue 19): a real LocalCluster, a real `dask scheduler` + `dask worker` pair
started here as subprocesses on 127.0.0.1, a real Zarr store; interruption and resume."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("xarray")
pytest.importorskip("zarr")

from perturb.errors import InvalidParameterError  # noqa: E402
from perturb.sweep import Grid, sweep  # noqa: E402
from perturb.sweep.points import evaluate_chunk  # noqa: E402
from perturb.sweep.store import create_store, open_store, pending_points, write_chunk  # noqa: E402
from perturb.validation import validate  # noqa: E402
from problems import get_problem  # noqa: E402

DUFFING = get_problem("duffing")
GRID = {"eps": np.linspace(0.02, 0.2, 4), "amplitude": np.linspace(0.5, 1.5, 3)}


@pytest.fixture(scope="module")
def cluster():
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
    ) as local:
        yield local


def test_a_local_cluster_sweep_gives_what_the_engine_gives_at_each_point(cluster, tmp_path):
    store = tmp_path / "duffing.zarr"
    dataset = sweep(
        DUFFING.create(), GRID, order=2, store=store, scheduler=cluster.scheduler_address
    )
    assert dict(dataset.sizes) == {"eps": 4, "amplitude": 3}
    assert bool(dataset["done"].all()) and int((dataset["status"] != 0).sum()) == 0
    assert dataset.attrs["problem"] == "duffing" and dataset.attrs["order"] == 2
    for eps in GRID["eps"][[0, -1]]:
        for amplitude in GRID["amplitude"][[0, -1]]:
            problem = DUFFING.create(eps=eps, amplitude=amplitude)
            period = problem.period(problem.solve(2))
            got = float(dataset["period"].sel(eps=eps, amplitude=amplitude))
            assert got == period  # the same number, to the bit


def test_validated_points_are_perturb_validate_to_the_digit(cluster, tmp_path):
    grid = {"eps": [0.05, 0.3], "amplitude": [1.0]}
    dataset = sweep(DUFFING.create(), grid, validate=True, store=tmp_path / "v.zarr",
                    scheduler=cluster.scheduler_address)  # fmt: skip
    codes = json.loads(dataset.attrs["verdict_codes"])
    for eps in grid["eps"]:
        report = validate(DUFFING.create(eps=eps, amplitude=1.0))
        point = dataset.sel(eps=eps, amplitude=1.0)
        assert codes[str(int(point["verdict"]))].startswith(report.outcome.name)
        assert float(point["orbit_error"]) == report.periodic_orbit.orbit_error
        assert float(point["slope"]) == report.slope.slope


def test_a_dask_scheduler_and_worker_started_by_hand(tmp_path):
    """`dask scheduler` and `dask worker` as subprocesses on 127.0.0.1, as a user would."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    scheduler = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port",
         str(port), "--dashboard-address", ":0"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
    )  # fmt: skip
    worker = None
    try:
        time.sleep(2)
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
             "--nworkers", "1", "--dashboard-address", ":0"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
        )  # fmt: skip
        time.sleep(3)
        out = subprocess.run(
            [sys.executable, "-m", "perturb", "sweep", "duffing", "--grid", "eps=0.02:0.2:3",
             "--grid", "amplitude=0.5:1.5:2", "--scheduler", address, "--output",
             str(tmp_path / "by-hand.zarr")],
            capture_output=True, text=True, env=env, timeout=300,
        )  # fmt: skip
        assert out.returncode == 0, out.stderr
        dataset = open_store(tmp_path / "by-hand.zarr")
        assert bool(dataset["done"].all())
    finally:
        for process in (worker, scheduler):
            if process is not None:
                process.terminate()
                process.wait(timeout=30)


def test_an_interrupted_sweep_resumes_computing_no_point_twice_and_losing_none(cluster, tmp_path):
    """A driver that died after some chunks: the store has them; resume computes the rest only
    (each point's values equal an uninterrupted run's)."""
    problem = DUFFING.create()
    grid = Grid.of(GRID)
    store = tmp_path / "cut.zarr"
    names = tuple(f"amplitude_{n}" for n in problem.state_names())
    from perturb.sweep.points import QUANTITIES

    create_store(store, grid, (*QUANTITIES, *names), _attrs(problem, grid, 1), resume=False)
    first = np.arange(5)
    write_chunk(store, grid, *evaluate_chunk(problem, grid, first, 1, False, names))
    assert list(pending_points(store, grid)) == list(range(5, grid.size))
    address = cluster.scheduler_address
    resumed = sweep(problem, grid, order=1, store=store, resume=True, scheduler=address)
    whole = sweep(problem, grid, order=1, scheduler=address)
    assert bool(resumed["done"].all())
    np.testing.assert_array_equal(resumed["period"].values, whole["period"].values)


def _attrs(problem, grid, order):
    from perturb import __version__

    fixed = {k: v for k, v in problem.values.items() if k not in grid.names}
    return {
        "problem": problem.name, "order": order, "validate": False,
        "fixed": json.dumps(fixed, sort_keys=True), "perturb_version": __version__,
        "status_codes": json.dumps({0: "computed", 1: "failed (see reason)"}),
    }  # fmt: skip


def test_a_killed_worker_loses_nothing(cluster, tmp_path):
    """A worker process killed mid-sweep: Dask re-runs its task elsewhere; every point done."""
    from distributed import Client

    client = Client(cluster.scheduler_address)
    pids = list(client.run(os.getpid).values())
    client.close()
    problem = DUFFING.create()
    grid = {"eps": np.linspace(0.02, 0.3, 6), "amplitude": np.linspace(0.5, 1.5, 4)}

    import threading

    def kill_soon():
        time.sleep(1.0)
        os.kill(pids[0], 9)

    threading.Thread(target=kill_soon, daemon=True).start()
    dataset = sweep(problem, grid, validate=True, store=tmp_path / "killed.zarr",
                    scheduler=cluster.scheduler_address)  # fmt: skip
    assert bool(dataset["done"].all())
    assert int((dataset["status"] != 0).sum()) == 0


@pytest.mark.parametrize(
    ("grid", "words"),
    [({"epz": [0.1]}, "did you mean 'eps'"), ({"eps": [0.2, 0.1]}, "increasing")],
)
def test_bad_grids_are_refused(grid, words):
    with pytest.raises(InvalidParameterError, match=words):
        sweep(DUFFING.create(), grid)


def test_absurd_sizes_ask_for_confirmation():
    grid = {"eps": np.linspace(0.01, 0.3, 4000), "amplitude": np.linspace(0.5, 2, 4000)}
    with pytest.raises(InvalidParameterError, match="confirm with --yes"):
        sweep(DUFFING.create(), grid)


def test_a_store_of_another_sweep_is_never_overwritten(cluster, tmp_path):
    store = tmp_path / "other.zarr"
    address = cluster.scheduler_address
    sweep(DUFFING.create(), {"eps": [0.1, 0.2]}, store=store, scheduler=address)
    with pytest.raises(InvalidParameterError, match="pass --resume"):
        sweep(DUFFING.create(), {"eps": [0.1, 0.2]}, store=store, scheduler=address)
    with pytest.raises(InvalidParameterError, match="another sweep"):
        sweep(DUFFING.create(), {"eps": [0.1, 0.3]}, store=store, resume=True, scheduler=address)
    (tmp_path / "not-a-store").mkdir()
    with pytest.raises(InvalidParameterError, match="not a sweep store"):
        sweep(DUFFING.create(), {"eps": [0.1]}, store=tmp_path / "not-a-store")
