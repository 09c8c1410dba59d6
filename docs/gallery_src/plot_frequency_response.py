"""
Frequency response
==================

:func:`~perturb.report.plots.plot_frequency_response` draws every branch of a driven system's
steady-state response over a sweep, continued through its folds at order 3: stable solid,
unstable dashed, the folds where the response jumps, the free system's backbone and the true
orbits shot on each branch (largest amplitude, both sides of the fold), drawn at their true
max ``|x|``. The forced, damped Duffing oscillator near its primary resonance
(``perturb response forced-duffing``).
"""

import numpy as np

from perturb.report.plots import plot_frequency_response
from perturb.response.model import problem_response
from problems import get_problem

duffing = get_problem("forced-duffing").create(eps=0.05, zeta=0.1, gamma=1.0, F=1.0)
result = problem_response(duffing, "Omega", np.linspace(0.95, 1.2, 51), order=3, validate=1)

fig = plot_frequency_response(result)
