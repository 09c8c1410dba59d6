"""Nothing runs that the user did not name: a module of the standard library's name lying in the
working folder (``multiprocessing.py``, ``struct.py``, ``selectors.py``) is never imported by
perturb's processes — the command itself run as ``python -m perturb`` (which puts the working
folder first on ``sys.path``), the Dask workers of a sweep and of a phase diagram, their
multiprocessing bootstrap and resource tracker.

Each planted module writes a marker file when imported; the runs must succeed and leave no marker.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: Modules of the standard library a Dask worker or the command imports, planted in the folder.
PLANTED = ("multiprocessing", "struct", "selectors")

#: Seconds after which a run is a hang, not a speed requirement.
HANG_GUARD = 600


def _plant(folder: Path) -> None:
    for name in PLANTED:
        (folder / f"{name}.py").write_text(
            "import os\n"
            f"open(os.path.join({str(folder)!r}, 'MARKER_{name}'), 'w').write(str(os.getpid()))\n"
        )


def _markers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.glob("MARKER_*"))


def _run(folder: Path, *argv: str, command=(sys.executable, "-m", "perturb")):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONSAFEPATH"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    return subprocess.run(
        [*command, *argv], cwd=folder, env=env, capture_output=True, text=True,
        timeout=HANG_GUARD, stdin=subprocess.DEVNULL,
    )  # fmt: skip


def test_the_command_run_as_a_module_imports_nothing_from_the_working_folder(tmp_path):
    _plant(tmp_path)
    done = _run(tmp_path, "solve", "duffing", "--times", "0,1", "--format", "json")
    assert done.returncode == 0, done.stderr
    assert _markers(tmp_path) == []


def test_the_sweeps_workers_import_nothing_from_the_working_folder(tmp_path):
    pytest.importorskip("distributed")
    _plant(tmp_path)
    argv = ["sweep", "duffing", "--grid", "eps=0.01:0.2:3", "--workers", "1", "--quiet"]
    done = _run(tmp_path, *argv, "--output", str(tmp_path / "s.zarr"))
    assert done.returncode == 0, done.stderr
    assert _markers(tmp_path) == []
    # the console script (the working folder is not on its path; its workers' bootstrap,
    # `python -c`, would put it first but for safe-path mode)
    script = Path(sys.executable).with_name("perturb")
    if script.exists():
        done = _run(tmp_path, *argv, "--format", "csv", command=(str(script),))
        assert done.returncode == 0, done.stderr
        assert _markers(tmp_path) == []


@pytest.mark.slow
def test_the_phase_diagrams_workers_import_nothing_from_the_working_folder(tmp_path):
    pytest.importorskip("distributed")
    _plant(tmp_path)
    done = _run(tmp_path, "phase-diagram", "forced-duffing", "--grid", "Omega=0.9:1.1:3",
                "--grid", "F=0.5:1:3", "--workers", "1", "--quiet")  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert _markers(tmp_path) == []
