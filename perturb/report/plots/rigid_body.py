"""A rigid body's attitude: Euler angles against time, its orientation in 3-D, and a GIF of it.

Convention (classical z-x-z, as in ``problems.rigid_body.euler_angles``): the rotation taking body
axes to space axes is

.. math:: R = R_Z(\\psi)\\,R_X(\\theta)\\,R_Z(\\varphi),

with :math:`\\psi` the precession about the space vertical :math:`Z`, :math:`\\theta` the nutation
and :math:`\\varphi` the proper rotation.  The columns of :math:`R` are the body axes in space
coordinates; the third, the body :math:`z` axis, is the symmetry (spin) axis whose trace on the unit
sphere is drawn.  The rotation is written here from this definition (perturb does not import
``problems``); a test checks it against the problems' derivation.

Angles come in as a mapping ``{"psi": ..., "theta": ..., "phi": ...}`` of arrays in **radians**, one
value per time (e.g. ``problem.euler_angles(solution, t)`` of a rigid-body problem).
"""

from __future__ import annotations

import os
from collections.abc import Mapping

import numpy as np

from perturb.errors import bad_value
from perturb.report.plots._inputs import as_series, as_times
from perturb.report.plots.style import (
    ANALYTIC_LABEL,
    TRUE_LABEL,
    axis_label,
    finish_stack,
    new_figure,
    publication_style,
)

__all__ = [
    "EULER_NAMES",
    "animate_orientation",
    "plot_euler_angles",
    "plot_orientation",
    "rotation_matrix",
]

#: The Euler angles in the order they are applied (precession, nutation, proper rotation).
EULER_NAMES = ("psi", "theta", "phi")

#: Most instants :func:`plot_orientation` draws: one 3-D panel each, three to a row; beyond six
#: the panels are too small to read (use :func:`animate_orientation`).
MAX_INSTANTS = 6

#: Frames of a GIF when none are asked: 120 frames at 20 fps, a 6 s loop of a few hundred kB.
DEFAULT_GIF_FRAMES = 120

#: Resolution of the GIF frames (dots per inch of a 4.8 in figure: 480 px square).
GIF_DPI = 100

#: Colours of the body x, y, z axes (matplotlib's colour-blind safe tab10: blue, orange, green).
AXIS_COLORS = ("C0", "C1", "C2")

#: Meridians and parallels of the faint unit-sphere wireframe (every 30 degrees).
SPHERE_LINES = (13, 7)

_MATH = {"psi": "\\psi", "theta": "\\theta", "phi": "\\varphi"}


def _rz(angle: np.ndarray) -> np.ndarray:
    c, s, zero, one = np.cos(angle), np.sin(angle), np.zeros_like(angle), np.ones_like(angle)
    return np.stack(
        [np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1), np.stack([zero, zero, one], -1)],
        -2,
    )


def _rx(angle: np.ndarray) -> np.ndarray:
    c, s, zero, one = np.cos(angle), np.sin(angle), np.zeros_like(angle), np.ones_like(angle)
    return np.stack(
        [np.stack([one, zero, zero], -1), np.stack([zero, c, -s], -1), np.stack([zero, s, c], -1)],
        -2,
    )


def rotation_matrix(psi, theta, phi) -> np.ndarray:
    """:math:`R = R_Z(\\psi) R_X(\\theta) R_Z(\\varphi)`, body axes to space axes.

    Parameters
    ----------
    psi, theta, phi : array_like
        Euler angles in radians (broadcast together).

    Returns
    -------
    numpy.ndarray, shape (..., 3, 3)
        ``R[..., :, k]`` is body axis ``k`` (x, y, z) in space coordinates.

    Examples
    --------
    A quarter turn of precession takes the body x axis to the space y axis:

    >>> import numpy as np
    >>> from perturb.report.plots import rotation_matrix
    >>> rotation_matrix(np.pi / 2, 0.0, 0.0)[:, 0].round(12) + 0.0
    array([0., 1., 0.])
    """
    psi, theta, phi = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (psi, theta, phi)))
    return _rz(psi) @ _rx(theta) @ _rz(phi)


