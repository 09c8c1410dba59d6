"""Work–precision diagram: error against wall time, one line per method."""

from __future__ import annotations

import math

from perturb.errors import bad_value
from perturb.report.plots.style import new_figure, publication_style

__all__ = ["plot_work_precision"]

#: Markers cycled over the methods so that the lines stay distinct in grey-scale print.
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "<", ">", "*")


def plot_work_precision(
    result, *, ax=None, title: str | None = None, annotate: tuple[str, ...] = ("analytic",)
):
    """Log–log diagram of the error against the wall time of every method of a work–precision run.

    Parameters
    ----------
    result : perturb.workprecision.WorkPrecision
        Its ``points`` (``method``, ``setting``, ``error``, ``seconds``) are read, and ``problem``,
        ``periods`` and ``reference`` for the title.  Points whose error is not finite (the
        derivation-time rows, failed runs) have no place on the diagram and are left out.
    ax : matplotlib.axes.Axes, optional
        Draw into these axes (their figure is returned); default: a new figure.
    title : str, optional
        Default: the problem, the horizon in periods and the reference integrator.
    annotate : tuple of str, optional
        Methods whose points are labelled with their setting (default: the analytic orders, whose
        cost need not grow with the order, so the line alone does not say which point is which).

    Returns
    -------
    matplotlib.figure.Figure
        One line per method, its points in the order they were measured (the sweep of the
        method's setting: orders, steps or tolerances).

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``result`` has no ``points`` with ``method``, ``setting``, ``error`` and ``seconds``.

    Examples
    --------
    A result built by hand (:func:`perturb.workprecision.work_precision` measures one):

    >>> from perturb.report.plots import plot_work_precision
    >>> from perturb.workprecision import WorkPoint, WorkPrecision
    >>> points = (WorkPoint("rk4", "10 steps/unit", 1e-5, 0.02), WorkPoint("rk4", "20 steps/unit", 6e-7, 0.04),
    ...           WorkPoint("analytic", "order 2", 1e-3, 0.001))
    >>> fig = plot_work_precision(WorkPrecision("demo", 10, 62.8, "heyoka", points))
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['rk4', 'analytic']
    """
    points = getattr(result, "points", None)
    if points is None or not all(
        hasattr(p, attr) for p in points for attr in ("method", "setting", "error", "seconds")
    ):
        raise bad_value(
            "result", type(result).__name__, "pass the WorkPrecision of work_precision()"
        )
    methods = dict.fromkeys(p.method for p in points if math.isfinite(p.error))
    if title is None:
        title = f"{result.problem}: {result.periods:g} periods, reference {result.reference}"
    with publication_style():
        if ax is None:
            fig, axes = new_figure(1, 1, height=4.4)
            ax = axes[0, 0]
        else:
            fig = ax.figure
        for i, method in enumerate(methods):
            chosen = [p for p in points if p.method == method and math.isfinite(p.error)]
            ax.plot(
                [p.seconds for p in chosen],
                [p.error for p in chosen],
                marker=MARKERS[i % len(MARKERS)],
                color=f"C{i % 10}",
                label=method,
            )
            if method in annotate:
                for p in chosen:
                    ax.annotate(
                        p.setting,
                        (p.seconds, p.error),
                        xytext=(5, 4),
                        textcoords="offset points",
                        fontsize="small",
                        color=f"C{i % 10}",
                    )
        ax.set_xscale("log")
        ax.set_yscale("log", nonpositive="mask")
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("max relative error [1]")
        ax.set_title(title)
        if len(methods) > 1:
            # beside the axes: with several methods "best" would still cover points
            ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return fig
