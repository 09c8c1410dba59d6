"""Exceptions and warnings of perturb: the only module that defines them.

Invalid input raises a subclass of :class:`ValueError` whose message names the argument, the value
received and the fix.  A valid run that fails numerically does *not* raise: it returns a result whose
``status`` says what went wrong (see :class:`perturb.solution.Status`).
"""

from __future__ import annotations

__all__ = [
    "AccuracyWarning",
    "CacheWarning",
    "ContinuationError",
    "IntegrationError",
    "InvalidParameterError",
    "InvalidSystemError",
    "MissingDependencyError",
    "OutputError",
    "ParameterOverflowError",
    "PerturbError",
    "ProblemLoadError",
    "SceneError",
    "SweepError",
    "UnknownNameError",
]


class PerturbError(Exception):
    """Root of every exception raised by perturb.

    Parameters
    ----------
    message : str
        What went wrong and, for bad input, the fix.

    Examples
    --------
    Catch anything perturb raises on purpose:

    >>> from perturb import PerturbError, PoincareMethod
    >>> try:
    ...     PoincareMethod(order=0)
    ... except PerturbError as error:
    ...     print(type(error).__name__)
    InvalidSystemError
    """


class InvalidSystemError(PerturbError, ValueError):
    """A quasilinear system, or an option of the method, is not well formed.

    A :class:`ValueError`: its message names the argument, the value and the fix.

    Parameters
    ----------
    message : str
        The argument, the value received and the fix.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> QuasilinearSystem([x], [xdot], [1, 2], [0])
    Traceback (most recent call last):
    ...
    perturb.errors.InvalidSystemError: `frequencies` has 2 entries but there are 1 coordinates: give one per coordinate
    """


class InvalidParameterError(PerturbError, ValueError):
    """A problem parameter or a command-line value is out of its admissible range.

    A :class:`ValueError`: its message names the argument, the value and the fix.

    Parameters
    ----------
    message : str
        The argument, the value received and the fix.

    Examples
    --------
    >>> from problems import get_problem
    >>> get_problem("duffing").create(amplitude=-1.0)
    Traceback (most recent call last):
    ...
    perturb.errors.InvalidParameterError: `amplitude` = -1 is invalid: give a value > 0
    """


class ParameterOverflowError(PerturbError, ValueError):
    """A parameter value past what floating point carries through the series (its powers and
    products overflow, ``kappa = 1e308``): the run fails with this reason (exit 1 from the
    command line), never with a normal-looking answer of nothing.

    Examples
    --------
    >>> from problems import get_problem
    >>> get_problem("linear-pair").create(kappa=1e308)
    Traceback (most recent call last):
    ...
    perturb.errors.ParameterOverflowError: `kappa` = 1e+308 is past the floats: the series' powers and products of it overflow; give |kappa| <= 1e+100
    """


class UnknownNameError(PerturbError, ValueError):
    """A problem, parameter, integrator or paper name that perturb does not know.

    A :class:`ValueError`; the message suggests the closest known name.

    Parameters
    ----------
    message : str
        The unknown name and the known ones (or the closest).

    Examples
    --------
    >>> from problems import get_problem
    >>> get_problem("dufing")
    Traceback (most recent call last):
    ...
    perturb.errors.UnknownNameError: ...
    """


class IntegrationError(PerturbError, RuntimeError):
    """A numerical integration failed; carries the solver's message, status and the time reached.

    The oracle's integrators do not raise it for a failed run (their :class:`~perturb.oracle.Trajectory`
    has a failed ``status`` instead); it is for callers that need an exception.

    Parameters
    ----------
    message : str
        The solver's message.
    status : int, optional
        The solver's status code.
    t_reached : float, optional
        The time the integration reached.

    Examples
    --------
    >>> from perturb import IntegrationError
    >>> error = IntegrationError("step size too small", status=-1, t_reached=2.5)
    >>> print(error)
    step size too small (status -1, reached t = 2.5)
    >>> error.t_reached
    2.5
    """

    def __init__(self, message: str, status: int | None = None, t_reached: float | None = None):
        super().__init__(f"{message} (status {status}, reached t = {t_reached})")
        self.message = message
        self.status = status
        self.t_reached = t_reached


