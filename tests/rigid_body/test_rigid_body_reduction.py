"""The derived reduction of the fast-spin disk (and the general body) to a quasilinear system.

Expected values are the reference's printed forms (``shared/reference/derivation.md`` section (c)
and SUMMARY (b)); the code derives its own and must agree modulo a + b = 1 for the disk.
"""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from perturb.errors import InvalidParameterError
from perturb.system import EPS, QuasilinearSystem
from problems.rigid_body.equations import (
    NONDIMENSIONAL_STATE,
    NondimensionalParameters,
    a,
    b,
    k,
    x0p,
    y0p,
    z0p,
)
from problems.rigid_body.numeric import nondimensional_rhs
from problems.rigid_body.reduction import (
    DISK_PARAMETERS,
    G0,
    INITIAL_VALUES,
    P0,
    G,
    P,
    dG,
    dG0,
    disk_reduction,
    dP,
    dP0,
    gamma3_0,
    general_body_reduction,
)

# --------------------------------------------------------------------------- printed forms
_NAMES = {s.name: s for s in (P, G, dP, dG, P0, G0, dP0, dG0, a, b, k, x0p, y0p)}
_NAMES["γ0pp"] = gamma3_0

PRINTED_F2 = (
    "G**2*P*a*k - G*P*a*x0p/b - 2*G*P*x0p - G*a*dG*dP*k + G*b*dG*dP*k - G*dG*dP*k - G*dP*y0p"
    " - G*dP*y0p/a - G0**2*P*a*k + 2*G0*P*x0p + G0*P0*a*x0p/b + P**3*a - P*P0**2*a - P*a*dP**2"
    " + P*b*dG**2*k - P*b*dG0**2*k + 2*P*b*dP**2 - P*b*dP0**2 - P*dG**2*k - 2*P*dG*y0p"
    " + 2*P*dG0*y0p + P*γ0pp**2*k - P*dG*y0p/a + 2*dG*dP*x0p - dG0*dP0*x0p"
)
PRINTED_PHI2 = (
    "G**3*a*k - 2*G**2*x0p - G*G0**2*a*k + 2*G*G0*x0p + G*P**2*a - G*P0**2*a - G*a*dG**2*k"
    " + 2*G*b*dG**2*k - G*b*dG0**2*k + G*b*dP**2 - G*b*dP0**2 - 3*G*dG*y0p + 2*G*dG0*y0p"
    " - G*dP**2 + G*γ0pp**2*k - P*a*dG*dP + P*b*dG*dP - P*dG*dP + dG**2*x0p + γ0pp**2*x0p/b"
)


def printed(text):
    return sp.sympify(text, locals=_NAMES)


def on_disk(expr):
    """Use a + b = 1 (the disk) to compare forms that differ only by it."""
    return sp.expand(sp.expand(expr).subs(b, 1 - a))


# --------------------------------------------------------------------------- numeric setup
ARM = math.hypot(1.0, 6.0)
#: Paper geometry (A=9, B=11, C=20, x0=1, y0=6), k = 0.5, gamma0'' = 0.3 (reference (c)).
DISK_VALUES = {"a": 0.45, "b": 0.55, "k": 0.5, "x0p": 1 / ARM, "y0p": 6 / ARM, "gamma3_0": 0.3}
#: A non-disk body (C = 15) with z0 = 0.5 for the general reduction.
BODY_VALUES = {
    "a": 0.6,
    "b": 11 / 15,
    "k": 0.5,
    "x0p": 1 / ARM,
    "y0p": 6 / ARM,
    "z0p": 0.5 / ARM,
    "gamma3_0": 0.3,
}
EPS_GRID = (0.04, 0.02, 0.01, 0.005)
#: Oracle tolerances: rtol as in the reference's oracle; atol per component below every residual.
ORACLE_RTOL = 1e-12
ORACLE_ATOL = np.full(6, 1e-14)
#: Allowed deviation of a fitted log-log slope from the predicted order.
SLOPE_TOL = 0.3
T_END = 20.0  # about three periods of the generating motion
N_SAMPLES = 801


