"""Sweeps on real Dask clusters and real Zarr stores: a LocalCluster, a worker killed mid-sweep, an
interrupted driver resumed, and a ``dask scheduler`` / ``dask worker`` pair started here on
127.0.0.1. Every result is compared with the same points computed in this process."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")

import perturb  # noqa: E402
from perturb._defaults import SWEEP_MAX_CONNECT_SECONDS  # noqa: E402
from perturb.cli import main  # noqa: E402
from perturb.sweep.derive import plan  # noqa: E402
from perturb.sweep.grid import parse_axis  # noqa: E402
from perturb.sweep.quantities import TIMINGS  # noqa: E402
from perturb.sweep.spec import SweepJob, check_spec  # noqa: E402
from perturb.sweep.task import run_chunk  # noqa: E402
from problems import get_problem  # noqa: E402

#: Variables that say how a point was computed, not what it is.
BOOKKEEPING = ("session",)
#: A validated Duffing grid: a few seconds of work on two workers.
DUFFING = ["eps=0.02:0.2:4", "amplitude=0.6:1.4:3"]
#: Seconds after which a wait is a hang, never a speed requirement: far beyond a chunk's seconds
#: on any machine, however loaded.
HANG_GUARD = 600


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
        silence_logs=50,
    )  # fmt: skip
    with Client(cluster, set_as_default=False) as c:
        yield c
    cluster.close()


def reference(problem, axes, **settings) -> dict:
    """The points computed in this process, in C order of the grid."""
    spec = check_spec(problem, [parse_axis(a) for a in axes], **settings)
    derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
    out = run_chunk(SweepJob(spec, derivation, "reference"), np.arange(spec.grid.size))
    shape = spec.grid.shape
    return {
        k: np.asarray(v).reshape(shape + np.shape(v)[1:])
        for k, v in out.items()
        if k not in TIMINGS
    }


def assert_same(ds, expected: dict) -> None:
    for name, values in expected.items():
        if name in BOOKKEEPING:
            continue
        stored = ds[f"sweep_{name}" if f"sweep_{name}" in ds.data_vars else name].values
        if values.dtype == object:
            assert [str(v) for v in stored.ravel()] == [str(v) for v in values.ravel()], name
        else:
            np.testing.assert_array_equal(stored, values, err_msg=name)


def test_a_local_cluster_computes_the_points_of_this_process(client, tmp_path):
    problem = get_problem("duffing").create()
    store = tmp_path / "duffing.zarr"
    ds = perturb.sweep(
        problem, DUFFING, validate=True, times=[0.0, 1.5], client=client, output=store
    )
    expected = reference(problem, DUFFING, validate=True, times=[0.0, 1.5])
    assert ds.sizes["eps"] == 4 and ds.sizes["amplitude"] == 3
    assert list(ds["component"].values) == ["x", "xdot"] and list(ds["time"].values) == [0.0, 1.5]
    assert_same(ds, expected)
    reopened = xr.open_zarr(store)
    assert_same(reopened, expected)
    assert reopened.attrs["complete"] and reopened.attrs["problem"] == "duffing"
    assert json.loads(reopened.attrs["settings"])["validate"] is True
    assert reopened.attrs["perturb_version"] == perturb.__version__
    assert np.all(reopened["session"].values == 1)
    # in memory (no store) the same numbers
    assert_same(
        perturb.sweep(problem, DUFFING, validate=True, times=[0.0, 1.5], client=client), expected
    )


def _written(store) -> int:
    try:
        return int(np.count_nonzero(zarr.open_group(str(store), mode="r")["session"][...]))
    except Exception:  # noqa: BLE001 - not created yet
        return 0


def _wait_for(condition, seconds: float, what: str) -> None:
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"timed out waiting for {what}")
        time.sleep(0.02)


def test_a_worker_killed_mid_sweep_loses_nothing(client, tmp_path):
    problem = get_problem("duffing").create()
    store = tmp_path / "killed.zarr"
    result: dict = {}

    def run():
        result["ds"] = perturb.sweep(
            problem, DUFFING, validate=True, client=client, output=store, chunk_points=2
        )

    thread = threading.Thread(target=run)
    thread.start()
    _wait_for(lambda: _written(store) > 0 or not thread.is_alive(), HANG_GUARD, "a first chunk")
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)  # the nanny starts a new worker
    thread.join(HANG_GUARD)
    assert not thread.is_alive() and "ds" in result
    size = 4 * 3
    assert 0 < _written(store) == size  # every point written, once (session 1: no rerun)
    ds = xr.open_zarr(store)
    assert ds.attrs["complete"] and np.all(ds["session"].values == 1)
    assert_same(ds, reference(problem, DUFFING, validate=True))
    client.wait_for_workers(2, timeout=HANG_GUARD)


def test_the_only_worker_killed_mid_sweep_loses_nothing(tmp_path):
    """The scattered job dies with the only worker holding it: its chunks are sent again with the
    job scattered afresh, not reported as lost (CI saw this when a worker that joined after the
    scatter outlived the one killed)."""
    from distributed import Client, LocalCluster

    problem = get_problem("duffing").create()
    store = tmp_path / "only.zarr"
    result: dict = {}
    cluster = LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None,
        silence_logs=50,
    )  # fmt: skip
    with cluster, Client(cluster, set_as_default=False) as one:

        def run():
            result["ds"] = perturb.sweep(
                problem, DUFFING, validate=True, client=one, output=store, chunk_points=2
            )

        thread = threading.Thread(target=run)
        thread.start()
        _wait_for(lambda: _written(store) > 0 or not thread.is_alive(), HANG_GUARD, "a chunk")
        (pid,) = one.run(os.getpid).values()
        os.kill(pid, signal.SIGKILL)  # the nanny starts a new worker, without the job
        thread.join(HANG_GUARD)
    assert not thread.is_alive() and "ds" in result
    assert _written(store) == 4 * 3
    assert_same(xr.open_zarr(store), reference(problem, DUFFING, validate=True))


def test_an_interrupted_driver_resumes_where_it_stopped(tmp_path, capsys):
    store = tmp_path / "interrupted.zarr"
    axes = ["eps=0.02:0.2:6", "amplitude=0.6:1.4:6"]
    command = [
        "sweep",
        "duffing",
        "--validate",
        "--workers",
        "1",
        "--output",
        str(store),
        "--quiet",
        "--chunk-points",  # many chunks on any machine (a fast one's pilot would make one)
        "6",
    ]
    for axis in axes:
        command += ["--grid", axis]
    argv = [sys.executable, "-m", "perturb", *command]
    driver = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _wait_for(lambda: _written(store) > 0 or driver.poll() is not None, HANG_GUARD, "a first chunk")
    driver.send_signal(signal.SIGINT)
    _, err = driver.communicate(timeout=HANG_GUARD)
    assert driver.returncode == 130, err
    assert "interrupted" in err and "--resume" in err and "Traceback" not in err
    first = zarr.open_group(str(store), mode="r")["session"][...]
    before = xr.open_zarr(store).load()
    assert 0 < np.count_nonzero(first) < first.size  # stopped part-way
    # the same command refuses to start again without --resume, and keeps the store as it is
    assert main(command) == 2
    assert "--resume" in capsys.readouterr().err
    assert np.array_equal(zarr.open_group(str(store), mode="r")["session"][...], first)
    resumed = subprocess.run(
        [*argv, "--resume"], capture_output=True, text=True, timeout=HANG_GUARD
    )
    assert resumed.returncode == 0, resumed.stderr
    ds = xr.open_zarr(store).load()
    session = ds["session"].values
    assert ds.attrs["complete"] and ds.attrs["sessions"] == 2
    assert np.all(session[first == 1] == 1)  # what was written is not computed again ...
    assert np.all(session[first == 0] == 2)  # ... and what was not is, once
    done = first == 1
    for name in ("period", "orbit_error", "verdict"):
        np.testing.assert_array_equal(ds[name].values[done], before[name].values[done])
    assert_same(ds, reference(get_problem("duffing").create(), axes, validate=True))


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_an_existing_cluster_started_by_hand(tmp_path, capsys):
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "dask"]
    scheduler = subprocess.Popen(
        [*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    worker = subprocess.Popen(
        [*dask, "worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        store = tmp_path / "by-hand.zarr"
        argv = ["sweep", "van-der-pol", "--grid", "eps=0.05:0.5:6", "--order", "2",
                "--scheduler", address, "--timeout", str(SWEEP_MAX_CONNECT_SECONDS), "--output", str(store)]  # fmt: skip
        code = main(argv)
        out, err = capsys.readouterr()
        assert code == 0, err
        assert "6 points" in out and str(store) in out
        ds = xr.open_zarr(store)
        problem = get_problem("van-der-pol").create()
        assert_same(ds, reference(problem, ["eps=0.05:0.5:6"], order=2))
    finally:
        for process in (worker, scheduler):
            process.terminate()
        for process in (worker, scheduler):
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()


def test_an_unreachable_scheduler_is_one_line_and_exit_2(tmp_path, capsys):
    address = f"tcp://127.0.0.1:{_free_port()}"  # nobody listens there
    clock = time.monotonic()
    code = main(["sweep", "duffing", "--grid", "eps=0.1:0.2:2", "--scheduler", address,
                 "--timeout", "1", "--output", str(tmp_path / "s.zarr")])  # fmt: skip
    elapsed = time.monotonic() - clock
    _, err = capsys.readouterr()
    assert code == 2 and err.count("\n") == 1 and address in err and "dask scheduler" in err
    assert elapsed < 30
    assert not (tmp_path / "s.zarr").exists()


def test_a_problem_from_a_file_travels_to_the_workers(client, tmp_path):
    source = tmp_path / "softening.py"
    source.write_text(
        "import sympy as sp\n"
        "from perturb import EPS, QuasilinearSystem\n"
        "from problems.base import ParameterSpec, Problem\n"
        "X, V, A = sp.symbols('x xdot amplitude')\n"
        "class Softening(Problem):\n"
        "    name = 'softening'\n"
        "    summary = 'x'' + x = eps x^3'\n"
        "    parameter_specs = (ParameterSpec('eps', 0.1, 'eps'), ParameterSpec('amplitude', 1.0, 'a'))\n"
        "    @classmethod\n"
        "    def build_system(cls):\n"
        "        return QuasilinearSystem([X], [V], [1], [EPS * X**3], parameters=[A])\n"
        "    def method_options(self):\n"
        "        return {'amplitudes': {'x': A}}\n"
    )
    from problems.loading import load_problem

    problem = load_problem(f"{source}:Softening").create()
    ds = perturb.sweep(problem, ["eps=0.05:0.2:4"], client=client)
    assert_same(ds, reference(problem, ["eps=0.05:0.2:4"]))
