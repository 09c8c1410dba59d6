"""A bounded kind prunes its own entries only, and the digest of a key refuses as documented."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

from perturb.cache import UNPICKLABLE, cached, digest


def test_pruning_a_kind_leaves_a_kind_whose_name_it_begins(cache_folder):
    cached("demo-more", ("kept",), lambda: "another kind's")
    for n in range(3):
        cached("demo", (n,), lambda n=n: n, keep=1)
    assert len(list(cache_folder.glob("demo-more-*.pkl"))) == 1
    assert cached("demo-more", ("kept",), lambda: "computed again") == "another kind's"
    assert len(list(cache_folder.glob("demo-[0-9a-f]*.pkl"))) == 1


def test_pruning_leaves_files_that_are_not_entries_of_the_kind(cache_folder):
    stray = cache_folder / "demo-notes.pkl"
    stray.write_text("a user's file")
    for n in range(3):
        cached("demo", (n,), lambda n=n: n, keep=1)
    assert stray.read_text() == "a user's file"


def test_a_cyclic_value_has_no_digest_and_says_so_as_documented():
    loop: list = []
    loop.append(loop)
    with pytest.raises(UNPICKLABLE):
        digest(loop)


#: A process that writes and reads entries of a bounded kind, many more than the bound, while
#: another does the same in the same folder: each prunes entries the other may have removed first.
_WRITER = textwrap.dedent(
    """
    import sys
    from perturb.cache import cached

    name, rounds, keep = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    wrong = 0
    for n in range(rounds):
        for key in (n, n // 2):  # the second reads an entry that may have been pruned meanwhile
            value = cached("bounded", (key,), lambda key=key: ("value", key), keep=keep)
            wrong += value != ("value", key)
    print(wrong)
    """
)


def test_two_processes_writing_past_the_bound_keep_it_and_read_only_their_keys(cache_folder):
    rounds, keep = 60, 5
    env = {**os.environ, "PERTURB_CACHE_DIR": str(cache_folder)}
    runs = [
        subprocess.Popen(
            [sys.executable, "-c", _WRITER, name, str(rounds), str(keep)],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for name in ("a", "b")
    ]
    outputs = [run.communicate(timeout=300) for run in runs]
    assert [run.returncode for run in runs] == [0, 0], [err for _, err in outputs]
    assert [out.strip() for out, _ in outputs] == ["0", "0"]
    assert all("Traceback" not in err and "perturb cache" not in err for _, err in outputs)
    assert len(list(cache_folder.glob("bounded-*.pkl"))) <= keep
    assert not list(cache_folder.glob("*.tmp"))


def test_a_folder_and_key_named_from_the_home_folder_are_there(tmp_path, monkeypatch):
    """``PERTURB_CACHE_DIR="~/cache"`` (quoted, so the shell leaves the tilde) is in the home
    folder, not a folder named ``~`` in the current one; so is the key file."""
    from perturb.cache import cache_dir, key_file

    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setenv("PERTURB_CACHE_DIR", "~/cache")
    monkeypatch.setenv("PERTURB_CACHE_KEY_FILE", "~/config/cache.key")
    assert cache_dir() == tmp_path / "cache"
    assert key_file() == tmp_path / "config" / "cache.key"


def test_a_killed_writers_leftovers_are_removed_and_nothing_else(cache_folder, tmp_path_factory):
    """A process killed while writing leaves ``tmp*.tmp`` behind; the next process to write into
    the folder removes those older than the leftover age, and nothing else."""
    from perturb._defaults import CACHE_LEFTOVER_SECONDS

    old = os.stat(cache_folder).st_mtime - 2 * CACHE_LEFTOVER_SECONDS
    left = cache_folder / "tmpkilled.tmp"
    left.write_bytes(b"half an entry")
    live = cache_folder / "tmpwriting.tmp"  # a writer's file of this very moment
    live.write_bytes(b"being written")
    notes = cache_folder / "notes.tmp"  # not a writer's name
    notes.write_text("a user's file")
    outside = tmp_path_factory.mktemp("outside") / "elsewhere"
    outside.write_text("not in the cache folder")
    link = cache_folder / "tmplink.tmp"  # a link is not removed, nor what it points to
    link.symlink_to(outside)
    for path in (left, notes, outside):
        os.utime(path, (old, old))
    os.utime(link, (old, old), follow_symlinks=False)
    cached("demo", ("a write",), lambda: 1)
    assert not left.exists()
    assert live.read_bytes() == b"being written"
    assert notes.read_text() == "a user's file"
    assert link.is_symlink() and outside.read_text() == "not in the cache folder"
