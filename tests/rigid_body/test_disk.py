"""The ``disk`` problem: inputs, the paper geometry, the paper's errata pinned, formulations, CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp

from perturb import PoincareMethod, Status
from perturb.cli import main
from perturb.errors import AccuracyWarning, InvalidParameterError
from perturb.validation import original_rhs
from problems import get_problem
from problems.rigid_body.equations import a, b, k, x0p, y0p
from problems.rigid_body.reduction import INITIAL_VALUES, REDUCED_STATE, gamma3_0
from tests.helpers import roundings

Disk = get_problem("disk")

#: The reference's values at the paper geometry, eps = 1e-4 (section (f), "true orbit by shooting").
#: Its amplitudes are the first-order seed left unresolved by an unconditioned shooting: the true
#: orbit has beta1/eps = 3.9179736, beta2/eps = 1.1276318 (tests/rigid_body/test_disk_shooting.py:
#: quadruple-precision shooting and an independent 40-digit mpmath route, both from exact rational
#: parameters; confirmed by our third-order solution, below). Its period is right.
REFERENCE_BETA1, REFERENCE_BETA2, TRUE_ALPHA = 3.87665, 1.11593, 1.03296
TRUE_BETA1, TRUE_BETA2 = 3.9179736, 1.1276318
PAPER_EPS = 1e-4
REL_TOL = 1e-3
#: At the paper geometry the detuning k*M3**2/2 is tiny (k = 2.5e-5), so the first-order amplitudes
#: carry a relative error of the size of |beta|^2/(k M3^2) = 0.0066 (the amplitude-dependent part of
#: the detuning, left out at first order). The true orbit shows 1.6 times that (1.06 %; the figure
#: 1.33 times once quoted came from double-rounded inputs): allow 2 times.
FIRST_ORDER_AMPLITUDE_TOL = 0.013
#: Two formulations (in eps, in mu = 1/eps) of the same first-order frequency series: a dozen
#: operations each.
FORMULATIONS = roundings(12)
#: gamma'' at t = 0 from the series: its terms (cos 0 = 1) summed, a few operations.
INITIAL_SUM = roundings(4)
#: An angle and the direction cosine it is taken from: an arccos/arctan2 and its cosine, a few
#: elementary functions.
ANGLE_ROUND_TRIP = roundings(4)


def paper_geometry(eps: float = PAPER_EPS, **overrides):
    """The paper's body with r0 chosen for the given eps = c/r0."""
    c = Disk.create(**overrides).scale_c()
    return Disk.create(r0=c / eps, **overrides)


def fast_geometry(eps: float, k_value: float = 0.5, gamma3: float = 0.3):
    """Paper geometry with c = 1 and the field set to k = k_value (the reference's test set)."""
    arm, C, M = math.hypot(1, 6), 20.0, 200.0
    return Disk.create(g=C / (M * arm), R=3 * C / (k_value * M * arm), r0=1 / eps, gamma3_0=gamma3)


@pytest.fixture(scope="module")
def solution():
    return Disk.create().solve(1)


def _leading(sol, values):
    """beta1/eps, beta2/eps, (T - 2 pi)/eps**2 from the symbolic solution."""
    term = sol.terms[0][1]
    subs = {s: values[s.name] for s in sol.system.parameters}
    beta1 = float(sp.sympify(term.at_zero()).subs(subs))
    beta2 = float(sp.sympify(term.derivative().at_zero()).subs(subs))
    alpha = float((-2 * sp.pi * sol.frequency[2] / sol.frequency[0] ** 3).subs(subs))
    return beta1, beta2, alpha


