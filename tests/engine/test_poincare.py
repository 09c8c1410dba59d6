"""The Poincaré construction against textbook results and exact solutions."""

import numpy as np
import pytest
import sympy as sp

from perturb import EPS, InvalidSystemError, PoincareMethod, QuasilinearSystem, Regime, Status
from perturb.steps import S
from problems import get_problem
from tests.helpers import roundings

x, xd, y, yd, A, mu = sp.symbols("x xdot y ydot A mu")
DUFFING = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A], name="duffing")
VDP = QuasilinearSystem([x], [xd], [1], [EPS * (1 - x**2) * xd], name="van der Pol")


def test_duffing_frequency_is_the_lindstedt_textbook_series():
    # Nayfeh, Perturbation Methods (1973) §4.1: omega = 1 + 3/8 eps A^2 - 21/256 eps^2 A^4 + 81/2048 eps^3 A^6
    sol = PoincareMethod(order=3, amplitudes={"x": A}).solve(DUFFING)
    assert sol.success
    expected = (
        1
        + sp.Rational(3, 8) * EPS * A**2
        - sp.Rational(21, 256) * EPS**2 * A**4
        + sp.Rational(81, 2048) * EPS**3 * A**6
    )
    assert sp.expand(sol.frequency_expr - expected) == 0
    # first-order correction x1 = A^3 (cos 3s - cos s)/32
    assert sp.expand(sol.terms[0][1].as_expr(S) - A**3 * (sp.cos(3 * S) - sp.cos(S)) / 32) == 0


def test_van_der_pol_limit_cycle_is_the_textbook_one():
    # amplitude 2, omega = 1 - eps^2/16 + 17 eps^4/3072, x1 = (3 sin s - sin 3s)/4
    sol = PoincareMethod(order=3).solve(VDP)
    assert sol.success
    assert sol.generating.cos_amplitudes[0] == 2
    assert len(sol.frequency) == 5  # the order-4 conditions fixing x_3 also give Omega_4
    assert sp.expand(sol.frequency_expr - (1 - EPS**2 / 16 + sp.Rational(17, 3072) * EPS**4)) == 0
    assert sp.expand(sol.terms[0][1].as_expr(S) - (3 * sp.sin(S) - sp.sin(3 * S)) / 4) == 0
    x2 = -sp.cos(S) / 8 + sp.Rational(3, 16) * sp.cos(3 * S) - sp.Rational(5, 96) * sp.cos(5 * S)
    assert sp.expand(sol.terms[0][2].as_expr(S) - x2) == 0


def test_order_zero_is_the_generating_solution():
    sol = PoincareMethod(order=1, amplitudes={"x": A}).solve(DUFFING)
    assert sol.terms[0][0].as_expr(S) == A * sp.cos(S)
    assert sol.frequency[0] == 1
    gen = sol.generating.expressions()["x"]
    # it solves the eps = 0 equation exactly
    assert sp.simplify(sp.diff(gen, S, 2) + gen) == 0


def test_large_and_small_regimes_give_the_same_solution():
    small = PoincareMethod(order=2, amplitudes={"x": A}).solve(DUFFING)
    large = PoincareMethod(order=2, amplitudes={"x": A}).solve(DUFFING.as_large_parameter(mu))
    assert large.system.regime is Regime.LARGE
    assert sp.expand(large.coordinate("x") - small.coordinate("x").subs(EPS, 1 / mu)) == 0
    t = np.linspace(0, 10, 7)
    np.testing.assert_allclose(
        large.evaluate(t, 20.0, {"A": 1.1}),
        small.evaluate(t, 0.05, {"A": 1.1}),
        rtol=1e-13,
        atol=FORMULATIONS * 1.1,  # x crosses zero: relative to the amplitude A = 1.1
    )


def test_linear_pair_is_reproduced_exactly():
    problem = get_problem("linear-pair").create(eps=0.05, kappa=0.7, omega=2.5)
    sol = problem.solve(4)
    assert sol.success
    k, w = sp.symbols("kappa omega", positive=True)
    # exact: lambda^2 = [1 + w^2 - sqrt((w^2-1)^2 + 4 eps^2 k^2)]/2 ; y/x = eps k/(w^2 - lambda^2)
    lam2 = (1 + w**2 - (w**2 - 1) * sp.sqrt(1 + 4 * EPS**2 * k**2 / (w**2 - 1) ** 2)) / 2  # w > 1
    n = len(sol.frequency)
    exact_series = sp.series(sp.sqrt(lam2), EPS, 0, n).removeO()
    assert sp.simplify(sol.frequency_expr - exact_series) == 0
    # y starts at eps^1: order 4 keeps it through eps^5 (relative accuracy eps^5, as x's)
    assert len(sol.terms[1]) == 6 and sol.terms[1][0].is_zero()
    ratio = sp.series(EPS * k / (w**2 - lam2), EPS, 0, 6).removeO()
    amp = sp.Symbol("amplitude", positive=True)
    y_cos = sp.Add(*(EPS**q * t.coefficient(1)[0] for q, t in enumerate(sol.terms[1])))
    assert sp.simplify(y_cos - amp * ratio) == 0
    assert all(t.is_zero() for t in sol.terms[0][1:])  # x = A cos(Omega t) exactly
    assert problem.period(sol) == pytest.approx(2 * np.pi / problem.exact_frequency(), rel=1e-9)


