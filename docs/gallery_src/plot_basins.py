"""
Basins of attraction
====================

Which of the coexisting steady states each initial state reaches: :func:`perturb.basins`
(``perturb basins``) integrates every state of the grid (heyoka's batch integrator, stroboscopic
returns only) until it stays within the capture radius of a steady state the series found and the
shooting proved; :func:`~perturb.report.plots.plot_basins` draws the map with the attractors, the
saddle and the first-order slow flow's separatrix (the saddle's stable manifold of the averaged
equations) over it. Here the bistable forced Duffing oscillator at Ω = 1.05 on the section at
drive phase 0: the small response's basin is the spiral arm around its attractor, bounded by the
separatrix to O(ε).
"""

from perturb import basins
from perturb.report.plots import plot_basins
from problems import get_problem

duffing = get_problem("forced-duffing").create(Omega=1.05)
result = basins(duffing, ["x=-3:3:60", "xdot=-3:3:60"])
ds, chart = result.dataset, result.catalogue
figure = plot_basins(
    ds["x"].values, ds["xdot"].values, ds["code"].values, result.names(),
    [(s.name, s.points) for s in chart.attractors], [(s.name, s.points) for s in chart.saddles],
    result.separatrix, xname="x", yname="xdot",
    title="forced-duffing, Omega = 1.05: "
    + ", ".join(f"{f.name} {f.fraction:.3f}±{f.error:.3f}" for f in result.fractions),
)  # fmt: skip
