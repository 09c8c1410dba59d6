"""Frequency-response plots: every branch (stable solid, unstable dashed), folds, backbone, the
true motion's points and curves; and the Floquet multipliers along the branches."""

from __future__ import annotations

import math

from perturb.errors import bad_value
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
        Stable segments solid, unstable dashed, folds as open circles, the backbone dotted, the
        true orbits (``perturb response --validate K``) as crosses; with ``--true``, the true
        curves in black beside them with their special points and where the two part
        (:func:`~perturb.report.plots.true_curve.draw_true_curves`).

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
    with publication_style():
        if ax is None:
            fig, axes = new_figure(1, 1, height=4.0)
            ax = axes[0, 0]
        else:
            fig = ax.figure
        for branch in response.branches(coordinate):
            for a, b in zip(branch, branch[1:], strict=False):
                style = "-" if (a.stable and b.stable) else "--"
                colour = "C0" if (a.stable and b.stable) else "C3"
                ax.plot([a.value, b.value], [a.norm(coordinate), b.norm(coordinate)],
                        style, color=colour, lw=1.4)  # fmt: skip
            if len(branch) == 1:
                p = branch[0]
                ax.plot([p.value], [p.norm(coordinate)], ".", color="C0" if p.stable else "C3")
        ax.plot([], [], "-", color="C0", label="stable")
        ax.plot([], [], "--", color="C3", label="unstable")
        if response.folds:
            ax.plot([f.value for f in response.folds],
                    [f.norms.get(coordinate, math.nan) for f in response.folds],
                    "o", mfc="none", color="k", label="fold")  # fmt: skip
        if result.backbone is not None and result.backbone.coordinate == coordinate:
            ax.plot(result.backbone.values, result.backbone.amplitudes, ":", color="0.4",
                    label="backbone")  # fmt: skip
        shot = [t for t in result.true if t.success]
        if shot:
            ax.plot([t.value for t in shot], [t.amplitude for t in shot], "x", color="k",
                    label="true motion")  # fmt: skip
        draw_true_curves(ax, result.true_curve, coordinate, result.parameter)
        ax.set_xlabel(result.parameter)
        ax.set_ylabel(f"amplitude |{coordinate}|")
        ax.set_xlim(min(response.grid), max(response.grid))
        ax.legend(loc="best", frameon=False)
        ax.set_title(title or f"{result.problem}: frequency response, order {response.order}")
    return fig


def plot_floquet_along_branches(result, *, ax=None, title=None):
    """The largest modulus of the Floquet multipliers the slow flow predicts, along each branch (1 dotted):
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
