"""What a :class:`~problems.Problem` subclass declares through its code, read once per class.

The subclass contract lets a problem compute its numbers in methods (``epsilon()`` returning
``amplitude**2``, method options with an amplitude in them). The case of a problem needs them as
declarations: its map (ε and the symbols as expressions in the parameters) and the parameters its
solution reads. Both are read by calling the methods once on the parameters as sympy symbols — a
method that does not go through with symbols (a comparison, ``math.sqrt``, ``int``) declares
nothing, and the case stays on the safe side (the declared map alone; every point its own
solution). The problem's own checks, over many points at once, are here too
(:func:`checked_columns`: what :meth:`~problems.Problem.create` says at each point).
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Mapping
from inspect import getattr_static

import numpy as np
import sympy as sp
from attrs import frozen

from perturb import PerturbError
from perturb.cache import held_warnings
from perturb.case import EPSILON_KEY, ParameterMap
from perturb.case.points import checked_point, message_of
from perturb.errors import InvalidParameterError, InvalidSystemError, defined_at
from perturb.oracle import PeriodicOrbit, SymbolicRHS
from perturb.validation import (
    Condition,
    Equations,
    Integrals,
    OrbitEstimate,
    original_rhs,
    system_equations,
)
from perturb.validation.capabilities import call_hook
from perturb.validation.model import system_integrals

__all__ = [
    "checked_columns",
    "checks_of",
    "declared_hooks",
    "declared_map",
    "older_hooks",
    "solution_reads",
    "traced_declarations",
]

#: The methods through which a subclass may compute its numbers itself (the subclass contract
#: allows it): the map reads them off the class as expressions (:func:`traced_declarations`).
OWN_NUMBERS = ("epsilon", "symbol_values")

#: The methods a point's numbers and solution come from: a class that overrides one of them
#: computes its own, so the solution it reads cannot be told from its method options.
OWN_METHODS = (
    "create",
    "with_parameters",
    "epsilon",
    "symbol_values",
    "parameter_value",
    "case",
    "solve",
    "_family_options",
    "__attrs_post_init__",
)


def declared_map(cls: type) -> dict:
    """The ``parameter_map`` the class declares, or the nearest parent's ({} if none does): a
    declaration of the subclass contract with no value on the base class, as ``name``. None
    declares no map, as leaving it out does; ``(key, expression)`` pairs are a map too.

    Raises
    ------
    perturb.errors.InvalidSystemError
        The declaration is not a mapping (a string, a number): one line naming where the class
        declares it and the fix.
    """
    owner = next((k for k in cls.__mro__ if "parameter_map" in vars(k)), None)
    declared = None if owner is None else vars(owner)["parameter_map"]
    if declared is None:
        return {}
    if isinstance(declared, Mapping):
        return dict(declared)
    if not isinstance(declared, str | bytes):
        try:
            return dict(declared)
        except (TypeError, ValueError):
            pass
    raise InvalidSystemError(
        f"{defined_at(owner, 'parameter_map')}: `{owner.__qualname__}.parameter_map` = "
        f"{declared!r} is invalid: give a dict {{symbol or 'epsilon': expression in the "
        "parameters}, e.g. {'epsilon': 'eps / 2'} (or leave it out: each symbol is the parameter "
        "of its name, ε the parameter eps)"
    )


def _overrides(cls: type, base: type, name: str) -> bool:
    return getattr_static(cls, name, None) is not getattr_static(base, name, None)


@frozen
class _SymbolicPoint:
    """The base map's expressions in the place of a case: a subclass's ``super().symbol_values()``
    or ``super().epsilon()`` reads them."""

    base: ParameterMap | None
    replace: dict

    @property
    def symbol_values(self) -> dict:
        if self.base is None:
            raise InvalidSystemError("no declared map to read")
        return {k: v.xreplace(self.replace) for k, v in self.base.symbols}

    @property
    def epsilon(self):
        if self.base is None or self.base.epsilon is None:
            raise InvalidSystemError("no declared epsilon to read")
        return self.base.epsilon.xreplace(self.replace)


def _probe(cls: type, base: ParameterMap | None, symbols: dict):
    """An instance of ``cls`` whose values are ``symbols`` (sympy objects; no check runs) and
    whose case reads the base map's expressions in them."""
    probe = object.__new__(cls)
    for name, value in (("values", symbols), ("_family", None), ("_symbolic", None)):
        object.__setattr__(probe, name, value)
    real = {sp.Symbol(n, real=True): s for n, s in symbols.items()}
    object.__setattr__(probe, "_case", _SymbolicPoint(base, real))
    return probe