# ---------------------------------------------------------------------------- inputs
@pytest.mark.parametrize(
    ("overrides", "fragment"),
    [
        ({"A": 0.0}, "`A` = 0"),
        ({"B": -1.0}, "`B` = -1"),
        ({"C": 0.0}, "`C` = 0"),
        ({"A": 1.0, "B": 1.0, "C": 20.0}, "triangle"),
        ({"C": 19.0}, "A + B - C = 1 "),
        ({"C": 19.0}, "rigid-body"),
        ({"z0": 0.5}, "`z0` = 0.5"),
        ({"gamma3_0": 1.5}, "`gamma3_0` = 1.5"),
        ({"gamma3_0": 1.0}, "M3"),
        ({"r0": 0.0}, "`r0` = 0"),
        ({"r0": -1.0}, "`r0` = -1"),
        ({"M": 0.0}, "`M` = 0"),
        ({"g": -1.0}, "`g` = -1"),
        ({"R": 0.0}, "`R` = 0"),
        ({"R": -5.0}, "`R` = -5"),
        ({"A": float("nan")}, "`A` = nan"),
        ({"x0": float("inf")}, "`x0` = inf"),
        ({"r0": float("inf")}, "`r0` = inf"),
        ({"x0": 0.0, "y0": 0.0}, "l = 0"),
    ],
)
def test_bad_input_is_one_line_naming_parameter_and_fix(overrides, fragment):
    with pytest.raises(InvalidParameterError) as info:
        Disk.create(**overrides)
    message = str(info.value)
    assert fragment in message
    assert "\n" not in message
    assert ":" in message  # value: fix


def test_r_infinite_is_accepted_but_has_no_solution_on_this_branch():
    problem = Disk.create(R=math.inf)
    assert problem.symbol_values()["k"] == 0
    solution = problem.solve(1)
    assert solution.status is Status.SINGULAR and "detuning" in solution.message


def test_defaults_are_the_papers_31_and_warn_about_eps(solution):
    problem = Disk.create()
    assert problem.values["r0"] == 1.3e-5 and problem.values["gamma3_0"] == 7e-6
    assert problem.epsilon() == pytest.approx(232.3553, rel=1e-6)
    extras = problem.report_extras()
    assert extras["mu"] == pytest.approx(1 / problem.epsilon())
    assert "fast-spin" in extras["regime"] and "NOT" in extras["regime"]
    with pytest.warns(AccuracyWarning):
        problem.state(solution, [0.0])


def test_order_above_three_is_refused():
    with pytest.raises(InvalidParameterError, match="`order` = 4"):
        Disk.create().solve(4)


@pytest.mark.slow
def test_second_order_period_against_the_true_orbit():
    """k = 0.5, gamma3_0 = 0.3, eps = 5e-3: the true orbit has (T - 2 pi)/eps^2 = 1.19547 (reference
    (f), shooting); first order gives 1.19821, second order must close most of the gap."""
    problem = fast_geometry(5e-3)
    eps = problem.epsilon()
    true_ratio = 1.19547
    first = (problem.period(problem.solve(1)) * problem.values["r0"] - 2 * math.pi) / eps**2
    second = (problem.period(problem.solve(2)) * problem.values["r0"] - 2 * math.pi) / eps**2
    assert abs(second - true_ratio) < 0.1 * abs(first - true_ratio)


# ---------------------------------------------------------------------------- paper geometry
def test_paper_geometry_against_the_true_periodic_orbit(solution):
    problem = paper_geometry()
    assert problem.symbol_values()["k"] == pytest.approx(2.465985e-5, rel=1e-6)
    beta1, beta2, alpha = _leading(solution, problem.symbol_values())
    # first order: the reference's (seed) numbers exactly, the period to 1e-3 of the truth, and the
    # amplitudes within the error the tiny detuning predicts
    assert beta1 == pytest.approx(REFERENCE_BETA1, rel=2e-5)
    assert beta2 == pytest.approx(REFERENCE_BETA2, rel=2e-5)
    assert alpha == pytest.approx(TRUE_ALPHA, rel=REL_TOL)
    assert beta1 == pytest.approx(TRUE_BETA1, rel=FIRST_ORDER_AMPLITUDE_TOL)
    assert beta2 == pytest.approx(TRUE_BETA2, rel=FIRST_ORDER_AMPLITUDE_TOL)
    # the same numbers from the numeric solution at eps = 1e-4 (physical period too)
    start = solution.initial_state(PAPER_EPS, problem.symbol_values())
    z = dict(zip(solution.state_names, start, strict=True))
    assert z["P"] / PAPER_EPS == pytest.approx(beta1, rel=1e-9)
    # the velocity carries the factor Omega = 1 + O(eps^2): 1e-7 > eps^2 |Omega_2|
    assert z["dP"] / PAPER_EPS == pytest.approx(beta2, rel=1e-7)
    tau_period = problem.period(solution) * problem.values["r0"]
    assert (tau_period - 2 * math.pi) / PAPER_EPS**2 == pytest.approx(TRUE_ALPHA, rel=REL_TOL)


