"""
Validity maps
=============

A sweep over two parameters (``perturb sweep``, ``perturb.sweep(...)``) gives one number a point;
:func:`~perturb.report.plots.plot_verdict_map`, :func:`~perturb.report.plots.plot_error_map`,
:func:`~perturb.report.plots.plot_slope_map` and :func:`~perturb.report.plots.plot_period_map`
draw them as maps over the two parameters. Here a small Duffing map (order 1, ε × amplitude),
each point checked with :func:`perturb.validate` in a plain loop — what a sweep computes at every
point, on Dask, for grids of thousands of points. The maps take plain arrays: ``x`` along the
first dimension, ``y`` along the second, as a sweep's Dataset orders them.
"""

import json

import numpy as np

from perturb import validate
from perturb.report.plots import (
    plot_error_map,
    plot_period_map,
    plot_slope_map,
    plot_verdict_map,
)
from perturb.sweep.status import code_of, coding_attrs
from perturb.validation import Verdict
from problems import get_problem

eps = np.array([0.05, 0.2, 0.5, 1.0, 2.0])
amplitude = np.array([0.5, 1.0, 1.5, 2.0])
duffing = get_problem("duffing").create()
shape = (eps.size, amplitude.size)
verdict, error, slope, period = (np.full(shape, np.nan) for _ in range(4))
for i, e in enumerate(eps):
    for j, a in enumerate(amplitude):
        report = validate(duffing.with_parameters(eps=float(e), amplitude=float(a)), periods=2)
        verdict[i, j] = code_of(report.outcome)
        period[i, j] = report.period
        if report.periodic_orbit is not None:
            error[i, j] = report.periodic_orbit.orbit_error
        if report.slope is not None:
            slope[i, j] = report.slope.slope
labels = {int(k): v for k, v in json.loads(coding_attrs(Verdict, "verdict")["labels"]).items()}

verdicts = plot_verdict_map(eps, amplitude, verdict, labels, xname="eps", yname="amplitude")

# %%
# The orbit error on a log scale, with the contour of the tolerance (0.1) that separates the
# accurate region from the rest:

errors = plot_error_map(eps, amplitude, error, tol=0.1, xname="eps", yname="amplitude")

# %%
# The measured order slope about the expected 2 (order 1): below 1.5 the order check fails.

slopes = plot_slope_map(
    eps, amplitude, slope, expected=2.0, band=0.5, xname="eps", yname="amplitude"
)

# %%
# The analytic period, which falls with the amplitude of the hardening spring:

periods = plot_period_map(eps, amplitude, period, xname="eps", yname="amplitude")
