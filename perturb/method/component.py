"""One root of the amplitude equations, the value object the root finders return
(:mod:`perturb.method.components` for the affine roots, :mod:`perturb.method.projective` for the
homogeneous ones)."""

from __future__ import annotations

from attrs import frozen

__all__ = ["Component"]


@frozen
class Component:
    """One root of the amplitude equations: values of the solved unknowns, the free amplitudes.

    Parameters
    ----------
    values : dict
        ``{unknown: value}``; values may depend on the ``free`` symbols and on unknowns the
        equations leave to later orders.
    free : tuple of sympy.Symbol
        The generating amplitudes the root leaves free (empty: an isolated root).
    """

    values: dict
    free: tuple
