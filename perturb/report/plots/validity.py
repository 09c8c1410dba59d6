"""Validity maps: a sweep over two parameters drawn as maps (verdict regions, the orbit error with
its tolerance contour, the measured order slope, the period).

Inputs are plain: the two axes' values (``x`` along the first dimension of each 2-D array, ``y``
along the second, as :func:`perturb.sweep` orders them) and the arrays. NaN cells (points not
computed, or where the quantity could not be measured) are left blank. An axis whose values are
positive and evenly spaced in their logarithm is drawn on a log scale.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots.style import display_name, new_figure, publication_style

__all__ = ["plot_error_map", "plot_period_map", "plot_slope_map", "plot_verdict_map"]

#: Colours of the verdicts by label (colour-blind safe; a verdict added later gets the next colour
#: of matplotlib's cycle).
VERDICT_COLOURS = {
    "valid": "#1a9850",
    "lower_order": "#91cf60",
    "undecided": "#bdbdbd",
    "invalid": "#d73027",
    "not_computed": "#ffffff",
}

#: Relative spread of the ratios of consecutive values under which an axis counts as logarithmic.
LOG_AXIS_SPREAD = 1e-6

#: Size of a map, inches (a square-ish plot with room for the colour bar).
MAP_WIDTH, MAP_HEIGHT = 5.6, 4.2


def _axis(values, argument: str) -> np.ndarray:
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise bad_value(argument, values, "pass a 1-D sequence of numbers") from None
    if array.ndim != 1 or array.size < 1 or not np.all(np.isfinite(array)):
        raise bad_value(argument, values, "pass a 1-D sequence of finite numbers")
    if array.size > 1 and not (np.all(np.diff(array) > 0) or np.all(np.diff(array) < 0)):
        raise bad_value(argument, values, "the values must be strictly monotonic (a grid axis)")
    return array


def _field(values, x: np.ndarray, y: np.ndarray, argument: str) -> np.ndarray:
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise bad_value(argument, "<not numbers>", "pass a 2-D array of numbers") from None
    if array.shape != (x.size, y.size):
        raise bad_value(
            argument,
            f"<array of shape {array.shape}>",
            f"pass shape ({x.size}, {y.size}): x along the first axis, y along the second",
        )
    return array


def _is_log(values: np.ndarray) -> bool:
    if values.size < 3 or np.any(values <= 0):
        return False
    ratios = values[1:] / values[:-1]
    return bool(np.ptp(ratios) <= LOG_AXIS_SPREAD * abs(ratios[0]) and abs(ratios[0] - 1) > 1e-3)


def _edges(values: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around the grid values (midpoints, and half a step beyond the ends)."""
    v = np.log(values) if log else values
    if v.size == 1:
        step = abs(v[0]) * 0.05 or 0.5
        edges = np.array([v[0] - step, v[0] + step])
    else:
        middle = (v[1:] + v[:-1]) / 2
        edges = np.concatenate(
            [[v[0] - (middle[0] - v[0])], middle, [v[-1] + (v[-1] - middle[-1])]]
        )
    return np.exp(edges) if log else edges


def _map_axes(x, y, xname: str, yname: str, title: str | None):
    fig, axes = new_figure(1, 1, width=MAP_WIDTH, height=MAP_HEIGHT)
    ax = axes[0, 0]
    logs = (_is_log(x), _is_log(y))
    if logs[0]:
        ax.set_xscale("log")
    if logs[1]:
        ax.set_yscale("log")
    ax.set_xlabel(display_name(xname))
    ax.set_ylabel(display_name(yname))
    if title:
        ax.set_title(title)
    return fig, ax, _edges(x, logs[0]), _edges(y, logs[1])


def _names(xname, yname) -> None:
    for argument, value in (("xname", xname), ("yname", yname)):
        if not isinstance(value, str) or not value:
            raise bad_value(argument, value, "pass the parameter's name")


