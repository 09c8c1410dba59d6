"""The derived Euler–Poisson equations against the reference's printed forms and their integrals.

Reference: ``shared/reference/derivation.md`` sections (a) and (b); the printed forms below are copied
from there on purpose (they are the expected values; the code derives its own).
"""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from perturb.errors import InvalidParameterError
from perturb.system import EPS
from problems.rigid_body import equations as eq
from problems.rigid_body import numeric
from problems.rigid_body.equations import (
    A1,
    B1,
    C1,
    DIMENSIONAL_STATE,
    NONDIMENSIONAL_STATE,
    A,
    B,
    C,
    M,
    NondimensionalParameters,
    R,
    RigidBodyParameters,
    a,
    b,
    g,
    gamma1,
    gamma2,
    gamma3,
    k,
    p1,
    q1,
    r1,
    x0,
    x0p,
    y0,
    y0p,
    z0,
    z0p,
)

#: The paper's example (31) geometry with a fast spin, used for numeric checks.
PAPER_BODY = RigidBodyParameters(A=9, B=11, C=20, x0=1, y0=6, z0=0.5, M=200, g=9.81, R=2000)
#: A generic state (p, q, r, gamma) with |gamma| = 1.
STATE = np.array([0.3, -0.2, 1.7, 0.6, 0.0, 0.8])
#: Agreement of two double-precision evaluations of the same rational expression.
ROUND_OFF = 1e-13


def printed_potential():
    return -M * g * (x0 * gamma1 + y0 * gamma2 + z0 * gamma3) + 3 * g / (2 * R) * (
        A * gamma1**2 + B * gamma2**2 + C * gamma3**2
    )


def test_potential_matches_reference():
    assert sp.expand(eq.potential() - printed_potential()) == 0


def test_potential_without_centre_is_uniform_gravity():
    assert sp.expand(eq.potential(sp.oo) + M * g * (x0 * gamma1 + y0 * gamma2 + z0 * gamma3)) == 0
    assert eq.potential(float("inf")) == eq.potential(sp.oo)


def test_unreduced_potential_differs_by_a_constant_on_the_sphere():
    full = eq.body_potential(2)
    # the dropped parts: the isotropic second moment (sigma) and the gamma-independent constant
    difference = sp.expand(full - eq.potential())
    on_sphere = sp.expand(difference.subs(gamma3**2, 1 - gamma1**2 - gamma2**2))
    assert not on_sphere.free_symbols & {gamma1, gamma2, gamma3}


def test_torque_matches_printed_Nx_and_is_cyclic():
    n = eq.torque()
    printed_nx = M * g * (y0 * gamma3 - z0 * gamma2) + 3 * g / R * (C - B) * gamma2 * gamma3
    assert sp.expand(n[0] - printed_nx) == 0
    cyclic = {
        A: B,
        B: C,
        C: A,
        x0: y0,
        y0: z0,
        z0: x0,
        gamma1: gamma2,
        gamma2: gamma3,
        gamma3: gamma1,
    }
    assert sp.expand(n[1] - n[0].xreplace(cyclic)) == 0
    assert sp.expand(n[2] - n[1].xreplace(cyclic)) == 0


def test_euler_equation_matches_printed_form():
    rhs = eq.euler_poisson_equations()
    p, q, r = DIMENSIONAL_STATE[:3]
    printed = (
        (B - C) * q * r
        + M * g * (y0 * gamma3 - z0 * gamma2)
        + 3 * g / R * (C - B) * gamma2 * gamma3
    ) / A
    assert sp.expand(rhs[0] - printed) == 0
    assert sp.expand(rhs[3] - (r * gamma2 - q * gamma3)) == 0


@pytest.mark.parametrize("R_value", [R, sp.oo], ids=["centre", "no-centre"])
@pytest.mark.parametrize("name", ["energy", "area", "geometric"])
def test_dimensional_integrals_are_conserved(R_value, name):
    rhs = eq.euler_poisson_equations(R_value)
    integral = eq.first_integrals(R_value)[name]
    assert sp.simplify(eq.time_derivative(integral, rhs, DIMENSIONAL_STATE)) == 0


def test_energy_matches_printed_form():
    p, q, r = DIMENSIONAL_STATE[:3]
    printed = (
        A * p**2
        + B * q**2
        + C * r**2
        - 2 * M * g * (x0 * gamma1 + y0 * gamma2 + z0 * gamma3)
        + 3 * g / R * (A * gamma1**2 + B * gamma2**2 + C * gamma3**2)
    )
    assert sp.expand(eq.first_integrals()["energy"] - printed) == 0


