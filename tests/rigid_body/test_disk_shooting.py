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
shooting here therefore runs on the same equations in conditioned coordinates:

1. the state relative to the seed, :math:`y = y_{ref} + s\\,u` (no cancellation in
   :math:`u(T) - u(0)`), with :math:`s_p = s_q = \\varphi|P|\\,` :data:`RESOLUTION` / :data:`TOL`, so
   that a relative error :data:`RESOLUTION` in :math:`P(0)` shows as a residual :data:`TOL`;
2. time in units :math:`1/\\lambda`, so that the Newton column :math:`\\partial F/\\partial T` is of
   the size of the P columns (the shooting's rank cut is 1e-9);
3. a constant extra component :math:`w` with time rate :math:`1 + \\lambda w`: a float64 period has
   granularity :math:`10^{-16}T`, which alone moves the P-phase by :math:`10^{-16}\\cdot2\\pi`, i.e.
   :math:`10^{-3}` of :math:`\\varphi` — :math:`w` takes up that last bit of the period;
4. heyoka in extended precision (80-bit long double, else quadruple).

Results (all seeds and conditioning choices agree to ~1e-6): k = 0.5, gamma3_0 = 0.3 reproduces
all printed digits of the reference (8.6977, 2.4848, 1.19547 at eps = 5e-3; 8.6650, 2.4756, 1.19753
at 2.5e-3). At the paper geometry the period agrees (1.03296) but the true amplitudes are
3.91076, 1.12556, **not** the reference's 3.87665, 1.11593: those are within 1.3e-5 of the first-order
seed (3.87670, 1.11592), which an unconditioned shooting cannot move. The true values exceed the
first order by 0.88 %, of the size of the amplitude-dependent detuning
:math:`|\\beta|^2/(kM_3^2) = 0.66\\,\\%` neglected at first order — the same mechanism gives the 0.50 %
(ratio 0.45 %) at k = 0.5, eps = 5e-3, where the reference resolved the orbit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from attrs import frozen

from perturb.oracle import Heyoka, SymbolicRHS, find_periodic_orbit, heyoka_available
from problems import get_problem

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="needs heyoka (extended precision)")

Disk = get_problem("disk")

#: Reference (f), true periodic orbits: (beta1/eps, beta2/eps, (T - 2 pi)/eps**2).
REFERENCE_K05 = {5e-3: (8.6977, 2.4848, 1.19547), 2.5e-3: (8.6650, 2.4756, 1.19753)}
REFERENCE_PAPER = (3.87665, 1.11593, 1.03296)
PAPER_EPS = 1e-4
#: Agreement required with the reference's numbers (relative).
REL_TOL = 1e-4
#: The true amplitudes at the paper geometry found here (agreement of seeds/settings ~1e-6).
TRUE_PAPER = (3.910760, 1.125556)

#: Relative error of P(0) that shows as a shooting residual TOL (see the module docstring).
RESOLUTION = 1e-6
TOL = 1e-12
#: eps values of the slope fit of the first-order amplitude error (k = 0.5, gamma3_0 = 0.3).
SLOPE_EPSILONS = (0.01, 0.005, 0.0025)
SLOPE_SLACK = 0.3
#: Largest |r1 - 1| + |gamma'' - gamma3_0| at dG = 0: the pins hold on the shooting section
#: gamma' = const, a time O(eps**3) away; such a mismatch moves beta/eps by < 1e-7 (relative).
PIN_MISMATCH = 1e-8

ARM, C_MOMENT, MASS = math.hypot(1.0, 6.0), 20.0, 200.0


def disk(eps: float, k: float | None = None, gamma3_0: float = 7e-6):
    """The paper's disk with r0 = 1 (so tau = t) and c = eps; ``k = None`` keeps R = 2000."""
    R = 2000.0 if k is None else 3 * C_MOMENT / (k * MASS * ARM)
    g = eps**2 * C_MOMENT / (MASS * ARM)
    return Disk.create(g=g, r0=1.0, R=R, gamma3_0=gamma3_0)


@frozen
class TrueOrbit:
    beta1: float  # P(0)/eps on the section dG = 0
    beta2: float  # dP(0)/eps
    alpha: float  # (T_tau - 2 pi)/eps**2
    first_order: tuple  # the same three from the analytic solution
    iterations: int
    pin_mismatch: float  # |r1 - 1| + |gamma'' - gamma3_0| at dG = 0


def _conditioned_rhs(problem, ref, scales, lam):
    state, exprs = problem.original_symbolic()
    u = sp.symbols("u0:7")
    shift = {state[i]: sp.Float(ref[i], 30) + sp.Float(scales[i], 30) * u[i] for i in range(6)}
    rate = (1 + sp.Float(lam, 30) * u[6]) * sp.Float(lam, 30)
    body = [e.xreplace(shift) * rate / sp.Float(scales[i], 30) for i, e in enumerate(exprs)]
    return SymbolicRHS(u, [*body, sp.Integer(0)])


