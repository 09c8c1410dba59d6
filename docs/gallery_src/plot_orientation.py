"""
Orientation in 3-D
==================

:func:`~perturb.report.plots.plot_orientation` draws the body axes on the unit sphere at a few
instants, with the trace of the spin axis over the whole span. The same fast-spin disk as in the
Euler-angle figure; :func:`~perturb.report.plots.animate_orientation` writes the same picture as a
GIF.
"""

import numpy as np

from perturb.report.plots import plot_orientation
from problems import get_problem

disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
solution = disk.solve(1)
period = disk.period(solution)
t = np.linspace(0.0, period, 400)
angles = disk.euler_angles(solution, t)

fig = plot_orientation(t, angles, instants=np.linspace(0.0, period, 4, endpoint=False))
