"""
Convergence: the error falls like ε^(N+1)
=========================================

:func:`~perturb.report.plots.plot_convergence` draws the error against the expansion parameter on
log–log axes, with the fitted slope and the expected one (``order + 1``). Here the points are the
ones :func:`perturb.validate` measured for its ``order`` check (Duffing, order 2: expected slope 3).
"""

from perturb import validate
from perturb.report.plots import plot_convergence
from problems import get_problem

report = validate(get_problem("duffing").create(eps=0.1, amplitude=1.0), order=2)
fit = report.slope  # the SlopeFit of the order check: the scanned epsilons and their errors
print(report.outcome, f"slope {fit.slope:.2f}")

fig = plot_convergence(fit.epsilons, fit.errors, order=2, slope=fit.slope, slope_band=0.5)
