"""Sweeps that cannot lie about their store (issue 31, item 6), on real Dask clusters and real
Zarr stores: a chunk deleted or corrupted is found and computed again with the same numbers; one
driver writes a store at a time; a store whose creation was cut short is replaced; the local
cluster's scheduler refuses peers without its credentials; ``--scheduler`` gives up on a server
that is not Dask within its timeout; ``--family`` is looked for along the grid."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import threading

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")

import perturb  # noqa: E402
from perturb.cli import main  # noqa: E402
from perturb.errors import InvalidParameterError, UnknownNameError  # noqa: E402
from perturb.sweep.grid import Grid, parse_axis  # noqa: E402
from perturb.sweep.lock import StoreLock  # noqa: E402
from perturb.sweep.spec import check_family  # noqa: E402
from perturb.sweep.store import STATE  # noqa: E402
from problems import get_problem  # noqa: E402

#: A validated Duffing axis: several chunks of a few points each.
AXIS = ["eps=0.02:0.2:8"]
# four chunks of two points on any machine (a fast machine's pilot would make one chunk of all)
CHUNK = 2
#: Variables compared before and after a repair (the bookkeeping ``session`` differs).
COMPARED = ("status", "period", "epsilon", "verdict", "orbit_error", "order_slope", "state")
#: Relative agreement of a recomputed chunk's floats with the first computation's: another worker
#: (or another machine: PERTURB_TEST_NOISE moves every integration by a few ulps) may round the
#: last bits otherwise (1e-13 relative measured at K = 4); a chunk misplaced or filled wrongly
#: differs at order 1.
SAME_NUMBERS = 1e-9


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
def original(client, tmp_path_factory):
    """A complete validated store and its values."""
    store = tmp_path_factory.mktemp("faults") / "original.zarr"
    problem = get_problem("duffing").create()
    perturb.sweep(problem, AXIS, validate=True, client=client, output=store, chunk_points=CHUNK)
    group = zarr.open_group(str(store), mode="r")
    assert len(group["period"].metadata.chunk_grid.chunk_shape) == 1
    return store, xr.open_zarr(store).load()


def _copy(original, tmp_path):
    store = tmp_path / "copy.zarr"
    shutil.copytree(original[0], store)
    return store


def _chunks(store, name):
    return sorted((store / name / "c").iterdir(), key=lambda p: int(p.name))


@pytest.mark.parametrize(
    "damage",
    [
        "delete period",
        "corrupt session",
        pytest.param("corrupt verdict", marks=pytest.mark.slow),
        pytest.param("empty reason", marks=pytest.mark.slow),
        pytest.param("delete status", marks=pytest.mark.slow),
    ],
)
def test_a_damaged_chunk_is_computed_again_with_the_same_numbers(
    client, original, tmp_path, damage
):
    store = _copy(original, tmp_path)
    how, name = damage.split()
    chunk = _chunks(store, name)[1]
    if how == "delete":
        chunk.unlink()
    elif how == "corrupt":
        chunk.write_bytes(b"not a zarr chunk")
    else:
        chunk.write_bytes(b"")
    ds = perturb.sweep(
        get_problem("duffing").create(), AXIS, validate=True, client=client, output=store,
        chunk_points=CHUNK, resume=True,
    )  # fmt: skip
    session = ds["session"].values
    assert set(session.tolist()) == {1, 2}  # the damaged chunk alone, once
    assert ds.attrs["complete"]
    for variable in COMPARED:
        _same(ds[variable].values, original[1][variable].values, variable)


@pytest.mark.parametrize("damage", ["folder", "link"])
def test_a_chunk_place_holding_a_folder_or_a_link_is_refused_before_any_work(
    original, tmp_path, damage, monkeypatch
):
    """A folder or a link where perturb writes a chunk: refused from the store's own files, with
    the place named, before a cluster is asked for (no client, no workers: the check comes first)
    and before the solution is derived; nothing is removed."""
    store = _copy(original, tmp_path)
    chunk = _chunks(store, "period")[1]
    chunk.unlink()
    if damage == "folder":
        chunk.mkdir()
    else:
        chunk.symlink_to(_chunks(store, "status")[0])
    before = sorted(p.name for p in store.rglob("*"))
    import perturb.sweep.driver as driver

    def no_cluster(*args, **kwargs):
        raise AssertionError("a cluster was asked for before the store was checked")

    monkeypatch.setattr(driver, "Cluster", no_cluster)
    with pytest.raises(InvalidParameterError, match=rf"period/c/{chunk.name} there is not a chunk"):
        perturb.sweep(get_problem("duffing").create(), AXIS, validate=True, output=store,
                      chunk_points=CHUNK, resume=True)  # fmt: skip
    assert sorted(p.name for p in store.rglob("*")) == before


def _same(actual, desired, name) -> None:
    """Equal codes and texts; floats within :data:`SAME_NUMBERS` (NaN where NaN)."""
    if np.issubdtype(np.asarray(desired).dtype, np.floating):
        np.testing.assert_allclose(actual, desired, rtol=SAME_NUMBERS, atol=0, err_msg=name)
    else:
        np.testing.assert_array_equal(actual, desired, err_msg=name)


def test_a_sound_store_is_not_computed_again(client, original, tmp_path):
    store = _copy(original, tmp_path)
    ds = perturb.sweep(
        get_problem("duffing").create(), AXIS, validate=True, client=client, output=store,
        chunk_points=CHUNK, resume=True,
    )  # fmt: skip
    assert np.all(ds["session"].values == 1) and ds.attrs["points_computed"] == 0


def test_one_driver_at_a_time(client, original, tmp_path):
    store = _copy(original, tmp_path)
    before = sorted(p.name for p in store.rglob("*"))
    with StoreLock(store):  # another driver writing it now
        with pytest.raises(InvalidParameterError, match="another perturb sweep is writing"):
            perturb.sweep(get_problem("duffing").create(), AXIS, validate=True, client=client,
                          output=store, resume=True)  # fmt: skip
    assert sorted(p.name for p in store.rglob("*")) == before


def test_a_cut_creation_is_replaced_by_the_same_sweep_only(client, original, tmp_path):
    store = _copy(original, tmp_path)
    group = zarr.open_group(str(store), mode="r+")
    group.attrs.update({STATE: "creating"})
    zarr.consolidate_metadata(str(store))
    shutil.rmtree(store / "verdict")
    problem = get_problem("duffing").create()
    with pytest.raises(InvalidParameterError, match="unfinished creation of another sweep"):
        perturb.sweep(problem, ["eps=0.02:0.2:9"], client=client, output=store, chunk_points=CHUNK)
    ds = perturb.sweep(
        problem, AXIS, validate=True, client=client, output=store, chunk_points=CHUNK
    )
    assert ds.attrs["complete"] and np.all(ds["session"].values == 1)
    np.testing.assert_array_equal(ds["verdict"].values, original[1]["verdict"].values)


def test_the_local_cluster_admits_only_its_own_peers():
    from distributed import Client

    from perturb.sweep.driver import Cluster

    with Cluster(workers=1) as cluster:
        address = cluster.client.scheduler.address
        assert address.startswith("tls://127.0.0.1:")
        assert cluster.client.submit(sum, [1, 2]).result() == 3
        for intruder in (address, address.replace("tls://", "tcp://")):
            with pytest.raises(Exception):  # noqa: B017 - refused: TLS, or no credentials
                Client(intruder, timeout=5, set_as_default=False).run(os.getpid)


class _NotDask:
    """A TCP server on 127.0.0.1 that is not a Dask scheduler."""

    def __init__(self, reply: bytes):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.held = []
        threading.Thread(target=self._serve, args=(reply,), daemon=True).start()

    def _serve(self, reply):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.held.append(conn)
            if reply:
                conn.sendall(reply)


@pytest.mark.parametrize(
    "reply",
    [
        b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n",
        pytest.param(b"", marks=pytest.mark.slow),  # silent
        pytest.param(b"\xff" * 64, marks=pytest.mark.slow),
    ],
)
def test_a_server_that_is_not_dask_is_refused_within_the_timeout(tmp_path, reply):
    server = _NotDask(reply)
    argv = [sys.executable, "-m", "perturb", "sweep", "duffing", "--grid", "eps=0.1,0.2",
            "--scheduler", f"tcp://127.0.0.1:{server.port}", "--timeout", "2",
            "--output", str(tmp_path / "s.zarr")]  # fmt: skip
    # the subprocess's own limit only guards the suite against a hang: the refusal is immediate
    run = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    assert run.returncode == 2, run.stderr
    assert run.stderr.count("\n") == 1 and "not a Dask scheduler" in run.stderr
    assert not (tmp_path / "s.zarr").exists()


@pytest.mark.parametrize("timeout", ["1e308", "inf", "61", "0", "-1", "nan"])
def test_timeouts_past_the_maximum_are_refused(capsys, tmp_path, timeout):
    code = main(["sweep", "duffing", "--grid", "eps=0.1,0.2", "--scheduler", "tcp://127.0.0.1:1",
                 "--timeout", timeout, "--output", str(tmp_path / "s.zarr")])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "--timeout" in err


def test_a_family_is_looked_for_along_the_grid():
    problem = get_problem("forced-duffing").create()  # at Omega = 1: one branch only
    with pytest.raises(UnknownNameError):
        problem.families(1).get("upper")
    grid = Grid((parse_axis("Omega=1.0:1.2:5"),))
    following = check_family(problem, "upper", grid, 1)
    assert following.case().family == "upper"
    with pytest.raises(UnknownNameError, match="lower.*middle.*upper|upper"):
        check_family(problem, "bogus", grid, 1)


def test_the_upper_branch_swept_over_the_frequency(client):
    problem = get_problem("forced-duffing").create()
    grid = Grid((parse_axis("Omega=0.95:1.2:6"),))
    following = check_family(problem, "upper", grid, 1)
    ds = perturb.sweep(following, ["Omega=0.95:1.2:6"], client=client)
    status = ds["status"].values
    ok = status == 0
    assert ok[-3:].all()  # past the fold the branch exists, point by point
    for omega, amplitude in zip(ds["Omega"].values[ok], ds["amplitude"].values[ok, 0],
                                strict=True):  # fmt: skip
        point = problem.with_parameters(Omega=float(omega))
        upper = point.families(1).get("upper")
        assert amplitude == pytest.approx(float(np.hypot(*upper.amplitudes.values())), rel=0.05)
    assert all("upper" in r for r in ds["reason"].values[~ok])


KILLER = """
import os
import sympy as sp
from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, V, A = sp.symbols("x xdot amplitude")


