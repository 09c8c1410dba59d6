"""Shared test configuration: hypothesis profiles (scipy's approach), the test noise
(PERTURB_TEST_NOISE) seeded per test, and small helpers."""

import os
import tempfile

# sympy picks its integer ground types at import: python-flint, when installed, switches them
# silently (and gmpy2 too). Pin pure-Python ground types so the suite tests one behaviour everywhere
# (tests/engine/test_native.py checks the pin took effect).
os.environ["SYMPY_GROUND_TYPES"] = "python"

import pytest
from hypothesis import HealthCheck, settings

# "ci": derandomized and without a database so every CI run draws the same examples;
# "dev": random, more examples, for local exploration (HYPOTHESIS_PROFILE=dev).
settings.register_profile(
    "ci",
    derandomize=True,
    database=None,
    deadline=None,
    max_examples=15,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("dev", deadline=None, max_examples=60)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

# Tests never read a user's cache: each session derives everything afresh into its own folder.
os.environ["PERTURB_CACHE_DIR"] = tempfile.mkdtemp(prefix="perturb-test-cache-")
# ... signed with a key of its own, outside that folder: tests never create or read the user's key.
os.environ["PERTURB_CACHE_KEY_FILE"] = os.path.join(
    tempfile.mkdtemp(prefix="perturb-test-key-"), "cache.key"
)


@pytest.fixture
def cache_folder(tmp_path, monkeypatch):
    """A fresh, empty disk-cache folder for one test, and cache warnings that fire again."""
    import perturb.cache

    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(perturb.cache, "_WARNED", set())
    return tmp_path


# PERTURB_TEST_NOISE=K (perturb/oracle/_noise.py): every integration and every shooting step moved
# by up to K ulps, as another machine would. The noise is seeded per test from its node id, and
# per fixture from its scope's node id and name (so a module fixture gets the same bits however
# the tests are selected). One test is one machine: the processes it starts inherit its seed, and
# the workers of a Dask cluster a fixture started (and their nannies, which restart them) take it.
def _seed_noise(key: str, clients=()) -> None:
    from perturb.oracle import _noise

    if not _noise.ULPS:
        return
    _noise.seed(key)
    for client in clients:
        client.run(_noise.seed, key)
        client.run(_noise.seed, key, nanny=True)


@pytest.hookimpl(tryfirst=True)
def pytest_fixture_setup(fixturedef, request):
    _seed_noise(f"{request.node.nodeid}::{fixturedef.argname}")


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_call(item):
    funcargs = getattr(item, "funcargs", {}).values()
    clients = [v for v in funcargs if type(v).__module__.startswith("distributed.client")]
    _seed_noise(item.nodeid, clients)


#: The clone's top level when the session began: a test that writes a file there (an ``--output``
#: taken relative to the working folder) would leave it in a user's clone.
_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_ROOT_ENTRIES = set(os.listdir(_ROOT))


def pytest_sessionfinish(session, exitstatus):
    """Fail the session when a test left a new entry at the clone's top level."""
    left = sorted(
        name
        for name in set(os.listdir(_ROOT)) - _ROOT_ENTRIES
        if not name.startswith(".") and not name.endswith(".egg-info") and name != "__pycache__"
    )
    if left:
        session.config.get_terminal_writer().line(
            f"tests wrote into the clone's top level: {left} (write into tmp_path instead)",
            red=True,
        )
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
