"""The disk's true periodic orbits by shooting (full Euler–Poisson system) against the reference.

The reference (derivation.md (f)) finds the true periodic orbit of the full 6-D system by shooting
and reads :math:`\\beta_1 = P(0)`, :math:`\\beta_2 = \\dot P(0)` on the section :math:`\\dot G = 0`
(the analytic solution's phase) with :math:`r_1 = 1`, :math:`\\gamma'' = \\gamma_0''`,
:math:`|\\boldsymbol\\gamma| = 1` there. We do the same with :func:`perturb.oracle.find_periodic_orbit`
and the reduction's exact forward map.

**Conditioning.** The P-oscillation is detuned from the G-oscillation by only
:math:`\\varepsilon^2 D`, :math:`D = kM_3^2/2`: its Floquet multipliers are
:math:`e^{\\pm i\\varphi}`, :math:`\\varphi = 2\\pi\\varepsilon^2 D`, so an error :math:`\\delta` (relative)
in :math:`P(0)` changes the periodicity defect by only :math:`\\varphi\\delta|P|`. At the paper
geometry (:math:`\\varepsilon = 10^{-4}`, :math:`k = 2.47\\times10^{-5}`) :math:`\\varphi = 7.7\\times10^{-13}`,
and in float64 that defect is below round-off: a plain shooting accepts any seed within ~1 % as
"converged" in 0 iterations (:func:`test_plain_shooting_cannot_resolve_the_paper_geometry`). The
shooting here is therefore the conditioned, extended-precision one of
:func:`problems.rigid_body.true_orbit.conditioned_true_orbit` (conditioned coordinates, time in
units of the detuning phase, heyoka in 80-bit or quadruple precision; see its module docstring).

**Exact inputs.** At the paper geometry a relative error of 1e-16 in one coefficient of the
resonant part of the equations (breaking A + B = C) moves the amplitudes by ~1e-3, so the shooting
is built from the parameters as exact rationals (:mod:`problems.rigid_body.exact_inputs`), each
coefficient rounded once to quadruple precision. A second route — a 40-digit mpmath Taylor
integration with its own Newton shooting (:mod:`problems.rigid_body.true_orbit_mp`, slow test
below) — gives the same orbit: beta1/eps = 3.917973581, beta2/eps = 1.127631771,
(T - 2 pi)/eps**2 = 1.0329529858, against 3.917973588, 1.127631773, 1.0329529858 here (agreement
2e-9). The figures 3.910760, 1.125556 quoted before came from double-rounded coefficients.

Results: k = 0.5, gamma3_0 = 0.3 reproduces all printed digits of the reference (8.6977, 2.4848,
1.19547 at eps = 5e-3; 8.6650, 2.4756, 1.19753 at 2.5e-3). At the paper geometry the period agrees
(1.03296) but the true amplitudes are 3.91797, 1.12763, **not** the reference's 3.87665, 1.11593:
those are within 1.3e-5 of the first-order seed (3.87670, 1.11592), which an unconditioned shooting
cannot move. The true values exceed the first order by 1.06 %, 1.6 times the amplitude-dependent
detuning :math:`|\\beta|^2/(kM_3^2) = 0.66\\,\\%` neglected at first order — the same mechanism
gives the 0.50 % (ratio 0.45 %) at k = 0.5, eps = 5e-3, where the reference resolved the orbit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from perturb.oracle import SymbolicRHS, find_periodic_orbit, heyoka_available
from problems import get_problem
from problems.rigid_body.true_orbit import conditioned_true_orbit
from problems.rigid_body.true_orbit_mp import mp_true_orbit

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="needs heyoka (extended precision)")

Disk = get_problem("disk")

#: Reference (f), true periodic orbits: (beta1/eps, beta2/eps, (T - 2 pi)/eps**2).
REFERENCE_K05 = {5e-3: (8.6977, 2.4848, 1.19547), 2.5e-3: (8.6650, 2.4756, 1.19753)}
REFERENCE_PAPER = (3.87665, 1.11593, 1.03296)
PAPER_EPS = 1e-4
#: Agreement required with the reference's numbers (relative).
REL_TOL = 1e-4
#: The true orbit at the paper geometry, (beta1/eps, beta2/eps, (T - 2 pi)/eps**2), where the two
#: routes agree: quadruple-precision conditioned shooting 3.917973588, 1.127631773, 1.03295298577;
#: 40-digit mpmath Taylor shooting 3.917973581, 1.127631771, 1.03295298577.
TRUE_PAPER = (3.9179736, 1.1276318, 1.0329529858)
#: Agreement required with TRUE_PAPER: the routes differ by 2e-9, each resolves the amplitudes to
#: ~1e-9, and the pinned digits are rounded by <= 1.5e-8 (relative); 1e-7 leaves a factor ~6.
TRUE_TOL = 1e-7
#: Least relative change a corrected seed shows: the seed 0.99 x first order is 2.1 % below the true
#: beta1 (the first order is 1.06 % below it), against a resolution ~1e-9 of the result.
SEED_CORRECTED = 1e-2
#: Agreement required of the two routes (the brief's 1e-6; they agree to 2e-9).
ROUTES_TOL = 1e-6

#: A plain shooting leaves P(0) where the guess put it, to this (relative): the P-direction's
#: singular value (phi ~ 7.7e-13 of the others) is below the rank cut 1e-9, so the steps leave it.
UNMOVED = 1e-9
#: eps values of the slope fit of the first-order amplitude error (k = 0.5, gamma3_0 = 0.3).
SLOPE_EPSILONS = (0.01, 0.005, 0.0025)
SLOPE_SLACK = 0.3
#: Largest |r1 - 1| + |gamma'' - gamma3_0| at dG = 0: the pins hold on the shooting section
#: gamma' = const, a time O(eps**3) away; such a mismatch moves beta/eps by < 1e-7 (relative).
PIN_MISMATCH = 1e-8
#: Upper bound of (beta_true/beta_first - 1) / (|beta|^2/(k M3^2)): an O(1) coefficient, 1.1 and 1.6
#: at the two geometries tested; 2 says "of the size of", not more.
EXCESS_RATIO_MAX = 2.0

ARM, C_MOMENT, MASS = math.hypot(1.0, 6.0), 20.0, 200.0


def disk(eps: float, k: float | None = None, gamma3_0: float = 7e-6):
    """The paper's disk with r0 = 1 (so tau = t) and c = eps; ``k = None`` keeps R = 2000."""
    R = 2000.0 if k is None else 3 * C_MOMENT / (k * MASS * ARM)
    g = eps**2 * C_MOMENT / (MASS * ARM)
    return Disk.create(g=g, r0=1.0, R=R, gamma3_0=gamma3_0)