def initial_state(gamma3_value, phase=0.4):
    s = math.sqrt(1 - gamma3_value**2)
    return np.array([0.2, 0.1, 1.0, s * math.cos(phase), s * math.sin(phase), gamma3_value])


def trajectory(values, eps):
    nd = NondimensionalParameters(
        a=values["a"],
        b=values["b"],
        k=values["k"],
        x0p=values["x0p"],
        y0p=values["y0p"],
        z0p=values.get("z0p", 0.0),
        eps=eps,
    )
    sol = solve_ivp(
        nondimensional_rhs(nd),
        (0, T_END),
        initial_state(values["gamma3_0"]),
        method="DOP853",
        rtol=ORACLE_RTOL,
        atol=ORACLE_ATOL,
        t_eval=np.linspace(0, T_END, N_SAMPLES),
    )
    assert sol.success, sol.message
    return sol.y


def errors_along(reduction, values, omega_sq):
    """max residuals of the P- and G-equations and of the inverse map, per eps."""
    rows = []
    for eps in EPS_GRID:
        y = trajectory(values, eps)
        fw = reduction.forward_function(values, eps)(y)
        z = fw[:4]
        z0 = (z[0, 0], z[2, 0], z[1, 0], z[3, 0])  # (P0, G0, dP0, dG0)
        rhs = reduction.rhs_function(values, eps)(z, z0)
        res_p = np.abs(fw[4] + omega_sq * z[0] - rhs[0]).max()
        res_g = np.abs(fw[5] + z[2] - rhs[1]).max()
        inverse = np.abs(reduction.inverse_function(values, eps)(z, z0) - y).max()
        # against the oracle's own |gamma|^2 (its drift, ~1e-12, would mask eps**5 at eps = 0.005)
        exact = (y[3:] ** 2).sum(axis=0)
        geometric = np.abs(geometric_function(reduction)(z, z0, values, eps) - exact).max()
        rows.append((res_p, res_g, inverse, geometric))
    return np.array(rows)


def geometric_function(reduction):
    """|gamma|**2 in the reduced variables, as a numeric function (its value on motions is 1)."""
    f = sp.lambdify(
        ((P, dP, G, dG), INITIAL_VALUES, (*reduction.parameters, EPS)), reduction.geometric_integral
    )
    return lambda z, z0, values, eps: f(
        tuple(z), z0, tuple(values[s.name] for s in reduction.parameters) + (eps,)
    )


def slope(values):
    return np.polyfit(np.log(EPS_GRID), np.log(values), 1)[0]


# --------------------------------------------------------------------------- disk, symbolic
@pytest.fixture(scope="module")
def disk():
    return disk_reduction(3)


def test_disk_system_shape(disk):
    system = disk.system
    assert isinstance(system, QuasilinearSystem)
    assert system.coordinates == (P, G) and system.velocities == (dP, dG)
    assert system.frequencies == (1, 1)
    assert system.parameter == EPS and system.parameters == DISK_PARAMETERS
    assert system.initial_values == INITIAL_VALUES == (P0, G0, dP0, dG0)
    assert system.leading_order == 2
    assert len(system.first_integrals) == 1


def test_disk_forcing_vanishes_below_second_order(disk):
    assert disk.F[0] == disk.F[1] == disk.Phi[0] == disk.Phi[1] == 0


def test_disk_second_order_matches_reference_literally(disk):
    # a and b are kept apart exactly as the reference prints them, so no a + b = 1 is needed
    assert sp.expand(disk.F[2] - printed(PRINTED_F2)) == 0
    assert sp.expand(disk.Phi[2] - printed(PRINTED_PHI2)) == 0


def test_rhs_is_the_sum_of_orders(disk):
    for rhs, coeffs in zip(disk.system.rhs, (disk.F, disk.Phi), strict=True):
        assert sp.expand(rhs - sum(EPS**n * c for n, c in enumerate(coeffs))) == 0


