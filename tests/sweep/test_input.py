"""Bad input to ``perturb sweep``: one line, exit 2, no traceback, nothing computed or overwritten;
the store's own rules (never overwrite, resume only the same sweep)."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("zarr")

from perturb.cli import main  # noqa: E402
from perturb.errors import InvalidParameterError  # noqa: E402
from perturb.sweep.derive import Derivation, DeriveMode, symbolic_derivation  # noqa: E402
from perturb.sweep.grid import parse_axis  # noqa: E402
from perturb.sweep.memory import MemoryResult  # noqa: E402
from perturb.sweep.spec import SweepJob, check_spec  # noqa: E402
from perturb.sweep.store import SweepStore  # noqa: E402
from perturb.sweep.task import run_chunk  # noqa: E402
from perturb.validation import with_epsilon
from problems import get_problem  # noqa: E402


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(code, err) -> str:
    assert code == 2 and err.startswith("perturb: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--grid", "epss=0.1:0.2:3"], "did you mean 'eps'"),
        (["--grid", "eps=0.1:0.2:0"], "N = 0"),
        (["--grid", "eps=0.1:0.2:10000", "--grid", "amplitude=1:2:10000"], "100,000,000 points"),
        (["--grid", "eps=0.1:0.2:3", "--set", "eps=0.1"], "also set with --set"),
        ([], "--grid: give at least one"),
        (["--grid", "eps=0.1:0.2:3", "--format", "zarr", "--no-output"], None),
        (["--grid", "eps=0.1:0.2:3", "--order", "0"], "--order 0"),
        (["--grid", "eps=0.1:0.2:3", "--workers", "0"], "--workers"),
        (
            ["--grid", "eps=0.1:0.2:3", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"],
            "drop --workers",
        ),
        (["--grid", "eps=0.1:0.2:3", "--format", "csv", "--resume"], "--resume"),
        (["--grid", "eps=0.1:0.2:3", "--integrator", "euler"], "integrator"),
    ],
)
def test_bad_input_is_one_line_exit_2(capsys, tmp_path, argv, words):
    store = str(tmp_path / "s.zarr")
    if "--no-output" in argv:  # the Zarr store needs --output
        argv = [a for a in argv if a != "--no-output"]
        err = one_line_error(*run(capsys, "sweep", "duffing", *argv)[::2])
        assert "--output" in err
        return
    if "--format" not in argv:
        argv = [*argv, "--output", store]
    code, _, err = run(capsys, "sweep", "duffing", *argv)
    assert words in one_line_error(code, err)
    assert not (tmp_path / "s.zarr").exists()


def test_yes_confirms_a_large_grid_then_the_store_is_checked(capsys, tmp_path):
    (tmp_path / "taken").write_text("mine")
    argv = ["sweep", "duffing", "--grid", "eps=0.1:0.2:10000", "--grid", "amplitude=1:2:1001",
            "--output", str(tmp_path / "taken"), "--yes"]  # fmt: skip
    err = one_line_error(*run(capsys, *argv)[::2])
    assert "not a perturb sweep store" in err  # past the size check, refused for the path
    assert (tmp_path / "taken").read_text() == "mine"


def _store(path, axes=("eps=0.05:0.1:3",), **settings):
    spec = check_spec(get_problem("duffing").create(), [parse_axis(a) for a in axes], **settings)
    job = SweepJob(spec, Derivation(DeriveMode.OWN, "test"), spec.fingerprint("0.1.0"))
    return SweepStore.prepare(
        path, job, resume=False, version="0.1.0", chunk_points=lambda: 2, extra={}
    )


def _listing(folder):
    return sorted(
        (p.relative_to(folder).as_posix(), p.read_bytes()) for p in folder.rglob("*") if p.is_file()
    )


def test_a_store_is_never_overwritten(capsys, tmp_path):
    folder = tmp_path / "data"
    folder.mkdir()
    (folder / "notes.txt").write_text("results of last year")
    err = one_line_error(
        *run(capsys, "sweep", "duffing", "--grid", "eps=0.05:0.1:3", "--output", str(folder))[::2]
    )
    assert (
        "not a perturb sweep store" in err
        and (folder / "notes.txt").read_text() == "results of last year"
    )

    store = tmp_path / "old.zarr"
    _store(store)
    before = _listing(store)
    # the same sweep without --resume
    err = one_line_error(
        *run(capsys, "sweep", "duffing", "--grid", "eps=0.05:0.1:3", "--output", str(store))[::2]
    )
    assert "--resume" in err
    # another grid, or another problem's settings, even with --resume
    for argv in (["--grid", "eps=0.05:0.1:4"], ["--grid", "eps=0.05:0.1:3", "--order", "2"]):
        err = one_line_error(
            *run(capsys, "sweep", "duffing", *argv, "--output", str(store), "--resume")[::2]
        )
        assert "holds another sweep" in err and ("grid" in err or "settings" in err)
    assert _listing(store) == before


def test_resume_reads_the_chunks_back(tmp_path):
    store = _store(tmp_path / "s.zarr", axes=("eps=0.05:0.1:5",))
    assert store.pending() == [0, 1, 2]
    job_spec = check_spec(get_problem("duffing").create(), [parse_axis("eps=0.05:0.1:5")])
    job = SweepJob(job_spec, Derivation(DeriveMode.OWN, "test"), "k")
    store.write(1, run_chunk(job, store.chunking.indices(1), session=1))
    again = SweepJob(job_spec, job.derivation, job_spec.fingerprint("0.1.0"))

    def reopen():
        return SweepStore.prepare(tmp_path / "s.zarr", again, resume=True, version="0.1.0",
                                  chunk_points=lambda: 99, extra={})  # fmt: skip

    with pytest.raises(InvalidParameterError, match="another perturb sweep is writing"):
        reopen()  # the first is still open: one writer at a time
    store.close()
    reopened = reopen()
    assert reopened.chunking.chunk == (2,) and reopened.pending() == [0, 2]
    reopened.close()


def test_points_as_csv_and_json(tmp_path):
    from perturb.report.sweep import sweep_as_csv, sweep_as_dict
    from perturb.sweep.grid import Chunking

    problem = get_problem("duffing").create()
    spec = check_spec(
        problem, [parse_axis("eps=0.05,0.1"), parse_axis("amplitude=-1,1")], times=[0.0, 1.0]
    )
    job = SweepJob(spec, Derivation(DeriveMode.OWN, "test"), "k")
    result = MemoryResult(job, Chunking.of(spec.grid.shape, 3), {})
    for number in result.chunking:
        result.write(number, run_chunk(job, result.chunking.indices(number)))
    ds = result.dataset()
    lines = sweep_as_csv(ds).splitlines()
    header = lines[0].split(",")
    assert header[:4] == ["eps", "amplitude", "status", "reason"]
    assert "sweep_amplitude[x]" in header and '"state[t=1.0,x]"' in lines[0]
    rows = lines[1:]
    assert len(rows) == 4 and rows[0].startswith("0.05,-1.0,invalid_parameters,")
    data = sweep_as_dict(ds)
    assert [p["parameters"] for p in data["points"]] == [
        {"eps": e, "amplitude": a} for e in (0.05, 0.1) for a in (-1.0, 1.0)
    ]
    ok = data["points"][1]
    point = problem.with_parameters(eps=0.05, amplitude=1.0)
    assert ok["status"] == "ok" and ok["period"] == point.period(point.solve(1))
    assert set(ok["state"]) == {"x", "xdot"} and len(ok["state"]["x"]) == 2
    assert data["points"][0]["status"] == "invalid_parameters"
    assert json.loads(json.dumps(data, allow_nan=True))["grid"][1]["values"] == [-1.0, 1.0]


def test_the_symbolic_derivation_is_a_declared_hook_kept_at_every_point():
    """A problem that offers it says so (no proxy, no signature probe); the symbolic problem
    stays symbolic at other parameter values and at another eps, on the same numbers."""
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    symbolic = disk.symbolic_derivation()
    assert symbolic is not None and symbolic._symbolic is True
    assert symbolic.case().values == disk.case().values
    assert with_epsilon(symbolic, 0.002)._symbolic is True
    assert with_epsilon(symbolic, 0.002).epsilon() == pytest.approx(0.002, rel=1e-12)
    assert symbolic.with_parameters(gamma3_0=0.3)._symbolic is True
    assert symbolic_derivation(get_problem("duffing").create()) is None  # already symbolic
    derivation = Derivation(DeriveMode.SYMBOLIC, "test")
    assert derivation.model_at(disk, {"gamma3_0": 0.3})._symbolic is True


def test_a_model_that_cannot_be_recreated_cannot_be_swept():
    from perturb.validation import SystemModel

    class Fixed(SystemModel):
        def with_parameters(self, **values):
            return None

    import sympy as sp

    from perturb import EPS, QuasilinearSystem

    x, v = sp.symbols("x v")
    system = QuasilinearSystem([x], [v], [1], [-EPS * x**3])
    model = Fixed(system, {"epsilon": 0.1}, {"amplitudes": {"x": 1}})
    with pytest.raises(InvalidParameterError, match="cannot be swept"):
        check_spec(model, [parse_axis("epsilon=0.1,0.2")])
    assert np.isfinite(SystemModel(system, {"epsilon": 0.1}, {"amplitudes": {"x": 1}}).epsilon())


def test_the_pilot_times_points_that_share_a_derivation():
    """With a derivation per distinct parameter set, the pilot's points are those of a chunk
    (the entering parameter fixed): timing points of different derivations sized the disk's
    r0 x gamma3_0 map into one-point chunks, each paying a derivation."""
    from perturb.sweep.driver import _pilot_indices

    spec = check_spec(
        get_problem("duffing").create(),
        [parse_axis("eps=0.05:0.1:5"), parse_axis("amplitude=1:2:6")],
    )
    per_point = SweepJob(spec, Derivation(DeriveMode.PER_POINT, "test", ("amplitude",)), "k")
    indices = _pilot_indices(per_point, 4)
    where = np.unravel_index(indices, spec.grid.shape)
    assert len(indices) == 4 and set(where[1]) == {0}  # amplitude fixed, eps varies
    own = SweepJob(spec, Derivation(DeriveMode.OWN, "test"), "k")
    assert _pilot_indices(own, 4) == [0, 1, 2, 3]  # the grid's first points, as before