def true_orbit(problem, offset: float = 0.0):
    """The library's conditioned shooting; these tests need it to converge."""
    orbit = conditioned_true_orbit(problem, offset=offset)
    assert orbit.success, orbit.message
    return orbit


@pytest.fixture(scope="module")
def paper():
    return true_orbit(disk(PAPER_EPS))


@pytest.fixture(scope="module")
def k05():
    return {eps: true_orbit(disk(eps, k=0.5, gamma3_0=0.3)) for eps in SLOPE_EPSILONS}


# ------------------------------------------------------------------------------ k = 0.5
@pytest.mark.parametrize("eps", sorted(REFERENCE_K05))
def test_k05_reproduces_the_reference(k05, eps):
    orbit = k05[eps]
    got = (orbit.beta1, orbit.beta2, orbit.alpha)
    assert got == pytest.approx(REFERENCE_K05[eps], rel=REL_TOL)
    # the pins (r1 = 1, gamma'' = gamma3_0) hold at dG = 0 as well as on the shooting section
    assert orbit.pin_mismatch < PIN_MISMATCH


def test_first_order_amplitude_error_falls_like_eps_squared(k05):
    eps = np.array(SLOPE_EPSILONS)
    err = np.array([abs(k05[e].first_order[0] - k05[e].beta1) for e in SLOPE_EPSILONS])
    slope = np.polyfit(np.log(eps), np.log(err), 1)[0]
    assert abs(slope - 2) < SLOPE_SLACK, (slope, err)


# ------------------------------------------------------------------------------ paper geometry
def test_paper_geometry_period_matches_the_reference(paper):
    assert paper.alpha == pytest.approx(REFERENCE_PAPER[2], rel=REL_TOL)
    assert paper.pin_mismatch < PIN_MISMATCH


