"""Right-hand sides analytic (not polynomial) in ε: expanded automatically, checked by a second route.

Each system of the gallery is solved twice: once as given (the engine expands its ε dependence), and
once by an independent route written here — a polynomial system in an auxiliary parameter ε' whose
series is re-expanded in ε after ε' = φ(ε) is put in, or a polynomial truncation built from a known
Taylor series. Both routes give exact series (sympy ``Rational``), so every comparison is an exact
equality: no tolerance.
"""

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb import EPS, InvalidSystemError, PoincareMethod, QuasilinearSystem, Regime

x, xd, A, mu = sp.symbols("x xdot A mu")
#: Highest power of ε compared. Every φ(ε) below starts at ε, so orders 0..ORDER of ε' are all the
#: re-expansion needs, and order 3 already mixes the second and third Taylor coefficients of φ.
ORDER = 3


def _system(rhs, **kw):
    return QuasilinearSystem([x], [xd], [1], [rhs], parameters=[A], **kw)


def _solve(system, order=ORDER):
    solution = PoincareMethod(order=order, amplitudes={"x": A}, cache=False).solve(system)
    assert solution.success, solution.message
    return solution


def _truncate(expr, order=ORDER):
    """``expr`` (a function of ε) as its Maclaurin polynomial through ε**order."""
    return sp.expand(sp.series(expr, EPS, 0, order + 1).removeO())


def _in_epsilon(solution, phi=EPS, order=ORDER):
    """State (in the strained time) and frequency of ``solution`` with its ε replaced by φ(ε)."""
    return (
        _truncate(solution.coordinate("x").subs(solution.parameter, phi), order),
        _truncate(solution.frequency_series().subs(solution.parameter, phi), order),
    )


#: The gallery: right-hand side as given, and φ such that it equals -φ(ε) x² (the second route).
SUBSTITUTIONS = {
    "rational": (-EPS * x**2 / (1 + EPS), EPS / (1 + EPS)),
    "sine": (-(x**2) * sp.sin(EPS), sp.sin(EPS)),
    "exponential": (-(x**2) * (sp.exp(EPS) - 1), sp.exp(EPS) - 1),
    "root": (-(x**2) * (sp.sqrt(1 + 2 * EPS) - 1), sp.sqrt(1 + 2 * EPS) - 1),
}


@pytest.fixture(scope="module")
def quadratic():
    """ẍ + x = -ε' x², x(0) = A: the polynomial route."""
    return _solve(_system(-EPS * x**2))


@pytest.mark.parametrize("name", sorted(SUBSTITUTIONS))
def test_analytic_dependence_equals_the_reexpanded_polynomial_route(name, quadratic):
    rhs, phi = SUBSTITUTIONS[name]
    analytic = _solve(_system(rhs))
    assert _in_epsilon(analytic) == _in_epsilon(quadratic, phi)


def test_large_parameter_rational_dependence_equals_the_polynomial_route(quadratic):
    """ẍ + x = -x²/(μ + 1) is -ε' x² with ε' = ε/(1 + ε), ε = 1/μ."""
    large = _solve(_system(-(x**2) / (mu + 1), parameter=mu, regime=Regime.LARGE))
    assert _in_epsilon(large, 1 / EPS) == _in_epsilon(quadratic, EPS / (1 + EPS))


def _sine_remainder_polynomial(top: int) -> sp.Expr:
    """(εx − sin εx)/ε through ε**top, from sin u = Σ (−1)^j u^(2j+1)/(2j+1)!."""
    u = EPS * x
    terms = [(-1) ** j * u ** (2 * j + 1) / sp.factorial(2 * j + 1) for j in range(1, top)]
    return sp.expand(-sp.Add(*terms) / EPS)


def test_removable_singularity_is_a_duffing_type_term():
    """(εx − sin εx)/ε = ε²x³/6 − ε⁴x⁵/120 + …: the same solution as its Taylor polynomial."""
    given = _solve(_system((EPS * x - sp.sin(EPS * x)) / EPS))
    polynomial = _solve(_system(_sine_remainder_polynomial(top=6)))
    assert _in_epsilon(given) == _in_epsilon(polynomial)


