"""Frequency-response plots: every branch (stable solid, unstable dashed), folds, backbone, the
true motion's points and curves; and the Floquet multipliers along the branches."""

from __future__ import annotations

import math

import numpy as np

from perturb.errors import bad_value
from perturb.report.marks import PointMark, point_mark
from perturb.report.plots.style import new_figure, publication_style
from perturb.report.plots.true_curve import draw_true_curves

__all__ = ["plot_floquet_along_branches", "plot_frequency_response"]


def _check(result):
    if not hasattr(result, "response") or not hasattr(result.response, "points"):
        raise bad_value(
            "result", type(result).__name__, "pass the ProblemResponse of problem_response()"
        )


def plot_frequency_response(result, *, coordinate: str | None = None, ax=None, title=None):
    """Amplitude against the swept parameter for every branch.

    Parameters
    ----------
    result : perturb.response.model.ProblemResponse
    coordinate : str, optional
        Whose amplitude (default: the first resonant coordinate).
    ax : matplotlib.axes.Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Every continued order-N curve, stable stretches solid, unstable dashed, where the series'
        terms do not decrease dotted grey; the grid points whose labels the series does not
        vouch for (:func:`perturb.report.marks.point_mark`: outside its domain, beyond its
        validity, a stability within its error of 1) as hollow grey circles; folds as open
        circles, branch points, Neimark-Sacker and period-doubling points by their own markers,
        each fold's uncertainty band (the series' own estimate) shaded ("?" where it cannot
        tell); the backbone dotted; the true orbits
        (``perturb response --validate K``) as crosses at their true amplitude, the analytic points
        off the truth by more than ``tol`` ringed. The amplitude is the response's ``measure``
        (max ``|x|`` by default), named on the axis.
        With ``--true``, the true curves in black beside them, their special points and where
        the two part (:func:`~perturb.report.plots.true_curve.draw_true_curves`).

    Raises
    ------
    ValueError
        When ``result`` is not a :func:`~perturb.response.model.problem_response` result.

    Examples
    --------
    >>> import numpy as np
    >>> from problems import get_problem
    >>> from perturb.response.model import problem_response
    >>> result = problem_response(get_problem("forced-duffing").create(), "Omega",
    ...                           np.linspace(0.95, 1.15, 9))
    >>> fig = plot_frequency_response(result)
    >>> fig.axes[0].get_xlabel()
    'Omega'
    """
    _check(result)
    response = result.response
    coordinate = coordinate or response.coordinates[0]
    measure = getattr(response, "measure", "initial")
    from perturb.steady.measures import MEASURES

    with publication_style():
        if ax is None:
            fig, axes = new_figure(1, 1, height=4.0)
            ax = axes[0, 0]
        else:
            fig = ax.figure
        low, high = min(response.grid), max(response.grid)
        if response.curves:
            for curve in response.curves:
                _draw_curve(ax, curve, coordinate, measure)
        else:  # a response without continued curves: its grid points, traced
            for branch in response.branches(coordinate):
                for a, b in zip(branch, branch[1:], strict=False):
                    good = bool(a.stable and b.stable)
                    ax.plot([a.value, b.value],
                            [a.amplitude(coordinate, measure), b.amplitude(coordinate, measure)],
                            "-" if good else "--", color="C0" if good else "C3", lw=1.4)  # fmt: skip
        ax.plot([], [], "-", color="C0", label="stable")
        ax.plot([], [], "--", color="C3", label="unstable")
        if any(not all(c.series_ok) for c in response.curves):
            ax.plot([], [], ":", color="0.6", label="series terms not decreasing")
        marked = [p for p in response.points if point_mark(p) is not PointMark.NONE]
        if marked:
            ax.plot([p.value for p in marked], [p.amplitude(coordinate, measure) for p in marked],
                    "o", ms=5, mfc="none", color="0.55",
                    label="label not vouched for by the series")  # fmt: skip
        folds = [f for f in response.folds if low <= f.value <= high]
        _draw_fold_bands(ax, folds, result.parameter)
        if folds:
            ax.plot([f.value for f in folds], [f.amplitude(coordinate, measure) for f in folds],
                    "o", mfc="none", color="k", label="fold")  # fmt: skip
        marks = {"branch-point": ("s", "branch point"), "neimark-sacker": ("D", "Neimark-Sacker"),
                 "period-doubling": ("^", "period doubling")}  # fmt: skip
        for kind, (marker, label) in marks.items():
            found = [p for p in response.special if p.kind == kind and low <= p.value <= high]
            if found:
                heights = [p.amplitude(coordinate, measure) for p in found]
                ax.plot([p.value for p in found], heights, marker, mfc="none", color="k",
                        label=label)  # fmt: skip
        if result.backbone is not None and result.backbone.coordinate == coordinate:
            ax.plot(result.backbone.values, result.backbone.amplitudes, ":", color="0.4",
                    label="backbone")  # fmt: skip
        shot = [t for t in result.true if t.success]
        if shot:
            first = coordinate == response.coordinates[0]
            heights = [t.true_amplitude if first else math.nan for t in shot]
            ax.plot([t.value for t in shot], heights, "x", color="k", label="true motion")
            off = [t for t in shot if t.within_tol is False]
            if off:
                ax.plot([t.value for t in off], [t.amplitude for t in off], "o", ms=9,
                        mfc="none", color="C1", label="analytic off the truth by > tol")  # fmt: skip
        draw_true_curves(ax, result.true_curve, coordinate, result.parameter)
        ax.set_xlabel(result.parameter)
        ax.set_ylabel(f"{MEASURES.get(measure, 'amplitude')} of {coordinate}")
        ax.set_xlim(low, high)
        ax.legend(loc="best", frameon=False)
        ax.set_title(title or f"{result.problem}: frequency response, order {response.order}")
    return fig


