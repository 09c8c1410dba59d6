"""Where the motion goes: basin maps, transients beside the slow flow, ramps beside the folds.

Inputs are plain: arrays, names and point lists (the CLI reads them off
:class:`perturb.dynamics.basins.BasinMap`, :class:`~perturb.dynamics.transient.Transient` and
:class:`~perturb.dynamics.ramp.Ramp`).
"""

from __future__ import annotations

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots.style import display_name, new_figure, publication_style
from perturb.report.plots.validity import MAP_HEIGHT, MAP_WIDTH, _axis, _edges

__all__ = ["plot_basins", "plot_ramp", "plot_transient"]

#: Colours of the basins (code 0, 1, ...), and of the outcomes that are not attractors.
BASIN_COLOURS = ("#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fdd0a2", "#c7e9c0", "#dadaeb")
OUTCOME_COLOURS = {-1: "0.55", -2: "0.2", -3: "white"}


def plot_basins(x, y, codes, names, attractors=(), saddles=(), separatrix=(), *, xname: str,
                yname: str, title=None):  # fmt: skip
    """A basin map: each initial state coloured by where its motion goes, the attractors and
    saddles marked, the slow flow's separatrix drawn over it.

    Parameters
    ----------
    x, y : array_like
        The grid's horizontal and vertical values (increasing).
    codes : array_like of int, shape (len(y), len(x))
        The code of each state (0, 1, …: attractors; negative: no convergence, escaped, not
        computed).
    names : mapping
        ``{code: name}`` for the legend.
    attractors, saddles : sequence of (name, points)
        Points of shape (k, 2) in (x, y).
    separatrix : sequence of array_like
        Curves of shape (K, 2) in (x, y).
    xname, yname : str

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.report.plots.dynamics import plot_basins
    >>> x = y = np.linspace(-1, 1, 5)
    >>> codes = (x[None, :] > 0).astype(int) + 0 * y[:, None]
    >>> fig = plot_basins(x, y, codes, {0: "left", 1: "right"}, [("left", [[-0.5, 0]])],
    ...                   xname="x", yname="xdot")
    >>> fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel()
    ('$x$', '$\\\\dot{x}$')
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    field = np.asarray(codes, dtype=int)
    if field.shape != (y.size, x.size):
        raise bad_value("codes", f"<array of shape {field.shape}>",
                        f"pass shape ({y.size}, {x.size}): y along the first axis")  # fmt: skip
    present = sorted(set(np.unique(field).tolist()))
    with publication_style():
        from matplotlib.colors import BoundaryNorm, ListedColormap
        from matplotlib.patches import Patch

        fig, axes = new_figure(1, 1, width=MAP_WIDTH + 0.8, height=MAP_HEIGHT)
        ax = axes[0, 0]
        index = {c: i for i, c in enumerate(present)}
        colours = [
            OUTCOME_COLOURS.get(c, "0.5") if c < 0 else BASIN_COLOURS[c % len(BASIN_COLOURS)]
            for c in present
        ]
        mapped = np.vectorize(index.get)(field)
        cmap = ListedColormap(colours)
        norm = BoundaryNorm(np.arange(-0.5, len(present)), cmap.N)
        ax.pcolormesh(_edges(x, False), _edges(y, False), mapped, cmap=cmap, norm=norm,
                      shading="flat", rasterized=True)  # fmt: skip
        handles = [Patch(facecolor=colours[index[c]], edgecolor="0.4", label=str(names.get(c, c)))
                   for c in present]  # fmt: skip
        for curve in separatrix:
            curve = np.asarray(curve, dtype=float)
            ax.plot(curve[:, 0], curve[:, 1], color="black", lw=1.0, ls="--")
        if len(separatrix):
            from matplotlib.lines import Line2D

            handles.append(Line2D([], [], color="black", ls="--", label="slow-flow separatrix"))
        for name, points in attractors:
            p = np.asarray(points, dtype=float)
            ax.plot(p[:, 0], p[:, 1], "o", ms=6, mfc="white", mec="black", mew=1.4)
            ax.annotate(str(name), p[0], textcoords="offset points", xytext=(6, 6), fontsize=8)
        for name, points in saddles:
            p = np.asarray(points, dtype=float)
            ax.plot(p[:, 0], p[:, 1], "x", ms=8, color="#d62728", mew=2.0)
            ax.annotate(f"{name} (saddle)", p[0], textcoords="offset points", xytext=(-8, 8),
                        ha="right", fontsize=8, color="#d62728")  # fmt: skip
        ax.set_xlim(x[0], x[-1])
        ax.set_ylim(y[0], y[-1])
        ax.set_xlabel(display_name(xname))
        ax.set_ylabel(display_name(yname))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
        if title:
            ax.set_title(title, fontsize=10)
    return fig


def plot_transient(times, x, envelope, slow_envelope, phase, slow_phase, *, coordinate: str,
                   settle_time=None, title=None):  # fmt: skip
    """A transient: the true motion with its envelope, the slow flow's envelope over it, and
    the phases below.

    Parameters
    ----------
    times, x : array_like
        The true motion of the coordinate.
    envelope, slow_envelope, phase, slow_phase : array_like
        The true motion's slow amplitude and phase, and the slow flow's.
    coordinate : str
    settle_time : float, optional
        When the motion settled (a vertical line).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.report.plots.dynamics import plot_transient
    >>> t = np.linspace(0, 100, 401)
    >>> envelope = 1 - np.exp(-t / 30)
    >>> fig = plot_transient(t, envelope * np.cos(t), envelope, 1 - np.exp(-t / 28), 0 * t, 0 * t,
    ...                      coordinate="x", settle_time=80.0)
    >>> len(fig.axes)
    2
    """
    t = np.asarray(times, dtype=float)
    with publication_style():
        fig, axes = new_figure(2, 1, sharex=True)
        top, bottom = axes[0, 0], axes[1, 0]
        top.plot(t, np.asarray(x), color="0.75", lw=0.5, label=f"{display_name(coordinate)} (true)")
        top.plot(t, np.asarray(envelope), color="#1f77b4", lw=1.2, label="envelope (true)")
        top.plot(t, np.asarray(slow_envelope), color="#d62728", lw=1.2, ls="--",
                 label="slow flow")  # fmt: skip
        bottom.plot(t, np.asarray(phase), color="#1f77b4", lw=1.0, label="true")
        bottom.plot(t, np.asarray(slow_phase), color="#d62728", lw=1.0, ls="--", label="slow flow")
        if settle_time is not None and np.isfinite(settle_time):
            for ax in (top, bottom):
                ax.axvline(settle_time, color="0.3", lw=0.8, ls=":")
        top.set_ylabel(display_name(coordinate))
        bottom.set_ylabel("phase (rad)")
        bottom.set_xlabel("t")
        top.legend(fontsize=8, loc="upper right")
        if title:
            top.set_title(title, fontsize=10)
    return fig


def plot_ramp(runs, folds=(), *, parameter: str, coordinate: str, title=None):
    """Ramps up and down: each run's envelope against the ramped parameter, its jump marked, the
    response curve's folds as vertical lines.

    Parameters
    ----------
    runs : sequence of (label, values, envelope, jump)
    folds : sequence of float
    parameter, coordinate : str

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.report.plots.dynamics import plot_ramp
    >>> w = np.linspace(0.99, 1.06, 200)
    >>> up = np.where(w < 1.045, 1 + 20 * (w - 0.99), 0.2)
    >>> fig = plot_ramp([("up", w, up, 1.045)], [1.0424], parameter="Omega", coordinate="x")
    >>> fig.axes[0].get_ylabel()
    'max |x| per drive period'
    """
    with publication_style():
        fig, axes = new_figure(1, 1)
        ax = axes[0, 0]
        for fold in folds:
            ax.axvline(fold, color="black", lw=0.8)
        for label, values, envelope, jump in runs:
            line = ax.plot(np.asarray(values), np.asarray(envelope), lw=0.9, label=label)[0]
            ax.axvline(jump, color=line.get_color(), lw=0.8, ls=":")
        if len(folds):
            from matplotlib.lines import Line2D

            handles, labels = ax.get_legend_handles_labels()
            handles.append(Line2D([], [], color="black", lw=0.8))
            labels.append("folds (response curve)")
            ax.legend(handles, labels, fontsize=8)
        else:
            ax.legend(fontsize=8)
        ax.set_xlabel(display_name(parameter))
        ax.set_ylabel(f"max |{coordinate}| per drive period")
        if title:
            ax.set_title(title, fontsize=10)
    return fig
