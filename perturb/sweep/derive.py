"""Derive once: which derivation serves the grid's points (:func:`plan`), and the model of a point.

Three ways, chosen on the driver (:class:`Derivation`):

``own``
    The problem's own solution serves every point: it is symbolic in the parameters (Duffing,
    van der Pol, any problem whose parameters are symbols of its system, the disk at order 1), or
    the swept parameters do not enter its derivation (the disk's ``r0``: only ε changes). Each
    point is then exactly what ``perturb validate`` computes there.
``symbolic``
    The problem offers a symbolic derivation (it defines ``symbolic_derivation()``,
    :class:`SymbolicDerivation`: the rigid bodies above order 1) and a swept
    parameter enters its specialised derivation: the solution symbolic in the body's parameters is
    derived once and every point evaluates it. ``perturb validate`` derives for the point's
    values instead; the two are the same exact series, evaluated in another form, so they agree
    to rounding (``docs/sweeps.md``); ask for ``per-point`` to get its very numbers.
``per-point``
    Each point's own derivation, as ``perturb validate`` does it, kept by the problem's caches:
    once per distinct derivation and worker process — when asked for, when the problem offers
    no symbolic derivation, or when each distinct derivation serves many points (a map over one
    entering parameter and one that does not enter: the disk's ``gamma3_0`` and ``r0``), which
    is then cheaper than evaluating the heavier symbolic solution everywhere.

A worker rebuilds the derivation once per process from this small description (the problem's
memory and disk caches keep it); shipping the pickled solution instead was measured and is
slower for the solutions that matter (``benchmarks/bench_sweep.md``).
"""

from __future__ import annotations

import enum
import math
from collections.abc import Mapping
from typing import Protocol, runtime_checkable

import numpy as np
from attrs import frozen

from perturb._defaults import SWEEP_POINTS_PER_DERIVATION
from perturb.case import CasePoints
from perturb.errors import InvalidParameterError, PerturbError
from perturb.validation.capabilities import label_of
from perturb.validation.model import Model

__all__ = ["DeriveMode", "Derivation", "SymbolicDerivation", "plan", "symbolic_derivation"]


@runtime_checkable
class SymbolicDerivation(Protocol):
    """A model whose solution can be derived once, symbolic in its parameters, for every
    parameter set of a sweep (the rigid bodies; a problem whose solution is symbolic already
    does not need it): a capability the model declares by defining the method.

    Examples
    --------
    >>> from perturb.sweep.derive import SymbolicDerivation
    >>> from problems import get_problem
    >>> isinstance(get_problem("disk").create(), SymbolicDerivation)
    True
    >>> isinstance(get_problem("duffing").create(), SymbolicDerivation)
    False
    """

    def symbolic_derivation(self): ...


def symbolic_derivation(model):
    """The model with its solution derived symbolic in its parameters
    (:class:`SymbolicDerivation`), or None: not offered.

    Examples
    --------
    >>> from perturb.sweep.derive import symbolic_derivation
    >>> from problems import get_problem
    >>> symbolic_derivation(get_problem("duffing").create()) is None  # symbolic already
    True
    """
    return model.symbolic_derivation() if isinstance(model, SymbolicDerivation) else None


class DeriveMode(enum.Enum):
    """How the grid's points get their solution; the values are the messages shown to users."""

    OWN = "the problem's own solution serves every point (one derivation)"
    SYMBOLIC = "one derivation symbolic in the swept parameters serves every point"
    PER_POINT = "each point's own derivation (once per distinct derivation and worker)"


#: What ``derive=`` accepts: the choice made here, or each point's own derivation.
DERIVE_CHOICES = ("auto", "per-point")


@frozen
class Derivation:
    """The derivation plan of a sweep (data: shipped to the workers inside the job).

    Attributes
    ----------
    mode : DeriveMode
    reason : str
        Why this mode (for the store's attributes and the log).
    """

    mode: DeriveMode
    reason: str
    #: The swept parameters that enter the derivation (per point: chunks keep them fixed).
    entering: tuple = ()

    def model_at(self, base: Model, values: Mapping[str, float]) -> Model:
        """The model of the point ``values`` (raises the model's own error for bad values)."""
        model = base.case().at(**values).model
        if model is None:
            raise InvalidParameterError(
                f"`problem` = {label_of(base)!r} cannot be re-created at other parameter values "
                "(its with_parameters gives none): it cannot be swept"
            )
        return _symbolic(model) if self.mode is DeriveMode.SYMBOLIC else model

    def columns_at(self, base: Model, columns: Mapping) -> CasePoints | None:
        """The points whose changed values are ``columns`` (name -> array), all at once
        (:meth:`perturb.case.Case.points`; None: each point's model is made one by one)."""
        model = _symbolic(base) if self.mode is DeriveMode.SYMBOLIC else base
        return model.case().points(columns)


