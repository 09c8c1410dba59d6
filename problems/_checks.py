"""A user's problem class run once at load time, so that its mistakes are named as the user's.

:func:`check_usable` runs the code a problem class supplies — ``build_system``, ``create`` with its
defaults, ``symbol_values``, ``epsilon``, ``method_options`` — and looks at the system it builds
for what perturb's symbolic construction cannot take: parameters without values, a right-hand side
that is not polynomial in the state where the construction must stay symbolic, an undefined
function, an expression that makes sympy recurse without end. Each is one
:class:`~perturb.errors.ProblemLoadError` line naming the class (its file), the cause and the
fix (``perturb`` exits 2), before any work: never an internal error or an overflow later.

A problem named by file or module is checked (:func:`problems.loading.load_problem`); the
built-in ones are checked by the test suite.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import sympy as sp

from perturb.errors import InvalidSystemError, PerturbError, ProblemLoadError

__all__ = ["check_usable"]

#: How much of an expression a message quotes.
SHOWN = 60


def _short(value) -> str:
    text = " ".join(str(value).split())
    return text if len(text) <= SHOWN else text[: SHOWN - 3] + "..."


def _raised(label: str, what: str, exc: BaseException) -> ProblemLoadError:
    detail = " ".join(str(exc).split())
    return ProblemLoadError(
        f"{label}: {what} raised {type(exc).__name__}{': ' + detail if detail else ''}: fix the "
        "class"
    )


def check_usable(cls, label: str) -> None:
    """Raise :class:`ProblemLoadError` unless the problem class ``cls`` can be used as it is.

    Parameters
    ----------
    cls : type
        A complete subclass of :class:`problems.base.Problem` (see
        :func:`problems._registry.check_problem_class`).
    label : str
        How messages name it (``path/to/file.py:Class``).

    Raises
    ------
    ProblemLoadError
        Its code raises, returns the wrong type, or builds a system perturb cannot construct a
        solution of (one line: the class, the cause, the fix).
    """
    from perturb import QuasilinearSystem

    try:
        system = cls.system()
    except RecursionError:
        raise ProblemLoadError(
            f"{label}: build_system() recursed without end (RecursionError): fix the class"
        ) from None
    except Exception as exc:  # noqa: BLE001 - the user's code: any failure is theirs to fix
        raise _raised(label, "build_system()", exc) from None
    if not isinstance(system, QuasilinearSystem):
        raise ProblemLoadError(
            f"{label}: build_system() returned {type(system).__name__}, not a "
            "perturb.QuasilinearSystem: return one"
        )
    problem = _default_instance(cls, label)
    _check_values(problem, system, label)
    _check_rhs(problem, system, label)


def _default_instance(cls, label: str):
    try:
        return cls.create()
    except InvalidSystemError as exc:  # a hook of the class, not the values: it names its line
        raise ProblemLoadError(" ".join(str(exc).split())) from None
    except PerturbError as exc:
        raise ProblemLoadError(
            f"{label}: its default parameters are refused ({' '.join(str(exc).split())}): fix "
            "the defaults in parameter_specs"
        ) from None
    except Exception as exc:  # noqa: BLE001 - the user's create/check_values
        raise _raised(label, "create() with the default parameters", exc) from None


def _check_values(problem, system, label: str) -> None:
    try:
        values = problem.symbol_values()
        eps = problem.epsilon()
        options = problem.method_options()
    except Exception as exc:  # noqa: BLE001 - the user's overrides
        raise _raised(label, "symbol_values(), epsilon() or method_options()", exc) from None
    if not isinstance(values, Mapping):
        raise ProblemLoadError(
            f"{label}: symbol_values() returned {type(values).__name__}: return a dict name -> "
            "number"
        )
    missing = sorted(p.name for p in system.parameters if p.name not in values)
    if missing:
        raise ProblemLoadError(
            f"{label}: the system's parameters {missing} have no values: add a "
            f"ParameterSpec({missing[0]!r}, default, doc) for each to parameter_specs (or give "
            "them in symbol_values())"
        )
    bad = [k for k, v in values.items() if not _real(v)]
    if bad:
        raise ProblemLoadError(
            f"{label}: symbol_values() gives {bad[0]} = {values[bad[0]]!r}: give finite real numbers"
        )
    if not _real(eps):
        raise ProblemLoadError(f"{label}: epsilon() returned {eps!r}: return a finite real number")
    if not isinstance(options, Mapping):
        raise ProblemLoadError(
            f"{label}: method_options() returned {type(options).__name__}: return a dict of "
            "PoincareMethod options, e.g. {'amplitudes': {'x': A}}"
        )
    if system.excitation is None:
        from perturb import PoincareMethod

        try:
            PoincareMethod(order=1, **options)
        except PerturbError as exc:
            raise ProblemLoadError(
                f"{label}: method_options(): {' '.join(str(exc).split())}"
            ) from None
        except TypeError as exc:
            raise _raised(label, "method_options()", exc) from None


def _real(value) -> bool:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return False
    return math.isfinite(number) and not isinstance(value, bool)


def _check_rhs(problem, system, label: str) -> None:
    """Undefined functions, recursion, and a non-polynomial right-hand side where the symbolic
    construction cannot expand it (parameters or amplitudes left symbolic)."""
    state = [*system.coordinates, *system.velocities]
    names = [str(s) for s in state]
    parameters = set(system.parameters)
    amplitudes = problem.method_options().get("amplitudes") or {}
    symbolic_amplitudes = any(
        isinstance(v, sp.Basic) and v.free_symbols for v in dict(amplitudes).values()
    )
    probe = {s: sp.Float(0.3 + 0.1 * i) for i, s in enumerate(state)}
    for i, rhs in enumerate(system.rhs):
        try:
            undefined = sorted({str(f.func) for f in rhs.atoms(sp.core.function.AppliedUndef)})
            if undefined:
                raise ProblemLoadError(
                    f"{label}: the right-hand side {i} ({_short(rhs)}) calls {undefined}, a "
                    "function sympy does not know: write it out in the state (a polynomial)"
                )
            rhs.subs(probe)
            polynomial = _polynomial(rhs, state)
        except RecursionError:
            raise ProblemLoadError(
                f"{label}: the right-hand side {i} makes sympy recurse without end "
                "(RecursionError while substituting numbers for the state): fix the expression "
                "(a function that rewrites itself?)"
            ) from None
        if polynomial:
            continue
        stray = sorted(str(p) for p in rhs.free_symbols & parameters)
        if stray or symbolic_amplitudes:
            why = (
                f"its parameters {stray} stay symbols"
                if stray
                else "its generating amplitudes stay symbols"
            )
            raise ProblemLoadError(
                f"{label}: the right-hand side {i} ({_short(rhs)}) is not polynomial in the state "
                f"{names}, and {why} in a problem's construction: write it as a polynomial in "
                "the state (the Taylor polynomial of sin(x), 1/(1+x), ... to the order you need)"
            )


def _polynomial(expr, state) -> bool:
    """Whether ``expr`` is a polynomial in ``state`` (its coefficients may hold anything else)."""
    try:
        sp.Poly(expr, *state)
    except (sp.PolynomialError, sp.GeneratorsNeeded):
        return False
    return True