def traced_declarations(cls: type, root: type, base: ParameterMap | None) -> dict:
    """The map declarations a subclass of ``root`` writes as code: its own ``epsilon()``
    (ε = amplitude²) or ``symbol_values()``, called once on the parameters as sympy symbols.
    A method that does not go through with symbols declares nothing, and the declared
    :attr:`~problems.Problem.parameter_map` stands alone."""
    own = [n for n in OWN_NUMBERS if _overrides(cls, root, n)]
    if not own:
        return {}
    symbols = {s.name: sp.Symbol(s.name, real=True) for s in cls.parameter_specs}
    probe = _probe(cls, base, symbols)
    out = {}
    with held_warnings(), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in own:
            try:
                value = getattr(probe, name)()
                read = {EPSILON_KEY: value} if name == "epsilon" else dict(value)
                read = {k: sp.sympify(v) for k, v in read.items()}
            except Exception:  # noqa: BLE001 - code that needs numbers declares nothing
                continue
            if all(isinstance(v, sp.Expr) and v.is_finite is not False for v in read.values()):
                out.update(read)
    own = {p.name for p in cls.system().parameters} | {EPSILON_KEY}
    return {k: v for k, v in out.items() if k in own}  # a name the system lacks declares nothing


def _free(value, found: set) -> bool:
    """Collect the free symbols of nested options into ``found``; False where a value is not
    one that sympy, numbers or strings make (it could hide a parameter)."""
    if isinstance(value, dict):
        return all(_free(k, found) and _free(v, found) for k, v in value.items())
    if isinstance(value, list | tuple | set | frozenset):
        return all(_free(v, found) for v in value)
    if isinstance(value, sp.Basic):
        found.update(value.free_symbols)
        return True
    return value is None or isinstance(value, str | bool | int | float | complex)


class _Read(sp.Dummy):
    """A parameter read as a symbol that refuses to be taken for a number: a method that
    compares it with a number, tests its truth, converts or formats it raises, and counts as
    reading it (sympy's ``a == 1`` would otherwise be a silent False)."""

    def _refuse(self, *args, **kwargs):
        raise TypeError(f"the parameter {self.name!r} is read as a number")

    __bool__ = __int__ = __float__ = __complex__ = __index__ = _refuse
    __str__ = __format__ = __round__ = _refuse

    def __eq__(self, other):
        if isinstance(other, sp.Basic):
            return super().__eq__(other)
        return self._refuse()

    def __ne__(self, other):
        return not self.__eq__(other)

    __hash__ = sp.Dummy.__hash__


def _reads(cls: type, base: ParameterMap, values: dict, name: str) -> bool:
    """Whether the method options hold the parameter ``name`` (the others at ``values``): read
    with ``name`` as a :class:`_Read` symbol; options that fail with it, or hold something
    sympy did not make, count as reading it."""
    read = _Read(name, real=True)
    numbers = {n: (read if n == name else sp.sympify(v)) for n, v in values.items()}
    probe = _probe(cls, base, numbers)
    found: set = set()
    try:
        with held_warnings(), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            options = probe.method_options()
            plain = _free(options, found)
    except Exception:  # noqa: BLE001 - options that need the number read it
        return True
    return not plain or read in found


def solution_reads(cls: type, root: type, base: ParameterMap, values: dict) -> frozenset | None:
    """The parameters of a subclass of ``root`` that its solution reads besides the system's
    symbols, the others at ``values``: those its method options hold, read one at a time as a
    symbol (:func:`_reads`). None (unknown) for a class that computes its points' numbers or
    solution itself (:data:`OWN_METHODS`)."""
    if any(_overrides(cls, root, name) for name in OWN_METHODS):
        return None
    values = {s.name: values[s.name] for s in cls.parameter_specs}
    return frozenset(n for n in values if _reads(cls, base, values, n))


