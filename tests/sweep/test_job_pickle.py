"""A sweep's job is what Dask sends to every worker: it must read back on a worker whose libraries
are not this process's. A README block failed on a fresh machine (mpmath 1.4.1 there, 1.3.0 here):
the parameter map's mpmath-lambdified function carried mpmath's whole namespace by value, and
every chunk failed to unpickle. The job now carries the map's expressions, never its compiled
functions."""

from __future__ import annotations

import pickle
import re

import pytest

cloudpickle = pytest.importorskip("cloudpickle")

from perturb.sweep.derive import plan  # noqa: E402
from perturb.sweep.grid import parse_axis  # noqa: E402
from perturb.sweep.spec import SweepJob, check_spec  # noqa: E402
from problems import get_problem  # noqa: E402

#: Modules whose objects a job may name only by reference (a worker imports its own).
BY_REFERENCE_ONLY = (rb"mpmath",)


@pytest.mark.parametrize(
    ("name", "values", "axes"),
    [
        ("disk", {"R": 0.123299}, ["r0=0.5:1.0:3", "gamma3_0=0.1:0.4:3"]),  # eps from the map
        ("forced-duffing", {}, ["Omega=0.95:1.2:3", "F=0.5:1:2"]),  # sigma from the map
    ],
)
def test_a_job_carries_no_library_namespace(name, values, axes):
    problem = get_problem(name).create(**values)
    problem.case().map.evaluate(dict(problem.values))  # the compiled functions made, as in a run
    spec = check_spec(problem, [parse_axis(a) for a in axes], order=1)
    derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
    blob = cloudpickle.dumps(SweepJob(spec, derivation, "test"))
    for module in BY_REFERENCE_ONLY:
        assert not re.search(module, blob), module


def test_a_parameter_map_reads_back_and_evaluates_the_same():
    problem = get_problem("disk").create(R=0.123299)
    mapping = problem.case().map
    before = mapping.evaluate(dict(problem.values))
    again = pickle.loads(pickle.dumps(mapping))
    assert again == mapping and again.evaluate(dict(problem.values)) == before
