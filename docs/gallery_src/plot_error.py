"""
Error against time
==================

:func:`~perturb.report.plots.plot_error` draws ``|analytic − true|`` on a logarithmic axis, each
component relative to its amplitude. Van der Pol's limit cycle at ε = 0.1 over ten periods, at
orders 1 and 3: two more orders lower the error by more than a hundredfold.
"""

import numpy as np

from perturb.oracle import choose
from perturb.report.plots import plot_error
from perturb.validation import original_equations
from problems import get_problem

problem = get_problem("van-der-pol").create(eps=0.1)
figures = []
for order in (1, 3):
    solution = problem.solve(order)
    t = np.linspace(0.0, 10 * problem.period(solution), 1000)
    analytic = problem.state(solution, t)
    y0 = np.array([analytic[name][0] for name in problem.state_names()])
    trajectory = choose().integrate(original_equations(problem, y0).rhs, (0.0, t[-1]), y0, t_eval=t)
    true = dict(zip(problem.state_names(), trajectory.y, strict=True))
    title = f"van der Pol, ε = 0.1, order {order}"
    figures.append(plot_error(t, analytic, true, time_unit="", title=title))
