"""Families of periodic solutions (issue 11, item 4): found, named, carried, checked by other routes.

Each expectation comes from a route that does not use the engine's construction: a textbook result
(Nayfeh, *Perturbation Methods*, §4.1: Duffing's and the quadratic oscillator's frequencies; van der
Pol's limit cycle), the averaged equations derived here in complex exponentials (independent of the engine's
trigonometric polynomials), or the true periodic orbit found by shooting the original equations.
"""

from __future__ import annotations

import math

import pytest
import sympy as sp

from perturb import EPS, InvalidSystemError, QuasilinearSystem, Status, UnknownNameError
from perturb.method.families import find_families
from perturb.method.family_names import name_families
from problems import get_problem
from tests.engine.henon_heiles import henon_heiles_families

X, Y, XDOT, YDOT = sp.symbols("x y xdot ydot")
Z = sp.Symbol("z")

DUFFING = QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], name="duffing")
VAN_DER_POL = QuasilinearSystem([X], [XDOT], [1], [EPS * (1 - X**2) * XDOT], name="van der Pol")


@pytest.fixture(scope="module")
def henon_heiles():
    return henon_heiles_families(2)


def _cos(k: int) -> sp.Expr:
    """cos(k s) as a Laurent polynomial in z = exp(i s) (the averaging is done in exponentials)."""
    return (Z**k + Z**-k) / 2


def _sin(k: int) -> sp.Expr:
    return (Z**k - Z**-k) / (2 * sp.I)


def _harmonic(expr: sp.Expr, k: int) -> tuple[sp.Expr, sp.Expr]:
    """Cosine and sine coefficients of harmonic ``k`` of a Laurent polynomial in z."""
    expr = sp.expand(expr)
    plus, minus = expr.coeff(Z, k), expr.coeff(Z, -k)
    if k == 0:
        return sp.expand(expr.subs(Z, 0) if not expr.has(Z) else plus), sp.S.Zero
    return sp.expand(plus + minus), sp.expand(sp.I * (plus - minus))


