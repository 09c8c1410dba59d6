"""Issue 11.5: a system given in the large parameter μ (ε = 1/μ) is answered in μ.

Frequency, period, printout and LaTeX are series in 1/μ with ε = 1/μ stated; the reference is
Duffing's ẍ + x + x³/μ = 0, whose Lindstedt frequency Ω = 1 + 3A²ε/8 − 21A⁴ε²/256 + O(ε³)
(Nayfeh, *Perturbation Methods*, §4.1) is written here in u = 1/μ and its period derived from it.
"""

import pytest
import sympy as sp

from perturb import EPS, PoincareMethod, QuasilinearSystem, Regime

x, xd, A, mu, u = sp.symbols("x xdot A mu u")
#: Ω of ẍ + x + u x³ = 0 through u² (Nayfeh §4.1), u = 1/μ.
NAYFEH_OMEGA = 1 + sp.Rational(3, 8) * A**2 * u - sp.Rational(21, 256) * A**4 * u**2


def _duffing(**kw):
    return QuasilinearSystem([x], [xd], [1], [-(x**3) * kw.pop("scale")], parameters=[A], **kw)


@pytest.fixture(scope="module")
def large():
    system = _duffing(scale=1 / mu, parameter=mu, regime=Regime.LARGE)
    return PoincareMethod(order=2, amplitudes={"x": A}, cache=False).solve(system)


@pytest.fixture(scope="module")
def small():
    return PoincareMethod(order=2, amplitudes={"x": A}, cache=False).solve(_duffing(scale=EPS))


def test_frequency_comes_back_in_mu(large):
    omega = large.frequency_series()
    assert omega.free_symbols == {A, mu}
    assert sp.expand(omega - NAYFEH_OMEGA.subs(u, 1 / mu)) == 0
    assert sp.expand(large.frequency_series(simplify=True) - omega) == 0


def test_period_comes_back_in_mu(large):
    period = sp.series(2 * sp.pi / NAYFEH_OMEGA, u, 0, 3).removeO()
    assert large.period_series().free_symbols == {A, mu}
    assert sp.expand(large.period_series() - period.subs(u, 1 / mu)) == 0


def test_small_regime_frequency_series_is_the_engine_series(small):
    assert small.frequency_series() == small.frequency_expr
    assert sp.expand(small.frequency_series() - NAYFEH_OMEGA.subs(u, EPS)) == 0


def test_printout_is_in_mu_and_states_epsilon_is_one_over_mu(large, small):
    text = str(large)
    omega_line = next(line for line in text.splitlines() if "Omega =" in line)
    assert "mu" in omega_line and "epsilon" not in omega_line
    assert "epsilon = 1/mu" in text
    assert "1/mu" not in str(small)


def test_latex_is_in_mu_and_states_epsilon_is_one_over_mu(large, small):
    latex = large.latex()
    lines = latex.split(" \\\\\n")
    assert all("varepsilon" not in line for line in lines[:-1])  # x and T: in mu only
    assert "\\mu" in lines[0] and "T =" in lines[1]
    assert lines[-1].startswith("\\Omega = ") and lines[-1].endswith(
        f"{sp.latex(EPS)} = \\frac{{1}}{{\\mu}}"
    )
    assert "\\Omega" not in small.latex()  # the small-parameter LaTeX is unchanged
