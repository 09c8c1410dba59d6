"""The :class:`Problem` base class: a physical model, its parameters and its quasilinear form.

A problem turns user-facing parameter values (validated, with defaults) into

* a :class:`perturb.QuasilinearSystem` (symbolic, derived once per class and cached),
* the options of :class:`perturb.PoincareMethod` that select its periodic solution,
* the physical state along the solution, under the names users know.

Subclass contract (as scipy's ``OdeSolver`` states its own):

1. set the class attributes ``name`` (the registry key), ``summary`` and ``parameter_specs``;
2. implement :meth:`Problem.build_system` (symbolic, no numbers);
3. declare :attr:`Problem.parameter_map` where the system's symbols or ε are not the parameters of
   the same names (``{"sigma": "(Omega - 1)/eps"}``, ``{"epsilon": "sqrt(M*g*l/C)/r0"}``: a
   :class:`perturb.case.ParameterMap`, checked once); ε is the parameter ``eps`` by default.
   An overridden ``epsilon()`` or ``symbol_values()`` declares the map as well when sympy can
   read it (``return self.values["amplitude"] ** 2``): it is called once on the parameters as
   symbols, and the map's inverse re-creates the problem at another ε;
3a. optionally override :meth:`Problem.method_options`, :meth:`Problem.state` (to map the
   quasilinear state back to physical variables) and :meth:`Problem.check_values` (whole-set
   checks), and define ``original_rhs()`` (the unreduced equations ``F(t, y)`` for validation);
4. optionally define the validation hooks ``original_equations(y0)`` and ``with_epsilon(eps)``
   (:mod:`perturb.validation.truth`: default, the system itself and the problem at its case
   moved to ``eps``), and declare optional physics by defining its
   method (:mod:`perturb.validation.capabilities`: ``integrals_of_motion`` — default: the
   system's own, unless the equations are the class's —, ``label`` — default: the ``name`` —,
   ``validity_estimates``, ``true_orbit``, ``shooting_setup``, ``euler_angles``,
   ``report_extras``); the older duck-typed hooks still work, read once when the class is made
   (``original_symbolic()``, ``first_integrals_function()``, ``validity_conditions()``,
   ``true_periodic_orbit(solution)``);
5. in the ``problems`` package, decorate the class with :func:`problems.register` (that alone lists
   it); elsewhere, name it as ``path/to/file.py:Class`` or declare it in the entry-point group
   ``perturb.problems`` (see :mod:`problems.loading`).

A problem *is* a :class:`perturb.validation.Model`: :func:`perturb.validation.validate` needs
nothing else. What a problem does beyond its contract is asked through functions of it
(:func:`perturb.validation.original_rhs`, :func:`perturb.validation.original_equations`,
:func:`perturb.validation.with_epsilon`, :func:`perturb.response.steady_state_of`); the methods of
those names that earlier versions had still answer, with a :class:`DeprecationWarning`
(:data:`MOVED`).
"""

from __future__ import annotations

import functools
import math
import uuid
import warnings
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from typing import ClassVar

import attrs
import numpy as np
from attrs import field, frozen

from perturb import (
    FamilyList,
    PeriodicSolution,
    QuasilinearSystem,
    Status,
)
from perturb._defaults import PARAMETER_MAX_MAGNITUDE
from perturb.case import Case, ParameterMap
from perturb.errors import (
    InvalidParameterError,
    InvalidSystemError,
    ParameterOverflowError,
    UnknownNameError,
    defined_at,
)
from perturb.validation import (
    Model,
    original_equations,
    original_rhs,
    quasilinear_state_names,
    state_along,
    with_epsilon,
)
from perturb.validation.frames import work_of
from perturb.validation.model import parameter_value_of
from problems._declared import (
    checked_columns,
    checks_of,
    declared_hooks,
    declared_map,
    older_hooks,
    solution_reads,
    traced_declarations,
)

__all__ = ["ParameterSpec", "Problem"]