def checks_of(problem, values: Mapping) -> None:
    """Run ``problem``'s whole-set :meth:`~problems.Problem.check_values` on ``values``. A
    refusal it returns instead of raising counts as raised: a string is the fix (as a
    :class:`~problems.ParameterSpec` check returns it), False refuses; None, True or the values
    themselves accept.

    Raises
    ------
    perturb.errors.InvalidParameterError
        The check refuses the values (raised, or returned).
    perturb.errors.InvalidSystemError
        The check returned other values (it checks them, it cannot change them) or something
        else: one line naming where it is defined and the fix.
    """
    found = call_hook(problem, "check_values", problem.check_values, "(self, values)", values)
    accepted = (
        found is None
        or (isinstance(found, bool | np.bool_) and bool(found))
        or (isinstance(found, str) and not found.strip())
        or (isinstance(found, Mapping) and dict(found) == dict(values))
    )
    if accepted:
        return
    shown = ", ".join(f"{name}={value!r}" for name, value in values.items())
    if isinstance(found, str):
        raise InvalidParameterError(f"the parameters {shown} are invalid: {found}")
    where = defined_at(type(problem), "check_values")
    if isinstance(found, bool | np.bool_):
        raise InvalidParameterError(
            f"the parameters {shown} are refused by check_values ({where}): give values it accepts"
        )
    raise InvalidSystemError(
        f"{where}: `check_values` returned {type(found).__name__} {found!r:.60}: it checks the "
        "values and cannot change them: raise an InvalidParameterError naming the value and the "
        "fix (or return the fix as a str), and return None where they are accepted"
    )


def checked_columns(problem, root: type, values: dict, grid: dict, size: int):
    """``(errors, notes)``: what :meth:`~problems.Problem.create` says at each point of ``grid``
    (the rest ``values``) — the first invalid parameter in the specs' order, then the whole-set
    :meth:`~problems.Problem.check_values` and its warnings — each spec's check run once per
    distinct value. None where a check raised anything but a refusal of bad values."""
    cls = type(problem)
    errors = [""] * size
    notes = [""] * size
    for spec in cls.parameter_specs:
        if spec.name not in grid:
            continue
        unique, inverse = np.unique(grid[spec.name], return_inverse=True)
        found = []
        for value in unique.tolist():
            try:
                spec.validate(value)
            except (PerturbError, ValueError) as exc:
                found.append(message_of(exc))
            except Exception:  # noqa: BLE001 - the per-point route records it as a failure
                return None
            else:
                found.append("")
        for i, k in enumerate(inverse.tolist()):
            if found[k] and not errors[i]:
                errors[i] = found[k]
    if _overrides(cls, root, "check_values"):  # whole-set checks: point by point
        names = [s.name for s in cls.parameter_specs]
        rows = {n: grid[n].tolist() for n in names if n in grid}
        for i in range(size):
            if errors[i]:
                continue
            point = {n: float(rows[n][i] if n in rows else values[n]) for n in names}
            checked = checked_point(functools.partial(checks_of, problem), point)
            if checked is None:
                return None
            errors[i], notes[i] = checked
    return errors, notes


#: The duck-typed hooks of earlier versions that a subclass may still define (docs/validation.md);
#: the typed hook each one stands for, where it is a capability of its own.
OLDER_HOOKS = {
    "original_symbolic": "original_equations",  # and read by the integrals below
    "first_integrals_function": None,  # read by the integrals below
    "validity_conditions": "validity_estimates",
    "true_periodic_orbit": "true_orbit",
}


def _validity_estimates(self) -> tuple:
    """The conditions of ``validity_conditions()`` as :class:`~perturb.validation.Condition`."""
    return tuple(Condition(*item) for item in self.validity_conditions())