def _euler_series(angles, n: int, argument: str) -> dict[str, np.ndarray]:
    return as_series(angles, n, argument, EULER_NAMES)


def _shown(angle: np.ndarray, degrees: bool, unwrap: bool) -> np.ndarray:
    angle = np.unwrap(angle) if unwrap else angle
    return np.degrees(angle) if degrees else angle


def plot_euler_angles(
    t,
    angles: Mapping,
    true_angles: Mapping | None = None,
    *,
    degrees: bool = True,
    unwrap: bool = True,
    time_unit: str = "s",
    title: str | None = None,
):
    """ψ, θ, φ against time, one panel each, analytic and (optionally) true overlaid.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times, increasing.
    angles : mapping with ``psi``, ``theta``, ``phi``
        The angles in radians at ``t``.
    true_angles : mapping with ``psi``, ``theta``, ``phi``, optional
        The angles of the true motion at ``t`` (dashed, on top).
    degrees : bool, optional
        Axis in degrees (default) or radians.
    unwrap : bool, optional
        Remove the 2π jumps of angles returned in (−π, π] (``numpy.unwrap``) so that a spinning
        angle draws as a ramp, not a saw-tooth (default).
    time_unit, title
        As in :func:`perturb.report.plots.plot_time_series`.

    Returns
    -------
    matplotlib.figure.Figure
        Its lines hold ``degrees(unwrap(angle))`` (or the variant asked for).

    Raises
    ------
    perturb.errors.InvalidParameterError
        If an angle is missing, ``t`` is not increasing or an array does not match ``t``.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 100)
    >>> angles = {"psi": 0.01 * t, "theta": 1.3 + 0.001 * np.sin(t), "phi": 2 * np.pi * t / 10}
    >>> from perturb.report.plots import plot_euler_angles
    >>> fig = plot_euler_angles(t, angles)
    >>> len(fig.axes)
    3
    """
    times = as_times(t)
    series = _euler_series(angles, times.size, "angles")
    reference = (
        None if true_angles is None else _euler_series(true_angles, times.size, "true_angles")
    )
    unit = "deg" if degrees else "rad"
    with publication_style():
        fig, axes = new_figure(3, 1, sharex=True, height=5.6)
        for ax, name in zip(axes[:, 0], EULER_NAMES, strict=True):
            ax.plot(
                times,
                _shown(series[name], degrees, unwrap),
                color="C0",
                lw=1.6,
                label=ANALYTIC_LABEL,
            )
            if reference is not None:
                ax.plot(
                    times,
                    _shown(reference[name], degrees, unwrap),
                    color="k",
                    lw=1.0,
                    ls=(0, (4, 3)),
                    label=TRUE_LABEL,
                    zorder=3,
                )
            ax.set_ylabel(axis_label(f"${_MATH[name]}$", unit))
        finish_stack(fig, axes, times, time_unit, reference is not None, title)
    return fig


def _at(times: np.ndarray, series: dict[str, np.ndarray], instants: np.ndarray) -> np.ndarray:
    """Rotation matrices at ``instants``: each angle unwrapped, then interpolated linearly."""
    psi, theta, phi = (np.interp(instants, times, np.unwrap(series[n])) for n in EULER_NAMES)
    return rotation_matrix(psi, theta, phi)


def _instants(instants, times: np.ndarray, limit: int | None) -> np.ndarray:
    try:
        chosen = np.atleast_1d(np.asarray(instants, dtype=float))
    except (TypeError, ValueError):
        raise bad_value("instants", instants, "pass a list of times") from None
    fix = f"pass 1 to {limit} times within [{times[0]:g}, {times[-1]:g}]"
    if chosen.ndim != 1 or chosen.size < 1 or (limit is not None and chosen.size > limit):
        raise bad_value("instants", instants, fix)
    if not np.all(np.isfinite(chosen)) or np.any((chosen < times[0]) | (chosen > times[-1])):
        raise bad_value("instants", instants, fix)
    return chosen


