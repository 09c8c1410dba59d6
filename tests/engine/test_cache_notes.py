"""The disk cache's warnings concern the machine (a full or read-only folder, a damaged entry),
never a result: a result's own warnings (the JSON's ``warnings``, a sweep point's) are those of a
run with the cache off, and the cache's warning still reaches the user, once."""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
import warnings

import pytest

import perturb.cache as cache_mod
import problems.base
from perturb.cache import cached, held_warnings
from perturb.cli import main
from perturb.errors import CacheWarning
from perturb.sweep.quantities import TIMINGS


@pytest.fixture
def full_disk(tmp_path, monkeypatch):
    """A cache folder on a full disk: every entry written fails with ENOSPC."""
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("PERTURB_CACHE_KEY_FILE", str(tmp_path / "config" / "cache.key"))
    monkeypatch.setattr(cache_mod, "_WARNED", set())

    def full(*args):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(cache_mod, "write_entry", full)  # what the cache writes through
    return tmp_path


def _solve_json(capsys, monkeypatch, folder: str) -> dict:
    monkeypatch.setenv("PERTURB_CACHE_DIR", folder)
    monkeypatch.setattr(problems.base, "_SOLUTION_CACHE", {})  # solved afresh: the disk is used
    assert main(["solve", "duffing", "--set", "eps=0.07", "--format", "json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_full_disk_leaves_the_solution_json_as_with_the_cache_off(full_disk, capsys, monkeypatch):
    off = _solve_json(capsys, monkeypatch, "off")
    with pytest.warns(CacheWarning, match="No space left") as given:
        full = _solve_json(capsys, monkeypatch, str(full_disk / "cache"))
    assert full == off
    assert sum(issubclass(w.category, CacheWarning) for w in given) == 1


def test_a_held_warning_is_given_after_the_block_that_records_a_results_warnings(full_disk):
    with pytest.warns(CacheWarning, match="No space left") as given:
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            assert cached("demo", ("held",), lambda: 42) == 42
            warnings.warn("the result's own note", UserWarning, stacklevel=1)
        assert [str(w.message) for w in caught] == ["the result's own note"]
    assert [issubclass(w.category, CacheWarning) for w in given] == [True]


def test_a_warning_held_inside_an_ignoring_block_is_given_after_it(full_disk):
    with pytest.warns(CacheWarning, match="No space left"):
        with held_warnings(), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with held_warnings():  # nested: held until the outermost block ends
                cached("demo", ("ignored",), lambda: 42)


def _sweep(tmp_path, folder: str) -> tuple[dict, str]:
    """A validated sweep on a real local cluster (one worker process), as a user runs it."""
    output = tmp_path / f"sweep-{len(list(tmp_path.glob('sweep-*')))}.json"
    argv = ["sweep", "duffing", "--grid", "amplitude=0.8,1.3", "--validate", "--workers", "1"]
    argv += ["--chunk-points", "1", "--format", "json", "--output", str(output), "--quiet"]
    env = {**os.environ, "PERTURB_CACHE_DIR": folder}
    env["PERTURB_CACHE_KEY_FILE"] = str(tmp_path / "config" / "cache.key")
    done = subprocess.run(
        [sys.executable, "-m", "perturb", *argv], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    return json.loads(output.read_text()), done.stderr


def _points(document: dict) -> list:
    return [{k: v for k, v in p.items() if k not in TIMINGS} for p in document["points"]]


@pytest.mark.slow  # two sweeps, each starting a local cluster
def test_an_unusable_folder_is_one_line_of_a_sweep_and_no_points_warning(tmp_path):
    not_a_folder = tmp_path / "file"
    not_a_folder.write_text("")  # unusable for every user, root too
    off, quiet = _sweep(tmp_path, "off")
    document, told = _sweep(tmp_path, str(not_a_folder))
    assert _points(document) == _points(off)
    assert not quiet
    assert told.count("perturb cache:") == 1 and "cannot create the folder" in told
