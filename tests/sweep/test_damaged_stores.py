"""``--resume`` never calls a store complete that does not open as the Dataset it promises: an
array whose metadata or whole folder is gone is made again and its points computed again; a chunk
replaced by a folder is one line (perturb removes nothing it did not write); a store named through
a symbolic link is the store; a cluster without workers is a failed status with advice, not
Dask's TimeoutError. Real LocalClusters, a real ``dask scheduler`` and real Zarr stores."""

from __future__ import annotations

import shutil
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")

from perturb.cli import main  # noqa: E402

GRID = ["--grid", "eps=0.01:0.2:3"]
#: Seconds after which a wait is a hang, not a speed requirement.
HANG_GUARD = 600


def _sweep(store, *extra) -> list[str]:
    return ["sweep", "duffing", *GRID, "--workers", "1", "--quiet", "--output", str(store), *extra]


@pytest.fixture(scope="module")
def complete(tmp_path_factory):
    store = tmp_path_factory.mktemp("stores") / "complete.zarr"
    assert main(_sweep(store)) == 0
    return store, xr.open_zarr(store).load()


def _copy(complete, tmp_path):
    store, reference = complete
    copy = tmp_path / "s.zarr"
    shutil.copytree(store, copy)
    return copy, reference


@pytest.mark.parametrize("damage", ["metadata", "array"])
def test_a_lost_array_is_made_again_and_computed(complete, tmp_path, capsys, damage):
    store, reference = _copy(complete, tmp_path)
    if damage == "metadata":
        (store / "period" / "zarr.json").unlink()
    else:
        shutil.rmtree(store / "period")
    assert main(_sweep(store, "--resume")) == 0, capsys.readouterr().err
    ds = xr.open_zarr(store).load()
    np.testing.assert_array_equal(ds["period"].values, reference["period"].values)
    assert ds.attrs["complete"] and ds.attrs["sessions"] == 2
    assert np.all(ds["session"].values == 2)  # the lost array's chunks were computed again


def test_a_chunk_replaced_by_a_folder_is_one_line(complete, tmp_path, capsys):
    store, _ = _copy(complete, tmp_path)
    chunk = store / "period" / "c" / "0"
    chunk.unlink()
    chunk.mkdir()
    (chunk / "mine.txt").write_text("a user's file")
    assert main(_sweep(store, "--resume")) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "damaged" in err and "period/c/0" in err, err
    assert (chunk / "mine.txt").read_text() == "a user's file"


def test_resume_through_a_symbolic_link(complete, tmp_path, capsys):
    store, reference = _copy(complete, tmp_path)
    link = tmp_path / "link.zarr"
    link.symlink_to(store)
    assert main(_sweep(link, "--resume")) == 0, capsys.readouterr().err
    assert link.is_symlink()
    np.testing.assert_array_equal(xr.open_zarr(link)["period"].values, reference["period"].values)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_a_cluster_without_workers_is_a_failed_status(tmp_path, capsys, monkeypatch):
    import perturb.sweep.watch as watch

    monkeypatch.setattr(watch, "SWEEP_NO_WORKER_SECONDS", 2.0)
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    scheduler = subprocess.Popen(
        [sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port", str(port),
         "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + HANG_GUARD
        while time.monotonic() < deadline:
            with socket.socket() as s:
                if s.connect_ex(("127.0.0.1", port)) == 0:
                    break
            time.sleep(0.2)
        store = tmp_path / "nw.zarr"
        argv = ["sweep", "duffing", *GRID, "--scheduler", address, "--quiet", "--output",
                str(store)]  # fmt: skip
        assert main(argv) == 1
        err = capsys.readouterr().err
        assert err.startswith("perturb: failed: no worker") and "--resume" in err, err
        assert "TimeoutError" not in err and "internal error" not in err
    finally:
        scheduler.terminate()
        scheduler.wait(HANG_GUARD)
