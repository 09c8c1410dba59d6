"""Test functions of a periodic orbit's period map: where a Floquet multiplier crosses the circle.

Along a curve of periodic orbits with monodromy :math:`M` (m × m), each function below is a
polynomial in the entries of M (smooth along the curve, even where two multipliers collide) that
vanishes exactly when a multiplier meets the unit circle in one way (Kuznetsov, *Elements of
Applied Bifurcation Theory*, §10.2; Govaerts, *Numerical Methods for Bifurcations of Dynamical
Equilibria*):

- :func:`fold_test` :math:`\\det(M - I) = \\prod(\\mu_i - 1)`: a real multiplier at +1 (a fold,
  or a branch point: the continuation's tangent and bordered determinant tell them apart);
- :func:`period_doubling_test` :math:`\\det(M + I) = \\prod(\\mu_i + 1)`: a real multiplier at −1;
- :func:`neimark_sacker_test` :math:`\\prod_{i<j}(\\mu_i\\mu_j - 1)`, the determinant of the
  bialternate product :math:`M \\odot M - I`: a pair with :math:`\\mu_i\\mu_j = 1`, a complex pair on
  the circle (Neimark–Sacker) or a real pair :math:`\\mu, 1/\\mu` (a neutral saddle, no
  bifurcation: :func:`is_neimark_sacker` tells them apart at the located point).

A conservative (symplectic) map has :math:`\\mu_i\\mu_j = 1` for every pair: the Neimark–Sacker
test is zero all along and carries no information; its sign changes there are round-off.
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np

__all__ = [
    "critical_multiplier",
    "fold_test",
    "is_neimark_sacker",
    "neimark_sacker_test",
    "period_doubling_test",
]


def fold_test(monodromy) -> float:
    """:math:`\\det(M - I)`: zero where a multiplier is +1 (a fold or a branch point).

    Parameters
    ----------
    monodromy : array_like, shape (m, m)

    Returns
    -------
    float

    Examples
    --------
    >>> fold_test([[1.0, 0.3], [0.0, 0.5]])
    0.0
    """
    m = np.asarray(monodromy, dtype=float)
    return float(np.linalg.det(m - np.eye(m.shape[0])))


def period_doubling_test(monodromy) -> float:
    """:math:`\\det(M + I)`: zero where a multiplier is −1 (a period doubling).

    Parameters
    ----------
    monodromy : array_like, shape (m, m)

    Returns
    -------
    float

    Examples
    --------
    >>> period_doubling_test([[-1.0, 0.3], [0.0, 0.5]])
    0.0
    """
    m = np.asarray(monodromy, dtype=float)
    return float(np.linalg.det(m + np.eye(m.shape[0])))


def neimark_sacker_test(monodromy) -> float:
    """:math:`\\prod_{i<j}(\\mu_i\\mu_j - 1)` over the multipliers (1 for a one-dimensional map):
    zero where two multipliers have the product 1 (a complex pair on the circle, or a neutral
    saddle).

    Parameters
    ----------
    monodromy : array_like, shape (m, m)

    Returns
    -------
    float
        Real (the pairs' products come in conjugate pairs).

    Examples
    --------
    A rotation by 0.3 rad (a complex pair on the circle) and a contraction of it:

    >>> c, s = math.cos(0.3), math.sin(0.3)
    >>> abs(neimark_sacker_test([[c, -s], [s, c]])) < 1e-15
    True
    >>> round(neimark_sacker_test([[0.9 * c, -0.9 * s], [0.9 * s, 0.9 * c]]), 12)
    -0.19
    """
    m = np.asarray(monodromy, dtype=float)
    mu = np.linalg.eigvals(m)
    product = complex(1.0)
    for a, b in combinations(mu, 2):
        product *= a * b - 1.0
    return float(product.real)


def critical_multiplier(monodromy, target: complex) -> complex:
    """The Floquet multiplier nearest ``target`` (+1 at a fold, −1 at a period doubling).

    Parameters
    ----------
    monodromy : array_like, shape (m, m)
    target : complex

    Returns
    -------
    complex

    Examples
    --------
    >>> critical_multiplier([[-0.99, 0.0], [0.0, 0.3]], -1.0)
    (-0.99+0j)
    """
    mu = np.linalg.eigvals(np.asarray(monodromy, dtype=float)).astype(complex)
    return complex(mu[int(np.argmin(np.abs(mu - target)))])


def is_neimark_sacker(monodromy, tolerance: float) -> tuple[bool, complex]:
    """Whether a zero of :func:`neimark_sacker_test` is a complex pair on the unit circle.

    Parameters
    ----------
    monodromy : array_like, shape (m, m)
    tolerance : float
        How close to the circle, and how far from the real axis, the pair must be.

    Returns
    -------
    (bool, complex)
        True with the multiplier of the pair in the upper half plane when a pair
        :math:`\\mu, \\bar\\mu` has :math:`||\\mu| - 1| \\le` ``tolerance`` and
        :math:`|\\operatorname{Im}\\mu| >` ``tolerance``; False with the pair's product nearest 1
        otherwise (a neutral saddle, or no such pair).

    Examples
    --------
    >>> c, s = math.cos(0.3), math.sin(0.3)
    >>> is_neimark_sacker([[c, -s], [s, c]], 1e-9)[0]
    True
    >>> is_neimark_sacker([[2.0, 0.0], [0.0, 0.5]], 1e-9)[0]  # a neutral saddle
    False
    """
    mu = np.linalg.eigvals(np.asarray(monodromy, dtype=float)).astype(complex)
    upper = [z for z in mu if z.imag > tolerance]
    if upper:
        best = min(upper, key=lambda z: abs(abs(z) - 1.0))
        if abs(abs(best) - 1.0) <= tolerance:
            return True, complex(best)
    pairs = list(combinations(mu, 2))
    if not pairs:
        return False, complex(math.nan, math.nan)
    a, b = min(pairs, key=lambda ab: abs(ab[0] * ab[1] - 1.0))
    return False, complex(a * b)
