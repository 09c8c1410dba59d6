"""Floquet multipliers of the order-N response: the variational equation along the series.

The stability of a periodic response y*(t) is that of δẏ = A(t) δy, A = ∂F/∂y the Jacobian of the
equations of motion along the orbit, over one period T: the eigenvalues of its monodromy Φ(T)
(Floquet). Here A is evaluated along the order-N series itself (the analytic orbit, every order of
it), so the multipliers are those of an orbit within O(ε^(N+1)) of the true one and converge
with N to the true multipliers. The slow flow's Jacobian of the order-N amplitude equations does
not: the amplitude equations of order N hold their roots to O(ε^(N+1)), not the linearised
dynamics around them (their trace wanders along a branch while the true one is fixed by the
damping).

The monodromy is integrated by the sixth-order Magnus method of Blanes, Casas & Ros (BIT 40, 2000)
on S equal steps of the strained time s, with B = A/ν at three Gauss-Legendre nodes a step:
α₁ = hB₂, α₂ = (√15h/3)(B₃ − B₁), α₃ = (10h/3)(B₃ − 2B₂ + B₁), C₁ = [α₁, α₂],
C₂ = −[α₁, 2α₃ + C₁]/60, Ω_k = α₁ + α₃/12 + [−20α₁ − α₃ + C₁, α₂ + C₂]/240, Φ ← exp(Ω_k) Φ.
Commutators have no trace, so det exp(Ω_k) = exp(tr α₁ + tr α₃/12) = exp of the three-node Gauss
quadrature of tr B over the step: the product of the multipliers is exp of the Gauss quadrature
of ∮ div F dt, **exactly** (Liouville's formula holds by construction, to rounding) —
exp(−2εζT) for linear damping, whatever S. Every point of a response is done at once, as arrays;
2 x 2 exponentials in closed form.
"""

from __future__ import annotations

import math

import numpy as np
from attrs import field, frozen

from perturb._defaults import MAGNUS_STEPS, MARGINAL_MULTIPLIER

__all__ = ["Stability", "stability_along"]

_GAUSS = (0.5 - math.sqrt(15) / 10, 0.5, 0.5 + math.sqrt(15) / 10)


@frozen
class Stability:
    """Floquet multipliers of responses, one row per point.

    Attributes
    ----------
    multipliers : ndarray of complex, shape (P, 2n)
        Sorted by decreasing modulus.
    liouville : ndarray, shape (P,)
        exp(∮ div F dt) along each orbit over its period: the product of its multipliers.
    stable : tuple of (bool or None)
        Every multiplier inside the unit circle (True), one outside (False), or the largest
        within ``MARGINAL_MULTIPLIER`` of it (None: on a fold, or undamped).
    """

    multipliers: np.ndarray = field(eq=False)
    liouville: np.ndarray = field(eq=False)
    stable: tuple = field(converter=tuple)


def _expm(m: np.ndarray) -> np.ndarray:
    """exp of a stack of small matrices: 2 x 2 in closed form, else scaling, Taylor to degree 12
    and squaring (error ~1e-17 relative once the scaled norm is below 1/2)."""
    if m.shape[-1] == 2:
        return _expm2(m)
    norm = float(np.max(np.sum(np.abs(m), axis=-1), initial=0.0))
    squarings = max(0, math.ceil(math.log2(max(norm, 1e-300) / 0.5)))
    a = m / 2.0**squarings
    out = np.eye(m.shape[-1]) + a
    term = a
    for k in range(2, 13):
        term = term @ a / k
        out = out + term
    for _ in range(squarings):
        out = out @ out
    return out


def _expm2(m: np.ndarray) -> np.ndarray:
    """exp of 2 x 2 matrices: e^τ [c I + s (M − τI)], τ = tr/2, q = τ² − det, c = cosh √q and
    s = sinh √q / √q (cos and sin of √−q for q < 0; their series near q = 0)."""
    a, b, c_, d = m[..., 0, 0], m[..., 0, 1], m[..., 1, 0], m[..., 1, 1]
    tau = 0.5 * (a + d)
    q = 0.25 * (a - d) ** 2 + b * c_
    root = np.sqrt(np.abs(q))
    small = np.abs(q) < 1e-6
    with np.errstate(invalid="ignore", divide="ignore"):
        ch = np.where(q >= 0, np.cosh(root), np.cos(root))
        sh = np.where(q >= 0, np.sinh(root), np.sin(root)) / root
    series = 1 + q / 6 + q * q / 120 + q**3 / 5040  # sinh(r)/r in q = ±r², to q⁴ ~ 1e-24
    sh = np.where(small, series, sh)
    ch = np.where(small, 1 + q / 2 + q * q / 24 + q**3 / 720 + q**4 / 40320, ch)
    scale = np.exp(tau)
    out = np.empty_like(m)
    out[..., 0, 0] = scale * (ch + sh * (a - tau))
    out[..., 0, 1] = scale * sh * b
    out[..., 1, 0] = scale * sh * c_
    out[..., 1, 1] = scale * (ch + sh * (d - tau))
    return out


