"""Published period-doubling and tongue cases for the true curve, caught once for the tests
(``test_true_curve_published.py``) and the benchmark (``benchmarks/bench_true_curve.py``).

- :class:`TwinWell`: the twin-well Duffing :math:`\\ddot x + k\\dot x - x + x^3 = \\Gamma\\cos\\omega t`
  (k = 0.3, ω = 1.2: the textbook period-doubling sequence of Jordan & Smith, *Nonlinear Ordinary
  Differential Equations*, ch. 13, after Holmes and Guckenheimer & Holmes: a period-1 orbit in one
  well at Γ = 0.20, period 2 at Γ = 0.27, period 4 at 0.28, chaos at 0.50), typed as a perturb
  problem about its right well: y = x − 1 in the time s = √2 t of the well's small oscillations,
  :math:`y'' + y = \\varepsilon(-2\\zeta y' - \\tfrac32 y^2 - \\tfrac12 y^3 + \\tfrac\\Gamma2\\cos\\theta)`,
  ζ = k/(2√2), θ = Ω s, Ω = ω/√2, ε = 1.
- :func:`brute_force_period_doubling`: the same oscillator's period doubling found without any
  shooting: the original equation in x and t integrated by scipy's DOP853 (rtol = atol = 1e-12)
  through thousands of forcing periods, the stroboscopic map sampled after the transients, and the
  period-2 splitting d(Γ) past the doubling fitted by d² = c₁(Γ − Γ_PD) + c₂(Γ − Γ_PD)² (the
  supercritical flip's square-root law).
- :func:`mathieu_edges`: the first instability tongue of :math:`\\ddot x + (1 + 2h\\varepsilon
  \\cos\\Omega t)x = 0` (the parametric-duffing problem undamped and linear) from scipy's Mathieu
  characteristic values and from a Hill determinant.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

Y, YDOT, THETA = sp.symbols("y ydot theta")
ZETA, GAMMA, SIGMA = sp.symbols("zeta Gamma sigma")

#: The textbook case: damping k and forcing frequency ω of the twin-well Duffing.
DAMPING, FREQUENCY = 0.3, 1.2
#: The published sequence: a period-1 orbit at this Γ, period 2 at the next.
PUBLISHED_PERIOD_ONE, PUBLISHED_PERIOD_TWO = 0.20, 0.27


class TwinWell(DrivenProblem):
    """ẍ + k ẋ − x + x³ = Γ cos ωt about its right well (module notes); ``Gamma`` is Γ, ``Omega``
    is ω/√2 (the time of the well's small oscillations)."""

    name = "twin-well-duffing"
    summary = "twin-well Duffing about its right well, in the time of its small oscillations"
    parameter_specs = (
        ParameterSpec("eps", 1.0, "scale of the small terms", positive),
        ParameterSpec("zeta", DAMPING / (2 * math.sqrt(2)), "scaled damping", non_negative),
        ParameterSpec("Gamma", 0.1, "forcing amplitude", positive),
        ParameterSpec("Omega", FREQUENCY / math.sqrt(2), "forcing frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        force = -2 * ZETA * YDOT - sp.Rational(3, 2) * Y**2 - Y**3 / 2 + GAMMA / 2 * sp.cos(THETA)
        return QuasilinearSystem(
            coordinates=[Y],
            velocities=[YDOT],
            frequencies=[1],
            rhs=[EPS * force],
            parameters=[ZETA, GAMMA, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
            name="twin-well-duffing",
        )


def _strobe(gamma: float, start, periods: int, keep: int):
    """The stroboscopic map's last ``keep`` points after ``periods`` forcing periods."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        return [y[1], -DAMPING * y[1] + y[0] - y[0] ** 3 + gamma * math.cos(FREQUENCY * t)]

    period = 2 * math.pi / FREQUENCY
    times = period * np.arange(periods - keep + 1, periods + 1)
    sol = solve_ivp(
        rhs, (0.0, periods * period), start, method="DOP853", rtol=1e-12, atol=1e-12,
        t_eval=times,
    )  # fmt: skip
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol.y.T


def brute_force_period_doubling(gammas, periods: int = 3000) -> dict:
    """The period doubling of the twin-well orbit by the stroboscopic map alone (module notes).

    Parameters
    ----------
    gammas : sequence of float
        Increasing forcing amplitudes just past the doubling (period 2 settled at each).
    periods : int
        Forcing periods integrated at each (the transients decay like the period-2 orbit's
        multiplier, slowly near the doubling).

    Returns
    -------
    dict
        ``gamma_pd`` (the fit's root), ``splits`` (d at each Γ), ``settled`` (the largest change of
        the two points over the last 200 periods, relative to d) and ``residual`` of the fit.
    """
    state = np.array([1.0, 0.0])
    splits, settled = [], []
    for gamma in gammas:
        points = _strobe(float(gamma), state, periods, 201)
        state = points[-1]
        d = float(np.linalg.norm(points[-1] - points[-2]))
        drift = float(np.linalg.norm(points[-1] - points[0]))  # 200 periods: the same phase
        splits.append(d)
        settled.append(drift / d if d > 0 else math.inf)
    g = np.asarray(gammas, dtype=float)
    d2 = np.asarray(splits) ** 2
    coeffs = np.polyfit(g, d2, 2)
    roots = [r.real for r in np.roots(coeffs) if abs(r.imag) < 1e-12 and r.real < g[0]]
    root = max(roots) if roots else math.nan
    residual = float(np.max(np.abs(np.polyval(coeffs, g) - d2)))
    return {"gamma_pd": root, "splits": splits, "settled": settled, "residual": residual}


def mathieu_edges(h_eps: float) -> list[float]:
    """The Ω of the first tongue's edges of ẍ + (1 + 2hε cos Ωt) x = 0 from scipy's a₁ and b₁.

    With τ = Ωt/2 it is Mathieu's x'' + (a − 2q cos 2τ) x = 0, a = 4/Ω², |q| = 4hε/Ω²; the edges
    are a = a₁(|q|) and a = b₁(|q|) (the sign of q swaps the two).
    """
    from scipy.optimize import brentq
    from scipy.special import mathieu_a, mathieu_b

    return sorted(
        brentq(lambda w, f=f: 4 / w**2 - f(1, 4 * h_eps / w**2), 1.0, 3.0, xtol=1e-15)
        for f in (mathieu_a, mathieu_b)
    )


def hill_edges(h_eps: float, harmonics: int = 40) -> list[float]:
    """The same edges from the Hill determinant: the 2π-periodic solutions Σ A_k cos((2k+1)τ)
    (or sin) with (a − (2k+1)²) A_k = q (A_{k−1} + A_{k+1}) and the reflected first term; 40
    harmonics converge to machine precision for |q| <= 1."""
    from scipy.optimize import brentq

    def lowest(q, sign):
        m = np.diag([(2.0 * k + 1) ** 2 for k in range(harmonics)])
        m += np.diag([q] * (harmonics - 1), 1) + np.diag([q] * (harmonics - 1), -1)
        m[0, 0] += sign * q
        return np.linalg.eigvalsh(m)[0]

    return sorted(
        brentq(lambda w, s=s: 4 / w**2 - lowest(4 * h_eps / w**2, s), 1.0, 3.0, xtol=1e-15)
        for s in (1, -1)
    )


X, XDOT = sp.symbols("x xdot")
MU, FORCE = sp.symbols("mu F")


class ForcedVanDerPol(DrivenProblem):
    """ẍ + x = ε(μ(1 − x²)ẋ + F cos Ωt): the entrainment of a self-excited oscillator. At strong
    forcing the locked response loses its stability through a Neimark–Sacker bifurcation (a
    complex pair of multipliers leaves the circle: the motion becomes quasi-periodic), where the
    first-order slow flow has its Hopf point at the amplitude √2 (Guckenheimer & Holmes, §2.1)."""

    name = "forced-van-der-pol"
    summary = "forced van der Pol oscillator near 1:1 entrainment"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms", positive),
        ParameterSpec("mu", 1.0, "negative damping at rest", positive),
        ParameterSpec("F", 2.0, "scaled forcing", positive),
        ParameterSpec("Omega", 1.0, "forcing frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[EPS * (MU * (1 - X**2) * XDOT + FORCE * sp.cos(THETA))],
            parameters=[MU, FORCE, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
            name="forced-van-der-pol",
        )


def neimark_sacker_by_forced_shooting(problem, low: float, high: float, guess) -> float:
    """The Ω in [low, high] where the largest |Floquet multiplier| of the forced van der Pol's
    response crosses 1, by the oracle's forced shooting in physical time (its own Newton and
    variational equations, scipy's DOP853) at each Ω and Brent's method on max|μ| − 1."""
    from scipy.optimize import brentq

    from perturb.oracle import SymbolicRHS, find_forced_orbit

    eps, mu, force = (problem.values[k] for k in ("eps", "mu", "F"))
    state = {"y": np.asarray(guess, dtype=float)}

    def excess(omega):
        f = -X + eps * (mu * (1 - X**2) * XDOT + force * sp.cos(THETA))
        rhs = SymbolicRHS((X, XDOT, THETA), (XDOT, f, omega))
        orbit = find_forced_orbit(rhs, state["y"], 2 * math.pi / omega, integrator="dop853")
        if not orbit.success:
            raise RuntimeError(orbit.message)
        state["y"] = np.asarray(orbit.initial_state)
        return float(np.max(np.abs(orbit.floquet_multipliers))) - 1.0

    return brentq(excess, low, high, xtol=1e-12)
