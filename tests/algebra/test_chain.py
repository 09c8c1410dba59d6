"""The resonant chain (issue 22): every branch certified, the count checked by an independent route."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import root

from perturb.algebra import RootStatus, certified_real_roots
from problems import get_problem
from problems.resonant_chain import chain_system


def _equations(n):
    """The order-1 amplitude equations of the chain, by the engine (x1's amplitude 1)."""
    from perturb import solve
    from perturb.method import conditions

    captured = {}
    original = conditions.ConditionSolver._solve_nonlinear

    def capture(self, eqs, unknowns, *args):
        captured.update(eqs=[sp.expand(e / sp.pi) for e in eqs], unknowns=list(unknowns))
        raise KeyboardInterrupt

    conditions.ConditionSolver._solve_nonlinear = capture
    try:
        solve(chain_system(n), order=1, amplitudes={"x1": 1}, cache=False)
    except KeyboardInterrupt:
        pass
    finally:
        conditions.ConditionSolver._solve_nonlinear = original
    return captured["eqs"], captured["unknowns"]


def _newton_roots(eqs, unknowns, starts=2000, seed=2024):
    """Distinct real roots by Newton from seeded starts over five decades (independent route)."""
    f = sp.lambdify([unknowns], eqs, "numpy")
    jac = sp.lambdify([unknowns], sp.Matrix(eqs).jacobian(unknowns), "numpy")
    rng = np.random.default_rng(seed)
    found = []
    for _ in range(starts):
        start = rng.choice([-1, 1], len(unknowns)) * 10 ** rng.uniform(-2, 3, len(unknowns))
        sol = root(lambda v: np.asarray(f(v), float), start, jac=lambda v: np.asarray(jac(v), float))
        if not sol.success or np.max(np.abs(f(sol.x))) > 1e-8 * max(1, np.max(np.abs(sol.x))):
            continue
        if not any(np.allclose(sol.x, r, rtol=1e-5, atol=1e-3) for r in found):
            found.append(sol.x)
    return found


def test_the_chain_of_two_has_the_in_phase_and_anti_phase_modes():
    """n = 2 by hand: a_x2 = ±1 (symmetric and antisymmetric); Ω1 = 3/8 and 3/8 + 3 = 27/8."""
    eqs, unknowns = _equations(2)
    found = certified_real_roots(eqs, unknowns, seconds=60, backend="sympy")
    omega = sp.Symbol("Omega1")
    assert found.status is RootStatus.SOLVED
    assert sorted(r[omega] for r in found.exact) == [sp.Rational(3, 8), sp.Rational(27, 8)]


@pytest.mark.slow
def test_the_chain_of_three_count_agrees_with_newton():
    eqs, unknowns = _equations(3)
    found = certified_real_roots(eqs, unknowns, seconds=120, backend="sympy")
    assert found.status is RootStatus.SOLVED
    numeric = _newton_roots(eqs, unknowns)
    assert len(found.roots) == len(numeric)
    for r in numeric:  # each numeric root is one of the certified ones
        assert any(
            np.allclose(r, [c[u] for u in unknowns], rtol=1e-5, atol=1e-3) for c in found.roots
        )


@pytest.mark.slow
def test_perturb_families_lists_every_branch_of_the_chain_of_three():
    families = get_problem("resonant-chain-3").create(eps=0.01).families(1)
    assert len(families) == 5 and all(f.status.ok for f in families)


@pytest.mark.slow
def test_a_chain_branch_is_confirmed_against_the_true_motion():
    from perturb import validate

    problem = get_problem("resonant-chain-3").create(eps=0.01)
    names = [f.name for f in problem.families(1)]
    report = validate(problem.with_family(names[0]), order=1)
    assert report.outcome.name == "VALID", report