@pytest.mark.parametrize("field_on", [True, False])
@pytest.mark.parametrize("name", ["energy", "area", "geometric"])
def test_nondimensional_integrals_are_conserved(field_on, name):
    rhs = eq.nondimensional_equations(field_on, ratios=False)
    integral = eq.nondimensional_integrals(field_on)[name]
    assert sp.simplify(eq.time_derivative(integral, rhs, NONDIMENSIONAL_STATE)) == 0


def test_nondimensional_equations_match_printed_forms():
    e = EPS
    g1, g2, g3 = gamma1, gamma2, gamma3
    printed = [
        -A1 * q1 * r1 + e * ((y0p * g3 - z0p * g2) / a + k * A1 * g2 * g3),
        -B1 * p1 * r1 + e * ((z0p * g1 - x0p * g3) / b + k * B1 * g1 * g3),
        e**2 * (-C1 * p1 * q1 + x0p * g2 - y0p * g1 + k * C1 * g1 * g2),
        r1 * g2 - e * q1 * g3,
        e * p1 * g3 - r1 * g1,
        e * (q1 * g1 - p1 * g2),
    ]
    derived = eq.nondimensional_equations()
    for d, pr in zip(derived, printed, strict=True):
        assert sp.expand(d - pr) == 0


def test_nondimensional_integrals_match_printed_forms():
    e = EPS
    ints = eq.nondimensional_integrals()
    energy = (
        e**2 * (a * p1**2 + b * q1**2)
        + r1**2
        - 2 * e**2 * (x0p * gamma1 + y0p * gamma2 + z0p * gamma3)
        + e**2 * k * (a * gamma1**2 + b * gamma2**2 + gamma3**2)
    )
    area = e * (a * p1 * gamma1 + b * q1 * gamma2) + r1 * gamma3
    assert sp.expand(ints["energy"] - energy) == 0
    assert sp.expand(ints["area"] - area) == 0


def test_ratio_form_equals_plain_form():
    with_ratios = eq.nondimensional_equations(ratios=True).subs(eq.inertia_ratio_values())
    plain = eq.nondimensional_equations(ratios=False)
    assert all(sp.simplify(u - v) == 0 for u, v in zip(with_ratios, plain, strict=True))


def test_disk_ratios():
    assert eq.inertia_ratio_values(disk=True) == {A1: 1, B1: -1, C1: b - a}


def test_dimensional_and_nondimensional_rhs_agree():
    r0 = 3.0
    nd = NondimensionalParameters.from_dimensional(PAPER_BODY, r0)
    c = nd.eps * r0
    y_nd = np.array([0.4, -0.7, 0.9, *STATE[3:]])
    y_dim = np.array([c * y_nd[0], c * y_nd[1], r0 * y_nd[2], *y_nd[3:]])
    f_dim = numeric.full_rhs(PAPER_BODY)(0.0, y_dim)
    f_nd = numeric.nondimensional_rhs(nd)(0.0, y_nd)
    scales = np.array([c * r0, c * r0, r0**2, r0, r0, r0])
    np.testing.assert_allclose(f_dim / scales, f_nd, rtol=ROUND_OFF, atol=ROUND_OFF)
    h_dim = numeric.integrals_function(PAPER_BODY)(y_dim)
    h_nd = numeric.nondimensional_integrals_function(nd)(y_nd)
    # energy / (C r0^2) and area / (C r0): the energy also drops the same constant in both
    np.testing.assert_allclose(
        h_dim[:2] / [PAPER_BODY.C * r0**2, PAPER_BODY.C * r0], h_nd[:2], rtol=ROUND_OFF
    )


def finite_difference_jacobian(f, y, step=1e-6):
    cols = []
    for i in range(len(y)):
        dy = np.zeros_like(y)
        dy[i] = step
        cols.append((f(0.0, y + dy) - f(0.0, y - dy)) / (2 * step))
    return np.array(cols).T


#: Central differences with step 1e-6 on O(1..1e3) values: truncation ~1e-12, round-off ~1e-10.
FD_TOL = 1e-7