def _draw_fold_bands(ax, folds, parameter: str) -> None:
    """Each fold's uncertainty band (the series' own estimate: ± the distance to the same fold
    one order lower), shaded; a fold whose band the series cannot tell is marked "?"."""
    labelled = False
    for f in folds:
        if math.isfinite(f.uncertainty):
            ax.axvspan(f.value - f.uncertainty, f.value + f.uncertainty, color="0.8", alpha=0.5,
                       lw=0, label=None if labelled else "fold uncertainty (series)")  # fmt: skip
            labelled = True
        else:
            ax.annotate("?", (f.value, 0), xycoords=("data", "axes fraction"), xytext=(0, 4),
                        textcoords="offset points", ha="center", fontsize=9, color="0.3")  # fmt: skip


def _draw_curve(ax, curve, coordinate: str, measure: str) -> None:
    """One continued curve: stable stretches solid, unstable dashed, where the series' terms do
    not decrease dotted grey; the style changes where the label does."""
    x = np.asarray(curve.values)
    y = np.asarray(curve.measures[measure][coordinate])
    kind = [
        ("series" if not ok else ("stable" if st else "unstable"))
        for st, ok in zip(curve.stable, curve.series_ok, strict=True)
    ]
    styles = {"stable": ("-", "C0"), "unstable": ("--", "C3"), "series": (":", "0.6")}
    start = 0
    for k in range(1, len(x) + 1):
        if k == len(x) or kind[k] != kind[start]:
            stop = min(k + 1, len(x))  # overlap one point: no gap where the style changes
            style, colour = styles[kind[start]]
            ax.plot(x[start:stop], y[start:stop], style, color=colour, lw=1.4)
            start = k


def plot_floquet_along_branches(result, *, ax=None, title=None):
    """The largest modulus of the order-N Floquet multipliers along each branch (1 dotted):
    above 1 the branch is unstable.

    Parameters
    ----------
    result : perturb.response.model.ProblemResponse
    ax : matplotlib.axes.Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        When ``result`` is not a :func:`~perturb.response.model.problem_response` result.

    Examples
    --------
    >>> import numpy as np
    >>> from problems import get_problem
    >>> from perturb.response.model import problem_response
    >>> result = problem_response(get_problem("forced-duffing").create(), "Omega",
    ...                           np.linspace(0.95, 1.15, 9))
    >>> fig = plot_floquet_along_branches(result)
    >>> fig.axes[0].get_ylabel()
    'max |Floquet multiplier|'
    """
    _check(result)
    response = result.response
    with publication_style():
        if ax is None:
            fig, axes = new_figure(1, 1, height=3.4)
            ax = axes[0, 0]
        else:
            fig = ax.figure
        low, high = min(response.grid), max(response.grid)
        if response.curves:  # along each continued curve, inside the sweep
            for i, curve in enumerate(response.curves):
                x = np.asarray(curve.values)
                keep = (x >= low) & (x <= high)
                ax.plot(x[keep], np.asarray(curve.largest)[keep], "-", color=f"C{i % 10}", lw=1.2)
        else:
            for i, branch in enumerate(response.branches()):
                largest = [max((abs(z) for z in p.multipliers), default=math.nan) for p in branch]
                ax.plot([p.value for p in branch], largest, "-", color=f"C{i % 10}", lw=1.2)
        shot = [t for t in result.true if t.success]
        if shot:
            ax.plot([t.value for t in shot], [t.floquet_max for t in shot], "x", color="k",
                    label="true motion")  # fmt: skip
            ax.legend(loc="best", frameon=False)
        ax.axhline(1.0, ls=":", color="0.4")
        ax.set_xlabel(result.parameter)
        ax.set_ylabel("max |Floquet multiplier|")
        ax.set_title(title or f"{result.problem}: stability along the branches")
    return fig