def test_paper_geometry_true_orbit_is_the_two_route_value(paper):
    assert (paper.beta1, paper.beta2, paper.alpha) == pytest.approx(TRUE_PAPER, rel=TRUE_TOL)
    assert paper.resolution < TRUE_TOL / 10


def test_paper_geometry_true_amplitudes_do_not_depend_on_the_seed(paper):
    """A seed 1 % below the family member is moved onto the same orbit: the result is far from
    the seed (farther than its resolution by orders of magnitude) and the paper's orbit to
    TRUE_TOL. (Not the iteration count: the last re-centring may converge in 0 Newton iterations
    on one machine and in 1 on another.)"""
    offset = -0.01
    other = true_orbit(disk(PAPER_EPS), offset=offset)
    seed = (1 + offset) * other.first_order[0]  # the seed's P(0)/eps, to O(eps**2)
    assert abs(other.beta1 / seed - 1) > SEED_CORRECTED  # the seed was really corrected
    assert (other.beta1, other.beta2) == pytest.approx((paper.beta1, paper.beta2), rel=TRUE_TOL)


def test_the_cli_geometry_gives_the_same_orbit_through_the_hook():
    """``perturb validate disk --set r0=30.2062``: the problem's hook, parameters as typed."""
    orbit = Disk.create(r0=30.2062).true_periodic_orbit()
    assert orbit.success, orbit.message
    assert "exact rational parameters" in orbit.message
    assert (orbit.beta1, orbit.beta2, orbit.alpha) == pytest.approx(TRUE_PAPER, rel=TRUE_TOL)


@pytest.mark.slow
def test_the_mpmath_route_agrees_with_the_quadruple_precision_route(paper):
    """The independent route: 40-digit mpmath Taylor integration, its own Newton shooting (~15 s)."""
    other = mp_true_orbit(disk(PAPER_EPS))
    assert other.last_step < 1e-9
    got = (other.beta1, other.beta2, float(other.alpha))
    assert got == pytest.approx((paper.beta1, paper.beta2, paper.alpha), rel=ROUTES_TOL)
    assert got == pytest.approx(TRUE_PAPER, rel=TRUE_TOL)


@pytest.mark.xfail(
    strict=True,
    reason="reference (f)'s 3.87665, 1.11593 are the first-order seed (3.87670, 1.11592) left "
    "unresolved by an unconditioned shooting; the true orbit has 3.91797, 1.12763",
)
def test_paper_geometry_amplitudes_match_the_reference(paper):
    assert (paper.beta1, paper.beta2) == pytest.approx(REFERENCE_PAPER[:2], rel=REL_TOL)


@pytest.mark.parametrize("which", ["paper", "k05"])
def test_amplitude_excess_is_the_amplitude_dependent_detuning(paper, k05, which):
    """beta_true/beta_first - 1 is of the size |beta|^2/(k M3^2) (the neglected detuning part):
    1.1 times it at k = 0.5, 1.6 times at the paper geometry (1.33 from double-rounded inputs)."""
    problem, orbit = (
        (disk(PAPER_EPS), paper) if which == "paper" else (disk(5e-3, 0.5, 0.3), k05[5e-3])
    )
    excess = orbit.beta1 / orbit.first_order[0] - 1
    assert 1.0 < excess / problem.detuning_ratio() < EXCESS_RATIO_MAX


def test_plain_shooting_cannot_resolve_the_paper_geometry():
    """Unconditioned (float64, physical state): a seed 1 % off is accepted as it is."""
    problem = disk(PAPER_EPS)
    solution = problem.solve(1)
    seed = problem.state_vector(solution, 0.0).astype(float)
    guess = seed.copy()
    guess[:2] *= 1.01
    rhs = SymbolicRHS(*problem.original_symbolic())
    orbit = find_periodic_orbit(
        rhs,
        guess,
        problem.period(solution),
        section_index=4,
        section_value=seed[4],
        fixed_indices=(2, 3, 5),
        n_trivial=4,
    )
    # "converged" where it started: P(0) is not moved (the P-direction is below the rank cut of
    # the Newton matrix, 1e-9 of its largest singular value), however many iterations the other
    # components take on a given machine; the orbit is 1 % off the true one
    assert orbit.success, orbit.message
    assert orbit.initial_state[0] == pytest.approx(1.01 * seed[0], rel=UNMOVED)
