"""The disk's solution symbolic in the body's parameters (``solve(order, symbolic=True)``), at
order 1 (the default route) in the default suite and at order 2 among the slow tests.

Two routes to the same exact object: the symbolic solution with the body's exact values put in
afterwards, and the specialised solution with the values put in before the reduction. They must
agree term by term, exactly (evaluation at numbers commutes with every step of the reduction and the
construction), and the physical states they give must agree to round-off.
"""

import numpy as np
import pytest
import sympy as sp

from perturb.errors import InvalidParameterError
from problems import get_problem

DISK = get_problem("disk")
#: Fast-spin disks where the theory holds (README's example and a second body).
BODIES = (
    {"r0": 0.755155, "R": 0.123299, "gamma3_0": 0.25},
    {"r0": 0.8, "R": 0.12, "gamma3_0": 0.3, "x0": 0.7},
)


@pytest.fixture(
    scope="module",
    # order 1 in the default suite (the default route: symbolic up to SYMBOLIC_MAX_ORDER); the
    # order-2 derivation takes minutes
    params=[1, pytest.param(2, marks=pytest.mark.slow)],
    ids=["order1", "order2"],
)
def symbolic(request):
    return DISK.create(**BODIES[0]).solve(request.param, symbolic=True)


def test_symbolic_solution_keeps_the_parameters_and_is_shared(symbolic):
    names = {s.name for s in symbolic.system.parameters}
    assert {"a", "b", "k", "gamma3_0"} <= names
    assert symbolic.frequency[2].free_symbols & set(symbolic.system.parameters)
    # one derivation serves every parameter set
    assert DISK.create(**BODIES[1]).solve(symbolic.order, symbolic=True) is symbolic


@pytest.mark.parametrize("values", BODIES)
def test_values_put_in_afterwards_equal_the_specialised_solution_exactly(symbolic, values):
    problem = DISK.create(**values)
    special = problem.solve(symbolic.order, symbolic=False)
    assert not special.system.parameters
    exact = problem.exact_values()
    for k, (mine, theirs) in enumerate(zip(symbolic.frequency, special.frequency, strict=True)):
        difference = mine.xreplace(exact) - theirs
        assert sp.simplify(difference) == 0, f"frequency term {k}"
    for name in symbolic.coordinates:
        difference = symbolic.coordinate(name).xreplace(exact) - special.coordinate(name)
        assert sp.simplify(sp.expand(difference)) == 0, name


@pytest.mark.parametrize("values", BODIES)
def test_both_routes_give_the_same_motion(symbolic, values):
    problem = DISK.create(**values)
    special = problem.solve(symbolic.order, symbolic=False)
    t = np.linspace(0.0, 3 * problem.period(special), 11)
    mine, theirs = problem.state_vector(symbolic, t), problem.state_vector(special, t)
    # both are float evaluations of the same exact series: round-off only
    assert np.max(np.abs(mine - theirs)) <= 1e3 * np.finfo(float).eps * np.max(np.abs(theirs))
    assert problem.period(symbolic) == pytest.approx(problem.period(special), rel=1e-13)


@pytest.mark.parametrize("bad", ["yes", 1.0, 2])
def test_symbolic_must_be_a_bool(bad):
    with pytest.raises(InvalidParameterError, match="`symbolic`"):
        DISK.create(**BODIES[0]).solve(1, symbolic=bad)
