"""series_domain (issue 9.4): a series outside its domain is recognised, with the reason."""

import pytest

from perturb.domain import series_domain
from perturb.validation.model import parameter_value_of
from problems import get_problem


def _domain(name, order=1, **parameters):
    problem = get_problem(name).create(**parameters)
    solution = problem.solve(order)
    return series_domain(solution, parameter_value_of(problem), problem.symbol_values())


@pytest.mark.parametrize(
    ("name", "order", "parameters"),
    [("duffing", 2, {"eps": 0.1}), ("van-der-pol", 3, {"eps": 0.1}), ("linear-pair", 1, {})],
)
def test_small_eps_is_inside(name, order, parameters):
    domain = _domain(name, order, **parameters)
    assert domain.ok and domain.reasons == ()
    assert domain.frequency > 0
    sizes = [s for s in domain.term_sizes if s]
    assert all(b < a for a, b in zip(sizes, sizes[1:], strict=False))


@pytest.mark.parametrize(
    ("name", "order", "parameters"),
    [("van-der-pol", 2, {"eps": 5.0}), ("resonant-pair", 1, {"eps": 10.0})],
)
def test_negative_frequency_is_outside(name, order, parameters):
    domain = _domain(name, order, **parameters)
    assert not domain.ok and domain.frequency < 0
    assert "not a positive number" in domain.reasons[0]


def test_terms_not_decreasing_is_outside():
    """Hardening Duffing at eps = 3: Omega = 1 + 3 eps/8 > 0, but eps Omega_1 = 9/8 > Omega_0."""
    domain = _domain("duffing", 1, eps=3.0)
    assert domain.frequency > 0 and not domain.ok
    assert domain.frequency_terms[1] == pytest.approx(9 / 8)
    assert any("not smaller" in r and "frequency" in r for r in domain.reasons)
