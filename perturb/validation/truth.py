"""The equations a model is checked against, and the model at another ε: three hooks a model
*may* define, each asked through one function here.

Most models are their quasilinear system and nothing more: the true motion is the system
written first order, and the model at another ε is its case moved there
(:meth:`perturb.case.Case.with_epsilon`). A model with equations of its own (a rigid body's
Euler-Poisson equations) or its own rescaling defines the hook; the functions below read it
when the class defines it and give the generic answer otherwise (no attribute probing: the class
is read, once):

==========================  ===========================================  =========================
the method a model defines  the generic answer                           asked through
==========================  ===========================================  =========================
``original_equations(y0)``  from ``original_rhs()``, else the system     :func:`original_equations`
``original_rhs()``          the system's vector field ``F(t, y)``        :func:`original_rhs`
``with_epsilon(eps)``       the model at its case moved to ``eps``       :func:`with_epsilon`
==========================  ===========================================  =========================
"""

from __future__ import annotations

import inspect
import weakref

from perturb.errors import InvalidSystemError, bad_value, defined_at
from perturb.validation._quasilinear import first_order_form, substitutions
from perturb.validation.capabilities import call_hook
from perturb.validation.model import Equations, parameter_value_of

__all__ = [
    "original_equations",
    "original_rhs",
    "system_equations",
    "with_epsilon",
]


#: Whether each model class defines each hook, by class (held weakly) and name (read once per
#: class, statically: a problem answers a moved member's old name with a warning, no hook).
_DEFINES: weakref.WeakKeyDictionary[type, dict[str, bool]] = weakref.WeakKeyDictionary()


def _defines(model, name: str) -> bool:
    known = _DEFINES.setdefault(type(model), {})
    if name not in known:
        known[name] = inspect.getattr_static(model, name, None) is not None
    return known[name]


def system_equations(model, y0=None) -> Equations:
    """The model's quasilinear system written first order, at its values: the true motion of a
    model with no equations of its own.

    Parameters
    ----------
    model : Model
    y0 : array_like, optional
        The initial state, needed only by systems whose equations contain initial values.

    Returns
    -------
    Equations

    Raises
    ------
    perturb.errors.InvalidParameterError
        The equations contain initial values and ``y0`` is None (one line: give y0).

    Examples
    --------
    >>> from perturb.validation.truth import system_equations
    >>> from problems import get_problem
    >>> duffing = get_problem("duffing").create(eps=0.1)
    >>> system_equations(duffing).rhs([1.0, 0.0])  # x'' = -x - eps x³ at x = 1
    array([ 0. , -1.1])
    """
    system = model.system()
    subs = substitutions(system, model.symbol_values(), parameter_value_of(model), y0)
    if subs is None:
        raise bad_value("y0", y0, "this system's equations contain initial values: give y0")
    return Equations(first_order_form(system, subs), quasilinear=True)


def original_equations(model, y0=None) -> Equations:
    """The equations ``model`` is checked against: its own ``original_equations(y0)``
    (a rigid body's Euler-Poisson equations), else its own ``original_rhs()``, else its
    quasilinear system (:func:`system_equations`).

    Parameters
    ----------
    model : Model
    y0 : array_like, optional
        The initial state, needed only by systems whose equations contain initial values.

    Returns
    -------
    Equations

    Raises
    ------
    perturb.errors.InvalidSystemError
        The model's hook cannot be called so, or returns something else than
        :class:`~perturb.validation.Equations` (one line naming where it is defined and the fix).

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.validation import original_equations
    >>> from problems import get_problem
    >>> disk, duffing = get_problem("disk").create(), get_problem("duffing").create()
    >>> original_equations(disk).quasilinear, original_equations(duffing).quasilinear
    (False, True)
    """
    if _defines(model, "original_equations"):
        hook = model.original_equations
        found = call_hook(model, "original_equations", hook, "(self, y0=None)", y0)
        if not isinstance(found, Equations):
            raise InvalidSystemError(
                f"{defined_at(type(model), 'original_equations')}: `original_equations(y0)` "
                f"returned {type(found).__name__}: return perturb.validation.Equations(rhs) (or "
                "define original_rhs(self) returning F(t, y) instead)"
            )
        return found
    if _defines(model, "original_rhs"):
        return Equations.from_time_rhs(original_rhs(model))
    return system_equations(model, y0)


def original_rhs(model):
    """The true motion of ``model`` as ``F(t, y)`` on the state of its ``state``: its own
    ``original_rhs()``, else its quasilinear system's vector field at
    its values (:meth:`perturb.QuasilinearSystem.vector_field`).

    Parameters
    ----------
    model : Model

    Returns
    -------
    callable
        ``F(t, y)`` returning a numpy array.

    Examples
    --------
    >>> from perturb.validation import original_rhs
    >>> from problems import get_problem
    >>> original_rhs(get_problem("duffing").create(eps=0.1))(0.0, [1.0, 0.0])
    array([ 0. , -1.1])
    """
    if _defines(model, "original_rhs"):
        return call_hook(model, "original_rhs", model.original_rhs, "(self)")
    return model.system().vector_field(parameter_value_of(model), model.symbol_values())


def with_epsilon(model, eps: float):
    """``model`` at the expansion parameter ``eps`` with every system symbol kept (what
    validation's order check scans): its own ``with_epsilon(eps)`` (a bare system's), else
    its case moved to ``eps`` (:meth:`perturb.case.Case.with_epsilon`: the disk moves ``r0``, a
    driven problem ``eps`` with ``Omega`` keeping σ), else None: no admissible move.

    Parameters
    ----------
    model : Model
    eps : float

    Returns
    -------
    Model or None

    Examples
    --------
    >>> from perturb.validation import with_epsilon
    >>> from problems import get_problem
    >>> disk = get_problem("disk").create()
    >>> moved = with_epsilon(disk, disk.epsilon() / 2)
    >>> round(moved.epsilon() / disk.epsilon(), 12), moved.values["r0"] > disk.values["r0"]
    (0.5, True)
    """
    if _defines(model, "with_epsilon"):
        return call_hook(model, "with_epsilon", model.with_epsilon, "(self, eps)", eps)
    try:
        moved = model.case().with_epsilon(eps)
    except InvalidSystemError:
        return None
    return None if moved is None else moved.model