def test_third_order_resolves_the_paper_geometry_orbit():
    """Order 3 brings the amplitude-dependent detuning in: the amplitudes move from the seed
    3.8767 to within 2e-3 of the true 3.91797 (the remainder is the next term, ~0.0066**2 * 40)."""
    problem = paper_geometry()
    solution = problem.solve(3)
    assert solution.success
    start = dict(
        zip(
            solution.state_names,
            solution.initial_state(PAPER_EPS, problem.symbol_values()),
            strict=True,
        )
    )
    assert start["P"] / PAPER_EPS == pytest.approx(TRUE_BETA1, rel=2e-3)
    assert start["dP"] / PAPER_EPS == pytest.approx(TRUE_BETA2, rel=2e-3)
    tau_period = problem.period(solution) * problem.values["r0"]
    assert (tau_period - 2 * math.pi) / PAPER_EPS**2 == pytest.approx(TRUE_ALPHA, rel=1e-4)


def test_amplitudes_are_the_references_closed_form(solution):
    problem = fast_geometry(0.01)
    v = problem.symbol_values()
    m3 = math.sqrt(1 - v["gamma3_0"] ** 2)
    g3, x, y, k_, a_, b_ = (v[n] for n in ("gamma3_0", "x0p", "y0p", "k", "a", "b"))
    v1 = m3 * g3 * (2 * (1 + a_) * y**2 / a_**2 - 2 * (1 + b_) * x**2 / b_**2 + a_ * k_**2 * m3**2)
    v2 = -6 * m3 * g3 * x * y / (a_ * b_)
    beta1, beta2, alpha = _leading(solution, v)
    assert beta1 == pytest.approx(v1 / (k_ * m3**2), rel=1e-12)
    assert beta2 == pytest.approx(-v2 / (k_ * m3**2), rel=1e-12)
    c1 = b_ - a_
    assert alpha == pytest.approx(
        math.pi * (2 * m3 * x + k_ * (g3**2 + 0.5 * c1 * m3**2)), rel=1e-12
    )


def test_paper_amplitudes_are_ours_over_b_with_beta2_reversed(solution):
    for problem in (paper_geometry(), fast_geometry(0.01)):
        v = problem.symbol_values()
        beta1, beta2, _ = _leading(solution, v)
        paper1, paper2 = problem.paper_amplitudes()
        assert paper1 == pytest.approx(beta1 / v["b"], rel=1e-10)
        assert paper2 == pytest.approx(-beta2 / v["b"], rel=1e-10)
    assert paper_geometry().paper_amplitudes() == pytest.approx((7.048538, -2.028946), rel=1e-6)


def test_paper_period_correction_is_off_by_half_k_c1_m3_squared(solution):
    problem = fast_geometry(0.01)
    v = problem.symbol_values()
    _, _, alpha = _leading(solution, v)
    m3_sq = 1 - v["gamma3_0"] ** 2
    erratum = math.pi * 0.5 * v["k"] * (v["b"] - v["a"]) * m3_sq
    assert problem.paper_period_correction() - alpha == pytest.approx(erratum, rel=1e-10)
    assert erratum > 1e-3  # visible at k = 0.5


