"""Test systems of the oracle tests with their exact solutions (closed forms, no integration)."""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.special import ellipj, ellipk

from perturb.oracle import SymbolicRHS

x, v = sp.symbols("x v")

#: Harmonic oscillator x'' + x = 0: x = x0 cos t + v0 sin t.
HARMONIC = SymbolicRHS((x, v), (v, -x))


def harmonic_exact(y0, t):
    """Exact state (2, n_t) of the harmonic oscillator."""
    x0, v0 = y0
    t = np.asarray(t, dtype=float)
    return np.array([x0 * np.cos(t) + v0 * np.sin(t), -x0 * np.sin(t) + v0 * np.cos(t)])


def duffing(alpha=1.0, beta=1.0) -> SymbolicRHS:
    """Hardening Duffing oscillator x'' + alpha x + beta x**3 = 0."""
    return SymbolicRHS((x, v), (v, -alpha * x - beta * x**3))


def duffing_period(amplitude, alpha=1.0, beta=1.0) -> float:
    """Exact period of x'' + alpha x + beta x**3 = 0 with x(0) = A, x'(0) = 0 (beta > 0).

    With omega**2 = alpha + beta A**2 and parameter m = beta A**2 / (2 omega**2), the motion is
    x = A cn(omega t | m) and the period is 4 K(m) / omega.
    """
    omega = np.sqrt(alpha + beta * amplitude**2)
    m = beta * amplitude**2 / (2 * omega**2)
    return 4 * ellipk(m) / omega


def duffing_exact(amplitude, t, alpha=1.0, beta=1.0):
    """Exact state (2, n_t) from x(0) = A, x'(0) = 0: x = A cn(omega t | m)."""
    omega = np.sqrt(alpha + beta * amplitude**2)
    m = beta * amplitude**2 / (2 * omega**2)
    sn, cn, dn, _ = ellipj(omega * np.asarray(t, dtype=float), m)
    return np.array([amplitude * cn, -amplitude * omega * sn * dn])


def van_der_pol(eps: float) -> SymbolicRHS:
    """Van der Pol oscillator x'' - eps (1 - x**2) x' + x = 0."""
    return SymbolicRHS((x, v), (v, eps * (1 - x**2) * v - x))