def plot_verdict_map(x, y, codes, labels: Mapping, *, xname: str, yname: str, title=None):
    """The verdict of every point as coloured regions, with a legend of the verdicts present.

    Parameters
    ----------
    x, y : array_like
        The two swept parameters' values.
    codes : array_like of int, shape (len(x), len(y))
        The verdict codes (the sweep's ``verdict`` variable).
    labels : mapping code -> label
        What each code means (the variable's ``labels`` attribute: ``{-1: "not_computed", 0:
        "valid", ...}``).
    xname, yname : str
        The parameters' names.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    Valid on the first two rows, invalid on the last (the codes and labels of a sweep's
    ``verdict`` variable):

    >>> import numpy as np
    >>> from perturb.report.plots import plot_verdict_map
    >>> codes = np.array([[0, 0, 0, 0], [0, 0, 0, 0], [1, 1, 1, 1]])
    >>> fig = plot_verdict_map([0.5, 0.75, 1.0], [0.1, 0.2, 0.3, 0.4], codes,
    ...                        {0: "valid", 1: "invalid"}, xname="r0", yname="gamma3_0")
    >>> [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    ['valid', 'invalid']
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    _names(xname, yname)
    field = _field(codes, x, y, "codes")
    if not isinstance(labels, Mapping) or not labels:
        raise bad_value("labels", labels, "pass a mapping code -> label")
    known = {int(k): str(v) for k, v in labels.items()}
    present = [int(c) for c in np.unique(field[np.isfinite(field)])]
    stray = [c for c in present if c not in known]
    if stray:
        raise bad_value("codes", stray, f"every code must be one of {sorted(known)}")
    with publication_style():
        from matplotlib.colors import BoundaryNorm, ListedColormap, to_hex
        from matplotlib.patches import Patch

        codes_all = sorted(known)
        cycle = iter(to_hex(f"C{i}") for i in range(10))
        colours = [VERDICT_COLOURS.get(known[c]) or next(cycle) for c in codes_all]
        cmap = ListedColormap(colours)
        bounds = np.concatenate([np.array(codes_all) - 0.5, [codes_all[-1] + 0.5]])
        fig, ax, xe, ye = _map_axes(x, y, xname, yname, title)
        ax.pcolormesh(xe, ye, field.T, cmap=cmap, norm=BoundaryNorm(bounds, cmap.N), shading="flat")
        handles = [
            Patch(
                facecolor=colours[codes_all.index(c)],
                edgecolor="0.5",
                label=known[c].replace("_", " "),
            )
            for c in present
        ]
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    return fig


def plot_error_map(
    x, y, error, *, tol: float, xname: str, yname: str, error_label="orbit error", title=None
):
    """log₁₀ of the error at every point, with the contour where it equals ``tol``.

    Parameters
    ----------
    x, y : array_like
        The two swept parameters' values.
    error : array_like, shape (len(x), len(y))
        The error (> 0; NaN or <= 0 where not measured: blank).
    tol : float
        The validation's tolerance (> 0): its contour separates accurate from inaccurate.
    xname, yname : str
        The parameters' names.
    error_label : str, optional
        What the error is, for the colour bar.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    An error growing like x² y, with its contour at the tolerance 0.1:

    >>> import numpy as np
    >>> from perturb.report.plots import plot_error_map
    >>> x, y = np.linspace(0.1, 1.0, 10), np.linspace(0.1, 1.0, 8)
    >>> fig = plot_error_map(x, y, np.outer(x**2, y), tol=0.1, xname="eps", yname="amplitude")
    >>> fig.axes[1].get_ylabel()
    'log$_{10}$ orbit error'
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    _names(xname, yname)
    field = _field(error, x, y, "error")
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise bad_value("tol", tol, "pass the tolerance, a number > 0")
    with np.errstate(all="ignore"):
        logs = np.where(field > 0, np.log10(field), np.nan)
    with publication_style():
        fig, ax, xe, ye = _map_axes(x, y, xname, yname, title)
        mesh = ax.pcolormesh(xe, ye, logs.T, cmap="viridis", shading="flat")
        fig.colorbar(mesh, ax=ax, label=f"log$_{{10}}$ {error_label}")
        level = math.log10(tol)
        finite = logs[np.isfinite(logs)]
        if x.size > 1 and y.size > 1 and finite.size and finite.min() < level < finite.max():
            lines = ax.contour(
                x, y, logs.T, levels=[level], colors="k", linewidths=1.2, linestyles="solid"
            )
            ax.clabel(lines, fmt={level: f"tol {tol:g}"}, fontsize=8)
    return fig


