"""The integrators by name, and the one rule for "which integrator": :func:`choose`.

:data:`INTEGRATORS` is the only registry: adding an integrator is one new module (a subclass of
:class:`~perturb.oracle.base.IntegratorBase`) and one line here.  Every part of perturb that runs an integrator on behalf of a user (validation, work-precision
diagrams, the command line) resolves the user's ``integrator`` argument here, so that a name, an
object or ``None`` means the same thing everywhere.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

from perturb._defaults import DEFAULT_RTOL, STIFF_RTOL
from perturb.errors import UnknownNameError, bad_value
from perturb.oracle.base import RHS, Integrator
from perturb.oracle.heyoka import Heyoka, heyoka_available
from perturb.oracle.rk4 import RK4
from perturb.oracle.scipy import Scipy
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["INTEGRATORS", "choose", "default_integrator", "get_integrator"]

#: Integrator factories by name (lower case); ``get_integrator(name, **opts)`` calls them.
INTEGRATORS: dict[str, Callable[..., Integrator]] = {
    "rk4": RK4,
    "dop853": functools.partial(Scipy, "DOP853"),
    "rk45": functools.partial(Scipy, "RK45"),
    "radau": functools.partial(Scipy, "Radau"),
    "lsoda": functools.partial(Scipy, "LSODA"),
    "heyoka": Heyoka,
}


def get_integrator(name: str, **options: Any) -> Integrator:
    """Build an integrator from its registry name.

    Parameters
    ----------
    name : str
        One of ``INTEGRATORS`` (case-insensitive): 'rk4', 'dop853', 'rk45', 'radau', 'lsoda', 'heyoka'.
    **options
        Passed to the factory, e.g. ``rtol=1e-10`` or ``steps_per_unit=100``.

    Raises
    ------
    perturb.errors.UnknownNameError
        If ``name`` is not registered; the message lists the known names.

    Examples
    --------
    >>> get_integrator("dop853", rtol=1e-10).name
    'scipy DOP853 (rtol=1e-10)'

    Returns
    -------
    Integrator
        A frozen value object; its ``name`` states the settings.
    """
    key = str(name).lower()
    if key not in INTEGRATORS:
        raise UnknownNameError(
            f"`name` = {name!r} is not a known integrator: use one of {sorted(INTEGRATORS)}"
        )
    return INTEGRATORS[key](**options)


def default_integrator(rhs: RHS | None = None) -> Integrator:
    """The integrator used when none is given: heyoka if importable, else scipy DOP853.

    Parameters
    ----------
    rhs : callable, optional
        The rhs to be integrated; if given and not a
        :class:`~perturb.oracle.symbolic.SymbolicRHS`, DOP853 is chosen since heyoka cannot
        integrate a plain numeric callable.

    Returns
    -------
    Integrator
        ``Heyoka()`` or ``Scipy('DOP853')``; the :class:`Trajectory` it returns names it.  This
        is :func:`choose` for a non-stiff system at the default tolerance.

    Examples
    --------
    A plain numeric callable cannot go to heyoka:

    >>> from perturb.oracle import default_integrator
    >>> default_integrator(lambda y: -y).name
    'scipy DOP853 (rtol=1e-12)'
    """
    return choose(None, symbolic=rhs is None or isinstance(rhs, SymbolicRHS))


#: Registry names of the adaptive scipy methods, which take ``rtol`` and ``max_steps``.
_SCIPY_NAMES = ("dop853", "rk45", "radau", "lsoda")


def choose(
    integrator: Integrator | str | None = None,
    *,
    rtol: float = DEFAULT_RTOL,
    stiff: bool = False,
    symbolic: bool = True,
    max_steps: int | None = None,
) -> Integrator:
    """The integrator to run: the user's (a name or an object) or the default for the problem.

    Parameters
    ----------
    integrator : Integrator, str or None
        ``None`` picks the default (see Notes); a registry name (``INTEGRATORS``, case-insensitive)
        builds that integrator with ``rtol`` and ``max_steps`` where it takes them; an
        :class:`Integrator` object is returned unchanged.
    rtol : float
        Relative tolerance of the scipy methods (heyoka and RK4 have their own accuracy settings).
    stiff : bool
        Whether the system is stiff (e.g. from Jacobian eigenvalues along the orbit).
    symbolic : bool
        Whether the rhs is available as a :class:`~perturb.oracle.SymbolicRHS` (heyoka needs it).
    max_steps : int, optional
        A step budget.  It switches the stiff default to the cheapest explicit method: a budgeted run
        only has to show how the motion departs, and heyoka's steps cost microseconds where Radau's
        cost a millisecond.

    Returns
    -------
    Integrator

    Raises
    ------
    perturb.errors.UnknownNameError
        If ``integrator`` is a name that is not registered; the message lists the known names.
    perturb.errors.InvalidParameterError
        If ``integrator`` is ``'heyoka'`` but the rhs is not symbolic, or is of another type.

    Notes
    -----
    The default (``integrator=None``), in order:

    1. stiff and no step budget: Radau at ``rtol = max(rtol, STIFF_RTOL)``;
    2. symbolic rhs and heyoka installed: heyoka at machine precision;
    3. otherwise DOP853 at ``rtol``.

    Examples
    --------
    >>> choose("dop853", rtol=1e-10).name
    'scipy DOP853 (rtol=1e-10)'
    >>> choose(stiff=True).name
    'scipy Radau (rtol=1e-10)'
    """
    budget: dict[str, Any] = {} if max_steps is None else {"max_steps": max_steps}
    if integrator is None:
        if stiff and max_steps is None:
            return Scipy("Radau", rtol=max(rtol, STIFF_RTOL))
        if symbolic and heyoka_available():
            return Heyoka(**budget)
        return Scipy("DOP853", rtol=rtol, **budget)
    if isinstance(integrator, str):
        key = integrator.lower()
        if key not in INTEGRATORS:
            raise UnknownNameError(
                f"`integrator` = {integrator!r} is not a known integrator: use one of "
                f"{sorted(INTEGRATORS)}"
            )
        if key in _SCIPY_NAMES:
            return get_integrator(key, rtol=rtol, **budget)
        if key == "heyoka":
            if not symbolic:
                raise bad_value(
                    "integrator",
                    integrator,
                    "this problem gives no symbolic equations (original_symbolic), which heyoka "
                    "needs; use 'dop853'",
                )
            return get_integrator(key, **budget)
        return get_integrator(key)
    if not isinstance(integrator, Integrator):
        raise bad_value(
            "integrator",
            integrator,
            f"pass None, a name in {sorted(INTEGRATORS)} or an integrator object",
        )
    return integrator
