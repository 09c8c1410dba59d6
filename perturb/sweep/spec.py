"""What a sweep computes: :class:`SweepSpec` (checked), its quantities and its fingerprint.

The spec is small and picklable: it travels to the workers inside each task (with the
:class:`~perturb.sweep.derive.Derivation`), and its :meth:`~SweepSpec.fingerprint` is stored in
the store's attributes so that ``--resume`` continues only the very same sweep.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Sequence

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    DEFAULT_PERIODS,
    DEFAULT_TOL,
    MAX_ORDER,
    MAX_OUTPUT_SAMPLES,
    MAX_TIMES,
    SAMPLES_PER_PERIOD,
    SWEEP_FAMILY_PROBES,
)
from perturb.cost import check_cost, sweep_cost
from perturb.errors import InvalidParameterError, PerturbError, bad_value
from perturb.sweep.derive import Derivation
from perturb.sweep.grid import Grid, check_names, check_size
from perturb.validation.capabilities import label_of
from perturb.validation.model import Model

__all__ = [
    "RESERVED_DIMS",
    "STORE_FORMAT",
    "SweepJob",
    "SweepSpec",
    "check_family",
    "check_spec",
]

#: Version of the store's layout (bumped when variables or attributes change meaning).
STORE_FORMAT = 1

#: Dimensions of the store besides the swept parameters.
RESERVED_DIMS = ("component", "time", "multiplier", "check")


def _times(value) -> tuple:
    array = np.atleast_1d(np.asarray(value, dtype=float))
    return tuple(float(v) for v in array.ravel())


@frozen
class SweepSpec:
    """A sweep, checked (see :func:`check_spec`).

    Attributes
    ----------
    model : Model
        The problem with its fixed parameters (the swept ones are replaced at each point).
    grid : Grid
    order : int
    validate : bool
        Shoot and judge every point (:func:`perturb.validation.validate`).
    times : tuple of float
        Physical times of the state recorded at each point.
    tol, periods : float
        The validation's accuracy tolerance and trajectory horizon (as ``perturb validate``).
    integrator : str or None
        The validation's integrator (None: its default choice).
    derive : str
        ``"auto"`` or ``"per-point"`` (:mod:`perturb.sweep.derive`).
    """

    model: Model
    grid: Grid
    order: int = 1
    validate: bool = False
    times: tuple = field(default=(0.0,), converter=_times)
    tol: float = DEFAULT_TOL
    periods: float = DEFAULT_PERIODS
    integrator: str | None = None
    derive: str = "auto"

    @property
    def label(self) -> str:
        return label_of(self.model)

    def fixed_parameters(self) -> dict[str, float]:
        """Every parameter in force that is not swept."""
        swept = set(self.grid.names)
        return {k: v for k, v in self.model.case().values.items() if k not in swept}

    def settings(self) -> dict:
        """The settings that define the sweep's numbers (JSON-ready)."""
        return {
            "order": self.order,
            "validate": self.validate,
            "times": list(self.times),
            "tol": self.tol,
            "periods": self.periods,
            "integrator": self.integrator,
            "derive": self.derive,
        }

    def fingerprint(self, version: str) -> str:
        """SHA-256 of everything the sweep's numbers depend on: the problem (its class and its
        model at the grid's first point, which names its family and fixed values), the grid, the
        settings and the perturb version."""
        try:
            first = self.model.case().at(**self.grid.point(0)).model
        except (PerturbError, ValueError):  # a point the problem refuses: the model as given
            first = None
        text = json.dumps(
            {
                "format": STORE_FORMAT,
                "problem": self.label,
                "class": type(self.model).__qualname__,
                "model": repr(first if first is not None else self.model),
                "grid": self.grid.as_list(),
                "settings": self.settings(),
                "version": version,
            },
            sort_keys=True,
        )
        return hashlib.sha256(text.encode()).hexdigest()


@frozen
class SweepJob:
    """What a task needs: the spec and the derivation plan (the solution is rebuilt per worker).

    Attributes
    ----------
    spec : SweepSpec
    derivation : Derivation
    key : str
        The spec's :meth:`~SweepSpec.fingerprint` (stored with the results; it names the tasks).
    """

    spec: SweepSpec
    derivation: Derivation
    key: str

    def fill_first(self) -> tuple[int, ...]:
        """The axes a chunk spans first: with one derivation per distinct parameter set, those
        that do not enter it (a chunk then needs one derivation)."""
        if not self.derivation.entering:
            return ()
        names = self.spec.grid.names
        return tuple(
            i for i in range(len(names) - 1, -1, -1) if names[i] not in self.derivation.entering
        )


def model_values(model: Model, grid: Grid) -> list[float]:
    """The model's own values of the swept parameters (a point it accepts, to probe with)."""
    values = model.case().values
    return [values[name] for name in grid.names]


def _order(order) -> int:
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or order < 1:
        raise bad_value("order", order, "pass an integer >= 1")
    if order > MAX_ORDER:
        raise bad_value("order", order, f"pass an integer <= {MAX_ORDER}")
    return int(order)


