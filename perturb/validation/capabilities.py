"""Optional physics a model may declare: small protocols, each one capability.

Most problems are an oscillator and nothing more; a few bring physics of their own (a rigid body
has Euler angles, the disk its own extended-precision orbit finder, the fast-spin bodies their
estimates of where the series holds). Such a hook is not a member of every model with an empty
default: a model *has* the capability when it defines the method, and validation, the CLI and
scenes ask through the functions below (typed protocols, no attribute probing):

==========================  =====================================  ==========================
capability                  the method a model defines             asked through
==========================  =====================================  ==========================
:class:`EulerAngles`        ``euler_angles(solution, t)``          :func:`has_euler_angles`
:class:`OwnTrueOrbit`       ``true_orbit(solution)``               :func:`own_true_orbit`
:class:`OwnShootingSetup`   ``shooting_setup()``                   :func:`own_shooting_setup`
:class:`ValidityEstimates`  ``validity_estimates()``               :func:`validity_estimates`
:class:`ReportExtras`       ``report_extras()``                    :func:`report_extras`
:class:`OwnIntegrals`       ``integrals_of_motion(y0)``            :func:`integrals_of_motion`
:class:`OwnLabel`           ``label()`` (else a ``name``)          :func:`label_of`
==========================  =====================================  ==========================

The last two have a generic answer a model without the method gets: the system's own first
integrals (or its energy), and the model's ``name`` or its class's.
"""

from __future__ import annotations

import inspect
import weakref
from typing import Protocol, runtime_checkable

from perturb.errors import InvalidSystemError, defined_at
from perturb.validation.model import Integrals, system_integrals

__all__ = [
    "EulerAngles",
    "Named",
    "OwnIntegrals",
    "OwnLabel",
    "OwnShootingSetup",
    "OwnTrueOrbit",
    "ReportExtras",
    "ValidityEstimates",
    "call_hook",
    "integrals_of_motion",
    "label_of",
    "own_shooting_setup",
    "own_true_orbit",
    "report_extras",
    "validity_estimates",
]


@runtime_checkable
class EulerAngles(Protocol):
    """A rigid body: its Euler angles (z-x-z: ``theta``, ``psi``, ``phi``) along a solution at
    physical times ``t``, by name.

    Examples
    --------
    >>> from perturb.validation.capabilities import EulerAngles
    >>> from problems import get_problem
    >>> isinstance(get_problem("disk").create(), EulerAngles)
    True
    """

    def euler_angles(self, solution, t) -> dict: ...


@runtime_checkable
class OwnTrueOrbit(Protocol):
    """A model-specific true periodic orbit (a :class:`~perturb.oracle.PeriodicOrbit`, which
    :class:`~perturb.validation.OrbitEstimate` builds from what a finder knows), asked for only
    when generic shooting cannot resolve the orbit (it is dearer).

    Examples
    --------
    >>> from perturb.validation.capabilities import OwnTrueOrbit
    >>> from problems import get_problem
    >>> [isinstance(get_problem(n).create(), OwnTrueOrbit) for n in ("disk", "duffing")]
    [True, False]
    """

    def true_orbit(self, solution): ...


@runtime_checkable
class OwnShootingSetup(Protocol):
    """The model's own shooting set-up (a :class:`~perturb.validation.ShootingSetup`, its dict
    form, or None: derived).

    Examples
    --------
    >>> from perturb.validation.capabilities import OwnShootingSetup
    >>> from perturb.validation import ShootingSetup
    >>> class Pinned:
    ...     def shooting_setup(self):
    ...         return ShootingSetup(section_index=1)
    >>> isinstance(Pinned(), OwnShootingSetup)
    True
    """

    def shooting_setup(self): ...


@runtime_checkable
class ValidityEstimates(Protocol):
    """The model's own estimates of where its expansion holds
    (:class:`~perturb.validation.Condition` objects: they warn, the verdict is measured).

    Examples
    --------
    >>> from perturb.validation.capabilities import ValidityEstimates
    >>> from problems import get_problem
    >>> isinstance(get_problem("disk").create(), ValidityEstimates)
    True
    """

    def validity_estimates(self) -> tuple: ...


@runtime_checkable
class ReportExtras(Protocol):
    """Numbers and sentences a model adds to a report of its solution (``perturb solve``'s JSON
    and table header: the rigid bodies' ``mu`` and ``regime``).

    Examples
    --------
    >>> from perturb.validation.capabilities import ReportExtras
    >>> from problems import get_problem
    >>> isinstance(get_problem("disk").create(), ReportExtras)
    True
    """

    def report_extras(self) -> dict: ...


