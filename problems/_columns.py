"""A problem's sweep points as columns: the body of :meth:`problems.Problem.parameter_columns`.

A sweep makes 10⁵ points a second only if it does not make 10⁵ problems. A problem's numbers
are its declared :class:`~perturb.case.ParameterMap` (ε and the symbols' values as expressions
in its parameters), so every point's numbers are columns of the grid
(:meth:`perturb.case.Case.columns`); when its method options do not read the parameters that
change from point to point, every valid point's solution is the same too: :func:`problem_columns` gives them, validated exactly as
:meth:`~problems.Problem.create` validates each point (the same checks, in the same order, the
same messages). Any other problem gets None, and the sweep makes its points one by one.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from inspect import getattr_static

import attrs
import numpy as np

from perturb import PerturbError, Regime
from perturb.validation import ParameterColumns
from perturb.validation.columns import reciprocal

__all__ = ["problem_columns"]

#: The methods of :class:`~problems.Problem` a point's numbers and solution come from: a class
#: that overrides one of them computes its own, and its points are made one by one.
OWN_METHODS = (
    "create",
    "with_parameters",
    "epsilon",
    "symbol_values",
    "parameter_value",
    "case",
    "solve",
    "family_options",
    "__attrs_post_init__",
)


class _ReadRecorder(dict):
    """A problem's values that note the names read (every name, when iterated or copied)."""

    def __init__(self, values: Mapping):
        super().__init__(values)
        self.read: set[str] = set()

    def _everything(self) -> None:
        self.read.update(super().keys())

    def __getitem__(self, key):
        self.read.add(key)
        return super().__getitem__(key)

    def get(self, key, default=None):
        self.read.add(key)
        return super().get(key, default)

    def __contains__(self, key) -> bool:
        self.read.add(key)
        return super().__contains__(key)

    def __iter__(self):
        self._everything()
        return super().__iter__()

    def keys(self):
        self._everything()
        return super().keys()

    def values(self):
        self._everything()
        return super().values()

    def items(self):
        self._everything()
        return super().items()

    def copy(self):
        self._everything()
        return dict(super().items())

    def __repr__(self) -> str:
        self._everything()
        return super().__repr__()

    def __or__(self, other):
        self._everything()
        return dict(super().items()) | other

    def __ror__(self, other):
        self._everything()
        return other | dict(super().items())


def _options_read(problem) -> set[str] | None:
    """The names of ``problem.values`` that its method options read (None: they raised)."""
    probe = attrs.evolve(problem)
    recorder = _ReadRecorder(problem.values)
    object.__setattr__(probe, "values", recorder)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            probe.method_options()
    except Exception:  # noqa: BLE001 - the points will say it, one by one
        return None
    return recorder.read


def _varying(columns: Mapping[str, np.ndarray]) -> set[str]:
    return {name for name, c in columns.items() if c.size and not np.all(c == c[0])}


def _message(exc: BaseException) -> str:
    return str(exc) or type(exc).__name__


def _validated(problem, columns: dict[str, np.ndarray], size: int, base: type):
    """Per point, the error :meth:`Problem.create` raises there and the warnings it gives
    (None: some check raised what ``create`` would not report as bad values)."""
    cls = type(problem)
    errors = [""] * size
    notes = [""] * size
    for spec in cls.parameter_specs:  # create's order: the first invalid parameter is named
        if spec.name not in columns:
            continue
        unique, inverse = np.unique(columns[spec.name], return_inverse=True)
        found = []
        for value in unique.tolist():
            try:
                spec.validate(value)
            except (PerturbError, ValueError) as exc:
                found.append(_message(exc))
            except Exception:  # noqa: BLE001 - the per-point route records it as a failure
                return None
            else:
                found.append("")
        for i, k in enumerate(inverse.tolist()):
            if found[k] and not errors[i]:
                errors[i] = found[k]
    whole_set = getattr_static(cls, "check_values") is not getattr_static(base, "check_values")
    if whole_set:  # whole-set checks: point by point
        names = [s.name for s in cls.parameter_specs]
        rows = {n: columns[n].tolist() for n in names if n in columns}
        for i in range(size):
            if errors[i]:
                continue
            values = {n: (rows[n][i] if n in rows else problem.values[n]) for n in names}
            values = {n: float(v) for n, v in values.items()}
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    problem.check_values(values)
                except (PerturbError, ValueError) as exc:
                    errors[i] = _message(exc)
                except Exception:  # noqa: BLE001 - the per-point route records it as a failure
                    return None
            if caught:
                notes[i] = "; ".join(dict.fromkeys(str(w.message) for w in caught))
    return errors, notes


def problem_columns(
    problem, columns: Mapping[str, np.ndarray], base: type
) -> ParameterColumns | None:
    """:meth:`problems.Problem.parameter_columns` (see the module docstring); ``base`` is
    :class:`~problems.Problem` itself, whose methods a class may override."""
    cls = type(problem)
    if any(getattr_static(cls, name) is not getattr_static(base, name) for name in OWN_METHODS):
        return None
    system = problem.system()
    if not system.frame.one_solution_for_all_points:  # a driven point has its own steady state
        return None
    try:
        case = problem.case()
    except PerturbError:  # a map that does not cover the system: the points say it one by one
        return None
    if case.map.epsilon is None:
        return None
    known = {s.name for s in cls.parameter_specs}
    columns = {name: np.asarray(c, dtype=float).ravel() for name, c in columns.items()}
    sizes = {c.size for c in columns.values()}
    if not columns or len(sizes) != 1 or not set(columns) <= known:
        return None
    size = sizes.pop()
    read = _options_read(problem)
    if read is None or read & _varying(columns):
        return None
    validated = _validated(problem, columns, size, base)
    if validated is None:
        return None
    errors, notes = validated
    valid = np.array([not e for e in errors], dtype=bool)

    def column(name: str) -> np.ndarray:
        value = columns[name] if name in columns else np.full(size, float(problem.values[name]))
        return np.where(valid, value, np.nan)

    computed = case.columns({name: column(name) for name in columns})
    eps = np.where(valid, computed.epsilon, np.nan)
    parameter_value = reciprocal(eps, valid) if system.regime is Regime.LARGE else eps
    if parameter_value is None:
        return None
    symbols = {name: np.where(valid, c, np.nan) for name, c in computed.symbols.items()}
    model = None
    if valid.any():
        first = int(np.flatnonzero(valid)[0])
        model = problem.case().at(**{n: float(c[first]) for n, c in columns.items()}).model
    return ParameterColumns(model, parameter_value, eps, symbols, errors, notes)
