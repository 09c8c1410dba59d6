"""A compiled heyoka integrator kept on disk is the one compiled afresh, for this processor only."""

import numpy as np
import pytest
import sympy as sp

import perturb.oracle.heyoka as hy_oracle
from perturb.cache import bypassed
from perturb.oracle import SymbolicRHS
from perturb.oracle.heyoka import Heyoka, heyoka_available

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="heyoka is not installed")

x, v = sp.symbols("x v")
DUFFING = SymbolicRHS((x, v), (v, -x - sp.Rational(1, 10) * x**3))
#: A start and a horizon of a few periods: enough steps for any difference in the code to show.
START, HORIZON = (0.7, -0.2), 20.0


def _compiled(rhs=DUFFING, fp_name="double", tol=None):
    """The integrator as the oracle gets it, past the in-memory cache (disk cache only)."""
    return hy_oracle._compiled_taylor.__wrapped__(rhs, fp_name, tol, False)


def _final(integrator) -> np.ndarray:
    ta = integrator.__copy__()
    ta.time = 0.0
    ta.state[:] = START
    ta.propagate_until(HORIZON)
    return np.array(ta.state)


@pytest.fixture
def builds(monkeypatch):
    """The calls of the compiler (each a JIT compilation), by rhs and options."""
    calls = []
    original = hy_oracle._build_taylor

    def counting(*args):
        calls.append(args)
        return original(*args)

    monkeypatch.setattr(hy_oracle, "_build_taylor", counting)
    return calls


def test_a_kept_integrator_is_read_back_and_integrates_bit_for_bit(cache_folder, builds):
    first = _compiled()
    assert len(builds) == 1 and len(list(cache_folder.glob("taylor-*.pkl"))) == 1
    second = _compiled()
    assert len(builds) == 1  # read back, not compiled
    with bypassed():
        fresh = _compiled()  # compiled afresh, the disk left alone
    assert len(builds) == 2
    assert np.array_equal(_final(second), _final(fresh))
    assert np.array_equal(_final(first), _final(fresh))


def test_another_field_precision_or_tolerance_is_compiled_not_read(cache_folder, builds):
    _compiled()
    other = SymbolicRHS((x, v), (v, -x - sp.Rational(1, 9) * x**3))
    _compiled(other)
    _compiled(tol=1e-10)
    extended = "long double" if "long double" in hy_oracle._fp_types() else "real128"
    _compiled(fp_name=extended)
    assert len(builds) == 4
    assert len(list(cache_folder.glob("taylor-*.pkl"))) == 4
    assert not np.array_equal(_final(_compiled(other)), _final(_compiled()))
    assert len(builds) == 4  # each read back now


def test_another_processor_does_not_read_this_ones_code(cache_folder, builds, monkeypatch):
    _compiled()
    monkeypatch.setattr(hy_oracle, "_host_cpu", lambda: "another processor")
    _compiled()
    assert len(builds) == 2
    assert len(list(cache_folder.glob("taylor-*.pkl"))) == 2


def test_an_unknown_processor_keeps_nothing(cache_folder, builds, monkeypatch):
    monkeypatch.setattr(hy_oracle, "_host_cpu", lambda: None)
    _compiled()
    _compiled()
    assert len(builds) == 2
    assert not list(cache_folder.glob("taylor-*.pkl"))


def test_the_processor_is_identified_here():
    """On Linux (where heyoka's wheels are) the processor is read from /proc/cpuinfo."""
    host = hy_oracle._host_cpu()
    assert host is None or len(host) == 64
    try:
        with open("/proc/cpuinfo") as fh:
            readable = any(line.startswith(("flags", "Features")) for line in fh)
    except OSError:
        readable = False
    assert (host is not None) == readable


def test_the_oracle_gives_the_same_trajectory_warm_and_cold(cache_folder):
    t = np.linspace(0.0, HORIZON, 41)
    runs = []
    for _ in range(2):  # the second reads the kept integrator (in a new process it would too)
        hy_oracle._compiled_taylor.cache_clear()
        hy_oracle._THREAD_STATE.__dict__.clear()
        runs.append(Heyoka().integrate(DUFFING, (0.0, HORIZON), START, t_eval=t))
    with bypassed():
        hy_oracle._compiled_taylor.cache_clear()
        hy_oracle._THREAD_STATE.__dict__.clear()
        runs.append(Heyoka().integrate(DUFFING, (0.0, HORIZON), START, t_eval=t))
    hy_oracle._compiled_taylor.cache_clear()
    hy_oracle._THREAD_STATE.__dict__.clear()
    assert len(list(cache_folder.glob("taylor-*.pkl"))) == 1
    for run in runs[1:]:
        assert run.success
        assert np.array_equal(run.y, runs[0].y)


def test_the_kept_integrators_are_bounded(cache_folder, builds, monkeypatch):
    """A sweep integrates a new field at every point: only the most recently written are kept."""
    monkeypatch.setattr(hy_oracle, "TAYLOR_CACHE_ENTRIES", 2)
    fields = [SymbolicRHS((x, v), (v, -x - sp.Rational(1, n) * x**3)) for n in (7, 8, 9)]
    for rhs in fields:
        _compiled(rhs)
    assert len(list(cache_folder.glob("taylor-*.pkl"))) == 2
    _compiled(fields[-1])
    assert len(builds) == 3  # the newest is read back


def test_the_variational_field_read_back_carries_its_own_key(cache_folder, builds):
    """The variational field comes from the cache with the key of its expressions, so its
    integrator is found again without printing them (and is the one compiled for them)."""
    derived = SymbolicRHS(DUFFING.state, DUFFING.expressions).variational  # derived, kept
    read = SymbolicRHS(DUFFING.state, DUFFING.expressions).variational  # read back
    assert read == derived
    printed = (tuple(map(sp.srepr, read.state)), tuple(map(sp.srepr, read.expressions)))
    assert read.cache_parts() == derived.cache_parts() == printed
    _compiled(derived)
    _compiled(read)
    assert len(builds) == 1
