"""The disk cache under faults (issue 10): damaged, foreign, stale or crafted entries, unsafe folders.

Every case asserts that the answer equals the freshly computed one (no wrong answer), that a bad
entry is recomputed and rewritten (the next read is a hit), and that no crafted pickle ever runs.
Entries are real: a Duffing-type solution written by :meth:`PoincareMethod.solve`.
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap
import warnings
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import perturb.cache as cache_mod
from perturb import EPS, PoincareMethod, QuasilinearSystem
from perturb.cache import Rejection, cached, decode, encode
from perturb.errors import CacheWarning

x, xd, A = sp.symbols("x xdot A")
SYSTEM = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A])
METHOD = PoincareMethod(order=1, amplitudes={"x": A})
#: Exactly the key ``METHOD.solve(SYSTEM)`` uses, so entries written by solve are read by the cases.
PARTS = METHOD._cache_key(SYSTEM)
#: The reference answer, computed with the cache off.
FRESH = PoincareMethod(order=1, amplitudes={"x": A}, cache=False).solve(SYSTEM)
ROOT = Path(__file__).resolve().parents[2]
#: Every damaged entry is checked against :func:`decode`; every third one also goes through the
#: whole read-recompute-rewrite path (each costs a pickle and a file write: ~1 ms).
FULL_PATH_STRIDE = 3


class Compute:
    """``compute`` for :func:`cached` that returns :data:`FRESH` itself and counts its calls: an
    answer that ``is FRESH`` was recomputed, an equal one that is not was read from disk."""

    def __init__(self):
        self.calls = 0

    def __call__(self):
        self.calls += 1
        return FRESH


@pytest.fixture
def store(tmp_path, monkeypatch):
    """A private cache folder and key file, fresh warning state, and one real entry in it."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    monkeypatch.setenv("PERTURB_CACHE_KEY_FILE", str(tmp_path / "config" / "cache.key"))
    monkeypatch.setattr(cache_mod, "_WARNED", set())
    METHOD.solve(SYSTEM)
    (entry,) = folder.glob("solution-*.pkl")
    return entry


def _secret() -> bytes:
    return Path(os.environ["PERTURB_CACHE_KEY_FILE"]).read_bytes()


def _assert_recomputed_and_repaired(entry: Path) -> None:
    """The damaged ``entry`` is not used, the answer is the fresh one and the entry is rewritten."""
    compute = Compute()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CacheWarning)
        answer = cached("solution", PARTS, compute)
    assert answer is FRESH and compute.calls == 1
    _assert_repaired()


def _assert_repaired() -> None:
    """The entry of :data:`PARTS` is valid: reading it computes nothing and gives the answer."""
    again = Compute()
    reread = cached("solution", PARTS, again)
    assert again.calls == 0 and reread is not FRESH and reread == FRESH


# ---------------------------------------------------------------------------------- the format


def test_entry_is_signed_and_self_describing(store):
    why, value = decode(
        store.read_bytes(), "solution", cache_mod._key("solution", PARTS), _secret()
    )
    assert why is None and value == FRESH
    key = Path(os.environ["PERTURB_CACHE_KEY_FILE"])
    assert key.stat().st_mode & 0o777 == 0o600
    assert not key.resolve().is_relative_to(store.parent.resolve())
    assert store.stat().st_mode & 0o077 == 0  # entries are private too


# ---------------------------------------------------------------------------------- damage


def test_every_truncation_is_recomputed(store):
    blob = store.read_bytes()
    key = cache_mod._key("solution", PARTS)
    for n in range(len(blob)):  # every offset: 0 bytes (empty file) up to one byte short
        assert decode(blob[:n], "solution", key, _secret())[0] is not None
        if n % FULL_PATH_STRIDE == 0:
            store.write_bytes(blob[:n])
            _assert_recomputed_and_repaired(store)


