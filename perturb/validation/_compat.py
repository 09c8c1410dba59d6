"""``original_system``: the original equations and integrals of a model in one object (the form
earlier versions exposed; :mod:`perturb.workprecision` uses it)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from attrs import frozen

from perturb.validation.model import Model, as_model

__all__ = ["OriginalSystem", "original_system"]


@frozen
class OriginalSystem:
    """The original equations of a model in the form the oracle needs.

    Attributes
    ----------
    names : tuple of str
        State names, in the order of the state vector.
    rhs : callable
        ``rhs(y) -> dy/dt`` (a :class:`perturb.oracle.SymbolicRHS` when symbolic).
    symbolic : bool
    integrals : callable or None
        ``y -> array`` of first-integral values.
    integral_names : tuple of str

    Examples
    --------
    >>> from perturb.validation import original_system
    >>> from problems import get_problem
    >>> original_system(get_problem("van-der-pol").create()).integrals is None
    True
    """

    names: tuple
    rhs: Callable
    symbolic: bool
    integrals: Callable | None
    integral_names: tuple


def original_system(problem: Model, y0: np.ndarray | None = None) -> OriginalSystem:
    """The original equations of ``problem`` (a :class:`Model`) and its named first integrals.

    Parameters
    ----------
    problem : Model
    y0 : ndarray, optional
        Initial state, needed only by systems whose equations depend on the initial values.

    Returns
    -------
    OriginalSystem
        The state names, the right-hand side, whether it is symbolic, and the first integrals.

    Examples
    --------
    >>> from perturb.validation import original_system
    >>> from problems import get_problem
    >>> system = original_system(get_problem("duffing").create(eps=0.1))
    >>> system.names, system.symbolic, system.integral_names
    (('x', 'xdot'), True, ('energy',))
    """
    model = as_model(problem)
    equations = model.original_equations(y0)
    integrals = model.integrals_of_motion(y0)
    return OriginalSystem(
        names=tuple(model.state_names()),
        rhs=equations.rhs,
        symbolic=equations.symbolic,
        integrals=None if integrals is None else integrals.function,
        integral_names=() if integrals is None else integrals.names,
    )