def _draw_sphere(ax) -> None:
    n_meridians, n_parallels = SPHERE_LINES
    u = np.linspace(0.0, 2 * np.pi, 4 * (n_meridians - 1) + 1)
    v = np.linspace(0.0, np.pi, 4 * (n_parallels - 1) + 1)
    x = np.outer(np.cos(u), np.sin(v))
    y = np.outer(np.sin(u), np.sin(v))
    z = np.outer(np.ones_like(u), np.cos(v))
    ax.plot_wireframe(x, y, z, rstride=4, cstride=4, color="0.6", lw=0.3, alpha=0.5)


def _setup_3d(ax) -> None:
    """Unit cube view of the unit sphere: no tick labels (the sphere is the scale), light panes."""
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_zlim(-1, 1)
    ax.set_box_aspect((1, 1, 1))
    ax.grid(False)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_ticks([-1, 0, 1])
        axis.set_ticklabels([])
        axis.pane.fill = False
        axis.pane.set_edgecolor("0.8")
    ax.set_xlabel("$X$ [1]", labelpad=-12)
    ax.set_ylabel("$Y$ [1]", labelpad=-12)
    ax.set_zlabel("$Z$ (vertical) [1]", labelpad=-12)
    # the space vertical through the fixed point, for reference
    ax.plot([0.0, 0.0], [0.0, 0.0], [-1.0, 1.0], color="0.5", lw=0.6, ls=":")


def _draw_body(ax, rotation: np.ndarray) -> list:
    """Body axes as segments from the fixed point (the origin), a dot at each tip; the lines."""
    lines = []
    for k, name in enumerate("xyz"):
        axis = rotation[:, k]
        (line,) = ax.plot(
            [0.0, axis[0]],
            [0.0, axis[1]],
            [0.0, axis[2]],
            color=AXIS_COLORS[k],
            lw=2.0,
            marker="o",
            markevery=[1],
            ms=4,
            label=f"body ${name}$ axis" + (" (spin)" if name == "z" else ""),
        )
        lines.append(line)
    return lines


def _draw_trace(ax, spin_axis: np.ndarray):
    (line,) = ax.plot(
        spin_axis[:, 0],
        spin_axis[:, 1],
        spin_axis[:, 2],
        color="k",
        lw=0.9,
        label="spin-axis trace",
    )
    return line


