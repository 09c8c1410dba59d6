"""Running a solver under a time budget: a forked child process, killed when the budget is spent."""

from __future__ import annotations

import multiprocessing
import pickle
import threading

__all__ = ["solve_bounded", "sympy_roots"]


def sympy_roots(eqs, unknowns) -> list[dict]:
    """``sympy.solve(eqs, unknowns, dict=True)`` without simplification (the default solver)."""
    import sympy as sp

    return sp.solve(eqs, unknowns, dict=True, simplify=False)


def _solve_worker(solver, eqs, unknowns, connection) -> None:
    try:
        connection.send(("ok", solver(eqs, unknowns)))
    except Exception as exc:  # noqa: BLE001 - the parent re-raises it as a failed status
        connection.send(("error", exc))
    finally:
        connection.close()


def solve_bounded(eqs, unknowns, seconds: float, solver=sympy_roots):
    """``solver(eqs, unknowns)`` (default :func:`sympy_roots`) with a time budget.

    The solve runs in a forked child process, which is killed when the budget is spent.
    Where a fork is not safe or not allowed — in a daemonic process (which may not have
    ``multiprocessing`` children: a Dask worker, a pool's worker), in a thread other than the
    main one (a fork copies the locks other threads hold, and the child can wait on them for
    ever: a Dask worker thread hung a Sphinx build so), or where the platform cannot fork — it
    runs in a helper interpreter (a subprocess, which copies no lock; one per process, kept warm
    between solves: :mod:`perturb.algebra.solver_process`), killed the same way; only a solver
    that cannot be pickled by reference (a local function) runs in-process, without a budget. Without this a phase diagram's points, derived on the workers, ran an exact solve
    that a budget would have cut after seconds for over 40 minutes.

    Parameters
    ----------
    eqs : list of sympy expressions
        The equations ``eqs = 0``.
    unknowns : sequence of sympy.Symbol
        What to solve for.
    seconds : float
        The time budget.
    solver : callable, optional
        ``solver(eqs, unknowns)``; must be picklable or a module-level function.

    Returns
    -------
    object
        What ``solver`` returns.

    Raises
    ------
    TimeoutError
        When the budget is spent (the child process is killed).
    NotImplementedError, ValueError
        Re-raised from the solver (any other exception of the solver becomes
        ``NotImplementedError`` with its text; a child that dies too).

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> solve_bounded([x**2 - 4], [x], 10.0)
    [{x: -2}, {x: 2}]
    """
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:  # pragma: no cover - platforms without fork
        context = None
    if context is None or multiprocessing.current_process().daemon or not _main_thread():
        # a daemonic process may not start multiprocessing children, and a fork from a thread
        # may deadlock: the helper interpreter, or (a local solver) here without a budget
        try:
            payload = pickle.dumps((solver, eqs, unknowns))
        except (pickle.PicklingError, AttributeError, TypeError):
            return solver(eqs, unknowns)
        from perturb.algebra.solver_process import solve_in_helper

        return _returned(*solve_in_helper(payload, seconds))
    receiver, sender = context.Pipe(duplex=False)
    child = context.Process(target=_solve_worker, args=(solver, eqs, unknowns, sender), daemon=True)
    child.start()
    sender.close()
    try:
        if not receiver.poll(seconds):
            raise TimeoutError
        kind, value = receiver.recv()
    except EOFError:
        raise NotImplementedError("the solver process died") from None
    finally:
        if child.is_alive():
            child.kill()
        child.join()
        receiver.close()
    return _returned(kind, value)


def _returned(kind: str, value):
    """The solver's value, or its exception re-raised (as ``NotImplementedError`` unless it is
    one or a ``ValueError``)."""
    if kind == "error":
        raise (
            value
            if isinstance(value, (NotImplementedError, ValueError))
            else NotImplementedError(str(value))
        )
    return value


def _main_thread() -> bool:
    """Whether this is the main thread (where a fork copies no lock another thread holds)."""
    return threading.current_thread() is threading.main_thread()
