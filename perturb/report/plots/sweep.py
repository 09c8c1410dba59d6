"""Validity maps: a sweep over two parameters drawn as regions and contours."""

from __future__ import annotations

import json
import math

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots.style import new_figure, publication_style

__all__ = ["plot_validity_map"]

#: The verdict codes' colours (VALID, INVALID, UNDECIDED, LOWER_ORDER) and the failed points'.
VERDICT_COLOURS = ("#1a7f37", "#cf222e", "#9a6700", "#0969da")
FAILED_COLOUR = "#8c8c8c"


def plot_validity_map(dataset, variable: str = "verdict", *, tol: float = 0.1, ax=None, title=None):
    """A two-parameter sweep (:func:`perturb.sweep.sweep`) as a map.

    Parameters
    ----------
    dataset : xarray.Dataset
        Two dimensions.
    variable : {"verdict", "orbit_error", "slope", "period", ...}
        ``verdict``: the regions, coloured by outcome; ``orbit_error``: log10 of it with the
        tolerance's contour; any other variable: its values.
    tol : float
        The contour drawn on ``orbit_error``.
    ax : matplotlib.axes.Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    dims = list(dataset.dims)
    if len(dims) != 2 or variable not in dataset:
        raise bad_value(
            "dataset", f"dims {dims}, variables {sorted(dataset.data_vars)}",
            "pass a sweep over two parameters holding the variable",
        )  # fmt: skip
    from matplotlib.colors import ListedColormap

    x_name, y_name = dims[1], dims[0]
    x, y = dataset[x_name].values, dataset[y_name].values
    values = np.asarray(dataset[variable].values, dtype=float)
    failed = np.asarray(dataset["status"].values, dtype=float) != 0
    with publication_style():
        if ax is None:
            fig, axes = new_figure(1, 1, height=4.2)
            ax = axes[0, 0]
        else:
            fig = ax.figure
        if variable == "verdict":
            codes = json.loads(dataset.attrs.get("verdict_codes", "{}"))
            shown = np.where(failed, len(VERDICT_COLOURS), values)
            cmap = ListedColormap([*VERDICT_COLOURS, FAILED_COLOUR])
            ax.pcolormesh(x, y, shown, cmap=cmap, vmin=-0.5, vmax=len(VERDICT_COLOURS) + 0.5,
                          shading="nearest")  # fmt: skip
            for code, colour in enumerate(VERDICT_COLOURS):
                if np.any(values == code):
                    label = codes.get(str(code), str(code)).split(":")[0]
                    ax.plot([], [], "s", color=colour, label=label)
            if np.any(failed):
                ax.plot([], [], "s", color=FAILED_COLOUR, label="failed")
            ax.legend(loc="best", frameon=True, fontsize="small")
        else:
            shown = np.log10(np.abs(values)) if variable == "orbit_error" else values
            mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(shown), shading="nearest")
            label = f"log10 {variable}" if variable == "orbit_error" else variable
            fig.colorbar(mesh, ax=ax, label=label)
            if variable == "orbit_error" and np.any(np.isfinite(shown)) and shown.shape[0] > 1:
                ax.contour(x, y, np.ma.masked_invalid(shown), levels=[math.log10(tol)],
                           colors="k", linewidths=1.2)  # fmt: skip
        ax.set_xlabel(x_name)
        ax.set_ylabel(y_name)
        ax.set_title(title or f"{dataset.attrs.get('problem', '')}: {variable}, order "
                     f"{dataset.attrs.get('order', '')}")  # fmt: skip
    return fig
