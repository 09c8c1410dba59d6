"""Basin maps on a real Dask LocalCluster into a real Zarr store: the same codes as in this
process, and a driver interrupted (SIGINT) or killed (SIGKILL) mid-map resumed without computing
a point twice or losing one."""

from __future__ import annotations

import signal
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")

from perturb.cli import main  # noqa: E402
from perturb.dynamics.basins import BasinStatus, basins  # noqa: E402
from tests.sweep.test_dask import HANG_GUARD, _wait_for, _written  # noqa: E402

GRID = ["x=-3:3:12", "xdot=-3:3:12"]


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


@pytest.fixture(scope="module")
def reference(bistable):
    return basins(bistable, GRID, workers=0)


def test_a_local_cluster_maps_what_this_process_maps(bistable, reference, client, tmp_path):
    store = tmp_path / "basins.zarr"
    result = basins(bistable, GRID, client=client, output=store, chunk_points=24)
    assert result.status is BasinStatus.OK
    np.testing.assert_array_equal(result.dataset["code"].values, reference.dataset["code"].values)
    np.testing.assert_array_equal(
        result.dataset["periods"].values, reference.dataset["periods"].values
    )
    reopened = xr.open_zarr(store)
    assert reopened.attrs["complete"] and reopened.attrs["kind"] == "basins"
    assert np.all(reopened["session"].values == 1)
    assert [f.count for f in result.fractions] == [f.count for f in reference.fractions]
    # the same request again needs --resume; a finished store resumes to nothing new
    from perturb.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match="resume"):
        basins(bistable, GRID, client=client, output=store, chunk_points=24)
    again = basins(bistable, GRID, client=client, output=store, resume=True, chunk_points=24)
    assert again.dataset.attrs["points_computed"] == 0
    # another request at that path is refused, whatever its flags
    with pytest.raises(InvalidParameterError, match="another request"):
        basins(bistable, GRID, client=client, output=store, resume=True, periods=50)


@pytest.mark.parametrize(
    "how", [signal.SIGINT, pytest.param(signal.SIGKILL, marks=pytest.mark.slow)]
)
def test_a_stopped_driver_resumes_where_it_stopped(reference, tmp_path, capsys, how):
    store = tmp_path / "stopped.zarr"
    command = ["basins", "forced-duffing", "--set", "Omega=1.05", "--workers", "1", "--output",
               str(store), "--quiet", "--chunk-points", "6"]  # fmt: skip
    for axis in GRID:
        command += ["--grid", axis]
    argv = [sys.executable, "-m", "perturb", *command]
    driver = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _wait_for(lambda: _written(store) > 0 or driver.poll() is not None, HANG_GUARD, "a first chunk")
    driver.send_signal(how)
    _, err = driver.communicate(timeout=HANG_GUARD)
    if how == signal.SIGINT:
        assert driver.returncode == 130, err
        assert "interrupted" in err and "--resume" in err and "Traceback" not in err
    first = zarr.open_group(str(store), mode="r")["session"][...]
    before = xr.open_zarr(store).load()
    assert 0 < np.count_nonzero(first) < first.size  # stopped part-way
    assert main(command) == 2  # the same command without --resume is refused ...
    assert "--resume" in capsys.readouterr().err
    assert np.array_equal(zarr.open_group(str(store), mode="r")["session"][...], first)
    resumed = subprocess.run([*argv, "--resume"], capture_output=True, text=True,
                             timeout=HANG_GUARD)  # fmt: skip
    assert resumed.returncode == 0, resumed.stderr
    ds = xr.open_zarr(store).load()
    session = ds["session"].values
    assert ds.attrs["complete"] and ds.attrs["sessions"] == 2
    assert np.all(session[first == 1] == 1)  # what was written is not computed again ...
    assert np.all(session[first == 0] == 2)  # ... and what was not is, once
    done = first == 1
    np.testing.assert_array_equal(ds["code"].values[done], before["code"].values[done])
    np.testing.assert_array_equal(ds["code"].values, reference.dataset["code"].values)