def test_resonant_pair_has_both_normal_modes():
    in_phase = get_problem("resonant-pair").create(mode=1).solve(2)
    anti = get_problem("resonant-pair").create(mode=-1).solve(2)
    kappa = sp.Symbol("kappa", positive=True)
    amp = sp.Symbol("amplitude", positive=True)
    # in phase: coupling inactive, Duffing frequency; anti-phase: Omega_1 = 3A^2/8 + kappa
    assert in_phase.frequency[1] == sp.Rational(3, 8) * amp**2
    assert sp.expand(anti.frequency[1] - (sp.Rational(3, 8) * amp**2 + kappa)) == 0
    assert len(anti.steps[0].branches) >= 2


def test_non_resonant_generating_amplitude_is_rejected():
    sys = QuasilinearSystem([x, y], [xd, yd], [1, sp.Rational(5, 2)], [EPS * y, EPS * x])
    with pytest.raises(InvalidSystemError, match="not resonant"):
        PoincareMethod(amplitudes={"x": 1, "y": 1}).solve(sys)


@pytest.mark.parametrize("order", [0, -1, 1.5, True])
def test_bad_order(order):
    with pytest.raises(InvalidSystemError, match="`order`"):
        PoincareMethod(order=order)


def test_bad_phase_coordinate_and_amplitude_names():
    with pytest.raises(InvalidSystemError, match="phase_coordinate"):
        PoincareMethod(phase_coordinate="z").solve(VDP)
    with pytest.raises(InvalidSystemError, match="amplitudes"):
        PoincareMethod(amplitudes={"q": 1}).solve(VDP)


def test_rootless_conditions_end_in_a_failed_status():
    # x'' + x = eps xdot: pure negative damping, only the trivial root
    sol = PoincareMethod(order=1).solve(QuasilinearSystem([x], [xd], [1], [EPS * xd]))
    assert sol.status is Status.NO_ROOT and not sol.success
    with pytest.raises(Exception, match="no admissible"):
        sol.raise_for_status()


def test_continuous_family_without_a_chosen_amplitude_is_undetermined():
    sol = PoincareMethod(order=1).solve(DUFFING.with_values({"A": 1}))
    assert sol.status is Status.UNDETERMINED
    assert "amplitudes=" in sol.status.value


def test_inconsistent_conditions_fail():
    # x'' + x = eps: forcing at the constant harmonic is fine; eps*cos-like resonance via y is not
    sys = QuasilinearSystem([x, y], [xd, yd], [1, 1], [EPS * y**3 + EPS, EPS * x])
    sol = PoincareMethod(order=1, amplitudes={"x": 1, "y": 0}).solve(sys)
    assert not sol.success
    assert sol.status in (Status.INCONSISTENT, Status.NO_ROOT)


def test_first_integral_is_constant_to_the_truncation_order():
    """The resonant pair's energy varies along the analytic orbit only at O(eps^(N+1))."""
    problem = get_problem("resonant-pair").create()
    system = problem.system()
    (energy,) = system.first_integrals
    values = problem.symbol_values()
    spreads = []
    eps_values = np.array([0.01, 0.02, 0.04])
    for eps in eps_values:
        sol = problem.solve(1)
        y = sol.evaluate(np.linspace(0, 7, 50), eps, values)
        h = sp.lambdify(
            system.state_symbols,
            energy.subs({EPS: eps, **{sp.Symbol(k, positive=True): v for k, v in values.items()}}),
        )
        e = h(*y)
        spreads.append(np.ptp(e))
    slope = np.polyfit(np.log(eps_values), np.log(spreads), 1)[0]
    assert abs(slope - 2) < 0.3  # order 1: the energy is conserved through O(eps)


def test_vanishing_small_divisor_is_an_error_not_a_nan():
    """A non-resonant coordinate pushed onto a resonance by its parameter value fails loudly."""
    from perturb import AccuracyWarning, SolutionFailed

    w = sp.Symbol("w", positive=True)
    sys = QuasilinearSystem([x, y], [xd, yd], [1, w], [-EPS * x**3, EPS * x**3], parameters=[w])
    sol = PoincareMethod(order=1, amplitudes={"x": 1}).solve(sys)
    assert sol.success
    with pytest.raises(SolutionFailed, match="small divisor"):
        sol.evaluate([0.0, 1.0], 0.1, {"w": 3.0})  # harmonic 3 of x^3 resonates with w = 3
    with pytest.warns(AccuracyWarning, match="within"):
        sol.evaluate([0.0, 1.0], 0.1, {"w": 3.0 + 1e-5})