@runtime_checkable
class OwnIntegrals(Protocol):
    """The model's own first integrals along its original equations (an
    :class:`~perturb.validation.Integrals`, or None: it has none to check): a model whose
    equations are not the quasilinear system's (a rigid body's Euler-Poisson equations) names
    the integrals of those.

    Examples
    --------
    >>> from perturb.validation.capabilities import OwnIntegrals
    >>> from problems import get_problem
    >>> [isinstance(get_problem(n).create(), OwnIntegrals) for n in ("disk", "duffing")]
    [True, False]
    """

    def integrals_of_motion(self, y0=None): ...


@runtime_checkable
class OwnLabel(Protocol):
    """The name a model is shown by in reports, computed by the model (a bare system's).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from perturb.validation import as_model
    >>> from perturb.validation.capabilities import OwnLabel
    >>> x, xdot = sp.symbols("x xdot")
    >>> system = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot])
    >>> isinstance(as_model(system, values={"epsilon": 0.1}), OwnLabel)
    True
    """

    def label(self) -> str: ...


@runtime_checkable
class Named(Protocol):
    """A model with a ``name`` (a problem's registry key): the name reports show.

    Examples
    --------
    >>> from perturb.validation.capabilities import Named
    >>> from problems import get_problem
    >>> isinstance(get_problem("duffing").create(), Named)
    True
    """

    name: str


def has_euler_angles(model) -> bool:
    """Whether ``model`` gives Euler angles (it declares
    :class:`~perturb.validation.capabilities.EulerAngles`).

    Parameters
    ----------
    model : Model

    Returns
    -------
    bool

    Examples
    --------
    >>> from perturb.validation import has_euler_angles
    >>> from problems import get_problem
    >>> has_euler_angles(get_problem("disk").create()), has_euler_angles(get_problem("duffing").create())
    (True, False)
    """
    return isinstance(model, EulerAngles)


def own_true_orbit(model, solution):
    """The model's own true orbit along ``solution`` (:class:`OwnTrueOrbit`), or None when it
    has no finder of its own.

    Parameters
    ----------
    model : Model
    solution : PeriodicSolution

    Returns
    -------
    OrbitEstimate or None

    Examples
    --------
    >>> from perturb.validation.capabilities import own_true_orbit
    >>> from problems import get_problem
    >>> duffing = get_problem("duffing").create()
    >>> own_true_orbit(duffing, duffing.solve(1)) is None
    True
    """
    return model.true_orbit(solution) if isinstance(model, OwnTrueOrbit) else None


def own_shooting_setup(model):
    """The model's own shooting set-up (:class:`OwnShootingSetup`), or None: derived.

    Parameters
    ----------
    model : Model

    Returns
    -------
    ShootingSetup, mapping or None

    Examples
    --------
    >>> from perturb.validation.capabilities import own_shooting_setup
    >>> from problems import get_problem
    >>> own_shooting_setup(get_problem("duffing").create()) is None
    True
    """
    return model.shooting_setup() if isinstance(model, OwnShootingSetup) else None


def validity_estimates(model) -> tuple:
    """The model's validity estimates (:class:`ValidityEstimates`); none by default.

    Parameters
    ----------
    model : Model

    Returns
    -------
    tuple of Condition

    Examples
    --------
    >>> from perturb.validation.capabilities import validity_estimates
    >>> from problems import get_problem
    >>> validity_estimates(get_problem("duffing").create())
    ()
    >>> validity_estimates(get_problem("disk").create())[0].name
    'ε = c/r0 small'
    """
    return tuple(model.validity_estimates()) if isinstance(model, ValidityEstimates) else ()


def report_extras(model) -> dict:
    """What the model adds to a report (:class:`ReportExtras`); nothing by default.

    Parameters
    ----------
    model : Model

    Returns
    -------
    dict

    Examples
    --------
    >>> from perturb.validation.capabilities import report_extras
    >>> from problems import get_problem
    >>> report_extras(get_problem("duffing").create())
    {}
    >>> sorted(report_extras(get_problem("disk").create()))
    ['mu', 'regime']
    """
    return dict(model.report_extras()) if isinstance(model, ReportExtras) else {}