# ---------------------------------------------------------------------------- F2 and Phi2
def _first_harmonic_numeric(expr, m1, m2, m3, values, samples=16):
    """cos/sin coefficients of expr on P = m1 cos + m2 sin, G = m3 cos (exact for degree < 8)."""
    P, dP, G, dG = REDUCED_STATE
    P0, G0, dP0, dG0 = INITIAL_VALUES
    f = sp.lambdify((P, dP, G, dG, P0, G0, dP0, dG0, a, b, k, x0p, y0p, gamma3_0), expr)
    s = 2 * np.pi * np.arange(samples) / samples
    y = f(
        m1 * np.cos(s) + m2 * np.sin(s),
        -m1 * np.sin(s) + m2 * np.cos(s),
        m3 * np.cos(s),
        -m3 * np.sin(s),
        m1,
        m3,
        m2,
        0.0,
        *(values[n] for n in ("a", "b", "k", "x0p", "y0p", "gamma3_0")),
    ) * np.ones_like(s)
    return 2 * np.mean(y * np.cos(s)), 2 * np.mean(y * np.sin(s))


@pytest.mark.parametrize(("m1", "m2"), [(0.0, 0.0), (0.3, -0.2), (-0.7, 0.5)])
def test_f2_first_harmonic_is_the_papers_l21_and_phi2_differs_as_the_reference_says(m1, m2):
    reduction = Disk.reduction()
    values = fast_geometry(0.01).symbol_values()
    a_, b_, k_, x = values["a"], values["b"], values["k"], values["x0p"]
    g3 = values["gamma3_0"]
    m3 = 0.9
    l21 = 2 * m3 * x + 0.5 * (a_ - b_) * (m2**2 - m1**2 - k_ * m3**2) + k_ * (g3**2 - 0.5 * m3**2)
    fc, fs = _first_harmonic_numeric(reduction.F[2], m1, m2, m3, values)
    assert fc == pytest.approx(m1 * l21, abs=1e-12)
    assert fs == pytest.approx(m2 * l21, abs=1e-12)
    # Phi2: ours (reference) vs the paper's (10), (12)
    c1 = b_ - a_
    ours_c = m3 * (-a_ * m1**2 - b_ * m2**2 + 2 * m3 * x + k_ * (g3**2 + 0.5 * c1 * m3**2))
    pc, ps = _first_harmonic_numeric(reduction.Phi[2], m1, m2, m3, values)
    assert pc == pytest.approx(ours_c, abs=1e-12)
    assert ps == pytest.approx(0.0, abs=1e-12)
    n21 = -(a_ * m1**2 + b_ * m2**2) + 2 * m3 * x + k_ * (g3**2 + m3**2 * c1)
    paper_c = (n21 - 0.25 * a_ * (m1**2 - m2**2)) * m3
    paper_s = -0.5 * a_ * m1 * m2 * m3
    assert paper_c - pc == pytest.approx(
        m3 * (0.5 * k_ * c1 * m3**2 - 0.25 * a_ * (m1**2 - m2**2)), abs=1e-12
    )
    assert paper_s - ps == pytest.approx(-0.5 * a_ * m1 * m2 * m3, abs=1e-12)


# ---------------------------------------------------------------------------- formulations
@pytest.mark.slow  # ~40 s (the disk's derivation in mu); the default suite checks the same
# equivalence on Duffing (tests/engine/test_poincare.py, tests/property: test_regime_equivalence)
def test_large_parameter_formulation_gives_the_same_solution(solution):
    problem = fast_geometry(0.02)
    large = PoincareMethod(order=1, **problem.method_options()).solve(
        problem.system().as_large_parameter()
    )
    assert large.success
    eps, values = problem.epsilon(), problem.symbol_values()
    t = np.linspace(0.0, 10.0, 7)
    np.testing.assert_allclose(
        large.evaluate(t, 1 / eps, values), solution.evaluate(t, eps, values), atol=1e-13
    )
    assert float(large.period_at(1 / eps, values)) == pytest.approx(
        float(solution.period_at(eps, values)), rel=FORMULATIONS
    )


