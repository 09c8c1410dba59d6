"""Error against the expansion parameter: the measured convergence beside the expected order."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots.style import new_figure, publication_style

__all__ = ["plot_convergence"]


def _positive_array(values, argument: str) -> np.ndarray:
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise bad_value(argument, values, "pass a 1-D sequence of numbers") from None
    if array.ndim != 1 or array.size < 1:
        raise bad_value(argument, values, "pass a 1-D sequence of numbers")
    return array


def _slope_limits(slope_band, expected: float) -> tuple[float, float] | None:
    if slope_band is None:
        return None
    fix = "pass a half-width > 0 (slopes order+1 ± band) or a pair (lowest, highest slope)"
    if isinstance(slope_band, int | float):
        if not (math.isfinite(slope_band) and slope_band > 0):
            raise bad_value("slope_band", slope_band, fix)
        return expected - slope_band, expected + slope_band
    if (
        isinstance(slope_band, Sequence)
        and len(slope_band) == 2
        and all(isinstance(v, int | float) and math.isfinite(v) for v in slope_band)
        and slope_band[0] < slope_band[1]
    ):
        return float(slope_band[0]), float(slope_band[1])
    raise bad_value("slope_band", slope_band, fix)


#: Up to this many distinct ε the horizontal ticks are the ε values themselves (plain numbers);
#: beyond, the usual decades.  A grid of a few ε within one decade otherwise gets crowded
#: "3×10⁻²"-style minor labels that overlap.
MAX_EPSILON_TICKS = 8


def _label_parameter_axis(ax, eps: np.ndarray) -> None:
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter, NullLocator

    values = np.unique(eps)
    if values.size <= MAX_EPSILON_TICKS:
        ax.xaxis.set_major_locator(FixedLocator(values))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
        ax.xaxis.set_minor_locator(NullLocator())
    else:
        ax.xaxis.set_minor_formatter(NullFormatter())


def plot_convergence(
    epsilons,
    errors,
    *,
    order: int,
    slope: float | None = None,
    slope_band: float | tuple[float, float] | None = None,
    parameter: str = "\\varepsilon",
    error_label: str = "max relative error [1]",
    title: str | None = None,
):
    """Log–log plot of the error against ε with the fitted and the expected slope.

    An expansion of order :math:`N` has an error :math:`O(\\varepsilon^{N+1})`: on log–log axes a
    line of slope :math:`N+1`.  The figure shows the measured points, the least-squares line
    through them (its slope in the legend) and the reference line of slope ``order + 1`` through
    the same centre point, so a wrong order shows as two diverging lines.

    Parameters
    ----------
    epsilons : array_like, shape (n,)
        Values of the expansion parameter (> 0).
    errors : array_like, shape (n,)
        The error at each value.  NaN and non-positive errors (failed points, errors at round-off)
        are shown where possible but left out of the fit.
    order : int
        Order of the expansion (>= 0): the expected slope is ``order + 1``.
    slope : float, optional
        A slope already measured (e.g. ``SlopeFit.slope`` of a validation report); the line is
        drawn with it through the points' centre.  Default: fitted here by least squares on
        ``log(error)`` against ``log(ε)``.
    slope_band : float or (float, float), optional
        Slopes counted consistent with the expected one: a half-width (``order + 1 ± band``) or
        the lowest and highest slope.  Drawn as a shaded wedge about the reference line.
    parameter : str, optional
        Mathtext of the parameter's symbol for the axis label (``"\\\\mu"`` for a large parameter).
    error_label : str, optional
        Vertical axis label (the error's definition and unit).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Lines, in order: the points, the fitted line (if two usable points), the reference line.

    Raises
    ------
    perturb.errors.InvalidParameterError
        On an ε <= 0, arrays of different lengths, a negative order or a bad ``slope_band``.

    Examples
    --------
    Errors that fall like ε³ (an order-2 solution):

    >>> import numpy as np
    >>> from perturb.report.plots import plot_convergence
    >>> eps = np.array([0.0125, 0.025, 0.05, 0.1])
    >>> fig = plot_convergence(eps, 0.3 * eps**3, order=2, slope_band=0.5)
    >>> fig.axes[0].get_legend_handles_labels()[1][:2]
    ['measured', 'fit: slope 3.00']
    """
    eps = _positive_array(epsilons, "epsilons")
    err = _positive_array(errors, "errors")
    if err.shape != eps.shape:
        raise bad_value("errors", errors, f"pass one error per epsilon ({eps.size} values)")
    if not np.all(np.isfinite(eps)) or np.any(eps <= 0):
        raise bad_value("epsilons", epsilons, "every epsilon must be finite and > 0")
    if isinstance(order, bool) or not isinstance(order, int) or order < 0:
        raise bad_value("order", order, "pass the expansion order, an integer >= 0")
    if slope is not None and not (isinstance(slope, int | float) and math.isfinite(slope)):
        raise bad_value("slope", slope, "pass a finite measured slope, or None to fit it")
    expected = order + 1.0
    band = _slope_limits(slope_band, expected)

    usable = np.isfinite(err) & (err > 0)
    log_eps, log_err = np.log(eps[usable]), np.log(err[usable])
    if slope is None and np.unique(log_eps).size >= 2:
        slope = float(np.polyfit(log_eps, log_err, 1)[0])
    with publication_style():
        fig, axes = new_figure(1, 1, height=4.0, width=5.0)
        ax = axes[0, 0]
        ax.plot(eps, err, "o", color="k", ls="none", label="measured", zorder=3)
        if usable.any():
            # lines through the centre of the usable points: log ε̄, log ē
            centre_x, centre_y = float(np.mean(log_eps)), float(np.mean(log_err))
            span = np.exp(np.linspace(log_eps.min(), log_eps.max(), 2))
            span = span if span[0] < span[-1] else eps[usable][:1] * np.array([0.8, 1.25])

            def through_centre(s: float) -> np.ndarray:
                return np.exp(centre_y + s * (np.log(span) - centre_x))

            if slope is not None:
                ax.plot(span, through_centre(slope), color="C0", label=f"fit: slope {slope:.2f}")
            ax.plot(
                span,
                through_centre(expected),
                color="C1",
                ls="--",
                label=f"expected: slope {expected:g} (order {order} + 1)",
            )
            if band is not None:
                ax.fill_between(
                    span,
                    through_centre(band[0]),
                    through_centre(band[1]),
                    color="C1",
                    alpha=0.15,
                    lw=0,
                    label=f"consistent: slope {band[0]:g} to {band[1]:g}",
                )
        ax.set_xscale("log")
        ax.set_yscale("log", nonpositive="mask")
        _label_parameter_axis(ax, eps)
        ax.set_xlabel(f"${parameter}$ [1]")
        ax.set_ylabel(error_label)
        ax.legend(loc="upper left")
        if title:
            fig.suptitle(title)
    return fig