def _positive(name: str, value, fix: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise bad_value(name, value, fix) from None
    if isinstance(value, bool) or not (math.isfinite(number) and number > 0):
        raise bad_value(name, value, fix)
    return number


def check_spec(
    model: Model,
    axes: Sequence,
    *,
    order=1,
    validate=False,
    times=(0.0,),
    tol=DEFAULT_TOL,
    periods=DEFAULT_PERIODS,
    integrator=None,
    derive="auto",
    yes=False,
) -> SweepSpec:
    """The :class:`SweepSpec` of these arguments, every one checked before any work.

    Raises
    ------
    perturb.errors.UnknownNameError
        An axis over a parameter the problem does not have (the closest is suggested), an
        unknown integrator.
    perturb.errors.InvalidParameterError
        A repeated axis, a parameter both swept and fixed, more points than allowed without
        ``yes``, a bad order, tolerance, horizon or times, a model that cannot be re-created at
        other values, an axis name that is one of the store's own dimensions.
    """
    if not isinstance(model, Model):
        raise bad_value(
            "problem", model, "pass a problem instance (problems.get_problem(name).create(...))"
        )
    grid = axes if isinstance(axes, Grid) else Grid(tuple(axes))
    known = list(model.case().values)
    check_names(grid.axes, known, label_of(model))
    for name in grid.names:
        if name in RESERVED_DIMS:
            raise InvalidParameterError(
                f"grid axis {name!r}: the store uses {name!r} for its own dimension; this "
                "parameter cannot be swept by name (rename it in the problem)"
            )
    check_size(grid.size, bool(yes))
    try:
        sweepable = (
            model.case().at(**dict(zip(grid.names, model_values(model, grid), strict=True))).model
        )
    except (PerturbError, ValueError):
        sweepable = True  # it can be re-created; these values it refuses (each point says so)
    if sweepable is None:
        raise InvalidParameterError(
            f"`problem` = {label_of(model)!r} cannot be re-created at other parameter values (its "
            "with_parameters gives none): it cannot be swept"
        )
    order = _order(order)
    tol = _positive("tol", tol, f"pass a positive relative tolerance such as {DEFAULT_TOL}")
    periods = _positive("periods", periods, "pass a positive number of periods, e.g. 10")
    if validate and periods * SAMPLES_PER_PERIOD > MAX_OUTPUT_SAMPLES:  # validate's own rule
        raise bad_value(
            "periods", periods,
            f"at most {MAX_OUTPUT_SAMPLES // SAMPLES_PER_PERIOD} periods (the validation's "
            "trajectory horizon)",
        )  # fmt: skip
    try:
        times = _times(times)
    except (TypeError, ValueError):
        raise bad_value("times", times, "pass a list of finite times") from None
    if not times or len(times) > MAX_TIMES or not all(math.isfinite(t) for t in times):
        raise bad_value("times", times, f"pass 1 to {MAX_TIMES} finite times")
    check_cost(sweep_cost(grid.size, order, bool(validate), len(times)), bool(yes))
    if integrator is not None:
        from perturb.oracle import choose

        choose(integrator)  # an unknown name fails here, before any work
    if derive not in ("auto", "per-point"):
        raise bad_value("derive", derive, "choose 'auto' or 'per-point'")
    return SweepSpec(
        model=model,
        grid=grid,
        order=order,
        validate=bool(validate),
        times=times,
        tol=tol,
        periods=periods,
        integrator=integrator,
        derive=derive,
    )


def check_family(model: Model, name: str, grid: Grid, order: int) -> Model:
    """``model`` following the family ``name`` (at a point of the grid where it exists: the
    swept values are replaced at every point), once the family is known to exist somewhere on
    the grid: at the model's own values, or else at one of :data:`SWEEP_FAMILY_PROBES` points
    spread over the grid (a driven problem's ``upper`` branch exists only past the fold, so the
    family is looked for along the grid, not at the default values alone). A point where the
    family does not exist says so in its status.

    Raises
    ------
    perturb.errors.UnknownNameError
        The family exists at none of these points (the message lists the names found).
    """
    from perturb.errors import UnknownNameError

    found: list[str] = []
    candidates = [model]
    size = grid.size
    picks = np.unique(np.linspace(0, size - 1, min(SWEEP_FAMILY_PROBES, size)).round().astype(int))
    for index in picks:
        try:
            candidates.append(model.case().at(**grid.point(int(index))).model)
        except (PerturbError, ValueError):
            continue  # a point the problem refuses: it says so in its own status
    for candidate in candidates:
        try:
            families = candidate.families(order)
        except (PerturbError, ValueError):
            continue
        names = [f.name for f in families]
        if name in names:  # the swept values are replaced at every point: this one is as good
            return candidate.case().with_family(name).model
        found += [n for n in names if n not in found]
    raise UnknownNameError(
        f"`family` = {name!r} is a family at none of the grid's points probed (its first, last "
        f"and {len(picks) - 2 if len(picks) > 2 else 0} between) nor at the problem's values: "
        f"choose from {found}"
    )