def test_every_single_byte_flip_is_recomputed(store):
    blob = store.read_bytes()
    key = cache_mod._key("solution", PARTS)
    reasons = {}
    for i in range(len(blob)):
        damaged = bytearray(blob)
        damaged[i] ^= 0xFF
        why, value = decode(bytes(damaged), "solution", key, _secret())
        assert why is not None and value is None  # 0 silent wrong answers
        reasons[why] = reasons.get(why, 0) + 1
        if i % FULL_PATH_STRIDE == 0:
            store.write_bytes(bytes(damaged))
            _assert_recomputed_and_repaired(store)
    # only the magic may be told apart without the key; everything else fails the signature
    assert set(reasons) == {Rejection.NOT_AN_ENTRY, Rejection.UNSIGNED}
    assert reasons[Rejection.NOT_AN_ENTRY] == len(cache_mod._MAGIC)


@settings(max_examples=60)
@given(data=st.data())
def test_any_byte_replacement_is_recomputed(tmp_path_factory, data):
    folder = tmp_path_factory.mktemp("flip")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("PERTURB_CACHE_DIR", str(folder / "cache"))
        mp.setenv("PERTURB_CACHE_KEY_FILE", str(folder / "cache.key"))
        METHOD.solve(SYSTEM)
        (entry,) = (folder / "cache").glob("solution-*.pkl")
        blob = bytearray(entry.read_bytes())
        i = data.draw(st.integers(0, len(blob) - 1), label="position")
        byte = data.draw(st.integers(0, 255).filter(lambda b: b != blob[i]), label="new byte")
        blob[i] = byte
        key = cache_mod._key("solution", PARTS)
        assert decode(bytes(blob), "solution", key, (folder / "cache.key").read_bytes())[0]
        entry.write_bytes(bytes(blob))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", CacheWarning)
            assert METHOD.solve(SYSTEM) == FRESH  # through the whole solve path
        _assert_repaired()


def test_damage_warns_once_per_process(store):
    compute = Compute()
    store.write_bytes(b"garbage")
    with pytest.warns(CacheWarning, match="not a perturb cache entry.*recomputed"):
        cached("solution", PARTS, compute)
    store.write_bytes(b"garbage")
    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)  # a second warning would fail here
        assert cached("solution", PARTS, compute) is FRESH
    assert compute.calls == 2


# ---------------------------------------------------------------------------------- misplaced


def test_foreign_entry_under_this_key_is_recomputed(store):
    other = PoincareMethod(order=2, amplitudes={"x": A})
    other.solve(SYSTEM)  # a valid, signed entry of other inputs
    (foreign,) = set(store.parent.glob("solution-*.pkl")) - {store}
    store.write_bytes(foreign.read_bytes())
    key = cache_mod._key("solution", PARTS)
    assert decode(store.read_bytes(), "solution", key, _secret())[0] is Rejection.FOREIGN
    with pytest.warns(CacheWarning, match="other inputs"):
        assert METHOD.solve(SYSTEM) == FRESH
    _assert_repaired()


def test_entry_of_another_kind_is_foreign(store):
    key = cache_mod._key("solution", PARTS)
    other = encode("reduction", key, "a reduction", _secret())
    assert decode(other, "solution", key, _secret())[0] is Rejection.FOREIGN


@pytest.mark.parametrize("field", ["perturb", "engine", "format", "sympy"])
def test_entry_of_another_version_is_recomputed(store, monkeypatch, field):
    current = cache_mod._environment()
    key = cache_mod._key("solution", PARTS)
    monkeypatch.setattr(cache_mod, "_environment", lambda: {**current, field: "older"})
    old = encode("solution", key, FRESH, _secret())  # signed by this user, same key, older build
    monkeypatch.setattr(cache_mod, "_environment", lambda: current)
    assert decode(old, "solution", key, _secret())[0] is Rejection.STALE
    store.write_bytes(old)
    _assert_recomputed_and_repaired(store)


def test_unsigned_and_foreign_signed_entries_are_recomputed(store):
    key = cache_mod._key("solution", PARTS)
    bare = pickle.dumps(FRESH)  # the format-1 entry: a bare pickle, even of the right answer
    forged = encode("solution", key, FRESH, b"\x00" * 32)  # well formed, another user's key
    for blob in (bare, forged):
        assert decode(blob, "solution", key, _secret())[0] is not None
        store.write_bytes(blob)
        _assert_recomputed_and_repaired(store)


