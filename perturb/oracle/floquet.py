"""How many Floquet multipliers of a periodic orbit must equal 1, from what the problem supplies.

For :math:`\\dot y = f(y)` with a :math:`T`-periodic orbit through :math:`y_0`, the monodromy
:math:`M = \\Phi(T)` has these eigenvectors and generalised eigenvectors at 1:

- autonomy: :math:`M f(y_0) = f(y_0)` (differentiate :math:`\\varphi_T(\\varphi_s(y_0)) =
  \\varphi_s(y_0)` in :math:`s`), always one;
- a first integral :math:`g` (:math:`\\nabla g \\cdot f = 0`): differentiating
  :math:`g(\\varphi_T(y)) = g(y)` gives :math:`\\nabla g(y_0)^{\\mathsf T} M = \\nabla g(y_0)^{\\mathsf T}`,
  a left eigenvector at 1.  With :math:`k` integrals independent at the orbit, the orbits form a
  :math:`k`-parameter family; differentiating :math:`\\varphi_{T(c)}(y_0(c)) = y_0(c)` along it,
  :math:`(M - I)\\,\\partial_c y_0 = -\\partial_c T\\, f(y_0)`: each family direction is a generalised
  eigenvector (a Jordan chain on :math:`f` where the period varies).  Multiplicity :math:`1 + k`.
- a Hamiltonian system with :math:`k` independent integrals in involution :math:`F_1 = H, \\dots,
  F_k`: each :math:`F_i` generates a flow commuting with the motion, so :math:`X_{F_i}(y_0)` is an
  eigenvector at 1 (for :math:`H` it is :math:`f` itself), and :math:`F_i` also moves the orbit
  along its family (the transverse, generalised eigenvector).  Multiplicity :math:`2k`; the
  multipliers come in pairs :math:`\\lambda, 1/\\lambda` (symplectic monodromy), so the count is
  even.  The energy is always one of them: a Hamiltonian orbit has at least 2.

These are lower bounds for a non-degenerate orbit (the other multipliers away from 1).
"""

from __future__ import annotations

import numpy as np

from perturb._defaults import TRIVIAL_MULTIPLIER_TOL
from perturb.errors import bad_value

__all__ = ["count_near_one", "expected_trivial_multipliers"]


def expected_trivial_multipliers(n_integrals: int, hamiltonian: bool = False) -> int:
    """Number of Floquet multipliers equal to 1 implied by the autonomy and the first integrals.

    Parameters
    ----------
    n_integrals : int
        Number of first integrals independent at the orbit.  For a Hamiltonian system these must
        be in involution, and the energy counts (it is implied when ``n_integrals`` is 0).
    hamiltonian : bool, optional
        Whether the system is Hamiltonian (canonical coordinates, symplectic flow).

    Returns
    -------
    int
        ``1 + n_integrals`` for a general system (autonomy + one per integral);
        ``2 * max(n_integrals, 1)`` for a Hamiltonian one (a symmetry direction and a family
        direction per integral in involution, the energy included).  See the module docstring.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``n_integrals`` is not a non-negative integer.

    Examples
    --------
    >>> expected_trivial_multipliers(0)  # van der Pol: autonomy only
    1
    >>> expected_trivial_multipliers(1, hamiltonian=True)  # Henon-Heiles: energy only
    2
    >>> expected_trivial_multipliers(2)  # Euler's free rigid body: energy and |L|**2
    3
    """
    if isinstance(n_integrals, bool) or not isinstance(n_integrals, int | np.integer):
        raise bad_value("n_integrals", n_integrals, "pass the number of first integrals (int >= 0)")
    if n_integrals < 0:
        raise bad_value("n_integrals", n_integrals, "pass the number of first integrals (int >= 0)")
    if hamiltonian:
        return 2 * max(int(n_integrals), 1)
    return 1 + int(n_integrals)


def count_near_one(multipliers, tol: float = TRIVIAL_MULTIPLIER_TOL) -> int:
    """Number of multipliers within ``tol`` of 1 (NaN multipliers count as not near)."""
    distances = np.abs(np.asarray(multipliers, dtype=complex) - 1.0)
    return int(np.sum(distances <= tol))
