"""Euler angles of a rigid body from its angular velocity and the vertical, derived with sympy.

Convention (classical z-x-z): the rotation taking body axes to space axes is

.. math:: R = R_Z(\\psi)\\,R_X(\\theta)\\,R_Z(\\varphi),

with :math:`\\psi` the precession about the space vertical :math:`Z`, :math:`\\theta` the nutation
(angle between :math:`Z` and the body :math:`z` axis) and :math:`\\varphi` the proper rotation.
The body components of :math:`Z` are the third row of :math:`R`; the body components of the angular
velocity come from :math:`R^{\\mathsf T}\\dot R = [\\omega]_\\times`. Everything below is obtained from
these two relations by sympy (nothing is typed by hand):

* :math:`\\gamma = (\\sin\\theta\\sin\\varphi, \\sin\\theta\\cos\\varphi, \\cos\\theta)`, hence
  :math:`\\theta = \\arccos\\gamma''` and :math:`\\varphi = \\operatorname{atan2}(\\gamma, \\gamma')`;
* the kinematic equations solved for the angle rates, in particular
  :math:`\\dot\\psi = (p\\sin\\varphi + q\\cos\\varphi)/\\sin\\theta`, which on the vertical reads
  :math:`\\dot\\psi = (p\\gamma + q\\gamma')/(\\gamma^2 + \\gamma'^2)`;
* :math:`\\psi` by quadrature of :math:`\\dot\\psi` (spectrally, over one period of a periodic motion).

References
----------
.. [1] The seed paper, equations (28)–(29) (not checked by the reference derivation).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import numpy as np
import sympy as sp
from attrs import frozen

from perturb._lambdify import numpy_lambdify
from perturb.errors import InvalidParameterError

__all__ = [
    "EulerKinematics",
    "angles_from_state",
    "euler_kinematics",
    "precession_by_quadrature",
]

psi, theta, phi = sp.symbols("psi theta phi", real=True)
psi_dot, theta_dot, phi_dot = sp.symbols("psi_dot theta_dot phi_dot", real=True)
_p, _q, _r = sp.symbols("p q r", real=True)
_g1, _g2, _g3 = sp.symbols("gamma1 gamma2 gamma3", real=True)

#: Samples per period for the spectral quadrature of the precession rate (a power of two).
QUADRATURE_POINTS = 512
#: sin(theta) below this makes psi and phi ill-defined (the body z axis is along the vertical).
GIMBAL_TOL = 1e-8


def _rotation(axis: int, angle: sp.Expr) -> sp.Matrix:
    c, s = sp.cos(angle), sp.sin(angle)
    if axis == 2:
        return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


@frozen
class EulerKinematics:
    """The derived relations (sympy expressions).

    Attributes
    ----------
    vertical : tuple of sympy.Expr
        Body components of the space vertical in terms of (theta, phi).
    rates : dict
        ``{psi_dot, theta_dot, phi_dot}`` in terms of (p, q, r, theta, phi).
    precession_rate : sympy.Expr
        psi_dot in terms of (p, q, gamma1, gamma2) only.
    """

    vertical: tuple
    rates: dict
    precession_rate: sp.Expr


def _canonical(expr: sp.Expr) -> sp.Expr:
    """Expanded polynomial in sines and cosines with every cos**2 replaced by 1 - sin**2."""

    def reduce_power(power: sp.Pow) -> sp.Expr:
        half, odd = divmod(int(power.exp), 2)
        base = power.base
        return base**odd * (1 - sp.sin(base.args[0]) ** 2) ** half

    expr = sp.expand(expr)
    expr = expr.replace(
        lambda e: e.is_Pow and isinstance(e.base, sp.cos) and e.exp.is_Integer and e.exp > 1,
        reduce_power,
    )
    return sp.expand(expr)


def _canonical_ratio(expr: sp.Expr) -> sp.Expr:
    num, den = sp.fraction(sp.together(expr))
    return sp.cancel(_canonical(num) / _canonical(den))


@cache
def euler_kinematics() -> EulerKinematics:
    """Derive the vertical and the angle rates from :math:`R = R_Z(\\psi)R_X(\\theta)R_Z(\\varphi)`."""
    angles, rates = (psi, theta, phi), (psi_dot, theta_dot, phi_dot)
    rot = _rotation(2, psi) * _rotation(0, theta) * _rotation(2, phi)
    rot_dot = sum(
        (rot.diff(x) * x_dot for x, x_dot in zip(angles, rates, strict=True)), sp.zeros(3)
    )
    skew = (rot.T * rot_dot).applyfunc(_canonical)
    if any(skew[i, j] + skew[j, i] != 0 for i in range(3) for j in range(3)):
        raise AssertionError(f"R^T dR/dt is not skew-symmetric: {skew}")
    omega_body = (skew[2, 1], skew[0, 2], skew[1, 0])
    vertical = tuple(_canonical(e) for e in rot[2, :])
    solved = sp.solve(
        [w - v for w, v in zip(omega_body, (_p, _q, _r), strict=True)], list(rates), dict=True
    )[0]
    rates_solved = {key: _canonical_ratio(val) for key, val in solved.items()}
    # psi_dot on the vertical: sin(phi) = gamma/sin(theta), cos(phi) = gamma'/sin(theta) and
    # sin(theta)**2 = gamma**2 + gamma'**2 (read off ``vertical``).
    s_theta = sp.Symbol("s_theta", positive=True)
    on_vertical = rates_solved[psi_dot].subs(sp.sin(theta), s_theta)
    on_vertical = on_vertical.subs({sp.sin(phi): _g1 / s_theta, sp.cos(phi): _g2 / s_theta})
    precession_rate = sp.cancel(sp.cancel(on_vertical).subs(s_theta**2, _g1**2 + _g2**2))
    if precession_rate.has(s_theta):
        raise AssertionError(f"precession rate not reduced to the vertical: {precession_rate}")
    check = _canonical_ratio(
        precession_rate.subs({_g1: vertical[0], _g2: vertical[1]}) - rates_solved[psi_dot]
    )
    if check != 0:
        raise AssertionError(
            f"precession rate on the vertical disagrees with the kinematics: {check}"
        )
    return EulerKinematics(vertical=vertical, rates=rates_solved, precession_rate=precession_rate)


@cache
def _precession_rate_function() -> Callable:
    rate = euler_kinematics().precession_rate
    return numpy_lambdify((_p, _q, _g1, _g2), rate)


def angles_from_state(gamma1, gamma2, gamma3) -> tuple[np.ndarray, np.ndarray]:
    """theta and phi from the vertical, inverting ``euler_kinematics().vertical``.

    Returns
    -------
    theta, phi : numpy.ndarray
        :math:`\\theta = \\arccos\\gamma''` in [0, pi], :math:`\\varphi = \\operatorname{atan2}(\\gamma, \\gamma')`.
    """
    vertical = euler_kinematics().vertical
    # the vertical is (sin th sin ph, sin th cos ph, cos th): check the form the inversion relies on
    expected = (sp.sin(theta) * sp.sin(phi), sp.sin(theta) * sp.cos(phi), sp.cos(theta))
    if any(_canonical(v - e) != 0 for v, e in zip(vertical, expected, strict=True)):
        raise AssertionError(f"unexpected vertical {vertical}")
    gamma3 = np.clip(np.asarray(gamma3, dtype=float), -1.0, 1.0)
    return np.arccos(gamma3), np.arctan2(gamma1, gamma2)


def precession_by_quadrature(
    state_at: Callable[[np.ndarray], dict], t, period: float
) -> np.ndarray:
    """:math:`\\psi(t) = \\int_0^t \\dot\\psi\\,dt'` for a motion of period ``period``.

    :math:`\\dot\\psi` is sampled at ``QUADRATURE_POINTS`` points of one period and integrated term by
    term in its Fourier series (exact for a band-limited rate, spectrally accurate otherwise):
    :math:`\\psi = \\bar\\nu t + \\sum_{j\\ne0} c_j (e^{ij\\Omega t} - 1)/(ij\\Omega)`, :math:`\\psi(0) = 0`.

    Parameters
    ----------
    state_at : callable
        ``state_at(times)`` returning a mapping with ``p, q, gamma1, gamma2``.
    t : array_like
        Times at which psi is wanted.
    period : float
        The period of the motion.
    """
    n = QUADRATURE_POINTS
    grid = np.arange(n) * (period / n)
    s = state_at(grid)
    sin_sq = np.asarray(s["gamma1"]) ** 2 + np.asarray(s["gamma2"]) ** 2
    if np.min(sin_sq) < GIMBAL_TOL**2:
        raise InvalidParameterError(
            f"`gamma3` reaches {np.max(np.abs(s['gamma3'])):.12g}: the body z axis passes through "
            "the vertical, where psi is undefined; choose |gamma3_0| < 1 away from 1"
        )
    rate = _precession_rate_function()(s["p"], s["q"], s["gamma1"], s["gamma2"])
    coeffs = np.fft.rfft(rate) / n
    omega = 2 * np.pi / period
    t = np.asarray(t, dtype=float)
    psi_t = coeffs[0].real * t
    for j in range(1, len(coeffs)):
        weight = 1.0 if (n % 2 == 0 and j == n // 2) else 2.0
        c = weight * coeffs[j]
        psi_t = psi_t + (c * (np.exp(1j * j * omega * t) - 1) / (1j * j * omega)).real
    return psi_t
