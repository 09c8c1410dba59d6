"""
Slow ramps through the hysteresis band
======================================

:func:`perturb.ramp` (``perturb ramp``) ramps the drive frequency linearly in time (the phase is
the integral of the frequency) through the true motion, up and down, and sets each jump beside the
fold of the response curve where the branch followed ends; :func:`~perturb.report.plots.plot_ramp`
draws the envelopes against Ω, the jumps dotted, the folds solid. The forced Duffing at ε = 0.02,
F = 0.5 at two rates: the slower ramp jumps nearer the folds.
"""

from perturb import ramp
from perturb.report.plots import plot_ramp
from problems import get_problem

duffing = get_problem("forced-duffing").create(eps=0.02, F=0.5)
loop = ramp(duffing, "Omega", 0.99, 1.06, [1e-5, 2.5e-6], both_ways=True, order=3)
figure = plot_ramp(
    [(f"{r.direction}, rate {r.rate:g}", r.values, r.envelope, r.jump) for r in loop.runs],
    loop.folds, parameter="Omega", coordinate="x", title="forced-duffing: ramps up and down",
)  # fmt: skip