class Killer(Problem):
    name = "killer"
    summary = "Duffing whose points past eps = 0.2 kill the Dask worker computing them"
    parameter_specs = (ParameterSpec("eps", 0.1, "eps"), ParameterSpec("amplitude", 1.0, "a"))

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [V], [1], [-EPS * X**3], parameters=[A])

    def method_options(self):
        return {"amplitudes": {"x": A}}

    def symbol_values(self):
        if self.values["eps"] > 0.2:
            try:
                from distributed import get_worker

                get_worker()
            except (ImportError, ValueError):
                pass  # not in a worker: the driver and the pilot live
            else:
                os._exit(1)
        return super().symbol_values()
"""


@pytest.mark.slow  # workers killed again and again until Dask gives the chunks up: ~1-2 min
def test_the_count_of_what_is_missing_is_the_stores(client, tmp_path):
    from perturb.errors import SweepError
    from problems.loading import load_problem

    (tmp_path / "killer.py").write_text(KILLER)
    problem = load_problem(f"{tmp_path / 'killer.py'}:Killer").create()
    store = tmp_path / "killed.zarr"
    with pytest.raises(SweepError) as info:
        perturb.sweep(
            problem,
            ["eps=0.05:0.4:8"],
            validate=True,
            client=client,
            output=store,
            chunk_points=CHUNK,
        )
    session = zarr.open_group(str(store), mode="r")["session"][...]
    missing = int(np.count_nonzero(session == 0))
    assert missing >= 4  # every point past eps = 0.2 (and its chunk-mates)
    assert f"{missing} of 8 points" in str(info.value) and "--resume" in str(info.value)
    client.wait_for_workers(2, timeout=120)