class _Payload:
    """Unpickling this writes ``marker``: the proof that a pickle ran code."""

    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (Path.write_text, (self.marker, "code ran"))


def test_crafted_pickle_never_runs(store, tmp_path):
    marker = tmp_path / "marker"
    evil = pickle.dumps(_Payload(marker))
    key = cache_mod._key("solution", PARTS)
    genuine = store.read_bytes()
    start = len(cache_mod._MAGIC) + cache_mod._TAG_SIZE
    (header_size,) = cache_mod._LENGTH.unpack_from(genuine, start)
    cut = start + cache_mod._LENGTH.size + header_size  # where the genuine payload begins
    attempts = [
        evil,  # bare
        encode("solution", key, _Payload(marker), b"\x01" * 32),  # signed with a guessed key
        genuine[:cut] + evil,  # the genuine signature and header over a swapped payload
        cache_mod._MAGIC + genuine[len(cache_mod._MAGIC) : cut] + evil,
    ]
    assert not marker.exists()  # building the attempts ran nothing
    for blob in attempts:
        store.write_bytes(blob)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", CacheWarning)
            assert METHOD.solve(SYSTEM) == FRESH
        _assert_repaired()
        assert not marker.exists()
    # the same bytes would have run code in a plain pickle reader: the marker test is live
    pickle.loads(evil)
    assert marker.exists()


def test_symlinked_entry_is_not_followed(store, tmp_path):
    target = tmp_path / "elsewhere"
    target.write_bytes(store.read_bytes())
    store.unlink()
    store.symlink_to(target)
    _assert_recomputed_and_repaired(store)
    assert not store.is_symlink()


# ---------------------------------------------------------------------------------- folders and key


def _solve_warning(match: str) -> None:
    """Solve once: the answer is right and exactly one :class:`CacheWarning` matches ``match``."""
    with pytest.warns(CacheWarning, match=match) as record:
        assert METHOD.solve(SYSTEM) == FRESH
    assert len([w for w in record if w.category is CacheWarning]) == 1


@pytest.fixture
def bare(tmp_path, monkeypatch):
    """Key file set, warnings reset; the caller chooses the folder."""
    monkeypatch.setenv("PERTURB_CACHE_KEY_FILE", str(tmp_path / "config" / "cache.key"))
    monkeypatch.setattr(cache_mod, "_WARNED", set())
    return tmp_path


def test_folder_writable_by_others_is_refused(bare, monkeypatch):
    folder = bare / "shared"
    folder.mkdir()
    folder.chmod(0o777)
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    _solve_warning("can be written by other users.*chmod go-w")
    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)  # once per process
        assert METHOD.solve(SYSTEM) == FRESH
    assert not list(folder.iterdir())  # nothing read, nothing written
    folder.chmod(0o775)  # group write alone is refused too
    monkeypatch.setattr(cache_mod, "_WARNED", set())
    _solve_warning("can be written by other users")
    folder.chmod(0o1777)  # sticky (as /tmp): others cannot replace our files
    assert METHOD.solve(SYSTEM) == FRESH
    assert len(list(folder.glob("solution-*.pkl"))) == 1


def test_folder_of_another_user_is_refused(bare, monkeypatch):
    folder = bare / "theirs"
    folder.mkdir(mode=0o700)
    if os.geteuid() == 0:
        os.chown(folder, 12345, 12345)
    else:  # cannot give a folder away: pretend to be someone else
        monkeypatch.setattr(cache_mod, "_uid", lambda: os.geteuid() + 1)
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    _solve_warning("belongs to user id")
    assert not list(folder.iterdir())


def test_uncreatable_folder_runs_without_cache(bare, monkeypatch):
    blocker = bare / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(blocker / "cache"))
    _solve_warning("cannot create the folder")
    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)  # once per process
        assert METHOD.solve(SYSTEM) == FRESH