def _symbolic(model: Model) -> Model:
    """The model's symbolic derivation (:func:`symbolic_derivation`; the plan chose this mode
    only where it is offered)."""
    symbolic = symbolic_derivation(model)
    if symbolic is None:
        raise InvalidParameterError(
            f"`problem` = {label_of(model)!r} offers no symbolic derivation: sweep it per point"
        )
    return symbolic


def _seen_in_columns(base: Model, axis, reference: tuple) -> int | None:
    """:func:`_entering` for one axis from the model's columns (no model per value): the number
    of distinct symbol values other than ``reference`` (at least 1 if any differs), 0 if none
    differs, None if the model does not offer columns."""
    try:
        found = base.case().points({axis.name: axis.array()})
    except (PerturbError, ValueError):
        return None
    if found is None:
        return None
    valid = found.valid()
    names = [name for name, _ in reference]
    if set(found.symbol_values) != set(names):
        return None
    if not names or not valid.any():
        return 0
    rows = np.stack([found.symbol_values[name][valid] for name in names], axis=1)
    distinct = {tuple(row) for row in np.unique(rows, axis=0).tolist()}
    values = tuple(value for _, value in reference)
    if distinct <= {values}:
        return 0
    return len(distinct - {values}) or 1


def _entering(base: Model, axes) -> dict[str, int]:
    """The axes whose values change the numbers the derivation is made for (symbol_values),
    with how many distinct sets of those numbers each gives."""
    reference = tuple(sorted(base.symbol_values().items()))
    found = {}
    for axis in axes:
        seen = _seen_in_columns(base, axis, reference)
        if seen is not None:
            if seen:
                found[axis.name] = seen
            continue
        seen = {reference}
        for value in axis.values:
            try:
                other = base.case().at(**{axis.name: value}).model
            except (PerturbError, ValueError):
                continue  # a value the problem refuses: that point will say so
            if other is not None:
                seen.add(tuple(sorted(other.symbol_values().items())))
        if len(seen) > 1:
            found[axis.name] = len(seen - {reference}) or 1
    return found


def plan(base: Model, axes, order: int, derive: str = "auto") -> tuple[Derivation, object]:
    """The derivation for a sweep of ``base`` over ``axes`` at ``order``, and the solution
    derived here (which also fills the caches the workers of this machine read).

    With ``derive="auto"``, a problem whose derivation the swept parameters enter and that
    offers a symbolic one is derived once symbolically — unless its own derivations would each
    serve :data:`SWEEP_POINTS_PER_DERIVATION` points or more (a map over one entering parameter
    and one that only scales ε): then each distinct derivation is made once, which is cheaper
    and gives ``perturb validate``'s very numbers.

    Raises
    ------
    perturb.errors.InvalidParameterError
        ``derive`` not one of :data:`DERIVE_CHOICES`.
    """
    if derive not in DERIVE_CHOICES:
        raise InvalidParameterError(
            f"`derive` = {derive!r} is invalid: choose from {list(DERIVE_CHOICES)}"
        )
    entering = _entering(base, axes)
    if derive == "per-point":
        return Derivation(
            DeriveMode.PER_POINT, "asked for (derive='per-point')", tuple(entering)
        ), None
    own = base.solve(order)
    if own.system.parameters:
        return Derivation(
            DeriveMode.OWN, "the problem's solution is symbolic in its parameters"
        ), own
    if not entering:
        return Derivation(
            DeriveMode.OWN, "the swept parameters do not enter the problem's derivation"
        ), own
    names = ", ".join(entering)
    points = math.prod(axis.size for axis in axes)
    derivations = math.prod(entering.values())
    if points >= SWEEP_POINTS_PER_DERIVATION * derivations:
        return Derivation(
            DeriveMode.PER_POINT,
            f"{names} enter the derivation, {derivations} distinct derivations serve "
            f"{points} points: each made once",
            tuple(entering),
        ), own
    symbolic = symbolic_derivation(base)
    if symbolic is not None:
        solution = symbolic.solve(order)
        return Derivation(
            DeriveMode.SYMBOLIC,
            f"{names} enter the derivation: derived once, symbolic in them",
        ), solution
    return Derivation(
        DeriveMode.PER_POINT,
        f"{names} enter the derivation and the problem offers no symbolic one",
        tuple(entering),
    ), own