# Generating solution P = M1 cos + M2 sin, G = M3 cos; exponentials w = exp(i tau) make the
# Fourier coefficients a polynomial-coefficient extraction.
M1, M2, M3, W = sp.symbols("M1 M2 M3 w")
_COS, _SIN = (W + 1 / W) / 2, (W - 1 / W) / (2 * sp.I)
GENERATING = {
    P: M1 * _COS + M2 * _SIN,
    dP: -M1 * _SIN + M2 * _COS,
    G: M3 * _COS,
    dG: -M3 * _SIN,
    P0: M1,
    dP0: M2,
    G0: M3,
    dG0: 0,
}


def first_harmonic(expr):
    """(cos, sin) coefficients of the first harmonic on the generating solution."""
    e = sp.expand(expr.subs(GENERATING))
    plus, minus = e.coeff(W, 1), e.coeff(W, -1)
    return sp.expand(plus + minus), sp.expand(sp.I * (plus - minus))


def test_first_harmonic_of_F2_is_L21(disk):
    cos_c, sin_c = first_harmonic(disk.F[2])
    l21 = (
        2 * M3 * x0p
        + sp.Rational(1, 2) * (a - b) * (M2**2 - M1**2 - k * M3**2)
        + k * (gamma3_0**2 - M3**2 / 2)
    )
    assert on_disk(cos_c - M1 * l21) == 0
    assert on_disk(sin_c - M2 * l21) == 0


def test_first_harmonic_of_Phi2_differs_from_paper_as_reference_says(disk):
    cos_c, sin_c = first_harmonic(disk.Phi[2])
    c1 = b - a
    reference = M3 * (
        -a * M1**2 - b * M2**2 + 2 * M3 * x0p + k * (gamma3_0**2 + sp.Rational(1, 2) * c1 * M3**2)
    )
    assert on_disk(cos_c - reference) == 0
    assert sin_c == 0
    # the paper's (10)/(12): N21* with k*C1*M3**2 and the spurious -a/4 (M1^2 - M2^2) M3 term
    paper = (
        -(a * M1**2 + b * M2**2)
        + 2 * M3 * x0p
        + k * (gamma3_0**2 + M3**2 * c1)
        - sp.Rational(1, 4) * a * (M1**2 - M2**2)
    ) * M3
    assert on_disk(cos_c - paper) != 0


def test_first_harmonic_of_F3_at_zero_amplitudes(disk):
    cos_c, sin_c = (c.subs({M1: 0, M2: 0}) for c in first_harmonic(disk.F[3]))
    v1 = (
        M3
        * gamma3_0
        * (2 * (1 + a) * y0p**2 / a**2 - 2 * (1 + b) * x0p**2 / b**2 + a * k**2 * M3**2)
    )
    v2 = -6 * M3 * gamma3_0 * x0p * y0p / (a * b)
    assert sp.simplify(on_disk(cos_c - v1 / 2)) == 0
    assert sp.simplify(on_disk(sin_c + v2 / 2)) == 0


def test_inverse_map_first_order_matches_reference(disk):
    pairs = list(zip(NONDIMENSIONAL_STATE, disk.full_state, strict=True))
    first = {v: sp.expand(e).coeff(EPS, 1) for v, e in pairs}
    zeroth = {v: sp.expand(e).coeff(EPS, 0) for v, e in pairs}
    assert zeroth == dict(zip(NONDIMENSIONAL_STATE, (P, -dP, 1, G, dG, gamma3_0), strict=True))
    # q1 = -dP + eps (y0' gamma''/a + k gamma' gamma''), gamma' = dG - eps b gamma0'' dP
    assert sp.expand(first[NONDIMENSIONAL_STATE[1]] - (y0p * gamma3_0 / a + k * dG * gamma3_0)) == 0
    assert on_disk(first[NONDIMENSIONAL_STATE[4]] + b * gamma3_0 * dP) == 0
    assert sp.expand(first[NONDIMENSIONAL_STATE[0]] - x0p * gamma3_0 / b) == 0
    assert sp.expand(first[NONDIMENSIONAL_STATE[2]]) == 0  # r1 = 1 + O(eps**2)


