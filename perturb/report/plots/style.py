"""Publication defaults shared by every plot, and the lazy import of matplotlib.

Every plotting function of :mod:`perturb.report.plots` builds its figure inside
:func:`publication_style` (a :func:`matplotlib.rc_context`, so the user's global ``rcParams`` are
never changed) through :func:`new_figure` (a bare :class:`matplotlib.figure.Figure`, never pyplot:
no global figure registry, so it works headless and from threads).

matplotlib is imported only when a figure is drawn: ``import perturb.report.plots`` costs nothing
and works without it.
"""

from __future__ import annotations

import contextlib
import re
import threading
from collections.abc import Iterator

from perturb._install import install_hint
from perturb.errors import MissingDependencyError

__all__ = [
    "MISSING_MATPLOTLIB",
    "ANALYTIC_LABEL",
    "PUBLICATION_RC",
    "TRUE_LABEL",
    "axis_label",
    "legend_above",
    "finish_stack",
    "display_name",
    "new_figure",
    "publication_style",
    "require_matplotlib",
]

#: The rc context changes matplotlib's global rcParams while it lasts: figures built at the same time
#: in several threads take turns, so none sees another's restored defaults half-way.
_STYLE_LOCK = threading.RLock()

#: The message of the error raised when matplotlib is missing: what to install.
MISSING_MATPLOTLIB = f"plots need matplotlib: {install_hint('plot')}"

#: Single-column figure width in inches (the usual journal column is 3.3-3.5 in; 6.4 in is a
#: full-width figure, readable on screen and in a two-column layout when scaled to the text width).
FIGURE_WIDTH = 6.4

#: Height of one panel of a stacked figure, inches: tall enough for a tick label every ~0.5 in.
PANEL_HEIGHT = 1.9

#: The rc parameters in force while a figure is built: readable fonts at the printed size, thin
#: frames, no top/right spines, frameless legends and no background grid (no chart junk),
#: colour-blind safe colours (matplotlib's default "tab10" cycle) and 200 dpi (fixed on the figure
#: when it is made, so ``savefig`` outside the context keeps it).  Saving options (``savefig.*``)
#: are not set: the figure is saved after the context has ended.
PUBLICATION_RC = {
    "font.size": 10,
    "axes.labelsize": 10,
    "axes.titlesize": 10,
    "legend.fontsize": 9,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "axes.linewidth": 0.8,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.grid": False,
    "axes.formatter.useoffset": False,
    "axes.formatter.limits": (-3, 4),
    "lines.linewidth": 1.4,
    "lines.markersize": 5,
    "legend.frameon": False,
    "figure.dpi": 200,
    "mathtext.default": "regular",
}

#: Label of the analytic curves in every legend.
ANALYTIC_LABEL = "analytic"
#: Label of the reference curves: the integrated original equations.
TRUE_LABEL = "true (integrated)"

_GREEK = (
    "alpha beta gamma delta epsilon eps zeta eta theta iota kappa lambda mu nu xi pi rho sigma "
    "tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Phi Psi Omega"
).split()


def require_matplotlib():
    """Import and return :mod:`matplotlib`, or raise the one-line install hint.

    Raises
    ------
    perturb.errors.MissingDependencyError
        (an :class:`ImportError`) if matplotlib is not installed.
    """
    try:
        import matplotlib
        import matplotlib.figure  # noqa: F401  (the OO entry point every plot uses)
    except ImportError as exc:
        raise MissingDependencyError(MISSING_MATPLOTLIB) from exc
    return matplotlib


@contextlib.contextmanager
def publication_style() -> Iterator[None]:
    """Context in which :data:`~perturb.report.plots.style.PUBLICATION_RC` is in force (the global rcParams are restored).

    Yields
    ------
    None
        Inside the ``with`` block, matplotlib's rcParams are the publication defaults.

    Examples
    --------
    >>> import matplotlib
    >>> from perturb.report.plots import publication_style
    >>> from perturb.report.plots.style import PUBLICATION_RC
    >>> before = matplotlib.rcParams["font.size"]
    >>> with publication_style():
    ...     inside = matplotlib.rcParams["font.size"]
    >>> inside == PUBLICATION_RC.get("font.size", inside), matplotlib.rcParams["font.size"] == before
    (True, True)
    """
    matplotlib = require_matplotlib()
    with _STYLE_LOCK, matplotlib.rc_context(PUBLICATION_RC):
        yield


def new_figure(
    nrows: int = 1,
    ncols: int = 1,
    *,
    height: float | None = None,
    width: float = FIGURE_WIDTH,
    **subplot_kw,
):
    """A pyplot-free figure with constrained layout and its axes.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes (``fig.subplots``; ``squeeze=False`` so ``axes`` is always 2-D).
    height : float, optional
        Figure height in inches (default: ``PANEL_HEIGHT`` per row, at least 3.2 in).
    width : float, optional
        Figure width in inches (default ``FIGURE_WIDTH``).
    **subplot_kw
        Passed to ``fig.subplots`` (``sharex``, ``subplot_kw``...).

    Returns
    -------
    fig : matplotlib.figure.Figure
    axes : numpy.ndarray of Axes, shape (nrows, ncols)
    """
    from matplotlib.figure import Figure

    if height is None:
        height = max(3.2, PANEL_HEIGHT * nrows)
    # constrained layout: the successor of tight_layout, which also makes room for legends and
    # suptitles and is kept up to date when the figure is resized or saved.
    fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw)
    return fig, axes


def display_name(name: str) -> str:
    """A state name as mathtext: ``xdot`` → :math:`\\dot{x}`, ``gamma1`` → :math:`\\gamma_1`.

    Names that are neither a symbol, a Greek letter nor either with a trailing index or ``dot``
    are returned unchanged.
    """
    match = re.fullmatch(r"([A-Za-z]+?)(\d*)(dot|_dot)?", name)
    if match is None:
        return name
    base, index, dot = match.groups()
    if base in _GREEK:
        symbol = "\\varepsilon" if base == "eps" else "\\" + base
    elif len(base) == 1:
        symbol = base
    else:
        return name
    if dot:
        symbol = f"\\dot{{{symbol}}}"
    if index:
        symbol = f"{symbol}_{{{index}}}"
    return f"${symbol}$"


def axis_label(quantity: str, unit: str | None) -> str:
    """``"quantity [unit]"``; a dimensionless quantity (``unit`` ``""`` or ``"1"``) gets ``[1]``.

    ``unit=None`` means the unit is unknown and none is printed.
    """
    if unit is None:
        return quantity
    return f"{quantity} [{unit or '1'}]"


def legend_above(ax) -> None:
    """The legend of ``ax`` in one row just above it: outside the data, below any suptitle
    (a figure-level "outside" legend would collide with the suptitle)."""
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(
        handles,
        labels,
        loc="lower center",
        bbox_to_anchor=(0.5, 1.02),
        ncols=len(labels),
        borderaxespad=0.0,
    )


def finish_stack(fig, axes, times, time_unit: str | None, legend: bool, title: str | None) -> None:
    """Close a column of panels sharing the time axis: its label and range, aligned y labels, the
    legend above the top panel (when a reference curve is drawn) and the title."""
    axes[-1, 0].set_xlabel(axis_label("$t$", time_unit))
    axes[-1, 0].set_xlim(times[0], times[-1])
    fig.align_ylabels(axes[:, 0])
    if legend:
        legend_above(axes[0, 0])
    if title:
        fig.suptitle(title)