def plot_slope_map(
    x, y, slope, *, expected: float, band: float | None = None, xname: str, yname: str, title=None
):
    """The measured order slope at every point, coloured about the expected ``order + 1``, with
    the contour ``expected - band`` below which the order check fails.

    Parameters
    ----------
    x, y : array_like
        The two swept parameters' values.
    slope : array_like, shape (len(x), len(y))
        The measured slopes (the sweep's ``order_slope``; NaN where not measured: blank).
    expected : float
        ``order + 1``: the colour map is centred on it.
    band : float, optional
        How far below ``expected`` a slope passes the order check (``SLOPE_TOLERANCE``).
    xname, yname : str
        The parameters' names.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.report.plots import plot_slope_map
    >>> slope = np.array([[3.0, 2.9, 2.2], [3.0, 3.1, 2.0]])
    >>> fig = plot_slope_map([0.1, 0.2], [1.0, 2.0, 3.0], slope, expected=3.0, band=0.5,
    ...                      xname="eps", yname="amplitude")
    >>> fig.axes[1].get_ylabel()
    'measured slope (expected 3)'
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    _names(xname, yname)
    field = _field(slope, x, y, "slope")
    if not (isinstance(expected, int | float) and math.isfinite(expected)):
        raise bad_value("expected", expected, "pass order + 1")
    if band is not None and not (
        isinstance(band, int | float) and math.isfinite(band) and band > 0
    ):
        raise bad_value("band", band, "pass the slope tolerance, a number > 0")
    with publication_style():
        from matplotlib.colors import TwoSlopeNorm

        fig, ax, xe, ye = _map_axes(x, y, xname, yname, title)
        finite = field[np.isfinite(field)]
        spread = max(float(np.max(np.abs(finite - expected))) if finite.size else 0.0, 0.5)
        norm = TwoSlopeNorm(vcenter=expected, vmin=expected - spread, vmax=expected + spread)
        mesh = ax.pcolormesh(xe, ye, field.T, cmap="RdBu", norm=norm, shading="flat")
        fig.colorbar(mesh, ax=ax, label=f"measured slope (expected {expected:g})")
        if band is not None and x.size > 1 and y.size > 1 and finite.size:
            level = expected - band
            if finite.min() < level < finite.max():
                lines = ax.contour(
                    x, y, field.T, levels=[level], colors="k", linewidths=1.2, linestyles="solid"
                )
                ax.clabel(lines, fmt={level: f"{level:g}"}, fontsize=8)
    return fig


def plot_period_map(x, y, period, *, xname: str, yname: str, unit: str = "", title=None):
    """The analytic period at every point, with a few labelled contours.

    Parameters
    ----------
    x, y : array_like
        The two swept parameters' values.
    period : array_like, shape (len(x), len(y))
        The periods (the sweep's ``period``).
    xname, yname : str
        The parameters' names.
    unit : str, optional
        The period's unit, for the colour bar.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.report.plots import plot_period_map
    >>> eps, a = np.linspace(0.0, 0.2, 5), np.linspace(0.5, 1.5, 4)
    >>> period = 2 * np.pi / (1 + 0.375 * np.outer(eps, a**2))  # Duffing's first order
    >>> fig = plot_period_map(eps, a, period, xname="eps", yname="amplitude")
    >>> fig.axes[1].get_ylabel()
    'period'
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    _names(xname, yname)
    field = _field(period, x, y, "period")
    with publication_style():
        fig, ax, xe, ye = _map_axes(x, y, xname, yname, title)
        mesh = ax.pcolormesh(xe, ye, field.T, cmap="cividis", shading="flat")
        fig.colorbar(mesh, ax=ax, label=f"period{f' [{unit}]' if unit else ''}")
        finite = field[np.isfinite(field)]
        if x.size > 1 and y.size > 1 and finite.size and np.ptp(finite) > 0:
            lines = ax.contour(x, y, field.T, levels=5, colors="w", linewidths=0.8)
            ax.clabel(lines, fontsize=7, fmt="%.4g")
    return fig
