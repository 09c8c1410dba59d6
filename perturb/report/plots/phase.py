"""Phase diagrams: the number of stable steady states over two parameters, with its boundaries.

Inputs are plain: the two axes' values (x along the second dimension of the map, y along the
first, as :func:`perturb.sweep.phase.phase_diagram` orders them), the map of counts (negative
where nothing was counted: blank) and the special points located on the lines of the grid, each
``(x, y, kind)``: folds, branch points, Neimark-Sacker and period-doubling points, drawn over the
map — where the count changes, a fold or branch-point curve runs.
"""

from __future__ import annotations

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots.style import display_name, new_figure, publication_style
from perturb.report.plots.validity import MAP_HEIGHT, MAP_WIDTH, _axis, _edges

__all__ = ["plot_phase_diagram"]

#: How each kind of special point is drawn: marker, face colour, edge colour, size.
SPECIAL_STYLE = {
    "fold": ("o", "black", "black", 9),
    "branch-point": ("x", "#d62728", "#d62728", 16),
    "neimark-sacker": ("^", "white", "#1f77b4", 16),
    "period-doubling": ("v", "white", "#9467bd", 16),
    "other": ("s", "white", "0.3", 9),
}


def plot_phase_diagram(x, y, counts, special=(), *, xname: str, yname: str, label=None,
                       title=None):  # fmt: skip
    """The count of stable steady states at every point as a map, the special points over it.

    Parameters
    ----------
    x, y : array_like
        The two parameters' values (increasing).
    counts : array_like of int, shape (len(y), len(x))
        The count at every point (negative: not counted, left blank).
    special : sequence of (x, y, kind)
        Special points on the lines of the grid (kinds of
        :data:`~perturb.report.plots.phase.SPECIAL_STYLE`; others drawn as ``other``).
    xname, yname : str
        The parameters' names.
    label : str, optional
        What is counted (the colour bar's label; default "stable steady states").

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    One stable state below a fold line at y = 0.5, two above:

    >>> import numpy as np
    >>> from perturb.report.plots import plot_phase_diagram
    >>> x, y = np.linspace(0.0, 1.0, 5), np.linspace(0.0, 1.0, 4)
    >>> counts = np.where(y[:, None] > 0.5, 2, 1) + 0 * x
    >>> folds = [(v, 0.5, "fold") for v in x]
    >>> fig = plot_phase_diagram(x, y, counts, folds, xname="Omega", yname="F")
    >>> fig.axes[0].get_xlabel(), len(fig.axes[0].collections)
    ('$\\\\Omega$', 2)
    """
    x, y = _axis(x, "x"), _axis(y, "y")
    for argument, value in (("xname", xname), ("yname", yname)):
        if not isinstance(value, str) or not value:
            raise bad_value(argument, value, "pass the parameter's name")
    try:
        field = np.asarray(counts, dtype=float)
    except (TypeError, ValueError):
        raise bad_value("counts", "<not numbers>", "pass a 2-D array of counts") from None
    if field.shape != (y.size, x.size):
        raise bad_value("counts", f"<array of shape {field.shape}>",
                        f"pass shape ({y.size}, {x.size}): y along the first axis")  # fmt: skip
    field = np.where(field < 0, np.nan, field)
    top = int(np.nanmax(field)) if np.any(np.isfinite(field)) else 0
    with publication_style():
        from matplotlib.colors import BoundaryNorm
        from matplotlib.lines import Line2D

        fig, axes = new_figure(1, 1, width=MAP_WIDTH, height=MAP_HEIGHT)
        ax = axes[0, 0]
        cmap = _discrete(top + 1)
        bounds = np.arange(-0.5, top + 1.0)
        mesh = ax.pcolormesh(_edges(x, False), _edges(y, False), field, cmap=cmap,
                             norm=BoundaryNorm(bounds, cmap.N), shading="flat")  # fmt: skip
        bar = fig.colorbar(mesh, ax=ax, ticks=range(top + 1))
        bar.set_label(label or "stable steady states")
        handles = []
        points = list(special)
        for kind, (marker, face, edge, size) in SPECIAL_STYLE.items():
            chosen = [(px, py) for px, py, k in points if (k if k in SPECIAL_STYLE else "other")
                      == kind]  # fmt: skip
            if not chosen:
                continue
            xs, ys = zip(*chosen, strict=True)
            edges = {} if marker in "x+" else {"edgecolors": edge}  # unfilled: the face colour
            ax.scatter(xs, ys, s=size, marker=marker, c=face, linewidths=0.8, zorder=3, **edges)
            handles.append(Line2D([], [], ls="", marker=marker, markerfacecolor=face,
                                  markeredgecolor=edge, label=kind.replace("-", " ")))  # fmt: skip
        if handles:  # below the map, one row: the colour bar keeps the right-hand side
            ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.16),
                      ncol=len(handles), frameon=False, fontsize="small")  # fmt: skip
        ax.set_xlim(x[0] - (x[-1] - x[0]) * 0.02, x[-1] + (x[-1] - x[0]) * 0.02)
        ax.set_xlabel(display_name(xname))
        ax.set_ylabel(display_name(yname))
        if title:
            ax.set_title(title, fontsize="medium")
    return fig


def _discrete(n: int):
    """n distinguishable colours, light for few states, dark for many (viridis sampled)."""
    from matplotlib import colormaps
    from matplotlib.colors import ListedColormap

    base = colormaps["viridis_r"]
    return ListedColormap([base(0.08 + 0.84 * k / max(n - 1, 1)) for k in range(n)])