def _true_orbit(self, solution) -> OrbitEstimate | None:
    """The orbit of ``true_periodic_orbit(solution)``, read into an
    :class:`~perturb.validation.OrbitEstimate`."""
    true = self.true_periodic_orbit(solution)
    if true is None or isinstance(true, PeriodicOrbit):
        return true  # the one orbit type (an OrbitEstimate is one)
    n_trivial = getattr(true, "n_trivial", None)
    return OrbitEstimate(
        success=bool(getattr(true, "success", False)),
        period=float(getattr(true, "period", math.nan)),
        initial_state=getattr(true, "initial_state", ()),
        message=str(getattr(true, "message", "")),
        floquet=tuple(getattr(true, "floquet", getattr(true, "multipliers", ()))),
        n_trivial=None if n_trivial is None else int(n_trivial),
        trivial_multiplier_error=float(getattr(true, "trivial_multiplier_error", math.nan)),
        resolution=float(getattr(true, "resolution", 0.0)),
        integrator=str(getattr(true, "integrator", "")),
    )


def _integrals_of_motion(self, y0=None) -> Integrals | None:
    """``first_integrals_function()`` (names from its ``names``, else ``I0, I1, ...``), else
    the system's own when the equations are the system's (no ``original_symbolic()`` giving
    them, no own ``original_rhs``), else none: the capability
    :class:`~perturb.validation.capabilities.OwnIntegrals` of a class that defines those."""
    older = self._older
    function = self.first_integrals_function() if "first_integrals_function" in older else None
    if function is not None:
        return Integrals(function, tuple(getattr(function, "names", ())))
    own = "original_symbolic" in older and self.original_symbolic() is not None
    if not own and "original_rhs" not in self._own:
        return system_integrals(self, y0)
    return None


def _original_equations(self, y0=None) -> Equations:
    """The equations of ``original_symbolic()`` (symbolic: heyoka compiles them), else the
    class's own ``original_rhs()``, else the system's: the hook
    ``original_equations(y0)`` (:mod:`perturb.validation.truth`) of a class that defines
    ``original_symbolic``."""
    symbolic = self.original_symbolic()
    if symbolic is not None:
        return Equations(SymbolicRHS(*symbolic))
    if "original_rhs" in self._own:
        return Equations.from_time_rhs(original_rhs(self))
    return system_equations(self, y0)


_TYPED = {
    "original_equations": _original_equations,
    "validity_estimates": _validity_estimates,
    "true_orbit": _true_orbit,
    "integrals_of_motion": _integrals_of_motion,
}

#: The hooks of the subclass contract whose definition by a class is read once per class:
#: ``original_rhs`` (equations of its own: the system's integrals do not hold there).
OWN_HOOKS = ("original_rhs",)


def _declare(cls: type, root: type, typed: str) -> None:
    """Give ``cls`` the typed hook ``typed`` read from an older one, unless the class or a parent
    below ``root`` defines the typed hook itself."""
    defined = [k for k in cls.__mro__[: cls.__mro__.index(root)] if typed in vars(k)]
    if not defined or all(vars(k)[typed] is _TYPED[typed] for k in defined):
        setattr(cls, typed, _TYPED[typed])


def older_hooks(cls: type, root: type) -> None:
    """Read the older hooks a new subclass of ``root`` defines, once, when the class is made:
    their names go into ``cls._older`` and a hook that stands for a capability
    (:mod:`perturb.validation.capabilities`) declares it, unless the class or a parent below
    ``root`` defines the typed hook itself."""
    own = {name for name in OLDER_HOOKS if name in vars(cls)}
    cls._older = frozenset(cls._older | own)
    for name in own:
        typed = OLDER_HOOKS[name]
        if typed is not None:
            _declare(cls, root, typed)


def declared_hooks(cls: type, root: type) -> None:
    """Read, once when the class is made, which hooks of :data:`OWN_HOOKS` a new subclass of
    ``root`` defines (into ``cls._own``), and give a class whose equations or integrals are its
    own (``first_integrals_function``, ``original_symbolic``, ``original_rhs``) the integrals
    that follow from them, unless it defines ``integrals_of_motion`` itself."""
    cls._own = frozenset(name for name in OWN_HOOKS if _overrides(cls, root, name))
    if cls._own & {"original_rhs"} or cls._older & {
        "first_integrals_function",
        "original_symbolic",
    }:
        _declare(cls, root, "integrals_of_motion")
