"""The time-budgeted solve of the amplitude equations (``solve_bounded``), also where it may not
start a child process: a daemonic process such as a Dask worker (the 100 x 100 disk map's points
derived on the workers failed with "daemonic processes are not allowed to have children")."""

from __future__ import annotations

import multiprocessing

import pytest
import sympy as sp

from perturb.algebra.budget import solve_bounded
from perturb.method.conditions import groebner_real_roots

X, Y = sp.symbols("x y")
#: A circle cut by a line: two real roots, irrational, found by the Groebner route.
EQUATIONS = [X**2 + Y**2 - 3, X - 2 * Y]


def _in_a_daemon(queue):
    try:
        roots = solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots)
        queue.put(("ok", sorted(str(sorted(r.items(), key=str)) for r in roots)))
    except BaseException as exc:  # noqa: BLE001 - reported to the parent
        queue.put(("error", f"{type(exc).__name__}: {exc}"))


def test_the_budgeted_solve_gives_its_roots():
    roots = solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots)
    assert len(roots) == 2
    for root in roots:
        assert abs(float(root[X] ** 2 + root[Y] ** 2) - 3) < 1e-12
        assert abs(float(root[X] - 2 * root[Y])) < 1e-12


@pytest.mark.skipif(
    "fork" not in multiprocessing.get_all_start_methods(), reason="needs fork to start a daemon"
)
def test_a_daemonic_process_solves_in_process_with_the_same_roots():
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    daemon = context.Process(target=_in_a_daemon, args=(queue,), daemon=True)
    daemon.start()
    kind, value = queue.get(timeout=120)
    daemon.join(timeout=30)
    here = solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots)
    assert kind == "ok", value
    assert value == sorted(str(sorted(r.items(), key=str)) for r in here)


def test_a_thread_other_than_the_main_one_solves_in_process():
    """A fork from a worker thread copies locks other threads hold (a Dask worker thread hung a
    Sphinx build): off the main thread the solve runs in this process, with the same roots."""
    import os
    import threading

    pids, results = [], []

    def solver(eqs, unknowns):
        pids.append(os.getpid())
        return groebner_real_roots(eqs, unknowns)

    thread = threading.Thread(
        target=lambda: results.append(solve_bounded(EQUATIONS, [X, Y], 30.0, solver))
    )
    thread.start()
    thread.join(120)
    assert not thread.is_alive() and pids == [os.getpid()]
    here = solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots)
    assert sorted(map(str, results[0])) == sorted(map(str, here))


#: A system sympy's solve does not finish in seconds: three dense cubics in three unknowns (27
#: complex roots without a closed form). Its budget, 1 s, is spent on any machine.
U, V, W = sp.symbols("u v w")
SLOW = [
    U**3 + 2 * V**2 * W - 3 * U * V + 5 * W - 7,
    V**3 - U * W**2 + 4 * U * V * W - 2 * V + 1,
    W**3 + 3 * U**2 * V - V * W + U - 11,
]
SLOW_BUDGET = 1.0


def _slow_in_a_daemon(queue):
    try:
        solve_bounded(SLOW, [U, V, W], SLOW_BUDGET)
        queue.put("finished")
    except TimeoutError:
        queue.put("timeout")
    except BaseException as exc:  # noqa: BLE001 - reported to the parent
        queue.put(f"{type(exc).__name__}: {exc}")


@pytest.mark.skipif(
    "fork" not in multiprocessing.get_all_start_methods(), reason="needs fork to start a daemon"
)
def test_a_daemonic_process_keeps_the_budget():
    """A Dask worker is daemonic: its solve runs in a fresh interpreter, killed when the budget
    is spent (it ran unbounded there, and a README phase diagram did not end in 40 minutes)."""
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    daemon = context.Process(target=_slow_in_a_daemon, args=(queue,), daemon=True)
    daemon.start()
    outcome = queue.get(timeout=300)
    daemon.join(timeout=30)
    assert outcome == "timeout"


def test_a_thread_keeps_the_budget_and_the_roots():
    """Off the main thread an importable solver runs in a fresh interpreter: the same roots as
    here, and a slow solve cut by its budget."""
    import threading

    outcomes = []

    def work():
        outcomes.append(solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots))
        try:
            solve_bounded(SLOW, [U, V, W], SLOW_BUDGET)
            outcomes.append("finished")
        except TimeoutError:
            outcomes.append("timeout")
        # the helper killed with the spent budget, the next solve starts another
        outcomes.append(solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots))

    thread = threading.Thread(target=work)
    thread.start()
    thread.join(300)
    here = sorted(map(str, solve_bounded(EQUATIONS, [X, Y], 30.0, groebner_real_roots)))
    assert not thread.is_alive()
    assert sorted(map(str, outcomes[0])) == here and outcomes[1] == "timeout"
    assert sorted(map(str, outcomes[2])) == here
