"""
Phase portrait
==============

:func:`~perturb.report.plots.plot_phase` draws one panel per (coordinate, velocity) pair. Two
coupled oscillators in 1:1 resonance (``resonant-pair``), on their anti-phase family: the two
panels are the two oscillators.
"""

import numpy as np

from perturb.report.plots import plot_phase
from problems import get_problem

problem = get_problem("resonant-pair").create(family="anti-phase")
solution = problem.solve(2)
t = np.linspace(0.0, problem.period(solution), 300)
state = problem.state(solution, t)

fig = plot_phase(state, pairs=[("x", "xdot"), ("y", "ydot")], title="resonant pair, anti-phase")
