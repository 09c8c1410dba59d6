"""A bounded kind prunes its own entries only, and the digest of a key refuses as documented."""

from __future__ import annotations

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
