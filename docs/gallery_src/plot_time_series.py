"""
Time series: the analytic solution beside the true motion
=========================================================

:func:`~perturb.report.plots.plot_time_series` draws each state component against time, the
analytic solution solid and the true motion (the original equation integrated from the same
initial state) dashed on top. Duffing's oscillator at ε = 0.3, order 2, over three periods.
"""

import numpy as np

from perturb.oracle import choose
from perturb.report.plots import plot_time_series
from perturb.validation import original_equations
from problems import get_problem

problem = get_problem("duffing").create(eps=0.3, amplitude=1.0)
solution = problem.solve(2)
t = np.linspace(0.0, 3 * problem.period(solution), 400)
analytic = problem.state(solution, t)  # {"x": ..., "xdot": ...}

# the true motion: the original equation integrated from the analytic initial state
y0 = np.array([analytic[name][0] for name in problem.state_names()])
trajectory = choose().integrate(original_equations(problem, y0).rhs, (0.0, t[-1]), y0, t_eval=t)
true = dict(zip(problem.state_names(), trajectory.y, strict=True))

fig = plot_time_series(t, analytic, true, time_unit="", title="Duffing, ε = 0.3, order 2")