def test_unwritable_folder_runs_without_cache(bare, monkeypatch):
    folder = bare / "cache"
    folder.mkdir(mode=0o700)
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    cache_mod._secret(folder)  # the key exists; only the folder refuses writes

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    # root ignores permission bits, so the refusal is simulated where files are created
    monkeypatch.setattr(cache_mod.tempfile, "mkstemp", refuse)
    _solve_warning("cannot write")
    assert METHOD.solve(SYSTEM) == FRESH
    assert not list(folder.iterdir())


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root ignores permission bits")
def test_read_only_folder_runs_without_cache(bare, monkeypatch):
    folder = bare / "cache"
    folder.mkdir(mode=0o500)
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    try:
        _solve_warning("cannot write")
        assert METHOD.solve(SYSTEM) == FRESH
    finally:
        folder.chmod(0o700)


@pytest.mark.parametrize(
    ("damage", "match"),
    [
        (lambda key: key.chmod(0o644), "open to other users.*chmod 600"),
        (lambda key: key.write_bytes(b"short"), "damaged"),
    ],
    ids=["readable-by-others", "wrong-length"],
)
def test_untrusted_key_disables_the_cache(store, damage, match):
    key = Path(os.environ["PERTURB_CACHE_KEY_FILE"])
    damage(key)
    for entry in store.parent.iterdir():
        entry.unlink()
    _solve_warning(match)
    assert not list(store.parent.iterdir())


def test_key_inside_the_cache_folder_is_refused(bare, monkeypatch):
    folder = bare / "cache"
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    monkeypatch.setenv("PERTURB_CACHE_KEY_FILE", str(folder / "cache.key"))
    _solve_warning("inside the cache folder")
    assert not (folder / "cache.key").exists()


# ---------------------------------------------------------------------------------- concurrency

_WORKER = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path
    import sympy as sp
    from perturb import EPS, PoincareMethod, QuasilinearSystem
    from perturb.cache import cached

    x, xd, A = sp.symbols("x xdot A")
    system = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A])
    ready, other = Path(sys.argv[1]), Path(sys.argv[2])
    computed = []

    def compute():
        computed.append(1)
        # both runs are inside compute at once, however the machine schedules them: neither has
        # written the entry, so both missed it and both will write it
        ready.with_suffix(".computing").touch()
        partner = other.with_suffix(".computing")
        deadline = time.monotonic() + 300  # a hang guard only
        while not partner.exists() and time.monotonic() < deadline:
            time.sleep(0.01)
        return PoincareMethod(order=2, amplitudes={"x": A}, cache=False).solve(system)

    sol = cached("concurrent", ("duffing", 2), compute)
    print(len(computed), sp.srepr(sol.frequency), sp.srepr(sol.coordinate("x")), sep="|")
    """
)


def test_two_concurrent_cold_runs(bare, monkeypatch):
    folder = bare / "cache"
    env = {
        **os.environ,
        "PERTURB_CACHE_DIR": str(folder),
        "PERTURB_CACHE_KEY_FILE": os.environ["PERTURB_CACHE_KEY_FILE"],
        "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
    }
    flags = [bare / "ready-0", bare / "ready-1"]
    runs = [
        subprocess.Popen(
            [sys.executable, "-c", _WORKER, str(flags[i]), str(flags[1 - i])],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for i in range(2)
    ]
    outputs = [run.communicate(timeout=300) for run in runs]
    assert all(run.returncode == 0 for run in runs), [err for _, err in outputs]
    fresh = PoincareMethod(order=2, amplitudes={"x": A}, cache=False).solve(SYSTEM)
    expected = f"{sp.srepr(fresh.frequency)}|{sp.srepr(fresh.coordinate('x'))}"
    for out, _ in outputs:
        computed, answer = out.strip().split("|", 1)
        assert computed == "1" and answer == expected  # both cold, both right
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(folder))
    (entry,) = folder.glob("concurrent-*.pkl")
    assert not list(folder.glob("*.tmp"))  # no temporary file left behind
    reread = cached("concurrent", ("duffing", 2), Compute())  # the entry ends valid: a hit
    assert reread is not FRESH and reread == fresh
