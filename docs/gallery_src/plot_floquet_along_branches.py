"""
Stability along the branches
============================

:func:`~perturb.report.plots.plot_floquet_along_branches` draws the largest modulus of the Floquet
multipliers along each branch of a frequency response (the variational equation along the order-N
orbit): above 1 the branch is unstable (the middle branch of the hardening Duffing oscillator), and
on the stable branches it is e^(−εζT), Liouville's bound for linear damping.
"""

import numpy as np

from perturb.report.plots import plot_floquet_along_branches
from perturb.response.model import problem_response
from problems import get_problem

result = problem_response(
    get_problem("forced-duffing").create(), "Omega", np.linspace(0.95, 1.2, 51)
)

fig = plot_floquet_along_branches(result)
