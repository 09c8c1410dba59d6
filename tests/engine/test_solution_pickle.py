"""A solution read back from a pickle (the disk cache, a Dask worker) is the same solution, its
construction steps read only when first used; the disk's reduced system read back from the
cache is the system built from the ring series."""

from __future__ import annotations

import pickle

import attrs
import sympy as sp

from perturb import EPS, PoincareMethod, QuasilinearSystem


def _van_der_pol():
    x, xdot = sp.symbols("x xdot")
    system = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    return PoincareMethod(order=3, cache=False).solve(system)


def test_a_pickled_solution_is_the_same_with_its_steps_read_on_first_use():
    solution = _van_der_pol()
    back = pickle.loads(pickle.dumps(solution))
    assert back == solution and back.frequency == solution.frequency
    assert back.terms == solution.terms
    assert back.steps._steps is None  # not read yet: evaluating does not need them
    assert back.evaluate([0.0, 1.0], 0.1).tolist() == solution.evaluate([0.0, 1.0], 0.1).tolist()
    assert back.steps._steps is None
    assert [str(s) for s in back.steps] == [str(s) for s in solution.steps]  # read now
    assert len(back.steps) == len(solution.steps) > 0


def test_a_solution_read_back_pickles_again_and_evolves():
    back = pickle.loads(pickle.dumps(_van_der_pol()))
    again = pickle.loads(pickle.dumps(back))  # its steps' bytes carried as they are
    assert [str(s) for s in again.steps] == [str(s) for s in _van_der_pol().steps]
    failed = attrs.evolve(again, message="changed")
    assert failed.message == "changed" and len(failed.steps) == len(back.steps) > 0


def test_the_disk_reduced_system_from_the_cache_is_the_built_one(cache_folder, monkeypatch):
    from problems import get_problem

    reduction = get_problem("disk").reduction()
    built = reduction._built_system()
    assert not any(cache_folder.glob("reduced-system-*.pkl"))
    first = attrs.evolve(reduction).system  # a fresh copy: computed, and kept
    assert any(cache_folder.glob("reduced-system-*.pkl"))

    def not_again(self):
        raise AssertionError("built again: the cache was not read")

    monkeypatch.setattr(type(reduction), "_built_system", not_again)
    second = attrs.evolve(reduction).system  # another: read back
    assert first == built and second == built
    assert second.rhs == built.rhs and second.first_integrals == built.first_integrals
