"""
A transient beside the slow flow
================================

:func:`perturb.transient` (``perturb transient``) integrates the true motion from one state and,
beside it, the slow flow — the amplitude equations as ODEs in slow time, here of order 2;
:func:`~perturb.report.plots.plot_transient` draws the motion, its envelope (the slow amplitude
read off the true motion) and the slow flow's, and the phases below. The bistable forced Duffing
from x = 2 at rest settles on its large response; the dotted line is when it entered that
state's capture radius for good.
"""

from perturb import transient
from perturb.report.plots import plot_transient
from problems import get_problem

duffing = get_problem("forced-duffing").create(Omega=1.05)
run = transient(duffing, {"x": 2.0, "xdot": 0.0}, 250, order=2)
figure = plot_transient(
    run.times, run.state[:, 0], run.envelope()[:, 0], run.envelope(slow=True)[:, 0],
    run.phase_of()[:, 0], run.phase_of(slow=True)[:, 0], coordinate="x",
    settle_time=run.settle_time, title=f"forced-duffing from x = 2: settles on {run.settled}",
)  # fmt: skip
