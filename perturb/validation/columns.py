"""Many parameter sets of one model at once: :class:`ParameterColumns`.

What :meth:`perturb.validation.Model.parameter_columns` gives a sweep: for P points (the values
of some parameters changed, as :meth:`~perturb.validation.Model.with_parameters` would change
them), each point's ε, its value of the solution's own parameter and of the system's symbols as
arrays, the one model whose solution serves every valid point, and for each point the message
that ``with_parameters`` raises there ("" where the values are valid). A model offers it only
where these are exactly what its points would give one by one.
"""

from __future__ import annotations

import numpy as np
from attrs import field, frozen

__all__ = ["ParameterColumns", "reciprocal", "system_columns"]


def _float_array(value) -> np.ndarray:
    return np.asarray(value, dtype=float)


@frozen(eq=False)
class ParameterColumns:
    """The points of a sweep as arrays (see the module docstring).

    Attributes
    ----------
    model : Model or None
        The model of the first valid point: its ``solve(order)`` is every valid point's solution
        (None: no point is valid).
    parameter_value : ndarray, shape (P,)
        Each point's :meth:`~perturb.validation.Model.parameter_value` (NaN where invalid).
    epsilon : ndarray, shape (P,)
        Each point's :meth:`~perturb.validation.Model.epsilon` (NaN where invalid).
    symbol_values : dict of str to ndarray of shape (P,)
        Each point's :meth:`~perturb.validation.Model.symbol_values`, by name.
    errors : tuple of str
        Per point, the message ``with_parameters`` raises at its values; "" where valid.
    notes : tuple of str
        Per point, the warnings its model gave while it was made ("; "-joined; "" for none).

    Examples
    --------
    Duffing's oscillator at three amplitudes, one of which it refuses:

    >>> import numpy as np
    >>> from problems import get_problem
    >>> duffing = get_problem("duffing").create(eps=0.1)
    >>> points = duffing.parameter_columns({"amplitude": np.array([0.5, -1.0, 2.0])})
    >>> points.valid().tolist()
    [True, False, True]
    >>> points.symbol_values["amplitude"].tolist(), points.epsilon.tolist()
    ([0.5, nan, 2.0], [0.1, nan, 0.1])
    >>> points.errors[1]
    '`amplitude` = -1 is invalid: give a value > 0'
    >>> points.model.solve(2) is duffing.with_parameters(amplitude=2.0).solve(2)
    True
    """

    model: object | None  # a Model (perturb.validation.model), or None
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


def system_columns(model, columns) -> ParameterColumns | None:
    """:meth:`SystemModel.parameter_columns`: the options do not depend on the values, so one
    solution serves every point (not offered for a driven system, whose solution does)."""
    from perturb.errors import InvalidParameterError
    from perturb.system import Regime
    from perturb.validation.values import check_system_values

    system = model.quasilinear
    columns = {str(n): np.asarray(c, dtype=float).ravel() for n, c in columns.items()}
    sizes = {c.size for c in columns.values()}
    if not system.frame.one_solution_for_all_points:
        return None
    if len(sizes) != 1 or not set(columns) <= set(model.values):
        return None
    size = sizes.pop()
    finite = np.all([np.isfinite(c) for c in columns.values()], axis=0)
    errors = [""] * size
    for i in np.flatnonzero(~finite):  # the point's own message
        try:
            check_system_values(system, {**model.values, **{n: c[i] for n, c in columns.items()}})
        except InvalidParameterError as exc:
            errors[i] = str(exc)

    def column(name: str) -> np.ndarray:
        value = columns.get(name, np.full(size, model.values[name]))
        return np.where(finite, value, np.nan)

    parameter_value = column(system.parameter.name)
    large = system.regime is Regime.LARGE
    eps = reciprocal(parameter_value, finite) if large else parameter_value
    if eps is None:
        return None
    symbols = {p.name: column(p.name) for p in system.parameters}
    first = None
    if finite.any():
        i = int(np.flatnonzero(finite)[0])
        first = model.case().at(**{n: float(c[i]) for n, c in columns.items()}).model
    return ParameterColumns(first, parameter_value, eps, symbols, errors, [""] * size)