def integrals_of_motion(model, y0=None) -> Integrals | None:
    """The model's first integrals with their names: its own (:class:`OwnIntegrals`; none where
    its class sets ``integrals_of_motion = None``), else the system's declared first integrals,
    else its energy when the forces derive from a potential, else None.

    Parameters
    ----------
    model : Model
    y0 : array_like, optional
        The initial state, needed only by systems whose equations contain initial values.

    Returns
    -------
    Integrals or None

    Examples
    --------
    >>> from perturb.validation.capabilities import integrals_of_motion
    >>> from problems import get_problem
    >>> integrals_of_motion(get_problem("duffing").create()).names
    ('energy',)
    >>> integrals_of_motion(get_problem("van-der-pol").create()) is None
    True
    """
    if _disabled(model, "integrals_of_motion"):
        return None  # ``integrals_of_motion = None`` on the class: it has none to check
    if not isinstance(model, OwnIntegrals):
        return system_integrals(model, y0)
    found = call_hook(
        model, "integrals_of_motion", model.integrals_of_motion, "(self, y0=None)", y0
    )
    if found is None or isinstance(found, Integrals):
        return found
    raise InvalidSystemError(
        f"{defined_at(type(model), 'integrals_of_motion')}: `integrals_of_motion(y0)` returned "
        f"{_shown(found)} ({type(found).__name__}): return Integrals(function, names) "
        "(perturb.validation.Integrals: the function of the state and one name per integral), "
        "or None when there are none"
    )


#: How :func:`label_of` names a model of each class (:class:`OwnLabel`, :class:`Named` or None:
#: its class's name), by class (held weakly, as every cache by class here): a driven problem's
#: families ask it at each of its points.
_LABEL_ROUTE: weakref.WeakKeyDictionary[type, type | None] = weakref.WeakKeyDictionary()


def label_of(model) -> str:
    """The name ``model`` is shown by in reports: its own ``label()`` (:class:`OwnLabel`), else
    its ``name`` (:class:`Named`: a problem's registry key), else its class's name.

    Parameters
    ----------
    model : Model

    Returns
    -------
    str

    Examples
    --------
    >>> from perturb.validation.capabilities import label_of
    >>> from problems import get_problem
    >>> label_of(get_problem("duffing").create())
    'duffing'
    """
    kind = type(model)
    route = _LABEL_ROUTE.get(kind)
    if route is None:  # asked once per class: a protocol's isinstance costs tens of microseconds
        route = _LABEL_ROUTE[kind] = (
            OwnLabel if isinstance(model, OwnLabel) else Named if isinstance(model, Named) else None
        )
    if route is OwnLabel:
        label = model.label  # a method, or the label itself (a string attribute, a property)
        label = label if isinstance(label, str) else call_hook(model, "label", label, "(self)")
        if not isinstance(label, str):
            raise InvalidSystemError(
                f"{defined_at(kind, 'label')}: `label` of {kind.__qualname__} gives "
                f"{_shown(label)} ({type(label).__name__}), not a str: return the name reports "
                "show as a str (or leave label out: the problem's name is shown)"
            )
        return label
    if route is Named:
        return str(model.name)
    return kind.__name__


def _disabled(model, name: str) -> bool:
    """Whether ``model``'s class sets the hook ``name`` to None (as ``__hash__ = None`` says a
    class has none): the capability is declared absent, not left to the generic answer."""
    for kind in type(model).__mro__:
        if name in vars(kind):
            return vars(kind)[name] is None
    return False


def call_hook(model, name: str, hook, form: str, *args):
    """``hook(*args)``, the method ``name`` of ``model``'s class, after checking that its
    signature takes ``args``.

    Parameters
    ----------
    model : object
        The model (a user's problem) whose class defines the hook.
    name : str
        The hook's name.
    hook : callable
        The bound method.
    form : str
        Its expected parameters, for the message (``"(self, y0=None)"``).
    *args
        What it is given.

    Returns
    -------
    object
        What the hook returns.

    Raises
    ------
    perturb.errors.InvalidSystemError
        Its signature cannot take ``args``: one line naming where the class defines it and the
        form to give it.

    Examples
    --------
    >>> from perturb.validation.capabilities import call_hook
    >>> class Odd:
    ...     def label(self, style):
    ...         return style
    >>> call_hook(Odd(), "label", Odd().label, "(self)")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    perturb.errors.InvalidSystemError: ...: `label(style)` cannot be called so: define it as label(self)
    """
    known = _CALLABLE_SO.setdefault(type(model), set())
    if (name, len(args)) not in known:  # once per class: a signature costs tens of microseconds
        try:
            signature = inspect.signature(hook)
        except (TypeError, ValueError):  # no signature to read (a builtin, a callable object)
            signature = None
        try:
            if signature is not None:
                signature.bind(*args)
        except TypeError:
            raise InvalidSystemError(
                f"{defined_at(type(model), name)}: `{name}{signature}` cannot be called so: "
                f"define it as {name}{form}"
            ) from None
        known.add((name, len(args)))
    return hook(*args)


#: The hooks :func:`call_hook` found callable with so many arguments: ``(name, count)`` by class.
_CALLABLE_SO: weakref.WeakKeyDictionary[type, set] = weakref.WeakKeyDictionary()


#: How many characters of a value a message shows.
_SHOWN = 60


def _shown(value) -> str:
    text = " ".join(repr(value).split())
    return text if len(text) <= _SHOWN else text[: _SHOWN - 3] + "..."
