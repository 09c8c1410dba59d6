"""The resonant chain (issue 22): every branch certified, the count checked by an independent route."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import root

from perturb._defaults import SLOPE_TOLERANCE
from perturb.algebra import RootStatus, certified_real_roots, msolve_binary
from perturb.algebra.msolve import msolve_real_roots
from perturb.algebra.split import cut, frequency_eliminants
from problems import get_problem
from tests.algebra.chain_equations import amplitude_equations, pairs_of

needs_msolve = pytest.mark.skipif(msolve_binary() is None, reason="needs the extra roots (msolve)")


def _sine(unknowns):
    return [u for u in unknowns if str(u).startswith("b_")]


def _newton_roots(eqs, unknowns, starts=2000, seed=2024):
    """Distinct real roots by Newton from seeded starts over five decades (independent route)."""
    f = sp.lambdify([unknowns], eqs, "numpy")
    jac = sp.lambdify([unknowns], sp.Matrix(eqs).jacobian(unknowns), "numpy")
    rng = np.random.default_rng(seed)
    found = []
    for _ in range(starts):
        start = rng.choice([-1, 1], len(unknowns)) * 10 ** rng.uniform(-2, 3, len(unknowns))
        sol = root(
            lambda v: np.asarray(f(v), float), start, jac=lambda v: np.asarray(jac(v), float)
        )
        if not sol.success or np.max(np.abs(f(sol.x))) > 1e-8 * max(1, np.max(np.abs(sol.x))):
            continue
        if not any(np.allclose(sol.x, r, rtol=1e-5, atol=1e-3) for r in found):
            found.append(sol.x)
    return found


def test_the_chain_of_two_has_the_in_phase_and_anti_phase_modes():
    """n = 2 by hand: a_x2 = ±1 (symmetric and antisymmetric); Ω1 = 3/8 and 3/8 + 3 = 27/8."""
    eqs, unknowns = amplitude_equations(2)
    found = certified_real_roots(eqs, unknowns, seconds=60, backend="sympy")
    omega = sp.Symbol("Omega1")
    assert found.status is RootStatus.SOLVED
    assert sorted(r[omega] for r in found.exact) == [sp.Rational(3, 8), sp.Rational(27, 8)]


@pytest.mark.slow
def test_the_chain_of_three_count_agrees_with_newton():
    eqs, unknowns = amplitude_equations(3)
    found = certified_real_roots(eqs, unknowns, seconds=120, backend="sympy")
    assert found.status is RootStatus.SOLVED
    numeric = _newton_roots(eqs, unknowns)
    assert len(found.roots) == len(numeric)
    for r in numeric:  # each numeric root is one of the certified ones
        assert any(
            np.allclose(r, [c[u] for u in unknowns], rtol=1e-5, atol=1e-3) for c in found.roots
        )


@pytest.mark.parametrize("n", [3, 4])
def test_the_cuts_refute_every_piece_with_a_sine_amplitude(n):
    """With the spring-power members, every piece where some sine amplitude is non-zero is
    proved empty (no leaf is left to solve); the one leaf is the standing waves b = 0."""
    eqs, unknowns = amplitude_equations(n)
    leaves = cut(eqs, unknowns, members=frequency_eliminants(eqs, unknowns, pairs_of(n)))
    assert len(leaves) == 1
    assert not set(leaves[0].unknowns) & set(_sine(unknowns))
    assert leaves[0].path == (
        f"sign symmetry in ({', '.join(map(str, _sine(unknowns)))}): all zero",
    )


@needs_msolve
def test_the_cut_system_and_the_whole_system_have_the_same_roots():
    """Two routes for the chain of 4: cut then solved, and msolve on the whole system at once
    (which knows nothing of the cuts): the same 8 roots."""
    eqs, unknowns = amplitude_equations(4)
    cut_route = certified_real_roots(eqs, unknowns, seconds=120, pairs=pairs_of(4))
    whole = msolve_real_roots(eqs, unknowns, 120)
    assert cut_route.status is whole.status is RootStatus.SOLVED
    assert len(cut_route.roots) == len(whole.roots) == 8
    for r in whole.roots:
        assert any(
            np.allclose([r[u] for u in unknowns], [c[u] for u in unknowns], rtol=1e-9, atol=1e-9)
            for c in cut_route.roots
        )


@pytest.mark.slow
def test_perturb_families_lists_every_branch_of_the_chain_of_three():
    """The five branches, each carried, each named by its mode shape (family_names rule 4)."""
    families = get_problem("resonant-chain-3").create(eps=0.01).families(1)
    assert len(families) == 5 and all(f.status.ok for f in families)
    assert sorted(f.name for f in families) == [
        "anti-phase-1",
        "anti-phase-2",
        "anti-phase-3",
        "in-phase",
        "shape-p0n",
    ]


@pytest.mark.slow
@needs_msolve
def test_the_chain_of_four_every_branch_counted_twice():
    """n = 4: the families (certified solver, every branch carried to order 1) against Newton
    from 2000 seeded starts on the whole amplitude system, which knows nothing of the cuts: a
    lower bound (starts in a box of five decades miss the branches of large amplitude), and every
    root it finds is one of the families'."""
    eqs, unknowns = amplitude_equations(4)
    families = get_problem("resonant-chain-4").create(eps=0.01).families(1)
    assert len(families) == 8 and all(f.status.ok for f in families)
    numeric = _newton_roots(eqs, unknowns)
    assert 0 < len(numeric) <= len(families)
    cosines = [i for i, u in enumerate(unknowns) if str(u).startswith("a_")]
    branches = [
        [float(sp.N(f.amplitudes[str(unknowns[i])[:-1]])) for i in cosines] for f in families
    ]
    for r in numeric:
        # the standing waves are multiple roots of the whole system in the sine amplitudes (msolve:
        # 128 roots with multiplicity, 120 without): Newton creeps there, b ~ 1e-3 when it stops
        assert np.max(np.abs(np.delete(r, [0, *cosines]))) < 1e-2
        assert any(np.allclose(r[cosines], b, rtol=1e-5, atol=1e-3) for b in branches), r


@pytest.mark.slow
@pytest.mark.parametrize(
    ("n", "family"),
    [
        (3, "in-phase"),
        (3, "shape-p0n"),
        (3, "anti-phase-1"),
        (4, "shape-ppnn"),
        (4, "anti-phase-localised-x2-1"),
    ],
)
def test_a_sample_of_chain_branches_is_confirmed_against_the_true_motion(n, family):
    """perturb validate on a sample of branches: a true periodic orbit near each, and the error
    of the order-1 solution falls like eps^2 along the branch itself (the slope scan re-creates
    the problem at other eps with the same family)."""
    from perturb import validate

    problem = get_problem(f"resonant-chain-{n}").create(eps=0.01, family=family)
    report = validate(problem, order=1)
    assert report.outcome.name == "VALID", report.verdict
    assert abs(report.slope.slope - 2) <= SLOPE_TOLERANCE  # order + 1, within the band
