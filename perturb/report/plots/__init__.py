"""Publication plots of perturb's results, each a function returning a matplotlib Figure.

Inputs are plain (times, mappings name → array, the work–precision result), so that the functions
do not depend on the shape of result classes.  matplotlib is imported only inside the functions:
importing this package works without it, and a plot then raises
:class:`perturb.errors.MissingDependencyError` (an :class:`ImportError`) with the install hint.

Modules: :mod:`.timeseries` (state against time, error, phase portraits), :mod:`.convergence`
(error against ε), :mod:`.workprecision`, :mod:`.rigid_body` (Euler angles, orientation, GIF),
:mod:`.response` (frequency responses, Floquet multipliers along the branches),
:mod:`.validity` (validity maps of a sweep over two parameters), :mod:`.phase` (phase diagrams:
stable steady states over two parameters, with their boundaries), :mod:`.dynamics` (basin maps,
transients beside the slow flow, ramps beside the folds), :mod:`.style` (the publication rc
context every function uses).
"""

from perturb.report.plots.convergence import plot_convergence
from perturb.report.plots.dynamics import plot_basins, plot_ramp, plot_transient
from perturb.report.plots.phase import plot_phase_diagram
from perturb.report.plots.response import plot_floquet_along_branches, plot_frequency_response
from perturb.report.plots.rigid_body import (
    animate_orientation,
    plot_euler_angles,
    plot_orientation,
    rotation_matrix,
)
from perturb.report.plots.style import publication_style
from perturb.report.plots.timeseries import plot_error, plot_phase, plot_time_series
from perturb.report.plots.validity import (
    plot_error_map,
    plot_period_map,
    plot_slope_map,
    plot_verdict_map,
)
from perturb.report.plots.workprecision import plot_work_precision

__all__ = [
    "animate_orientation",
    "plot_basins",
    "plot_convergence",
    "plot_error",
    "plot_error_map",
    "plot_floquet_along_branches",
    "plot_frequency_response",
    "plot_phase_diagram",
    "plot_ramp",
    "plot_euler_angles",
    "plot_orientation",
    "plot_period_map",
    "plot_phase",
    "plot_slope_map",
    "plot_time_series",
    "plot_transient",
    "plot_verdict_map",
    "plot_work_precision",
    "publication_style",
    "rotation_matrix",
]
