"""A scene file and its strict parser: :class:`Scene`, :func:`parse_scene` (read from a file by
:mod:`perturb.scene.files`).

A scene is a TOML file naming a problem, its parameters, the solve settings and the outputs wanted
(``perturb report SCENE.toml --output DIR``)::

    [problem]
    name = "disk"                 # a registered name, "path/to/file.py:Class" or "module:Class"
    [parameters]                  # any problem parameter; the rest take the problem's defaults
    r0 = 0.755155
    [solve]
    order = 1                     # default: 3 for a driven problem, 1 for a free one
    periods = 3                   # horizon, in periods of the analytic solution
    [outputs]                     # each false (empty) unless asked for
    table = true
    plots = ["time_series", "error"]

The parser knows every section and key: an unknown one, a value of the wrong type or out of range
and malformed TOML raise :class:`perturb.errors.SceneError` with one line naming the file, the line
where it can be found, the value and the fix, and the closest known name (difflib). Problem and
parameter names are checked later, against the problem (:mod:`perturb.scene.checks`): this
module does not know the problems (``perturb`` never imports ``problems``).
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable, Mapping

import attrs
from attrs import field, frozen

from perturb._defaults import (
    MAX_ORDER,
    MAX_TIMES,
    MAX_VALIDATE,
    SCENE_MAX_PERIODS,
    SCENE_MAX_REPEAT,
    SCENE_MAX_SAMPLES_PER_PERIOD,
    SCENE_PERIODS,
    SCENE_SAMPLES_PER_PERIOD,
)
from perturb.errors import SceneError
from perturb.scene.checks import Checker, close_name, line_of

__all__ = [
    "EULER_PLOTS",
    "PLOT_FORMATS",
    "PLOT_NAMES",
    "RESPONSE_PLOTS",
    "TRUTH_PLOTS",
    "Outputs",
    "MAP_PLOTS",
    "ResponseSettings",
    "Scene",
    "SweepSettings",
    "WorkPrecisionSettings",
    "parse_scene",
]

#: The plots a scene may ask for (``[outputs] plots``), each a function of perturb.report.plots.
PLOT_NAMES = (
    "time_series",
    "error",
    "phase",
    "convergence",
    "work_precision",
    "euler",
    "orientation",
    "verdict_map",
    "error_map",
    "slope_map",
    "period_map",
    "frequency_response",
    "floquet_multipliers",
)

#: Validity maps of the ``[sweep]`` (two axes); all but the period map need ``validate = true``.
MAP_PLOTS = frozenset({"verdict_map", "error_map", "slope_map", "period_map"})
VALIDATED_MAPS = frozenset({"verdict_map", "error_map", "slope_map"})

#: Plots of the ``[response]`` (a driven problem's frequency response).
RESPONSE_PLOTS = frozenset({"frequency_response", "floquet_multipliers"})


#: Plots drawn beside the true motion: they need an integration of the original equations (the
#: convergence plot the validation's ε scan, the work-precision plot the integrator runs).
TRUTH_PLOTS = frozenset({"time_series", "error", "phase", "convergence", "work_precision"})

#: Plots of a rigid body's Euler angles: they need the angles (of the analytic solution only).
EULER_PLOTS = frozenset({"euler", "orientation"})

#: File formats of the plots: PNG always unless changed, PDF and SVG on request.
PLOT_FORMATS = ("png", "pdf", "svg")


# ---------------------------------------------------------------------------------- value objects
@frozen
class Outputs:
    """What a scene asks to be written; every entry is off unless asked for.

    Attributes
    ----------
    table : bool
        ``solution.csv`` and ``solution.json``: the analytic state over the horizon.
    euler : bool
        ``euler.csv``: the Euler angles of the analytic solution (rigid bodies only).
    validation : bool
        ``validation.json``: the check against the true motion and its verdict.
    work_precision : bool
        ``work_precision.csv``: error against run time of the analytic solution and integrators.
    latex : bool
        ``solution.tex``: the derived formulas as LaTeX.
    sweep : bool
        ``sweep.zarr`` and ``sweep.csv``: the ``[sweep]`` section's points.
    response : bool
        ``response.csv`` and ``response.json``: the ``[response]`` section's frequency response.
    plots : tuple of str
        Names from :data:`PLOT_NAMES`.
    formats : tuple of str
        File formats of each plot, from :data:`PLOT_FORMATS` (default PNG only).
    """

    table: bool = False
    euler: bool = False
    validation: bool = False
    work_precision: bool = False
    latex: bool = False
    sweep: bool = False
    response: bool = False
    plots: tuple = field(default=(), converter=tuple)
    formats: tuple = field(default=("png",), converter=tuple)

    @property
    def needs_truth_trajectory(self) -> bool:
        """Whether the original equations are integrated for the time-series, error or phase plots."""
        return bool({"time_series", "error", "phase"} & set(self.plots))

    @property
    def needs_validation(self) -> bool:
        return self.validation or "convergence" in self.plots

    @property
    def needs_work_precision(self) -> bool:
        return self.work_precision or "work_precision" in self.plots

    @property
    def needs_euler(self) -> bool:
        return self.euler or bool(EULER_PLOTS & set(self.plots))

    @property
    def needs_sweep(self) -> bool:
        return self.sweep or bool(MAP_PLOTS & set(self.plots))

    @property
    def needs_response(self) -> bool:
        return self.response or bool(RESPONSE_PLOTS & set(self.plots))

    @property
    def needs_state(self) -> bool:
        """Whether the analytic state is evaluated over the horizon (tables and state plots)."""
        return self.table or self.needs_truth_trajectory


@frozen
class WorkPrecisionSettings:
    """The ``[work_precision]`` section (defaults: the scene's horizon and order, one run a point)."""

    periods: float | None = None
    orders: int | None = None
    repeat: int = 1


@frozen
class SweepSettings:
    """The ``[sweep]`` section: the grid over the problem's parameters and what each point gets.

    Attributes
    ----------
    grid : tuple of str
        The axes, as ``perturb sweep --grid`` takes them (``"r0=0.5:1:21"``).
    validate : bool
        Validate every point (needed by the verdict, error and slope maps).
    times : tuple of float
        Times of the state recorded at each point.
    workers : int or None
        Worker processes of the local Dask cluster (None: one per core).
    derive : str
        ``"auto"`` or ``"per-point"``.
    """

    grid: tuple = field(converter=tuple)
    validate: bool = False
    times: tuple = field(default=(0.0,), converter=tuple)
    workers: int | None = None
    derive: str = "auto"


@frozen
class ResponseSettings:
    """The ``[response]`` section: the frequency response of a driven problem.

    Attributes
    ----------
    sweep : str
        The swept parameter and its values, as ``perturb response --sweep`` takes them
        (``"Omega=0.95:1.2:51"``).
    validate : int
        Points of each branch shot against the true motion (Floquet multipliers; 0: none).
    """

    sweep: str
    validate: int = 0


@frozen
class Scene:
    """A parsed scene file (data only: :func:`perturb.scene.run.run_scene` computes it).

    Attributes
    ----------
    problem : str
        The problem: a registered name, ``path/to/file.py:Class`` or ``module:Class``.
    family : str or None
        The family of periodic solutions followed (``perturb families``), None for the default.
    parameters : dict
        Parameter values by name; the others take the problem's defaults.
    order : int or None
        ``[solve] order``; None when the scene gives none: the one default order of every
        command (3 for a driven problem, 1 for a free one:
        :attr:`perturb.validation.frames.FrameWork.default_order`), put in when the scene runs
        (:func:`perturb.scene.run.with_order`) and printed in its summary.
    periods : float
        Horizon in periods of the analytic solution.
    samples : int
        Samples per period of the tables and plots.
    integrator : str or None
        The oracle's integrator (None: its default choice).
    tol : float or None
        The validation's accuracy tolerance (None: its default).
    outputs : Outputs
    work_precision : WorkPrecisionSettings
    sweep : SweepSettings or None
        The ``[sweep]`` section, if any (computed only when an output needs it).
    response : ResponseSettings or None
        The ``[response]`` section, if any (computed only when an output needs it).
    source : str
        Where the scene was read from (shown in messages).
    text : str
        The scene file's text (copied into the report folder as written).
    folder : str
        The folder of the scene file: a relative path inside the scene (a problem file,
        ``"my_oscillator.py:MyOscillator"``) is taken from there, not from the working folder
        ("" for a scene given as text: the working folder; :func:`perturb.scene.problem_spec`).
    """

    problem: str
    family: str | None = None
    parameters: dict = field(factory=dict, converter=dict)
    order: int | None = None
    periods: float = float(SCENE_PERIODS)
    samples: int = SCENE_SAMPLES_PER_PERIOD
    integrator: str | None = None
    tol: float | None = None
    outputs: Outputs = field(factory=Outputs)
    work_precision: WorkPrecisionSettings = field(factory=WorkPrecisionSettings)
    sweep: SweepSettings | None = None
    response: ResponseSettings | None = None
    source: str = "<scene>"
    text: str = field(default="", repr=False)
    folder: str = ""

    def error(self, detail: str) -> SceneError:
        """A :class:`SceneError` about this scene, prefixed with its source."""
        return SceneError(f"{self.source}: {detail}")


# ---------------------------------------------------------------------------------- the schema
_SECTIONS = ("problem", "parameters", "solve", "outputs", "work_precision", "sweep", "response")
_OUTPUT_FLAGS = ("table", "euler", "validation", "work_precision", "latex", "sweep", "response")


def _keys(section: str) -> tuple[str, ...]:
    return {
        "problem": ("name", "family"),
        "solve": ("order", "periods", "samples", "integrator", "tol"),
        "outputs": (*_OUTPUT_FLAGS, "plots", "formats"),
        "work_precision": ("periods", "orders", "repeat"),
        "sweep": ("grid", "validate", "times", "workers", "derive"),
        "response": ("sweep", "validate"),
    }[section]


def _section(data: Mapping, name: str, check: Checker) -> dict:
    """The table ``[name]`` (empty when absent), its keys checked against the schema."""
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise check.fail(None, table, f"[{name}] must be a table: write it as a [{name}] section")
    if name == "parameters":
        return table
    known = _keys(name)
    for key in table:
        if key not in known:
            raise SceneError(
                f"{check.source}: "
                + (f"line {line}: " if (line := line_of(check.text, name, key)) else "")
                + f"unknown key {key!r} in [{name}]{close_name(key, known)}; the keys are "
                f"{', '.join(known)}"
            )
    return table


def _parse_data(data: Mapping, source: str, text: str) -> Scene:
    for name in data:
        if name not in _SECTIONS:
            line = line_of(text, name, None)
            where = f"line {line}: " if line else ""
            raise SceneError(
                f"{source}: {where}unknown section [{name}]{close_name(name, _SECTIONS)}; the sections "
                f"are {', '.join(f'[{s}]' for s in _SECTIONS)}"
            )
    checkers: dict[str, Checker] = {s: Checker(source, text, s) for s in _SECTIONS}
    tables = {s: _section(data, s, checkers[s]) for s in _SECTIONS}

    problem, c = tables["problem"], checkers["problem"]
    if "name" not in problem:
        where = "add a [problem] section with " if "problem" not in data else "add "
        raise SceneError(
            f'{source}: the scene names no problem: {where}name = "duffing" (a name from '
            "`perturb list`, path/to/file.py:Class or module:Class)"
        )
    fields: dict = {"problem": c.string("name", problem["name"])}
    if "family" in problem:
        fields["family"] = c.string("family", problem["family"])

    parameters, c = {}, checkers["parameters"]
    for key, value in tables["parameters"].items():
        if isinstance(value, bool) or not isinstance(value, int | float) or math.isnan(value):
            raise c.fail(key, value, "write a real number, e.g. 0.25")
        parameters[key] = float(value)
    fields["parameters"] = parameters

    solve, c = tables["solve"], checkers["solve"]
    readers: dict[str, Callable] = {
        "order": lambda k, v: c.integer(k, v, 1, MAX_ORDER),
        "periods": lambda k, v: c.positive(k, v, SCENE_MAX_PERIODS),
        "samples": lambda k, v: c.integer(k, v, 4, SCENE_MAX_SAMPLES_PER_PERIOD),
        "integrator": c.string,
        "tol": c.positive,
    }
    fields.update({key: readers[key](key, value) for key, value in solve.items()})
    rows = fields.get("periods", SCENE_PERIODS) * fields.get("samples", SCENE_SAMPLES_PER_PERIOD)
    if rows > MAX_TIMES:
        key = "samples" if "samples" in solve else "periods"
        raise c.fail(
            key, solve[key], f"periods x samples = {rows:,.0f} rows of the tables: give at most "
            f"{MAX_TIMES:,} (fewer periods or samples)",
        )  # fmt: skip

    out, c = tables["outputs"], checkers["outputs"]
    flags = {key: c.boolean(key, out[key]) for key in _OUTPUT_FLAGS if key in out}
    if "plots" in out:
        flags["plots"] = c.names("plots", out["plots"], PLOT_NAMES)
    if "formats" in out:
        flags["formats"] = c.names("formats", out["formats"], PLOT_FORMATS)
        if not flags["formats"]:
            raise c.fail("formats", out["formats"], 'name at least one format, e.g. ["png"]')
    fields["outputs"] = Outputs(**flags)

    wp, c = tables["work_precision"], checkers["work_precision"]
    settings = {}
    if "periods" in wp:
        settings["periods"] = c.positive("periods", wp["periods"], SCENE_MAX_PERIODS)
    if "orders" in wp:
        settings["orders"] = c.integer("orders", wp["orders"], 1, MAX_ORDER)
    if "repeat" in wp:
        settings["repeat"] = c.integer("repeat", wp["repeat"], 1, SCENE_MAX_REPEAT)
    fields["work_precision"] = WorkPrecisionSettings(**settings)
    if "sweep" in data:
        fields["sweep"] = _sweep_section(tables["sweep"], checkers["sweep"])
    _check_maps(fields["outputs"], fields.get("sweep"), checkers["outputs"])
    if "response" in data:
        fields["response"] = _response_section(tables["response"], checkers["response"])
    if fields["outputs"].needs_response and "response" not in fields:
        outputs = fields["outputs"]
        asked = "response" if outputs.response else "plots"
        value = True if outputs.response else next(p for p in outputs.plots if p in RESPONSE_PLOTS)
        raise checkers["outputs"].fail(
            asked, value, 'it needs a [response] section (sweep = "Omega=0.9:1.2:61")'
        )
    return Scene(**fields, source=source, text=text)


def _sweep_section(table: dict, c: Checker) -> SweepSettings:
    """The ``[sweep]`` section, its axes parsed (their names are checked against the problem
    later, :func:`check_sweep_names`)."""
    from perturb.errors import InvalidParameterError
    from perturb.sweep.grid import parse_axis

    if "grid" not in table:
        raise c.fail(None, table, 'give grid = ["NAME=START:STOP:N", ...]')
    grid = table["grid"]
    if not isinstance(grid, list) or not grid or not all(isinstance(g, str) for g in grid):
        raise c.fail("grid", grid, 'write a list of axes in quotes, e.g. ["r0=0.5:1:21"]')
    for axis in grid:
        try:
            parse_axis(axis)
        except InvalidParameterError as exc:
            raise c.fail("grid", axis, str(exc).split(": ", 1)[-1]) from None
    settings: dict = {"grid": tuple(grid)}
    if "validate" in table:
        settings["validate"] = c.boolean("validate", table["validate"])
    if "times" in table:
        times = table["times"]
        ok = (
            isinstance(times, list)
            and times
            and all(
                isinstance(t, int | float) and not isinstance(t, bool) and math.isfinite(t)
                for t in times
            )
        )
        if not ok:
            raise c.fail("times", times, "write a list of finite times, e.g. [0.0, 1.5]")
        settings["times"] = tuple(float(t) for t in times)
    if "workers" in table:
        settings["workers"] = c.integer("workers", table["workers"], 1, 4096)
    if "derive" in table:
        derive = table["derive"]
        if derive not in ("auto", "per-point"):
            raise c.fail("derive", derive, 'write "auto" or "per-point"')
        settings["derive"] = derive
    return SweepSettings(**settings)


def _response_section(table: dict, c: Checker) -> ResponseSettings:
    """The ``[response]`` section (its parameter is checked against the problem later,
    :func:`perturb.scene.run.check_scene`)."""
    from perturb.errors import InvalidParameterError
    from perturb.response.model import parse_sweep

    if "sweep" not in table:
        raise c.fail(None, table, 'give sweep = "NAME=START:STOP:N", e.g. "Omega=0.9:1.2:61"')
    sweep = table["sweep"]
    if not isinstance(sweep, str):
        raise c.fail("sweep", sweep, 'write it in quotes, e.g. "Omega=0.9:1.2:61"')
    try:
        parse_sweep(sweep, "sweep")
    except InvalidParameterError as exc:
        raise c.fail("sweep", sweep, str(exc).split(": ", 1)[-1]) from None
    settings: dict = {"sweep": sweep}
    if "validate" in table:
        settings["validate"] = c.integer("validate", table["validate"], 0, MAX_VALIDATE)
    return ResponseSettings(**settings)


def _check_maps(outputs: Outputs, sweep: SweepSettings | None, c: Checker) -> None:
    """The maps and ``sweep = true`` need a ``[sweep]``; maps two axes; three of them validation."""
    maps = [p for p in outputs.plots if p in MAP_PLOTS]
    if (maps or outputs.sweep) and sweep is None:
        asked = "sweep = true" if outputs.sweep else f"plot {maps[0]!r}"
        raise c.fail(
            "sweep" if outputs.sweep else "plots",
            True if outputs.sweep else maps[0],
            f"{asked} needs a [sweep] section (grid = [...])",
        )
    if maps and len(sweep.grid) != 2:
        raise c.fail(
            "plots", maps[0], f"a map needs a [sweep] over two axes, not {len(sweep.grid)}"
        )
    needing = [p for p in maps if p in VALIDATED_MAPS]
    if needing and not sweep.validate:
        raise c.fail("plots", needing[0], "this map needs validate = true in [sweep]")


# ---------------------------------------------------------------------------------- front doors
def parse_scene(text: str, source: str = "<scene>", folder: str = "") -> Scene:
    """The :class:`Scene` a TOML text describes.

    Parameters
    ----------
    text : str
        The scene file's content.
    source : str, optional
        Where it came from, shown at the start of every message.
    folder : str, optional
        The folder relative paths inside the scene are taken from (default: the working folder).

    Returns
    -------
    Scene

    Raises
    ------
    perturb.errors.SceneError
        Malformed TOML (with its line and column), an unknown section or key (with the closest
        known one), a value of the wrong type or range, a missing problem name.

    Examples
    --------
    >>> scene = parse_scene('[problem]\\nname = "duffing"\\n[outputs]\\ntable = true')
    >>> scene.problem, scene.order, scene.outputs.table, scene.outputs.validation
    ('duffing', None, True, False)
    """
    if not isinstance(text, str):
        raise SceneError(f"{source}: the scene must be text (TOML), got {type(text).__name__}")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{source}: malformed TOML: {' '.join(str(exc).split())}") from None
    return attrs.evolve(_parse_data(data, source, text), folder=str(folder))
