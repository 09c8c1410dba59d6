"""
Euler angles of a rigid body
============================

:func:`~perturb.report.plots.plot_euler_angles` draws precession ψ, nutation θ and proper
rotation φ against time (degrees, unwrapped). The fast-spin disk (ε = 0.004, a Newtonian field)
at order 1 over three periods; ``problem.euler_angles`` maps the solution to the angles.
"""

import numpy as np

from perturb.report.plots import plot_euler_angles
from problems import get_problem

disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
solution = disk.solve(1)
t = np.linspace(0.0, 3 * disk.period(solution), 600)
angles = disk.euler_angles(solution, t)  # {"psi": ..., "theta": ..., "phi": ...} in radians

fig = plot_euler_angles(t, angles, title="fast-spin disk, order 1")