class AccuracyWarning(UserWarning):
    """A result is returned but its accuracy is doubtful (small divisor, large expansion parameter).

    A warning, not an error: the result is still returned. Turn it into an error with
    ``warnings.simplefilter("error", AccuracyWarning)``.

    Parameters
    ----------
    message : str
        What makes the result doubtful, with the figure.

    Examples
    --------
    >>> import warnings
    >>> from perturb import AccuracyWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("eps = 232 is not small", AccuracyWarning)
    >>> caught[0].category.__name__
    'AccuracyWarning'
    """


def bad_value(
    argument: str, value: object, fix: str, cls: type[ValueError] = InvalidParameterError
):
    """Build the one-line error used for every bad input: argument, value, fix.

    Examples
    --------
    >>> raise bad_value("order", 0, "pass an integer >= 1")
    Traceback (most recent call last):
    ...
    perturb.errors.InvalidParameterError: `order` = 0 is invalid: pass an integer >= 1
    """
    return cls(f"`{argument}` = {value!r} is invalid: {fix}")


def defined_at(owner, name: str | None = None) -> str:
    """Where a user's code is defined, for a one-line error: ``file:line`` of the function
    ``owner`` or, with ``name``, of the class ``owner``'s attribute ``name`` (a method, a
    property's getter; else the class that sets it), else the dotted name.

    Examples
    --------
    >>> from perturb.errors import defined_at
    >>> from problems import get_problem
    >>> defined_at(get_problem("duffing"), "check_values")  # doctest: +ELLIPSIS
    '.../problems/duffing.py:...'
    """
    import inspect

    if name is not None:  # the class in the method resolution order that defines it
        owner = next((k for k in owner.__mro__ if name in vars(k)), owner)
    value = inspect.getattr_static(owner, name, None) if name is not None else owner
    function = value.fget if isinstance(value, property) else value
    function = function.__func__ if isinstance(function, classmethod | staticmethod) else function
    code = function.__code__ if inspect.isfunction(function) else None
    if code is not None:
        return f"{code.co_filename}:{code.co_firstlineno}"
    if inspect.isclass(owner):
        try:
            return f"{inspect.getsourcefile(owner)}:{inspect.getsourcelines(owner)[1]}"
        except (OSError, TypeError):  # no source to read: the class by its name
            return f"{owner.__module__}.{owner.__qualname__}"
    return repr(owner)


class CacheWarning(UserWarning):
    """The disk cache was bypassed or repaired (unsafe folder, unusable key, invalid entry); the
    result is still computed afresh and correct."""


class ProblemLoadError(PerturbError, ValueError):
    """A problem named by file or module (``path/to/file.py:Class``), or installed through an entry
    point, that cannot be loaded: missing file, syntax or import error, missing or incomplete class."""


class MissingDependencyError(PerturbError, ImportError):
    """An optional dependency (an extra such as ``perturb[plot]``) is not installed; the message
    names the extra to install."""


class SceneError(PerturbError, ValueError):
    """A scene file (``perturb report SCENE.toml``) that cannot be used: malformed TOML (the line is
    named), an unknown section, key, problem, parameter or plot name (the closest is suggested), a
    value of the wrong type, or an output folder that cannot be written."""


class SweepError(PerturbError, RuntimeError):
    """A sweep that could not finish: chunks whose workers died again and again, or an
    interrupted run (the store keeps every point written; ``--resume`` continues it)."""


class OutputError(PerturbError, ValueError):
    """An output path perturb must not or cannot write: a file or a report folder's file that
    perturb did not write (never overwritten without ``--force``, a folder's never), an empty
    path, a folder that does not exist or cannot be written, an unknown plot format."""


class ContinuationError(PerturbError, RuntimeError):
    """A continuation that could not follow its curve to the end, raised on request
    (:meth:`perturb.continuation.Curve.raise_for_status`): the message says where and why."""
