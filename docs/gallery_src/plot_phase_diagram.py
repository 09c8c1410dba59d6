"""
Phase diagram
=============

How many stable steady states a driven system has at every point of two of its parameters:
:func:`perturb.phase_diagram` (``perturb phase-diagram``) counts them with the certified
first-order census at every point, continues the order-N response along each line of the grid,
and locates the folds where the count changes; :func:`~perturb.report.plots.plot_phase_diagram`
draws the map with those boundaries. Here the forced Duffing oscillator over the forcing
frequency Ω and the forcing level F (a small grid on a Dask cluster of one in-process worker:
``perturb phase-diagram`` starts worker processes, ``--scheduler`` uses a cluster's, and
``--output`` keeps the maps in a Zarr store). Inside the fold lines two stable responses coexist
(the hysteresis band), outside them one.
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
        duffing, ["Omega=0.95:1.5:23", "F=0.2:1:5"], columns=False, client=client
    )
kinds = {int(k): v for k, v in json.loads(ds["special_kind"].attrs["meanings"]).items()}
first_order = ds["special_order"].values == 0
special = [
    (float(x), float(y), kinds[int(k)])
    for x, y, k in zip(
        ds["special_x"].values[first_order],
        ds["special_y"].values[first_order],
        ds["special_kind"].values[first_order],
        strict=True,
    )
]
figure = plot_phase_diagram(
    np.asarray(ds["Omega"].values), np.asarray(ds["F"].values),
    np.asarray(ds["n_stable_first_order"].values), special, xname="Omega", yname="F",
    title="forced-duffing: stable steady states (first order, certified)",
)  # fmt: skip