def test_initial_state_is_the_physical_one(solution):
    problem = fast_geometry(0.01)
    s = problem.state(solution, 0.0)
    assert s["r"] == pytest.approx(problem.values["r0"], rel=1e-12)
    assert s["gamma3"] == pytest.approx(problem.values["gamma3_0"], abs=INITIAL_SUM)
    # first order: the geometric integral holds to O(eps**2) (G(0) is truncated at O(eps))
    norm = s["gamma1"] ** 2 + s["gamma2"] ** 2 + s["gamma3"] ** 2
    assert abs(norm - 1.0) < 10 * problem.epsilon() ** 2
    assert problem.state_names() == ("p", "q", "r", "gamma1", "gamma2", "gamma3")


def test_symbolic_original_rhs_matches_the_numeric_one():
    for problem in (fast_geometry(0.01), Disk.create(R=math.inf)):
        state, exprs = problem.original_symbolic()
        f = sp.lambdify(state, exprs)
        y = np.array([0.1, -0.2, 3.0, 0.6, 0.0, 0.8])
        np.testing.assert_allclose(f(*y), original_rhs(problem)(0.0, y), rtol=1e-13, atol=1e-15)


def test_euler_angles_follow_from_the_state_and_the_kinematics(solution):
    problem = fast_geometry(0.02)
    period = problem.period(solution)
    t = np.linspace(0.0, 2 * period, 41)
    angles = problem.euler_angles(solution, t)
    s = problem.state(solution, t)
    np.testing.assert_allclose(np.cos(angles["theta"]), s["gamma3"], atol=ANGLE_ROUND_TRIP)
    # |gamma| = 1 holds to O(eps**2) at first order, so sin(theta) sin(phi) = gamma1 to that order
    defect = 10 * problem.epsilon() ** 2
    np.testing.assert_allclose(
        np.sin(angles["theta"]) * np.sin(angles["phi"]), s["gamma1"], atol=defect
    )
    phi = np.arctan2(s["gamma1"], s["gamma2"])
    np.testing.assert_allclose(phi, angles["phi"], atol=ANGLE_ROUND_TRIP * np.pi)
    assert angles["psi"][0] == 0.0
    # psi_dot = (p sin phi + q cos phi)/sin theta, checked by central differences
    h = period * 1e-5
    psi_plus = problem.euler_angles(solution, t + h)["psi"]
    psi_minus = problem.euler_angles(solution, t - h)["psi"]
    rate = (psi_plus - psi_minus) / (2 * h)
    sin_theta = np.hypot(s["gamma1"], s["gamma2"])  # on the computed vertical
    expected = (s["p"] * np.sin(angles["phi"]) + s["q"] * np.cos(angles["phi"])) / sin_theta
    np.testing.assert_allclose(rate, expected, atol=1e-6 * np.max(np.abs(expected)))


# ---------------------------------------------------------------------------- CLI
def test_cli_solve_disk_end_to_end(capsys, solution):
    r0 = fast_geometry(0.01).values
    argv = ["solve", "disk", "--times", "0,0.5,1", "--format", "json", "--euler"]
    for name in ("g", "R", "r0", "gamma3_0"):
        argv += ["--set", f"{name}={r0[name]!r}"]
    assert main(argv) == 0
    payload = json.loads(capsys.readouterr().out)
    assert set(payload["state"]) == {"p", "q", "r", "gamma1", "gamma2", "gamma3"}
    assert set(payload["euler"]) == {"theta", "psi", "phi"}
    assert payload["mu"] == pytest.approx(100.0)
    assert "fast-spin" in payload["regime"]
    assert payload["period"] == pytest.approx(2 * math.pi * 0.01, rel=1e-3)


def test_cli_bad_disk_input_exits_2(capsys):
    assert main(["solve", "disk", "--set", "C=19"]) == 2
    err = capsys.readouterr().err
    assert "rigid-body" in err and err.count("\n") == 1


def test_cli_default_disk_is_outside_its_domain(capsys, solution):
    """Issue 9.4: at the paper's eps = 232 the series gives a negative period: a failed status with
    the reason and exit 1, not a table."""
    assert main(["solve", "disk", "--times", "0"]) == 1
    out, err = capsys.readouterr()
    assert out == "" and "outside its domain" in err and "not a positive number" in err