_SYSTEM_CACHE: dict[tuple, QuasilinearSystem] = {}
_SOLUTION_CACHE: dict[tuple, PeriodicSolution] = {}
_FAMILY_CACHE: dict[tuple, FamilyList] = {}
_MAP_CACHE: dict[tuple, ParameterMap] = {}
_READS_CACHE: dict[tuple, frozenset | None] = {}


_OPTION_KEYS: dict = {}
#: Most keys kept by :func:`_options_key` (options that carry parameter values differ per point).
_OPTION_KEYS_SIZE = 4096


def _frozen_options(value):
    """``value`` (nested dicts, lists, sympy objects, numbers) as a hashable tuple, or None."""
    if isinstance(value, dict):
        items = [(k, _frozen_options(v)) for k, v in value.items()]
        return None if any(v is None for _, v in items) else ("dict", tuple(items))
    if isinstance(value, list | tuple):
        items = [_frozen_options(v) for v in value]
        return None if any(v is None for v in items) else (type(value).__name__, tuple(items))
    try:
        hash(value)
    except TypeError:
        return None
    return (type(value).__name__, value)


def _options_key(options: dict) -> str:
    """``repr(sorted(options.items()))``, the solution cache's key of the method options, kept per
    options so that a solve already cached costs a dictionary lookup instead of printing sympy
    expressions (a sweep asks for it at every point)."""
    frozen_ = _frozen_options(options)
    if frozen_ is None:
        return repr(sorted(options.items()))
    key = _OPTION_KEYS.get(frozen_)
    if key is None:
        if len(_OPTION_KEYS) >= _OPTION_KEYS_SIZE:
            _OPTION_KEYS.clear()
        key = _OPTION_KEYS[frozen_] = repr(sorted(options.items()))
    return key


@frozen
class ParameterSpec:
    """A named parameter with its default, meaning and admissible range.

    Parameters
    ----------
    name : str
    default : float
    doc : str
        One line: meaning and unit.
    check : callable, optional
        ``check(value) -> str | None``; a returned string is the fix shown to the user.
    allow_inf : bool
        Whether ``inf`` is an admissible value (e.g. a distance meaning "absent").

    Examples
    --------
    >>> from problems import ParameterSpec
    >>> from problems.base import positive
    >>> spec = ParameterSpec("amplitude", 1.0, "initial displacement", positive)
    >>> spec.validate(2.5)
    2.5
    >>> spec.validate(-1.0)
    Traceback (most recent call last):
    ...
    perturb.errors.InvalidParameterError: `amplitude` = -1 is invalid: give a value > 0
    """

    name: str
    default: float
    doc: str
    check: Callable[[float], str | None] | None = None
    allow_inf: bool = False

    def validate(self, value) -> float:
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise InvalidParameterError(
                f"`{self.name}` = {value!r} is not a number: give a real value"
            ) from None
        if math.isnan(value) or (math.isinf(value) and not self.allow_inf):
            raise InvalidParameterError(
                f"`{self.name}` = {value} is not finite: give a finite real value"
            )
        # a parameter that admits inf (a distance meaning "absent") enters through its inverse:
        # any finite value is as good; the others overflow past the bound
        if not self.allow_inf and math.isfinite(value) and abs(value) > PARAMETER_MAX_MAGNITUDE:
            raise ParameterOverflowError(
                f"`{self.name}` = {value:g} is past the floats: the series' powers and products "
                f"of it overflow; give |{self.name}| <= {PARAMETER_MAX_MAGNITUDE:g}"
            )
        if self.check is not None:
            fix = self.check(value)
            if fix:
                raise InvalidParameterError(f"`{self.name}` = {value:g} is invalid: {fix}")
        return value


def positive(value: float) -> str | None:
    """Check helper: strictly positive."""
    return None if value > 0 else "give a value > 0"


def _class_key(cls: type) -> tuple[str, str, str]:
    """The key of a problem class in the per-class caches: its module, its name and the identity
    it was given when made — two classes of one name in one file (the second redefining the
    first) are two classes, and a copy of a class sent to a worker is the class it copies."""
    return (cls.__module__, cls.__qualname__, cls._identity)