def _move_to_section(problem, y, forward):
    """Slide along the flow to dG = 0 (the analytic solution's phase): second-order Taylor steps."""
    state, exprs = problem.original_symbolic()
    flow = SymbolicRHS(state, exprs)
    c, r0 = problem.scale_c(), problem.values["r0"]
    units = np.array([c, c, r0, 1.0, 1.0, 1.0])
    for _ in range(3):
        z = forward(y / units)
        dt = -z[3] / z[5] / r0  # dG/d2G in tau
        f = flow(y)
        y = y + dt * f + 0.5 * dt**2 * (flow.jacobian(y) @ f)
    return y, forward(y / units)


def true_orbit(problem, offset: float = 0.0) -> TrueOrbit:
    """The true periodic orbit of the analytic solution's family member, seeded ``offset`` off."""
    solution = problem.solve(1)
    eps, r0 = problem.epsilon(), problem.values["r0"]
    g3 = problem.values["gamma3_0"]
    seed = problem.state_vector(solution, 0.0).astype(float)
    period = problem.period(solution)
    # the family member: r = r0, gamma'' = gamma3_0, |gamma| = 1 on the section gamma' = seed's
    ref = seed.copy()
    ref[2], ref[5] = r0, g3
    ref[3] = math.sqrt(1 - ref[4] ** 2 - g3**2)
    phi = 2 * math.pi * eps**2 * problem.detuning()
    amplitude = math.hypot(ref[0], ref[1])
    scales = np.ones(6)
    scales[:2] = phi * amplitude * RESOLUTION / TOL
    lam = phi / max(1.0, amplitude / scales[0])
    rhs = _conditioned_rhs(problem, ref, scales, lam)
    u0 = np.zeros(7)
    u0[:2] = offset * ref[:2] / scales[:2]
    orbit = find_periodic_orbit(
        rhs,
        u0,
        period / lam,
        section_index=4,
        fixed_indices=(2, 3, 5),
        direction=-1,
        n_trivial=5,
        integrator=Heyoka(high_precision=True),
        y_scale=1.0,
        tol=TOL,
    )
    assert orbit.success, orbit.message
    y = ref + scales * orbit.initial_state[:6]
    t_true = orbit.period * lam * (1 + lam * orbit.initial_state[6])
    forward = problem.reduction().forward_function(problem.symbol_values(), eps)
    y, z = _move_to_section(problem, y, forward)
    z0 = solution.initial_state(eps, problem.symbol_values())
    start = dict(zip(solution.state_names, z0, strict=True))
    first = (start["P"] / eps, start["dP"] / eps, (period * r0 - 2 * math.pi) / eps**2)
    return TrueOrbit(
        beta1=float(z[0] / eps),
        beta2=float(z[1] / eps),
        alpha=float((t_true * r0 - 2 * math.pi) / eps**2),
        first_order=first,
        iterations=orbit.iterations,
        pin_mismatch=float(abs(y[2] / r0 - 1) + abs(y[5] - g3)),
    )


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


def test_paper_geometry_true_amplitudes_do_not_depend_on_the_seed(paper):
    for offset in (0.01, -0.01):
        other = true_orbit(disk(PAPER_EPS), offset=offset)
        assert other.iterations >= 1  # the seed was really corrected
        assert (other.beta1, other.beta2) == pytest.approx((paper.beta1, paper.beta2), rel=1e-5)
    assert (paper.beta1, paper.beta2) == pytest.approx(TRUE_PAPER, rel=1e-5)


@pytest.mark.xfail(
    strict=True,
    reason="reference (f)'s 3.87665, 1.11593 are the first-order seed (3.87670, 1.11592) left "
    "unresolved by an unconditioned shooting; the true orbit has 3.91076, 1.12556",
)
def test_paper_geometry_amplitudes_match_the_reference(paper):
    assert (paper.beta1, paper.beta2) == pytest.approx(REFERENCE_PAPER[:2], rel=REL_TOL)


@pytest.mark.parametrize("which", ["paper", "k05"])
def test_amplitude_excess_is_the_amplitude_dependent_detuning(paper, k05, which):
    """beta_true/beta_first - 1 is of the size |beta|^2/(k M3^2) (the neglected detuning part)."""
    problem, orbit = (
        (disk(PAPER_EPS), paper) if which == "paper" else (disk(5e-3, 0.5, 0.3), k05[5e-3])
    )
    excess = orbit.beta1 / orbit.first_order[0] - 1
    assert 1.0 < excess / problem.detuning_ratio() < 1.5


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
    assert orbit.success and orbit.iterations == 0
    assert orbit.initial_state[0] == pytest.approx(1.01 * seed[0], rel=1e-9)