def plot_orientation(
    t,
    angles: Mapping,
    instants,
    *,
    spin_trace: bool = True,
    time_unit: str = "s",
    title: str | None = None,
):
    """The body's orientation in 3-D at chosen instants, one panel per instant.

    Each panel shows the body axes as segments from the fixed point (the origin) on a faint unit
    sphere, in space axes (:math:`Z` the vertical), and the trace of the body :math:`z` (spin)
    axis on the sphere over the whole time span.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times of the angles, increasing.
    angles : mapping with ``psi``, ``theta``, ``phi``
        Euler angles in radians at ``t``.
    instants : sequence of float
        1 to ``MAX_INSTANTS`` times within ``t``; the angles are unwrapped and interpolated
        linearly to them (sample ``t`` finely enough for that).
    spin_trace : bool, optional
        Draw the spin axis's trace (default).
    time_unit, title
        As in :func:`perturb.report.plots.plot_time_series`.

    Returns
    -------
    matplotlib.figure.Figure
        Per panel, the lines are the space vertical (dotted), the body x, y, z axes
        (``[0, R[:, k]]``), then the trace (``R[:, :, 2]`` at every ``t``).

    Raises
    ------
    perturb.errors.InvalidParameterError
        If an angle is missing, or the instants are outside ``t`` or more than ``MAX_INSTANTS``.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 100)
    >>> angles = {"psi": 0.01 * t, "theta": 1.3 + 0.001 * np.sin(t), "phi": 2 * np.pi * t / 10}
    >>> from perturb.report.plots import plot_orientation
    >>> fig = plot_orientation(t, angles, instants=[0.0, 5.0])
    >>> len(fig.axes)
    2
    """
    times = as_times(t)
    series = _euler_series(angles, times.size, "angles")
    chosen = _instants(instants, times, MAX_INSTANTS)
    rotations = _at(times, series, chosen)
    spin_axis = rotation_matrix(*(series[n] for n in EULER_NAMES))[:, :, 2]
    ncols = min(chosen.size, 3)
    nrows = -(-chosen.size // ncols)
    with publication_style():
        fig, axes = new_figure(
            nrows,
            ncols,
            height=2.6 * nrows + 0.7,
            width=2.4 * ncols + 0.6,
            subplot_kw={"projection": "3d"},
        )
        for i, ax in enumerate(axes.flat):
            if i >= chosen.size:  # removed, not hidden: a hidden 3-D axes breaks the layout
                ax.remove()
                continue
            _setup_3d(ax)
            _draw_sphere(ax)
            _draw_body(ax, rotations[i])
            if spin_trace:
                _draw_trace(ax, spin_axis)
            ax.set_title(f"$t$ = {chosen[i]:.4g} {time_unit}".rstrip())
        handles, labels = axes.flat[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncols=len(labels))
        if title:
            fig.suptitle(title)
    return fig


def animate_orientation(
    t,
    angles: Mapping,
    path,
    *,
    fps: int = 20,
    frames: int | None = None,
    spin_trace: bool = True,
    time_unit: str = "s",
    title: str | None = None,
):
    """Write a GIF of the body's orientation over the time span (matplotlib's PillowWriter).

    Parameters
    ----------
    t, angles, spin_trace, time_unit, title
        As in :func:`plot_orientation`.
    path : str or os.PathLike
        The GIF to write (its folder must exist; the name must end in ``.gif``).
    fps : int, optional
        Frames per second.
    frames : int, optional
        Number of frames, at evenly spaced instants from ``t[0]`` to ``t[-1]`` (default:
        ``min(len(t), DEFAULT_GIF_FRAMES)``).

    Returns
    -------
    matplotlib.figure.Figure
        The figure as at the last frame.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``path`` does not end in ``.gif`` or its folder does not exist, or ``fps``/``frames`` < 1.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 100)
    >>> angles = {"psi": 0.01 * t, "theta": 1.3 + 0.001 * np.sin(t), "phi": 2 * np.pi * t / 10}
    >>> import os
    >>> from perturb.report.plots import animate_orientation
    >>> fig = animate_orientation(t, angles, "spin.gif", frames=3)
    >>> os.path.getsize("spin.gif") > 0
    True
    """
    times = as_times(t)
    series = _euler_series(angles, times.size, "angles")
    target = os.fspath(path) if isinstance(path, str | os.PathLike) else None
    if target is None or not target.lower().endswith(".gif"):
        raise bad_value("path", path, "pass a file name ending in .gif")
    folder = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(folder):
        raise bad_value("path", path, f"its folder {folder!r} does not exist; create it first")
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise bad_value("fps", fps, "pass an integer >= 1")
    if frames is None:
        frames = min(times.size, DEFAULT_GIF_FRAMES)
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise bad_value("frames", frames, "pass an integer >= 1")
    instants = np.linspace(times[0], times[-1], frames)
    rotations = _at(times, series, instants)
    spin_axis = rotation_matrix(*(series[n] for n in EULER_NAMES))[:, :, 2]
    from matplotlib.animation import PillowWriter

    with publication_style():
        fig, axes = new_figure(1, 1, height=4.8, width=4.8, subplot_kw={"projection": "3d"})
        ax = axes[0, 0]
        _setup_3d(ax)
        _draw_sphere(ax)
        body = _draw_body(ax, rotations[0])
        if spin_trace:
            _draw_trace(ax, spin_axis)
        ax.legend(loc="upper left", fontsize=8)
        if title:
            fig.suptitle(title)
        writer = PillowWriter(fps=fps)
        with writer.saving(fig, target, dpi=GIF_DPI):
            for instant, rotation in zip(instants, rotations, strict=True):
                for k, line in enumerate(body):
                    line.set_data_3d(
                        [0.0, rotation[0, k]], [0.0, rotation[1, k]], [0.0, rotation[2, k]]
                    )
                ax.set_title(f"$t$ = {instant:.4g} {time_unit}".rstrip())
                writer.grab_frame()
    return fig