def _solution_reads(cls: type, values: dict) -> frozenset | None:
    """The parameters the class's solution reads besides its system's symbols, the others at
    ``values`` (:func:`problems._declared.solution_reads`, kept per class and values)."""
    key = (*_class_key(cls), tuple(sorted(values.items())))
    if key not in _READS_CACHE:
        if len(_READS_CACHE) >= _OPTION_KEYS_SIZE:
            _READS_CACHE.clear()
        _READS_CACHE[key] = solution_reads(cls, Problem, cls._map(), values)
    return _READS_CACHE[key]


@frozen
class Problem(Model, ABC):
    """A registered problem with validated parameter values (see the module docstring).

    Make one with :meth:`create`, which fills in the defaults and validates the values.

    Parameters
    ----------
    values : mapping
        Every parameter's value, by name (as :meth:`create` builds it).
    family : str, optional
        The family of periodic solutions :meth:`solve` follows (see :meth:`families`;
        ``create(family=NAME)``); default: the one :meth:`method_options` selects.

    Attributes
    ----------
    name : str
        The registry key (``perturb solve NAME``); a class attribute.
    summary : str
        One line for ``perturb list``; a class attribute.
    parameter_specs : tuple of ParameterSpec
        The parameters with their defaults and admissible ranges; a class attribute.

    Examples
    --------
    A problem in a few lines — Duffing's oscillator with a softening cubic term, its amplitude a
    parameter:

    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from problems import ParameterSpec, Problem
    >>> x, xdot, a = sp.symbols("x xdot a")
    >>> class Softening(Problem):
    ...     name = "softening"
    ...     summary = "x'' + x = eps x^3, x(0) = a"
    ...     parameter_specs = (ParameterSpec("eps", 0.1, "cubic strength"), ParameterSpec("a", 1.0, "x(0)"))
    ...     @classmethod
    ...     def build_system(cls):
    ...         return QuasilinearSystem([x], [xdot], [1], [EPS * x**3], parameters=[a])
    ...     def method_options(self):
    ...         return {"amplitudes": {"x": a}}
    >>> problem = Softening.create(eps=0.05)
    >>> solution = problem.solve(2)
    >>> solution.frequency_series()
    -21*a**4*epsilon**2/256 - 3*a**2*epsilon/8 + 1
    >>> round(problem.period(solution), 6)  # 2 pi / Omega at eps = 0.05, a = 1
    6.404585
    """

    name: ClassVar[str]
    summary: ClassVar[str]
    parameter_specs: ClassVar[tuple[ParameterSpec, ...]]
    #: How the parameters become the system's symbols and ε: ``{symbol name: expression in the
    #: parameters}`` and, under ``"epsilon"``, ε's (strings or sympy expressions). A symbol not
    #: declared is the parameter of the same name; ε is the parameter ``eps`` unless declared.
    #: Optional, as a declaration of the class (none: every symbol its parameter's).
    parameter_map: ClassVar[Mapping[str, object]]
    #: The older duck-typed hooks the class defines (``original_symbolic``,
    #: ``first_integrals_function``, ...), read once when the class is made
    #: (:func:`problems._declared.older_hooks`).
    _older: ClassVar[frozenset] = frozenset()
    #: The hooks of :data:`problems._declared.OWN_HOOKS` the class defines (``original_rhs``),
    #: read once when the class is made (:func:`problems._declared.declared_hooks`).
    _own: ClassVar[frozenset] = frozenset()
    #: The class's own identity, given when it is made (:func:`_class_key`).
    _identity: ClassVar[str] = "Problem"

    values: dict = field(converter=dict)
    #: The family of periodic solutions :meth:`solve` follows, by its name in :meth:`families`
    #: (None: the one :meth:`method_options` selects): the constructor's ``family``. Set it with
    #: ``create(family=NAME)``; read it from :meth:`case` (``problem.case().family``).
    _family: str | None = field(default=None, kw_only=True)
    #: Whether :meth:`solve` derives the solution symbolic in the parameters (one derivation for
    #: every parameter set) instead of for these values; None: the problem's default: the
    #: constructor's ``symbolic``. Offered by problems that define ``symbolic_derivation`` (the
    #: rigid bodies: the capability :class:`perturb.sweep.derive.SymbolicDerivation`).
    _symbolic: bool | None = field(default=None, kw_only=True)
    #: This point's :class:`~perturb.case.Case`, made on first use (the map is evaluated once).
    _case: Case | None = field(default=None, init=False, eq=False, repr=False)

    def __attrs_post_init__(self):
        checks_of(self, self.values)  # a refusal returned counts as raised

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        cls._identity = uuid.uuid4().hex  # its own, for the per-class caches (_class_key)
        older_hooks(cls, Problem)
        declared_hooks(cls, Problem)

    @classmethod
    def create(cls, family: str | None = None, **overrides) -> Problem:
        """The problem with default parameters, some of them overridden by name, following the
        family ``family`` of :meth:`families` (None: the one :meth:`method_options` selects;
        checked when solved). A family is a name: a number given as ``family`` (``--set
        family=1``, a grid over it) is a parameter the problem does not have, and says so."""
        known = {s.name for s in cls.parameter_specs}
        if "family" in known:
            raise InvalidSystemError(
                f"{defined_at(cls, 'parameter_specs')}: {cls.name} has a parameter named "
                "`family`, which is create's keyword for the family of solutions: rename it"
            )
        unknown = sorted(set(overrides) - known)
        if family is not None and not isinstance(family, str):
            unknown = ["family"]
        if unknown:
            told = cls._map().set_by(unknown[0], "set")  # a system symbol the map sets
            raise UnknownNameError(
                f"`{unknown[0]}` is not a parameter of {cls.name}: "
                + (f"{told} (the parameters: {sorted(known)})" if told else
                   f"choose from {sorted(known)}")
            )  # fmt: skip
        values = {s.name: overrides.get(s.name, s.default) for s in cls.parameter_specs}
        values = {s.name: s.validate(values[s.name]) for s in cls.parameter_specs}
        return cls(values) if family is None else cls(values, family=family)

    def check_values(self, values: Mapping[str, float]) -> None:
        """Whole-set checks beyond single parameters (e.g. the triangle inequality): raise an
        :class:`~perturb.errors.InvalidParameterError` naming the value and the fix, or return
        the fix as a string (as a :class:`ParameterSpec` check does); None accepts."""
        return None

    # ------------------------------------------------------------------ to override
    @classmethod
    @abstractmethod
    def build_system(cls) -> QuasilinearSystem:
        """The symbolic quasilinear system (no numbers: derived once per class)."""

    def epsilon(self) -> float:
        """The value of the expansion parameter ε for these parameters (from the map)."""
        return self.case().epsilon

    def method_options(self) -> dict:
        """Options of :class:`perturb.PoincareMethod` (amplitudes, phase coordinate, branch)."""
        return {}

    def symbol_values(self) -> dict[str, float]:
        """Numeric values of the system's free symbols, by name (from the map)."""
        return self.case().symbol_values

    # ------------------------------------------------------------------ the seam
    @classmethod
    def _map(cls) -> ParameterMap:
        """The declared :attr:`parameter_map`, checked against the system once per class.

        Raises
        ------
        perturb.errors.InvalidSystemError
            A system symbol the map does not cover, or an expression in names that are not
            parameters (one line naming it and the fix).
        """
        key = _class_key(cls)
        if key not in _MAP_CACHE:
            parameters = cls.system().parameters
            user = [s.name for s in cls.parameter_specs]
            declared = dict(declared_map(cls))
            try:
                base = ParameterMap.declare(parameters, user, declared)
            except InvalidSystemError:
                base = None
            traced = traced_declarations(cls, Problem, base)
            if base is None:  # the declarations alone do not cover the system: raise if still not
                base = ParameterMap.declare(parameters, user, {**declared, **traced})
            elif traced:
                try:  # what the methods read as (keys the system does not have: they stand alone)
                    base = ParameterMap.declare(parameters, user, {**declared, **traced})
                except InvalidSystemError:
                    pass
            _MAP_CACHE[key] = base
        return _MAP_CACHE[key]

    def case(self) -> Case:
        """These values as a :class:`perturb.case.Case`: the system, the map, the point, the
        family; its other points are checked as :meth:`create` checks them."""
        if self._case is None:
            made = Case(
                self.system(), self._map(), self.values, self._family, check=self._checked,
                model_of=self._at, check_columns=self._checked_columns,
                solution_reads=functools.partial(_solution_reads, type(self)),
                evaluates_directly=self._evaluates_directly(),
            )  # fmt: skip
            object.__setattr__(self, "_case", made)
        return self._case

    def _checked(self, values: dict) -> dict:
        return dict(type(self).create(**values).values)

    def _checked_columns(self, values: dict, grid: dict, size: int):
        return checked_columns(self, Problem, values, grid, size)

    def _at(self, case: Case) -> Problem:
        """This problem at ``case``'s values (checked by :meth:`_checked` already) and family:
        the model a case gives its clients (:attr:`perturb.case.Case.model`)."""
        made = attrs.evolve(self, values=case.values, family=case.family)
        object.__setattr__(made, "_case", case)
        return made

    # ------------------------------------------------------------------ shared machinery
    @classmethod
    def system(cls) -> QuasilinearSystem:
        key = _class_key(cls)
        if key not in _SYSTEM_CACHE:
            _SYSTEM_CACHE[key] = cls.build_system()
        return _SYSTEM_CACHE[key]

    def _carry(self, problem: Problem) -> Problem:
        """``problem`` (made at other values) on this one's family and derivation."""
        if self._family is None and self._symbolic is None:
            return problem
        return attrs.evolve(problem, family=self._family, symbolic=self._symbolic)

    def _family_options(self, order: int) -> tuple[QuasilinearSystem, dict]:
        """The system and the options that define the frame of :meth:`families` at ``order``.

        The options of :meth:`method_options` without ``branch`` (the families are the branches):
        ``amplitudes`` that the problem fixes stay fixed (a parameter such as Duffing's
        ``amplitude`` picks the member of a continuum; a first integral fixes the disk's G(0)).
        """
        options = {k: v for k, v in self.method_options().items() if k != "branch"}
        return self.system(), options

    def families(self, order: int = 1) -> FamilyList:
        """Every family of periodic solutions (:func:`perturb.find_families`), carried to ``order``.

        For a driven problem: every branch of the steady-state response at these parameter
        values (``trivial``, ``lower``, ``middle``, ``upper``, …), each with its stability."""
        system, options = self._family_options(order)
        work = work_of(system)  # free: find_families; driven: the branches at these values
        key = (*_class_key(type(self)), order, system, repr(sorted(options.items())))
        key = (*key, *work.point_key(self))
        if key not in _FAMILY_CACHE:
            _FAMILY_CACHE[key] = work.families(self, system, order, options)
        return _FAMILY_CACHE[key]

    def _family_solution(self, order: int, name: str) -> PeriodicSolution:
        """The solution of the family ``name`` at ``order``.

        Raises :class:`~perturb.errors.UnknownNameError` (listing the known names) for an unknown
        name. A continuum whose free amplitude is not a parameter of this problem gives a solution
        with status ``UNDETERMINED`` that says so.
        """
        family = self.families(order).get(name)
        solution = family.solution
        own = set(self.system().parameters)
        open_ = [p.name for p in solution.system.parameters if p not in own]
        if open_ and solution.success:
            return attrs.evolve(
                solution,
                status=Status.UNDETERMINED,
                message=(
                    f"family {name!r} is a continuum in {open_}, which {self.name} does not fix "
                    f"(its parameters: {sorted(s.name for s in self.parameter_specs)}); "
                    "solve the system from Python with a value for it"
                ),
            )
        return solution

    def solve(self, order: int = 1, family: str | None = None) -> PeriodicSolution:
        """The symbolic periodic solution (cached per class, order and method options).

        ``family`` (or the problem's own: ``create(family=NAME)``) names a family of
        :meth:`families` to follow instead of the one :meth:`method_options` selects. A driven problem's solution is the
        branch of its steady-state response at these parameter values (default: the largest
        amplitude; :meth:`families` lists them all).
        """
        name = family if family is not None else self._family
        work = work_of(self.system())  # free: one solution for all points; driven: a branch here
        if name is not None:
            return work.solve(
                self, order, {}, name, named=lambda n: self._family_solution(order, n)
            )
        options = self.method_options()
        key = (*_class_key(type(self)), order, _options_key(options))
        key = (*key, *work.point_key(self))
        if key not in _SOLUTION_CACHE:
            _SOLUTION_CACHE[key] = work.solve(self, order, options)
        return _SOLUTION_CACHE[key]

    def state_names(self) -> tuple[str, ...]:
        """Names of the state components :meth:`state` returns (a driven problem's phase
        θ = Ωt last)."""
        return quasilinear_state_names(self.system())

    def state(self, solution: PeriodicSolution, t) -> dict[str, np.ndarray]:
        """The state along ``solution`` at physical times ``t``, by name."""
        return state_along(solution, t, parameter_value_of(self), self.symbol_values())

    def with_parameters(self, **values) -> Problem:
        """The same problem with some parameters changed (validated as by :meth:`create`), on the
        same family (the Model hook a sweep makes its points with)."""
        return self._carry(type(self).create(**{**self.values, **values}))

    def period(self, solution: PeriodicSolution) -> float:
        """The period in physical time."""
        return float(solution.period_at(parameter_value_of(self), self.symbol_values()))

    def __getattr__(self, name: str):
        """A member that left the class (:data:`MOVED`): what replaces it, with a
        :class:`DeprecationWarning` naming the replacement."""
        moved = MOVED.get(name)
        if moved is None:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        replacement, make = moved
        warnings.warn(
            f"problem.{name}(...) is deprecated and will be removed: use {replacement}",
            DeprecationWarning,
            stacklevel=2,
        )
        return make(self)

    def _evaluates_directly(self) -> bool:
        """True unless the class maps the solution to its own state or period (``state``,
        ``period`` overridden): :attr:`perturb.case.Case.evaluates_directly`."""
        own = type(self).state is Problem.state and type(self).period is Problem.period
        return own and work_of(self.system()).state_is_solution()  # driven: the phase added


