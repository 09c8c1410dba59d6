"""Running a solver under a time budget: a forked child process, killed when the budget is spent."""

from __future__ import annotations

import multiprocessing
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
    Where the platform cannot fork, in a daemonic process (which may not have children: a
    Dask worker, a ``multiprocessing`` pool's worker), or in a thread other than the main one (a
    fork copies the locks other threads hold, and the child can wait on them for ever: a Dask
    worker thread hung a Sphinx build so), it runs in-process without a budget.

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
    if multiprocessing.current_process().daemon or not _main_thread():
        # a daemonic process (a Dask worker, a multiprocessing pool's worker) may not start
        # children, and a fork from a thread may deadlock: the solve runs here, without a
        # budget, as where the platform cannot fork
        return solver(eqs, unknowns)
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:  # pragma: no cover - platforms without fork
        return solver(eqs, unknowns)
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
