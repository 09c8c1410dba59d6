"""
Phase diagram
=============

How many stable steady states a driven system has at every point of two of its parameters:
:func:`perturb.phase_diagram` (``perturb phase-diagram``) continues the order-N response along
each line of the grid (stability from the Floquet multipliers along the order-N orbit), counts
the certified first-order steady states at every point as well, and locates the folds where the
counts change; :func:`~perturb.report.plots.plot_phase_diagram` draws a map with those
boundaries. Here the forced Duffing oscillator over the forcing frequency Ω and the forcing level
F, the responses continued at order 1 (a small grid on a Dask cluster of one in-process worker:
``perturb phase-diagram`` starts worker processes, ``--scheduler`` uses a cluster's, and
``--output`` keeps the maps in a Zarr store). Inside the fold lines two stable responses coexist (the hysteresis
band), outside them one.

Which count to read where the amplitude is large: at F = 0.5 the continued curve's jump-down
fold is at Ω = 1.0945 (order 1; 1.0941 at order 3, where shooting finds true orbits on both
sides of it: ``perturb response forced-duffing --set F=0.5 --validate``), while the certified
first-order count (``n_stable_first_order``, the classical slow flow's folds) puts it at 1.117.
"""

import json

import numpy as np
from distributed import Client, LocalCluster

import perturb
from perturb.report.plots import plot_phase_diagram
from problems import get_problem

duffing = get_problem("forced-duffing").create()
with (
    LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cluster,
    Client(cluster) as client,
):
    ds = perturb.phase_diagram(
        duffing, ["Omega=0.95:1.2:26", "F=0.1:0.6:6"], order=1, columns=False, client=client
    )
kinds = {int(k): v for k, v in json.loads(ds["special_kind"].attrs["meanings"]).items()}
order_n = ds["special_order"].values == 1
special = [
    (float(x), float(y), kinds[int(k)])
    for x, y, k in zip(
        ds["special_x"].values[order_n],
        ds["special_y"].values[order_n],
        ds["special_kind"].values[order_n],
        strict=True,
    )
]
figure = plot_phase_diagram(
    np.asarray(ds["Omega"].values), np.asarray(ds["F"].values),
    np.asarray(ds["n_stable"].values), special, xname="Omega", yname="F",
    title="forced-duffing: stable steady states (continued, order 1)",
)  # fmt: skip
