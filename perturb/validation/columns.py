"""Many parameter sets of one model at once: :class:`ParameterColumns`.

What :meth:`perturb.validation.Model.parameter_columns` gives a sweep: for P points (the values
of some parameters changed, as :meth:`~perturb.validation.Model.with_parameters` would change
them), each point's ε, its value of the solution's own parameter and of the system's symbols as
arrays, the one model whose solution serves every valid point, and for each point the message
that ``with_parameters`` raises there ("" where the values are valid). A model offers it only
where these are exactly what its points would give one by one.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from attrs import field, frozen

if TYPE_CHECKING:
    from perturb.validation.model import Model

__all__ = ["ParameterColumns"]


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
    """

    model: Model | None
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
