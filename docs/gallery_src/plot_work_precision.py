"""
Work–precision diagram
======================

:func:`~perturb.report.plots.plot_work_precision` draws the error against the wall time of every
method that :func:`perturb.workprecision.work_precision` ran: the analytic solution at orders 1..N
and the integrators at several settings. A short run (3 periods, one repeat) keeps the build quick;
the :doc:`tutorial <../tutorials/work-precision>` reads such a diagram.
"""

from perturb.report.plots import plot_work_precision
from perturb.workprecision import work_precision
from problems import get_problem

result = work_precision(
    get_problem("duffing").create(eps=0.05, amplitude=1.0),
    periods=3,
    orders=3,
    rk4_steps=(10, 40, 160),
    tolerances=(1e-6, 1e-9, 1e-12),
    scipy_methods=("DOP853", "RK45"),
    repeat=1,
)
fig = plot_work_precision(result)