def test_truncated_system_refuses_orders_that_need_the_missing_terms():
    """A series known through eps^2 (truncation 3) gives van der Pol's order 1 (needs order 2) but
    not order 2 (needs the conditions of order 3)."""
    vdp2 = QuasilinearSystem([x], [xd], [1], [EPS * (1 - x**2) * xd], truncation=3)
    assert PoincareMethod(order=1, cache=False).solve(vdp2).success
    deeper = PoincareMethod(order=2, cache=False).solve(vdp2)
    assert deeper.status is Status.TRUNCATED and "epsilon^3" in deeper.message
    with pytest.raises(InvalidSystemError, match="truncation"):
        QuasilinearSystem([x], [xd], [1], [EPS * x], truncation=1)


def test_simplified_display_is_the_same_expression():
    sol = get_problem("resonant-pair").create(mode=-1).solve(2)
    for name in sol.coordinates:
        assert sp.simplify(sol.coordinate(name, simplify=True) - sol.coordinate(name)) == 0
    assert sp.simplify(sol.period_series(simplify=True) - sol.period_series()) == 0
    assert "\\cos" in sol.latex() and "T =" in sol.latex(simplify=False)


kappa = sp.Symbol("kappa", positive=True)
COUPLED_VDP = QuasilinearSystem(
    [x, y],
    [xd, yd],
    [1, 1],
    [
        EPS * ((1 - x**2) * xd + kappa * (y - x)),
        EPS * ((1 - y**2) * yd + kappa * (x - y)),
    ],
    parameters=[kappa],
    name="coupled van der Pol",
)
#: Far below the seconds sympy would need to enumerate the coupled pair's amplitude roots (hours):
#: spent on any machine, however fast, so the outcome (the budget's status, or the branch given
#: taking over) does not depend on the machine's speed.
SHORT_BUDGET = 1.0
#: Two formulations (eps, mu = 1/eps) of the same order-2 series: a dozen operations a term.
FORMULATIONS = roundings(12)


def test_numeric_amplitude_equations_are_solved_by_a_groebner_basis():
    """Coupled van der Pol with kappa = 1/2: sympy's solve runs for hours (roots of high degree);
    the Groebner path finds the synchronised cycles x = +-y = 2 cos s at once."""
    system = COUPLED_VDP.with_values({"kappa": sp.Rational(1, 2)})
    sol = PoincareMethod(order=1, cache=False).solve(system)
    assert sol.success, sol.message
    amplitudes = {(r[sp.Symbol("a_x0")], r[sp.Symbol("a_y0")]) for r in sol.steps[0].branches}
    assert {(2, 2), (2, -2)} <= amplitudes  # in phase and in anti-phase, exact
    assert sol.generating.cos_amplitudes == (2, 2) and sol.frequency[:3] == (
        1,
        0,
        -sp.Rational(1, 16),
    )
    anti = PoincareMethod(order=1, cache=False, branch={"a_y0": -2}).solve(system)
    assert anti.frequency[1] == sp.Rational(1, 2)  # Omega_1 = kappa for the anti-phase cycle


def test_amplitude_equations_sympy_cannot_solve_end_in_a_status_not_a_hang():
    """Issue 22: a budget spent is SOLVER_BUDGET (not NO_ROOT, which means proved), and the
    message names the option that raises the budget and the size of the system."""
    sol = PoincareMethod(order=1, cache=False, solve_seconds=SHORT_BUDGET).solve(COUPLED_VDP)
    assert sol.status is Status.SOLVER_BUDGET and "branch=" in sol.message
    assert "solve_seconds" in sol.message and "unknowns" in sol.message


def test_branch_supplies_the_root_sympy_cannot_enumerate():
    """The synchronised limit cycle x = y = 2 cos s: the frequency is van der Pol's."""
    method = PoincareMethod(
        order=1,
        cache=False,
        solve_seconds=SHORT_BUDGET,
        branch={"a_x0": 2, "a_y0": 2, "b_y0": 0},
    )
    sol = method.solve(COUPLED_VDP)
    assert sol.success, sol.message
    assert sol.frequency[:3] == (1, 0, -sp.Rational(1, 16))
    bad = PoincareMethod(
        order=1, cache=False, solve_seconds=SHORT_BUDGET, branch={"a_x0": 1, "a_y0": 2, "b_y0": 0}
    ).solve(COUPLED_VDP)
    assert bad.status is Status.INCONSISTENT