def test_removable_singularity_frequency_is_duffings_with_delta_eps_squared_over_six():
    """ẍ + x = δx³ (δ = ε²/6, softening): Ω = 1 − 3δA²/8 + O(δ²) — the Duffing series in δ."""
    given = _solve(_system((EPS * x - sp.sin(EPS * x)) / EPS))
    duffing = _solve(_system(EPS * x**3), order=1)  # ẍ + x = δ x³ by the polynomial path
    delta = EPS**2 / 6
    assert duffing.frequency[1] == -sp.Rational(3, 8) * A**2  # Nayfeh §4.1 with the sign of δ
    assert _in_epsilon(given)[1] == _truncate(duffing.frequency_expr.subs(EPS, delta))


@pytest.mark.parametrize(
    ("rhs", "kw", "fragment"),
    [
        (x**2 / EPS, {}, "pole"),
        (sp.sqrt(EPS) * x**2, {}, "branch point"),
        (EPS * sp.log(EPS) * x**2, {}, "branch point or an essential singularity"),
        (sp.exp(-1 / EPS) * x**2, {}, "essential singularity"),
        (mu**2 * x**2 / (mu + 1), {"parameter": mu, "regime": Regime.LARGE}, "pole"),
        (sp.sqrt(mu) * x**2 / mu, {"parameter": mu, "regime": Regime.LARGE}, "branch point"),
    ],
)
def test_what_has_no_maclaurin_series_is_refused_in_one_line(rhs, kw, fragment):
    with pytest.raises(InvalidSystemError) as info:
        _system(rhs, **kw)  # refused when the system is built, before any construction
    message = str(info.value)
    assert isinstance(info.value, ValueError)
    assert fragment in message and "rhs[0]" in message
    assert "\n" not in message


def test_a_pole_still_says_the_lowest_power_must_be_positive():
    with pytest.raises(InvalidSystemError, match="lowest power of epsilon must be positive"):
        _system(x**2 / EPS)


# ---------------------------------------------------------------------- polynomial input: untouched
polynomials = st.lists(
    st.tuples(
        st.integers(1, 3), st.integers(0, 3), st.integers(0, 1), st.integers(-3, 3).filter(bool)
    ),
    min_size=1,
    max_size=4,
)


def _polynomial(terms) -> sp.Expr:
    return sp.Add(*(c * EPS**k * x**a * xd**b for k, a, b, c in terms))


@given(polynomials)
def test_polynomial_input_keeps_the_fast_path(terms):
    """The coefficients are exactly those of ``sympy.Poly`` (no series, no re-simplification)."""
    f = _polynomial(terms)
    system = _system(f)
    expected = tuple(sp.expand(sp.Poly(f, EPS).coeff_monomial(EPS**k)) for k in range(5))
    assert system.expansion(4) == (expected,)
    assert system.leading_order == min(k for k, _, _, _ in terms if f.coeff(EPS, k) != 0)


@given(polynomials)
def test_polynomial_written_as_a_rational_function_gives_the_same_expansion(terms):
    """f·(1 − ε²)/(1 − ε) is f·(1 + ε): the series path agrees with the fast path on it."""
    f = _polynomial(terms)
    rhs = f * (1 - EPS**2) / (1 - EPS)
    with pytest.raises(sp.PolynomialError):  # genuinely not a polynomial as written
        sp.Poly(sp.expand(rhs), EPS)
    disguised = _system(rhs)
    plain = _system(sp.expand(f * (1 + EPS)))
    assert disguised.expansion(6) == plain.expansion(6)
    assert disguised.leading_order == plain.leading_order


def test_disguised_polynomial_van_der_pol_gives_the_identical_solution():
    """The whole construction, not only the expansion: identical frequency and state series."""
    vdp = -EPS * (x**2 - 1) * xd  # van der Pol: limit cycle of amplitude 2
    plain = PoincareMethod(order=2, cache=False).solve(_system(vdp))
    disguised = PoincareMethod(order=2, cache=False).solve(
        _system(vdp * (1 - EPS**2) / ((1 - EPS) * (1 + EPS)))
    )
    assert plain.success and disguised.success
    assert disguised.frequency == plain.frequency
    assert sp.expand(disguised.coordinate("x") - plain.coordinate("x")) == 0