def _product(steps: np.ndarray) -> np.ndarray:
    """steps[:, S-1] @ ... @ steps[:, 0] for a stack (P, S, d, d), by pairwise products."""
    while steps.shape[1] > 1:
        if steps.shape[1] % 2:
            eye = np.broadcast_to(np.eye(steps.shape[-1]), (steps.shape[0], 1, *steps.shape[2:]))
            steps = np.concatenate((steps, eye), axis=1)
        steps = steps[:, 1::2] @ steps[:, 0::2]
    return steps[:, 0]


def monodromy(motion, series, x: np.ndarray, params: np.ndarray, eps: np.ndarray,
              steps: int = MAGNUS_STEPS) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The monodromy over one period of the response at each compiled point ``x`` (P, k), and
    exp of the quadrature of the divergence: ``(Φ (P, 2n, 2n), liouville (P,))``."""
    nu, cos, sin = series.evaluate(x)  # (P,), (P, n, H+1)
    h = 2 * math.pi / steps
    s = np.concatenate([(np.arange(steps) + c) * h for c in _GAUSS])  # (3S,)
    j = np.arange(cos.shape[-1])
    c_js, s_js = np.cos(np.outer(j, s)), np.sin(np.outer(j, s))  # (H+1, 3S)
    position = cos @ c_js + sin @ s_js  # (P, n, 3S)
    velocity = nu[:, None, None] * ((sin * j) @ c_js - (cos * j) @ s_js)
    state = np.concatenate((position, velocity), axis=1).transpose(0, 2, 1)  # (P, 3S, 2n)
    theta = motion.p * np.broadcast_to(s, state.shape[:2])
    pp = np.broadcast_to(params[:, None, :], (*state.shape[:2], params.shape[-1]))
    ee = np.broadcast_to(eps[:, None], state.shape[:2])
    b = motion.jacobian(state, theta, pp, ee) / nu[:, None, None, None]  # (P, 3S, d, d)
    b1, b2, b3 = b[:, :steps], b[:, steps : 2 * steps], b[:, 2 * steps :]
    a1 = h * b2
    a2 = (math.sqrt(15) * h / 3) * (b3 - b1)
    a3 = (10 * h / 3) * (b3 - 2 * b2 + b1)
    c1 = a1 @ a2 - a2 @ a1
    m = 2 * a3 + c1
    c2 = -(a1 @ m - m @ a1) / 60
    left, right = -20 * a1 - a3 + c1, a2 + c2
    omega = a1 + a3 / 12 + (left @ right - right @ left) / 240
    phi = _product(_expm(omega))
    trace = np.trace(omega, axis1=-2, axis2=-1)  # the Gauss quadrature of tr B, step by step
    liouville = np.exp(np.sum(trace, axis=1))
    return phi, liouville


def stability_along(motion, series, x, params, eps, steps: int = MAGNUS_STEPS) -> Stability:
    """:class:`Stability` of the order-N responses at the compiled points ``x`` (P, k).

    ``params`` (P, m) the system's parameter values and ``eps`` (P,) at each point (``x`` holds
    them too, after the amplitudes: they are passed apart for the equations of motion).
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    if x.shape[0] == 0:
        return Stability(np.zeros((0, 2 * motion.n), complex), np.zeros(0), ())
    phi, liouville = monodromy(motion, series, x, np.atleast_2d(params), np.atleast_1d(eps), steps)
    # a monodromy past the floats (an orbit of 10^9 time units, eps = 10): no multipliers, and
    # no stability claimed either way
    finite = np.all(np.isfinite(phi), axis=(-2, -1))
    values = np.full(phi.shape[:-1], complex(math.nan, math.nan))
    if np.any(finite):
        values[finite] = np.linalg.eigvals(phi[finite])
    order = np.argsort(-np.abs(values), axis=1, kind="stable")
    values = np.take_along_axis(values, order, axis=1)
    largest = np.abs(values[:, 0])
    stable = tuple(
        None if not math.isfinite(m) or abs(m - 1.0) <= MARGINAL_MULTIPLIER else bool(m < 1.0)
        for m in largest
    )
    return Stability(values, liouville, stable)