def test_geometric_integral_matches_paper_6(disk):
    h = sp.expand(disk.geometric_integral)
    assert sp.expand(h.coeff(EPS, 0) - (G**2 + dG**2 + gamma3_0**2)) == 0
    # the O(eps) bracket of (6) is the constant 2 gamma0'' (a P0 G0 - b dP0 dG0) on the disk
    assert on_disk(h.coeff(EPS, 1) - 2 * gamma3_0 * (a * P0 * G0 - b * dP0 * dG0)) == 0


def test_forward_after_inverse_is_identity_to_order():
    # symbolic at order 2 (the numeric scaling tests cover orders 3 and 4)
    reduction = disk_reduction(2)
    order = reduction.order
    subs = dict(zip(NONDIMENSIONAL_STATE, reduction.full_state, strict=True))
    for target, expr in zip((P, dP, G, dG), reduction.reduced_state, strict=True):
        composed = sp.expand(expr.subs(subs))
        truncated = sum(composed.coeff(EPS, n) * EPS**n for n in range(order + 1))
        assert on_disk(truncated - target) == 0


def test_initial_state_is_consistent(disk):
    # at tau = 0 the inverse map gives r1 = 1 and gamma'' = gamma3_0 to the order kept
    at_zero = {P: P0, dP: dP0, G: G0, dG: dG0}
    for i in (2, 5):
        diff = sp.expand(disk.full_state[i].subs(at_zero) - disk.initial_full_state[i])
        assert diff == 0
    assert disk.initial_full_state[2] == 1 and disk.initial_full_state[5] == gamma3_0


# --------------------------------------------------------------------------- disk, numeric
@pytest.mark.parametrize("order", [3, 4], ids=["order3", "order4"])
def test_disk_residual_scales_as_next_order(order):
    rows = errors_along(disk_reduction(order), DISK_VALUES, 1.0)
    for column in rows.T:
        assert abs(slope(column) - (order + 1)) < SLOPE_TOL, rows


# --------------------------------------------------------------------------- general body
def test_general_body_first_order_matches_reference():
    red = general_body_reduction(2)
    a1, b1 = (1 - b) / a, (a - 1) / b
    f1 = (z0p / a - a1 * z0p / b - k * a1 * (1 + b1) * gamma3_0) * G + a1 * x0p * gamma3_0 / b
    phi1 = (1 + b1) * gamma3_0 * P
    assert red.F[0] == red.Phi[0] == 0
    assert sp.simplify(red.F[1] - f1) == 0
    assert sp.simplify(red.Phi[1] - phi1) == 0
    assert sp.simplify(red.system.frequencies[0] ** 2 - (-a1 * b1)) == 0
    assert red.system.frequencies[1] == 1


def test_general_body_residual_scales_as_next_order():
    red = general_body_reduction(2)
    omega_sq = (
        (1 - BODY_VALUES["a"]) * (1 - BODY_VALUES["b"]) / (BODY_VALUES["a"] * BODY_VALUES["b"])
    )
    rows = errors_along(red, BODY_VALUES, omega_sq)
    for column in rows.T:
        assert abs(slope(column) - 3) < SLOPE_TOL, rows


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("order", [0, -1, 2.5, True, 99])
def test_invalid_order(order):
    with pytest.raises(InvalidParameterError, match="`order`"):
        disk_reduction(order)


@pytest.mark.parametrize(
    ("changes", "argument"),
    [
        ({"gamma3_0": 1.5}, "`gamma3_0`"),
        ({"gamma3_0": float("nan")}, "`gamma3_0`"),
        ({"a": -0.45}, "`a`"),
        ({"k": -1.0}, "`k`"),
    ],
)
def test_invalid_numeric_values(disk, changes, argument):
    with pytest.raises(InvalidParameterError, match=argument):
        disk.inverse_function({**DISK_VALUES, **changes}, 0.01)


def test_missing_values_and_bad_eps(disk):
    with pytest.raises(InvalidParameterError, match="`values`"):
        disk.rhs_function({"a": 0.45}, 0.01)
    with pytest.raises(InvalidParameterError, match="`eps`"):
        disk.forward_function(DISK_VALUES, -0.01)
