"""The state against time: analytic beside true, the error between them, and phase portraits.

Inputs are plain arrays so that any result can be plotted: times ``t`` (1-D) and mappings
``name → array`` (one value per time) for the analytic state and, optionally, the true motion,
e.g. ``problem.state(solution, t)`` and the rows of an integrated :class:`perturb.oracle.Trajectory`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots._inputs import as_series, as_times, pick_names, units_for
from perturb.report.plots.style import (
    ANALYTIC_LABEL,
    TRUE_LABEL,
    axis_label,
    display_name,
    finish_stack,
    legend_above,
    new_figure,
    publication_style,
)

__all__ = ["plot_error", "plot_phase", "plot_time_series"]


def _draw_pair(ax, x, y, x_true=None, y_true=None):
    """The analytic curve (solid) and the true one (dashed, drawn on top so both stay visible)."""
    ax.plot(x, y, color="C0", lw=1.6, label=ANALYTIC_LABEL)
    if x_true is not None:
        ax.plot(x_true, y_true, color="k", lw=1.0, ls=(0, (4, 3)), label=TRUE_LABEL, zorder=3)


def plot_time_series(
    t,
    analytic: Mapping,
    true: Mapping | None = None,
    *,
    names: Sequence[str] | None = None,
    time_unit: str = "s",
    units: Mapping[str, str] | None = None,
    title: str | None = None,
):
    """Each state component against time, one panel per component, analytic and true overlaid.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times, increasing.
    analytic : mapping name → array_like of shape (n,)
        The analytic state at ``t`` (e.g. ``problem.state(solution, t)``).
    true : mapping name → array_like of shape (n,), optional
        The true motion at the same times (drawn dashed on top of the analytic curve).
    names : sequence of str, optional
        Components to plot, in order (default: every key of ``analytic``).
    time_unit : str, optional
        Unit of ``t`` for the axis label (``""`` for dimensionless time).
    units : mapping name → str, optional
        Unit of each component; a component not listed is labelled dimensionless (``[1]``).
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``t`` is not increasing, a name is missing or an array does not match ``t``.
    perturb.errors.MissingDependencyError
        If matplotlib is not installed.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2 * np.pi, 50)
    >>> analytic = {"x": np.cos(t), "xdot": -np.sin(t)}
    >>> true = {"x": np.cos(1.01 * t), "xdot": -1.01 * np.sin(1.01 * t)}
    >>> from perturb.report.plots import plot_time_series
    >>> fig = plot_time_series(t, analytic, true, time_unit="")
    >>> print([ax.get_ylabel() for ax in fig.axes])
    ['$x$ [1]', '$\\\\dot{x}$ [1]']
    """
    times = as_times(t)
    names = pick_names(names, analytic)
    series = as_series(analytic, times.size, "analytic", names)
    reference = None if true is None else as_series(true, times.size, "true", names)
    unit_of = units_for(units, names)
    with publication_style():
        fig, axes = new_figure(len(names), 1, sharex=True)
        for ax, name in zip(axes[:, 0], names, strict=True):
            _draw_pair(
                ax,
                times,
                series[name],
                None if reference is None else times,
                None if reference is None else reference[name],
            )
            ax.set_ylabel(axis_label(display_name(name), unit_of[name]))
        finish_stack(fig, axes, times, time_unit, reference is not None, title)
    return fig


def plot_error(
    t,
    analytic: Mapping,
    true: Mapping,
    *,
    names: Sequence[str] | None = None,
    relative: bool = True,
    time_unit: str = "s",
    units: Mapping[str, str] | None = None,
    title: str | None = None,
):
    """``|analytic − true|`` against time on a logarithmic axis, one line per component.

    Parameters
    ----------
    t, analytic, true, names, time_unit, units, title
        As in :func:`plot_time_series` (``true`` is required).
    relative : bool, optional
        Divide each component's error by its amplitude ``max |true|`` (default), so components of
        different sizes share one axis.  A component whose amplitude is zero is plotted absolute
        and says so in the legend.

    Returns
    -------
    matplotlib.figure.Figure
        Exact zeros (e.g. at ``t = 0`` when both start from the same state) are not drawn on the
        logarithmic axis; the lines still hold them.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``true`` is missing, ``t`` is not increasing, a name is missing or an array does not match.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2 * np.pi, 50)
    >>> analytic = {"x": np.cos(t), "xdot": -np.sin(t)}
    >>> true = {"x": np.cos(1.01 * t), "xdot": -1.01 * np.sin(1.01 * t)}
    >>> from perturb.report.plots import plot_error
    >>> fig = plot_error(t, analytic, true, time_unit="")
    >>> len(fig.axes[0].lines), fig.axes[0].get_yscale()
    (2, 'log')
    """
    times = as_times(t)
    names = pick_names(names, analytic)
    series = as_series(analytic, times.size, "analytic", names)
    if true is None:
        raise bad_value("true", None, "pass the true motion (name -> array) to measure an error")
    reference = as_series(true, times.size, "true", names)
    unit_of = units_for(units, names)
    with publication_style():
        fig, axes = new_figure(1, 1)
        ax = axes[0, 0]
        for i, name in enumerate(names):
            error = np.abs(series[name] - reference[name])
            amplitude = float(np.max(np.abs(reference[name])))
            label = display_name(name)
            if relative and amplitude > 0:
                error = error / amplitude
            elif relative:
                label += " (absolute: zero amplitude)"
            elif unit_of[name]:
                label += f" [{unit_of[name]}]"
            ax.plot(times, error, color=f"C{i % 10}", label=label)
        ax.set_yscale("log", nonpositive="mask")
        ax.set_xlim(times[0], times[-1])
        ax.set_xlabel(axis_label("$t$", time_unit))
        if relative:
            ax.set_ylabel("|analytic − true| / amplitude [1]")
        elif len(names) == 1:
            ax.set_ylabel(axis_label("|analytic − true|", unit_of[names[0]]))
        else:
            ax.set_ylabel("|analytic − true| (units in legend)")
        if len(names) > 1:
            ax.legend(loc="best")
        if title:
            fig.suptitle(title)
    return fig


def _pairs(pairs) -> list[tuple[str, str]]:
    fix = "pass a list of (coordinate, velocity) name pairs, e.g. [('x', 'xdot')]"
    if isinstance(pairs, str) or not isinstance(pairs, Sequence) or not pairs:
        raise bad_value("pairs", pairs, fix)
    checked = []
    for pair in pairs:
        if (
            isinstance(pair, str)
            or not isinstance(pair, Sequence)
            or len(pair) != 2
            or not all(isinstance(name, str) for name in pair)
        ):
            raise bad_value("pairs", pairs, fix)
        checked.append((pair[0], pair[1]))
    return checked


def _length(values: Mapping, argument: str) -> int:
    if not isinstance(values, Mapping) or not values:
        raise bad_value(argument, values, "pass a non-empty mapping name -> array")
    return int(np.size(next(iter(values.values()))))


def plot_phase(
    analytic: Mapping,
    true: Mapping | None = None,
    pairs: Sequence[tuple[str, str]] = (("x", "xdot"),),
    *,
    units: Mapping[str, str] | None = None,
    title: str | None = None,
):
    """Phase portraits: one panel per pair of components (e.g. a coordinate and its velocity).

    Parameters
    ----------
    analytic : mapping name → array_like
        The analytic state at some times (all arrays of one length).
    true : mapping name → array_like, optional
        The true motion (its own times; all its arrays of one length), drawn dashed on top.
    pairs : sequence of (str, str), optional
        ``(horizontal, vertical)`` component names of each panel.
    units, title
        As in :func:`plot_time_series`.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``pairs`` is not a list of name pairs, or a name is missing.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2 * np.pi, 50)
    >>> analytic = {"x": np.cos(t), "xdot": -np.sin(t)}
    >>> true = {"x": np.cos(1.01 * t), "xdot": -1.01 * np.sin(1.01 * t)}
    >>> from perturb.report.plots import plot_phase
    >>> fig = plot_phase(analytic, true)
    >>> len(fig.axes), len(fig.axes[0].lines)  # one panel; analytic and true
    (1, 2)
    """
    pairs = _pairs(pairs)
    names = list(dict.fromkeys(name for pair in pairs for name in pair))
    series = as_series(analytic, _length(analytic, "analytic"), "analytic", names)
    reference = None
    if true is not None:
        reference = as_series(true, _length(true, "true"), "true", names)
    unit_of = units_for(units, names)
    with publication_style():
        # a square-ish panel per pair: a closed orbit should look like one
        fig, axes = new_figure(1, len(pairs), height=3.6, width=min(3.6 * len(pairs) + 0.6, 9.6))
        for ax, (h, v) in zip(axes[0], pairs, strict=True):
            _draw_pair(
                ax,
                series[h],
                series[v],
                None if reference is None else reference[h],
                None if reference is None else reference[v],
            )
            ax.set_xlabel(axis_label(display_name(h), unit_of[h]))
            ax.set_ylabel(axis_label(display_name(v), unit_of[v]))
        if reference is not None:
            legend_above(axes[0, 0])
        if title:
            fig.suptitle(title)
    return fig
