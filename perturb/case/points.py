"""Many points of a case at once, checked: :class:`CasePoints` (a sweep's fast route).

A sweep makes 10⁵ points a second only if it does not make 10⁵ models. A case knows its map
(ε and the symbols' values as expressions in the user parameters), so every point's numbers are
the map evaluated over columns (:meth:`perturb.case.Case.columns`); what the case must be told is
declared by its front door (:class:`perturb.case.Case`'s fields):

* ``check_columns`` — the model's own checks of many points at once (each point's message and
  the warnings it gives, exactly as the point checked alone); without it the case checks each
  point with ``check``;
* ``solution_reads`` — the user parameters the solution depends on besides the system's symbols
  (the method options read them) at a point; None: unknown, every point may have its own
  solution.

:meth:`perturb.case.Case.points` offers the points only where one solution serves them all and
the numbers are what the points give one by one; otherwise None, and the caller makes each
point's model.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping

import numpy as np
from attrs import field, frozen

from perturb.cache import held_warnings
from perturb.errors import PerturbError

__all__ = ["CasePoints", "checked_point", "each_checked", "reciprocal"]


def _float_array(value) -> np.ndarray:
    return np.asarray(value, dtype=float)


@frozen(eq=False)
class CasePoints:
    """The points of a case as arrays, checked (see the module docstring).

    Attributes
    ----------
    model : object or None
        The model of the first valid point (:attr:`perturb.case.Case.model`): its
        ``solve(order)`` is every valid point's solution (None: no point is valid).
    parameter_value : ndarray, shape (P,)
        Each point's ε, or μ = 1/ε for a large-parameter system (NaN where invalid).
    epsilon : ndarray, shape (P,)
        Each point's ε (NaN where invalid).
    symbol_values : dict of str to ndarray of shape (P,)
        Each system symbol's value at each point, by name.
    errors : tuple of str
        Per point, the message its check raises; "" where valid.
    notes : tuple of str
        Per point, the warnings its check gave ("; "-joined; "" for none).

    Examples
    --------
    Duffing's oscillator at three amplitudes, one of which it refuses:

    >>> import numpy as np
    >>> from problems import get_problem
    >>> duffing = get_problem("duffing").create(eps=0.1)
    >>> points = duffing.case().points({"amplitude": np.array([0.5, -1.0, 2.0])})
    >>> points.valid().tolist()
    [True, False, True]
    >>> points.symbol_values["amplitude"].tolist(), points.epsilon.tolist()
    ([0.5, nan, 2.0], [0.1, nan, 0.1])
    >>> points.errors[1]
    '`amplitude` = -1 is invalid: give a value > 0'
    >>> points.model.solve(2) is duffing.case().at(amplitude=2.0).model.solve(2)
    True
    """

    model: object | None
    parameter_value: np.ndarray = field(converter=_float_array)
    epsilon: np.ndarray = field(converter=_float_array)
    symbol_values: dict = field(converter=dict)
    errors: tuple = field(converter=tuple)
    notes: tuple = field(converter=tuple)

    @property
    def size(self) -> int:
        """The number of points P."""
        return len(self.errors)

    def valid(self) -> np.ndarray:
        """Boolean mask of the points whose values are valid."""
        return np.array([not e for e in self.errors], dtype=bool)


def reciprocal(values: np.ndarray, valid: np.ndarray) -> np.ndarray | None:
    """``1 / values`` (ε from μ, or μ from ε) where ``valid``; None if a valid value is 0 (the
    per-point route then reports the point's own error)."""
    if np.any(values[valid] == 0):
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        return 1.0 / values


def message_of(exc: BaseException) -> str:
    """What a point's failed check says (its type's name when it says nothing)."""
    return str(exc) or type(exc).__name__


def checked_point(check, point: Mapping) -> tuple[str, str] | None:
    """``(error, note)`` of ``check(point)``: its message where it refuses the point ("" where
    not) and the warnings it gives ("; "-joined); None where it raised anything but a refusal
    of bad values (the per-point route records that as a failure)."""
    error = ""
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            check(point)
        except (PerturbError, ValueError) as exc:
            error = message_of(exc)
        except Exception:  # noqa: BLE001 - the per-point route records it as a failure
            return None
    return error, "; ".join(dict.fromkeys(str(w.message) for w in caught))


def each_checked(check, values: Mapping, grid: Mapping[str, np.ndarray], size: int):
    """``(errors, notes)``: :func:`checked_point` at each point of ``grid`` (the rest
    ``values``); None where a check raised anything but a refusal of bad values."""
    rows = {name: column.tolist() for name, column in grid.items()}
    errors, notes = [""] * size, [""] * size
    for i in range(size):
        found = checked_point(check, {**values, **{name: row[i] for name, row in rows.items()}})
        if found is None:
            return None
        errors[i], notes[i] = found
    return errors, notes


def points_of(case, grid: Mapping[str, np.ndarray]) -> CasePoints | None:
    """:meth:`perturb.case.Case.points` (see the module docstring)."""
    from perturb.system import Regime

    grid = {str(name): np.asarray(c, dtype=float).ravel() for name, c in grid.items()}
    sizes = {c.size for c in grid.values()}
    if not grid or len(sizes) != 1 or not set(grid) <= set(case.map.user):
        return None
    size = sizes.pop()
    varying = {name for name, c in grid.items() if c.size and not np.all(c == c[0])}
    reads = None if case.solution_reads is None else case.solution_reads(case.values)
    if reads is None or reads & varying:
        return None
    if not case.system.frame.one_solution_for_all_points:  # a driven point has its own
        return None
    if case.map.epsilon is None:
        return None
    if case.check_columns is not None:
        checked = case.check_columns(case.values, grid, size)
    else:
        checked = each_checked(case.check, case.values, grid, size)
    if checked is None:
        return None
    errors, notes = checked
    valid = np.array([not e for e in errors], dtype=bool)
    masked = {name: np.where(valid, c, np.nan) for name, c in grid.items()}
    computed = case.columns(masked)
    eps = np.where(valid, computed.epsilon, np.nan)
    own = case.system.parameter.name
    if case.system.regime is not Regime.LARGE:
        parameter_value = eps
    elif own in case.map.user and case.map.epsilon == 1 / case.map.user_symbols[own]:
        parameter_value = masked.get(own, np.where(valid, float(case.values[own]), np.nan))
        if np.any(parameter_value[valid] == 0):  # ε = 1/0: the point says it, one by one
            return None
    else:
        parameter_value = reciprocal(eps, valid)
    if parameter_value is None:
        return None
    symbols = {name: np.where(valid, c, np.nan) for name, c in computed.symbols.items()}
    model = None
    if valid.any():
        first = int(np.flatnonzero(valid)[0])
        model = case.at(**{name: float(c[first]) for name, c in grid.items()}).model
    return CasePoints(model, parameter_value, eps, symbols, errors, notes)