def _steady_state(problem: Problem) -> Callable:
    from perturb.response import steady_state_of

    return lambda order=1: steady_state_of(problem, order)


#: The members that left :class:`Problem` (each a function of the problem now, or the
#: constructor's keyword), by name: ``(replacement, the old call made from it)``. A script that
#: calls one still gets its answer, with a :class:`DeprecationWarning` naming the replacement;
#: a class that defines one of the hooks among them is read as before
#: (:mod:`perturb.validation.truth`).
MOVED: dict[str, tuple[str, Callable]] = {
    "original_rhs": (
        "perturb.validation.original_rhs(problem)",
        lambda problem: lambda solution=None: original_rhs(problem),
    ),
    "original_equations": (
        "perturb.validation.original_equations(problem, y0)",
        lambda problem: lambda y0=None: original_equations(problem, y0),
    ),
    "with_epsilon": (
        "perturb.validation.with_epsilon(problem, eps)",
        lambda problem: lambda eps: with_epsilon(problem, eps),
    ),
    "steady_state": ("perturb.response.steady_state_of(problem, order)", _steady_state),
    "with_family": (
        "Problem.create(..., family=NAME) (or problem.case().with_family(NAME).model)",
        lambda problem: lambda name: problem.case().with_family(name).model,
    ),
}