def _first_harmonic(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    return _harmonic(expr, 1)


# ---------------------------------------------------------------------- one-coordinate systems
def test_duffing_is_one_continuum_with_the_textbook_frequency():
    families = find_families(DUFFING, 2)
    assert families.names == ("continuum",)
    (family,) = families
    a = sp.Symbol("a_x")
    assert family.kind == "continuum" and family.free == ("a_x",)
    assert family.status is Status.SUCCESS
    # Nayfeh §4.1: omega = 1 + 3 eps a²/8 - 21 eps² a⁴/256 for x(0) = a
    assert sp.expand(family.frequency[1] - sp.Rational(3, 8) * a**2) == 0
    assert sp.expand(family.frequency[2] + sp.Rational(21, 256) * a**4) == 0


def test_van_der_pol_is_one_isolated_limit_cycle_of_amplitude_two():
    families = find_families(VAN_DER_POL, 2)
    assert families.names == ("limit-cycle",)
    (family,) = families
    assert family.kind == "isolated" and family.free == ()
    # the root a = -2 is the same cycle half a period later: reported once, with a > 0
    assert family.amplitudes == {"a_x": 2}
    assert family.frequency[:3] == (1, 0, sp.Rational(-1, 16))  # omega = 1 - eps²/16 + ...
    assert family.status is Status.SUCCESS


# ---------------------------------------------------------------------- Hénon–Heiles
def test_henon_heiles_families_at_the_first_order_that_selects_them(henon_heiles):
    # order 1 leaves every amplitude free (Omega1 = 0): the families come from order 2; the
    # order-2 line in every direction is restricted by the order-4 conditions (issue 21.3: the
    # general "line" it used to report does not exist; tests/engine/test_families_degenerate.py)
    assert henon_heiles.family_order == 2
    assert set(henon_heiles.names) == {
        "y-line", "line-30", "line-150", "bowed-0", "bowed-60", "bowed-120",
        "circle-ccw", "circle-cw",
    }  # fmt: skip
    a_x, a_y = sp.symbols("a_x a_y")
    by_name = {f.name: f for f in henon_heiles}
    assert by_name["y-line"].amplitudes == {"a_x": 0, "b_x": 0, "a_y": a_y}
    assert by_name["bowed-0"].amplitudes == {"a_x": a_x, "a_y": 0, "b_y": 0}
    assert by_name["line-30"].amplitudes == {"a_x": a_x, "a_y": sp.sqrt(3) * a_x / 3, "b_y": 0}
    assert all(f.free == ("a_x",) for n, f in by_name.items() if n != "y-line")
    assert by_name["circle-ccw"].amplitudes == {"a_x": a_x, "a_y": 0, "b_y": a_x}
    assert by_name["circle-cw"].amplitudes == {"a_x": a_x, "a_y": 0, "b_y": -a_x}
    assert all(f.kind == "continuum" for f in henon_heiles)


def test_henon_heiles_order_two_amplitude_equations_by_averaging(henon_heiles):
    """The families' generating amplitudes solve the order-2 averaged equations, derived here.

    Order 1 (quadratic forcing, harmonics 0 and 2 only): Omega1 = 0 and the first-order corrections
    are the forced responses, computed here by hand from ``w'' + w = f`` harmonic by harmonic. The
    first harmonic of the order-2 forcing must then vanish (with 2 Omega2 times the generating one).
    """
    a, c, d, omega2 = sp.symbols("a c d Omega2")
    x0, y0 = a * _cos(1), c * _cos(1) + d * _sin(1)

    def forced(f):  # the periodic solution of w'' + w = f, f with harmonics 0 and 2 only
        f = sp.expand(f)
        assert _harmonic(f, 1) == (0, 0)
        const = f.coeff(Z, 0)
        c2, s2 = _harmonic(f, 2)
        return const + (c2 * _cos(2) + s2 * _sin(2)) / (1 - 4)

    x1, y1 = forced(-2 * x0 * y0), forced(-(x0**2 - y0**2))
    fx2 = -2 * (x0 * y1 + x1 * y0) + 2 * omega2 * x0
    fy2 = -(2 * x0 * x1 - 2 * y0 * y1) + 2 * omega2 * y0
    equations = [*_first_harmonic(fx2), *_first_harmonic(fy2)]
    for family in henon_heiles:
        if family.name == "y-line":
            continue  # found with y as phase coordinate; checked below
        amp = {k: sp.sympify(v) for k, v in family.amplitudes.items()}
        values = {a: amp["a_x"], c: amp["a_y"], d: amp["b_y"], omega2: family.frequency[2]}
        for equation in equations:
            assert sp.simplify(equation.xreplace(values)) == 0, (family.name, equation)


def test_henon_heiles_y_line_is_the_quadratic_oscillator(henon_heiles):
    # On x = 0: y'' + y = eps y², Nayfeh §4.1 (alpha2 = -1): omega = 1 - 5 eps² a²/12 + ...
    family = henon_heiles.get("y-line")
    a_y = sp.Symbol("a_y")
    assert family.phase_coordinate == "y"
    assert family.frequency[1] == 0
    assert sp.expand(family.frequency[2] + sp.Rational(5, 12) * a_y**2) == 0
    # the tilt of the line (a_x1, a_x2) is fixed by the conditions four orders up, which the
    # construction now runs: x = 0 at every order, as it must (the y axis is invariant: x'' = -2xy)
    assert family.status is Status.SUCCESS
    assert all(term.is_zero() for term in family.solution.terms[0])


def test_henon_heiles_general_line_does_not_survive_order_four(henon_heiles):
    with pytest.raises(UnknownNameError, match="line-30"):
        henon_heiles.get("line")


@pytest.mark.parametrize("name", ["circle-ccw", "circle-cw"])
def test_henon_heiles_circles_match_the_true_periodic_orbits(henon_heiles, name):
    """Shooting from the analytic start converges to a true orbit whose period the series gives.

    The frequency is known through eps^K (K = len(frequency) - 1); the period error must fall as
    eps^(K+1): halving eps divides it by ~2^(K+1). Accepting a slope above K + 1/2 leaves room for
    the next term's coefficient without admitting a wrong eps^K term (slope <= K).
    """
    from perturb.oracle import SymbolicRHS, find_periodic_orbit, heyoka_available

    if not heyoka_available():
        pytest.skip("shooting with the variational equations takes minutes without heyoka")

    family = henon_heiles.get(name)
    assert family.status is Status.SUCCESS
    amplitude = 0.5
    values = {"a_x": amplitude}
    K = len(family.frequency) - 1
    errors = []
    for eps in (0.08, 0.04):
        e = sp.Rational(eps).limit_denominator(100)
        rhs = SymbolicRHS(
            (X, Y, XDOT, YDOT), (XDOT, YDOT, -X - 2 * e * X * Y, -Y - e * (X**2 - Y**2))
        )
        start = family.solution.initial_state(eps, values)
        period = float(family.solution.period_at(eps, values))
        orbit = find_periodic_orbit(
            rhs, start, period, section_index=2, fixed_indices=0, n_trivial=2
        )
        assert orbit.success, orbit.message
        errors.append(abs(orbit.period - period))
    slope = math.log2(errors[0] / errors[1])
    assert slope > K + 0.5, (errors, slope)


# ---------------------------------------------------------------------- the resonant pair
def test_resonant_pair_families_solve_the_averaged_equations():
    """In-phase, anti-phase and a third normal mode, as the averaged equations give them."""
    problem = get_problem("resonant-pair").create()
    families = problem.families(1)
    assert families.names == ("anti-phase", "in-phase", "line")
    kappa, amplitude = sp.symbols("kappa amplitude", positive=True)
    c, d, omega1 = sp.symbols("c d Omega1")
    x0, y0 = amplitude * _cos(1), c * _cos(1) + d * _sin(1)
    fx = -(x0**3) + kappa * (y0 - x0) + 2 * omega1 * x0
    fy = -(y0**3) + kappa * (x0 - y0) + 2 * omega1 * y0
    equations = [*_first_harmonic(fx), *_first_harmonic(fy)]
    roots = sp.solve(equations, [c, d, omega1], dict=True)
    expected = {sp.simplify(r[c]) for r in roots if r.get(d, 0) == 0 and r[c] != 0}
    found = {sp.simplify(sp.sympify(f.amplitudes["a_y"]).subs(sp.Symbol("amplitude"), amplitude))
             for f in families}  # fmt: skip
    found = {sp.simplify(v.subs(sp.Symbol("kappa"), kappa)) for v in found}
    assert found == expected
    assert all(f.amplitudes["b_y"] == 0 and f.free == ("a_x",) for f in families)


@pytest.mark.parametrize(("mode", "name"), [(1, "in-phase"), (-1, "anti-phase")])
def test_family_selection_equals_the_problems_branch(mode, name):
    problem = get_problem("resonant-pair").create(mode=mode)
    before = problem.solve(2)
    chosen = problem.solve(2, family=name)
    assert chosen.status is Status.SUCCESS
    for row_a, row_b in zip(before.terms, chosen.terms, strict=True):
        for ta, tb in zip(row_a, row_b, strict=True):
            assert (ta - tb).expand().is_zero()
    assert all(
        sp.expand(p - q) == 0 for p, q in zip(before.frequency, chosen.frequency, strict=True)
    )
    assert problem.case().with_family(name).model.solve(2) is chosen


def test_unknown_family_lists_the_known_ones():
    problem = get_problem("resonant-pair").create()
    with pytest.raises(UnknownNameError, match=r"choose from \['anti-phase', 'in-phase', 'line'\]"):
        problem.solve(1, family="sideways")


def test_branch_is_refused():
    with pytest.raises(InvalidSystemError, match="branch"):
        find_families(DUFFING, 1, branch={"a_x0": 1})


# ---------------------------------------------------------------------- names
def test_names_are_structural_and_deterministic():
    a = sp.Symbol("a_x")
    described = [
        ({"a_x": a, "a_y": -a, "b_y": 0}, ("a_x",)),
        ({"a_x": a, "a_y": 2 * a, "b_y": 0}, ("a_x",)),
        ({"a_x": a, "a_y": a, "b_y": 0}, ("a_x",)),
        ({"a_x": a, "a_y": a / 2, "b_y": a / 3}, ("a_x",)),
        ({"a_x": a, "a_y": 0, "b_y": -2 * a}, ("a_x",)),
    ]
    names = name_families(described)
    # canonical order: by the sorted text of the amplitudes ('2*a_x' < 'a_x')
    assert names == ["anti-phase", "in-phase-1", "in-phase-2", "family-1", "ellipse-cw"]
    assert name_families(described[::-1]) == names[::-1]  # independent of the order found
