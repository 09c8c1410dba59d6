"""The disk's second O(eps**2) family M1**2 + M2**2 = k M3**2 at order 3 (docs/problems/disk-second-family.md).

On the circle M1 = R cos(chi), M2 = R sin(chi), R**2 = k M3**2, the order-3 periodicity conditions are
solvable only where the projection of the order-3 forcing on the left null vector of the (rank-1)
order-2 Jacobian vanishes. For k = 1/2, gamma3_0 = 3/10, a = 9/20, b = 11/20, x0' = 1/sqrt(37),
y0' = 6/sqrt(37) that condition is 3960 cos(chi) - 13757 sin(chi) = 0: two isolated orbits,
chi* = atan(3960/13757) and chi* + pi. The engine reaches them with the P amplitude R cos(chi*) and the
sign of b_P0 as branch; any other point of the circle is INCONSISTENT at order 3.

Two ways to ask the engine for these orbits, both pinned below: fixing P(0) = R cos(chi*) through
``amplitudes`` holds it at every order, which leaves no room for the O(eps) shift of chi that only
order 4 fixes (its O(eps) terms are then not the true ones; only the generating amplitudes and Omega2
are); giving both generating amplitudes through ``branch`` fixes only order 0, and the O(eps) terms
come out right (checked against the shooting). The shooting test checks the orbits against the true
motion.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb import PoincareMethod, Status
from perturb.oracle import heyoka_available
from problems.rigid_body._body import geometric_constraint
from problems.rigid_body.equations import a, b, k, x0p, y0p
from problems.rigid_body.reduction import disk_reduction, gamma3_0

VALUES = {
    k: sp.Rational(1, 2),
    gamma3_0: sp.Rational(3, 10),
    a: sp.Rational(9, 20),
    b: sp.Rational(11, 20),
    x0p: 1 / sp.sqrt(37),
    y0p: 6 / sp.sqrt(37),
}
M3 = sp.sqrt(1 - VALUES[gamma3_0] ** 2)
R = sp.sqrt(VALUES[k]) * M3
#: The solvability condition on the circle: S(chi) = 3960 cos(chi) - 13757 sin(chi) (up to a factor).
S_COS, S_SIN = 3960, 13757
HYP = sp.sqrt(S_COS**2 + S_SIN**2)
CHI_STAR = math.atan2(S_COS, S_SIN)  # 0.2802762633835997
#: Omega2 on the orbits (both signs): 28789833713/409873298000 - sqrt(3367)/370.
OMEGA2 = sp.Rational(28789833713, 409873298000) - sp.sqrt(3367) / 370
#: Order-3 radial correction of the amplitude, R_1 = -4.650791 cos(chi*) (sign follows cos chi).
RADIAL_1 = -4.650791172 * S_SIN / float(HYP)


@pytest.fixture(scope="module")
def system_and_g0():
    reduction = disk_reduction(3)
    system = reduction.system.with_values(VALUES)
    return system, geometric_constraint(reduction).xreplace(VALUES)


def _solve(system_and_g0, cos_chi, sin_chi):
    system, g0 = system_and_g0
    method = PoincareMethod(
        order=1,
        amplitudes={"G": g0, "P": R * cos_chi},
        phase_coordinate="G",
        branch={"b_P0": R * sin_chi},
        cache=False,
    )
    return method.solve(system)


@pytest.mark.parametrize("sign", [1, -1], ids=["chi*", "chi*+pi"])
def test_the_two_roots_of_the_solvability_condition_are_consistent(system_and_g0, sign):
    solution = _solve(system_and_g0, sign * S_SIN / HYP, sign * S_COS / HYP)
    assert solution.status is Status.SUCCESS, solution.message
    b_p0 = solution.generating.sin_amplitudes[0]
    assert float(b_p0) == pytest.approx(sign * float(R) * math.sin(CHI_STAR), rel=1e-12)
    assert float(solution.frequency[2]) == pytest.approx(float(OMEGA2), rel=1e-12)
    # the engine stops at order 3 (a_P1 = 0 pinned, b_P1 fixed by the radial condition)
    assert len(solution.steps) == 3


@pytest.mark.parametrize("cos_chi, sin_chi", [(sp.Rational(3, 5), sp.Rational(4, 5)), (1, 0)])
def test_other_points_of_the_circle_are_inconsistent_at_order_3(system_and_g0, cos_chi, sin_chi):
    solution = _solve(system_and_g0, cos_chi, sin_chi)
    assert solution.status is Status.INCONSISTENT
    assert "order 3" in solution.message


# ------------------------------------------------------------------------------ true motion
@pytest.mark.skipif(not heyoka_available(), reason="needs heyoka (extended precision)")
@pytest.mark.parametrize("sign", [1, -1], ids=["chi*", "chi*+pi"])
def test_true_periodic_orbits_exist_at_the_predicted_angle(sign):
    """Conditioned shooting of the full Euler–Poisson system seeded at the generating orbit."""
    from perturb.oracle import Heyoka, find_periodic_orbit
    from problems.rigid_body.true_orbit import _conditioned_rhs, _move_to_section
    from tests.rigid_body.test_disk_shooting import disk

    chi = CHI_STAR + (0.0 if sign > 0 else math.pi)
    r, m3 = float(R), float(M3)
    errors = {}
    for eps in (0.005, 0.0025):
        problem = disk(eps, k=0.5, gamma3_0=0.3)
        values = problem.symbol_values()
        r0, c = problem.values["r0"], problem.scale_c()
        p0, dp0 = r * math.cos(chi), r * math.sin(chi)
        inverse = problem.reduction().inverse_function(values, eps)
        ref = np.array(inverse((p0, dp0, m3, 0.0), (p0, m3, dp0, 0.0)), float)
        ref *= np.array([c, c, r0, 1.0, 1.0, 1.0])
        ref[2], ref[5] = r0, 0.3
        ref[3] = math.sqrt(1 - ref[4] ** 2 - 0.3**2)
        period = 2 * math.pi / (1 + eps**2 * float(OMEGA2)) / r0
        phi = 2 * math.pi * eps**3  # the tangential direction is resolved only at O(eps**3)
        amplitude = math.hypot(ref[0], ref[1])
        scales = np.ones(6)
        scales[:2] = phi * amplitude * 1e-6 / 1e-12
        lam = phi / max(1.0, amplitude / scales[0])
        orbit = find_periodic_orbit(
            _conditioned_rhs(problem, ref, scales, lam),
            np.zeros(7),
            period / lam,
            section_index=4,
            fixed_indices=(2, 3, 5),
            n_trivial=5,
            integrator=Heyoka(high_precision=True),
            y_scale=1.0,
            tol=1e-12,
        )
        assert orbit.success, orbit.message
        y = ref + scales * orbit.initial_state[:6]
        forward = problem.reduction().forward_function(values, eps)
        _, z = _move_to_section(problem, y, forward)
        t_true = orbit.period * lam * (1 + lam * orbit.initial_state[6]) * r0
        d_chi = math.remainder(math.atan2(z[1], z[0]) - chi, 2 * math.pi)
        d_r = math.hypot(z[0], z[1]) - r
        errors[eps] = (d_chi / eps, d_r / eps, t_true / period / r0 - 1)
    for eps, (chi_1, r_1, rel_period) in errors.items():
        assert abs(chi_1) < 0.1  # chi_true - chi* = O(eps), small coefficient (~ -0.04 sign)
        assert r_1 == pytest.approx(RADIAL_1 * sign, abs=0.6)  # -> the order-3 radial term
        assert abs(rel_period) < 3 * eps**3  # period right to O(eps**2) (Omega3 ~ 1.45)
    # the radial correction converges to the order-3 value (error of r_1 falls with eps)
    assert abs(errors[0.0025][1] - RADIAL_1 * sign) < abs(errors[0.005][1] - RADIAL_1 * sign)


#: Extrapolation to eps -> 0 of the conditioned shooting at eps = 0.01, 0.005, 0.0025 (see the module's
#: page): the true orbit's O(eps) radial correction and O(eps^3) period term at chi*.
SHOOTING_RADIAL_1, SHOOTING_PERIOD_TERM = -4.456, 9.119
#: The extrapolation above is linear in eps from three points: about 1 % uncertain.
EXTRAPOLATION_TOL = 0.01


def test_branch_on_the_family_fixes_only_the_generating_amplitudes():
    """branch = {a_P0, b_P0} at chi* leaves the corrections to the later orders: order 4 fixes b_P1
    and Omega3, and they agree with the true orbits found by shooting."""
    reduction = disk_reduction(4)  # order 1 on this family needs the conditions of order 4
    system = reduction.system.with_values(VALUES)
    g0 = geometric_constraint(reduction).xreplace(VALUES)
    branch = {"a_P0": R * S_SIN / HYP, "b_P0": R * S_COS / HYP}
    solution = PoincareMethod(
        order=1, amplitudes={"G": g0}, phase_coordinate="G", branch=branch, cache=False
    ).solve(system)
    assert solution.status is Status.SUCCESS, solution.message
    a_p1 = float(solution.deviations["P"][0])
    b_p1 = float(solution.terms[0][1].coefficient(1)[1] + 0)  # sine amplitude of P at order 1
    radial = a_p1 * math.cos(CHI_STAR) + b_p1 * math.sin(CHI_STAR)
    assert radial == pytest.approx(SHOOTING_RADIAL_1, rel=EXTRAPOLATION_TOL)
    assert -2 * math.pi * float(solution.frequency[3]) == pytest.approx(
        SHOOTING_PERIOD_TERM, rel=EXTRAPOLATION_TOL
    )
    # order 2 would need epsilon^5, which this reduction does not contain: a clear failed status
    deeper = PoincareMethod(
        order=2, amplitudes={"G": g0}, phase_coordinate="G", branch=branch, cache=False
    ).solve(system)
    assert deeper.status is Status.TRUNCATED and "epsilon^5" in deeper.message