def test_jacobians_match_finite_differences():
    f, jac = numeric.full_rhs(PAPER_BODY), numeric.full_jacobian(PAPER_BODY)
    np.testing.assert_allclose(
        jac(0.0, STATE), finite_difference_jacobian(f, STATE), atol=FD_TOL, rtol=FD_TOL
    )
    nd = NondimensionalParameters.from_dimensional(PAPER_BODY, 3.0)
    f, jac = numeric.nondimensional_rhs(nd), numeric.nondimensional_jacobian(nd)
    np.testing.assert_allclose(
        jac(0.0, STATE), finite_difference_jacobian(f, STATE), atol=FD_TOL, rtol=FD_TOL
    )


#: Relative drift of the integrals over the run at rtol 1e-12 (reference: <= 1e-11).
DRIFT_TOL = 1e-10


@pytest.mark.parametrize("R_value", [2000.0, math.inf])
def test_integrals_conserved_numerically(R_value):
    body = RigidBodyParameters(A=9, B=11, C=20, x0=1, y0=6, z0=0.5, M=200, g=9.81, R=R_value)
    sol = solve_ivp(
        numeric.full_rhs(body),
        (0, 5.0),
        STATE * [1, 1, 10, 1, 1, 1],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
    )
    assert sol.success
    h = numeric.integrals_function(body)(sol.y)
    drift = np.abs(h - h[:, :1]).max(axis=1) / np.maximum(np.abs(h[:, 0]), 1.0)
    assert drift.max() < DRIFT_TOL


def test_integrals_function_shapes():
    h = numeric.integrals_function(PAPER_BODY)
    assert h(STATE).shape == (3,)
    assert h(np.tile(STATE[:, None], (1, 4))).shape == (3, 4)


@pytest.mark.parametrize(
    ("changes", "argument"),
    [
        ({"A": 0.0}, "`A`"),
        ({"B": -1.0}, "`B`"),
        ({"C": float("nan")}, "`C`"),
        ({"C": 25.0}, "`C`"),  # 9 + 11 < 25: triangle inequality
        ({"A": 40.0}, "`A`"),
        ({"M": 0.0}, "`M`"),
        ({"g": -9.81}, "`g`"),
        ({"R": 0.0}, "`R`"),
        ({"R": float("nan")}, "`R`"),
        ({"x0": float("nan")}, "`x0`"),
    ],
)
def test_invalid_body_parameters(changes, argument):
    data = {"A": 9, "B": 11, "C": 20, "x0": 1, "y0": 6, "M": 200, "g": 9.81, "R": 2000}
    data.update(changes)
    with pytest.raises(InvalidParameterError, match=argument):
        RigidBodyParameters(**data)


def test_disk_passes_triangle_inequality():
    RigidBodyParameters(A=9, B=11, C=20, x0=1, y0=6)


def test_invalid_nondimensional_parameters():
    with pytest.raises(InvalidParameterError, match="`x0p`"):
        NondimensionalParameters(a=0.45, b=0.55, k=0.5, x0p=1.0, y0p=1.0, eps=0.01)
    with pytest.raises(InvalidParameterError, match="`k`"):
        NondimensionalParameters(a=0.45, b=0.55, k=-1.0, x0p=1.0, y0p=0.0, eps=0.01)
    with pytest.raises(InvalidParameterError, match="`eps`"):
        NondimensionalParameters(a=0.45, b=0.55, k=0.5, x0p=1.0, y0p=0.0, eps=0.0)
    with pytest.raises(InvalidParameterError, match="triangle"):
        NondimensionalParameters(a=0.2, b=0.3, k=0.5, x0p=1.0, y0p=0.0, eps=0.01)


def test_paper_parameters_reproduce_printed_scales():
    body = RigidBodyParameters.from_paper()
    nd = NondimensionalParameters.from_dimensional(body, 1.3e-5)
    assert nd.k == pytest.approx(2.465985e-5, rel=1e-6)
    assert nd.eps * 1.3e-5 == pytest.approx(3.020620e-3, rel=1e-6)  # c
    assert (nd.x0p, nd.y0p) == pytest.approx((0.1643990, 0.9863939), rel=1e-6)


def test_the_numeric_functions_are_still_importable_from_equations():
    """They moved to problems.rigid_body.numeric; users' `from ...equations import full_rhs` still works."""
    from problems.rigid_body.equations import full_rhs, nondimensional_rhs

    assert full_rhs is numeric.full_rhs and nondimensional_rhs is numeric.nondimensional_rhs
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        eq.nope  # noqa: B018 - the attribute access is the test
