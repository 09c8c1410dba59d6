"""The resonant chain problems: derived from their potential, registered by size."""

import sympy as sp

from perturb import EPS
from perturb.validation import with_epsilon
from problems import get_problem
from problems.resonant_chain import chain_of, chain_system


def test_the_equations_are_minus_the_gradient_of_the_springs_energy():
    x1, x2, x3 = sp.symbols("x1 x2 x3")
    rhs = chain_system(3).rhs
    by_hand = [
        -EPS * (x1**3 + (x1 - x2) ** 3),
        -EPS * ((x2 - x1) ** 3 + (x2 - x3) ** 3),
        -EPS * ((x3 - x2) ** 3 + x3**3),
    ]
    assert all(sp.expand(a - b) == 0 for a, b in zip(rhs, by_hand, strict=True))


def test_every_size_is_registered_and_any_size_can_be_made():
    for n in (2, 3, 4, 6):
        assert get_problem(f"resonant-chain-{n}").n == n
    assert len(chain_of(5).build_system().coordinates) == 5


def test_a_problem_at_another_eps_keeps_its_family():
    """validate's slope scan re-creates the problem at other eps: it must follow the same family
    (it followed the default one, so every family of a chain showed the same slope)."""
    problem = get_problem("resonant-chain-2").create(eps=0.05, family="anti-phase")
    moved = with_epsilon(problem, 0.01)
    assert moved.case().family == "anti-phase" and moved.values["eps"] == 0.01
