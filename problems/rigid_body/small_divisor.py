"""Where the classical fast-spin solution carries the small divisor :math:`1/(1-\\omega^2)`.

With :math:`a = A/C`, :math:`b = B/C` and :math:`\\delta = a + b - 1 = ab(1-\\omega^2)` (zero for the
disk), the first-order term of :math:`P = p_1` of :class:`~problems.rigid_body.fast_spin.FastSpinRigidBody`
is written as a Laurent series in :math:`\\delta`. The analysis below is done on the engine's symbolic
solution, not on typed formulas.

Findings (checked by ``tests/rigid_body/test_fast_spin.py``):

* the only pole at first order is in the :math:`\\cos\\tau` coefficient of :math:`P_1`, with residue
  :math:`-z_0' M_3 (2b - 1)`, i.e. :math:`-z_0'M_3(2B-C)/(C\\,ab(1-\\omega^2))`: finite only for
  :math:`z_0 = 0` or :math:`A = B`;
* its :math:`k`-term is :math:`k A_1 \\gamma_0'' M_3 (1+B_1)/(1-\\omega^2) = k(1-b)\\gamma_0''M_3`:
  the factor :math:`(1+B_1)/(1-\\omega^2) = a` stays finite, and tends to :math:`k a\\gamma_0''M_3` on the
  disk — the origin of the paper's shift :math:`\\gamma_2 = \\gamma - \\varepsilon a\\gamma_0''p_2`;
* the constant term :math:`x_0'\\gamma_0''/(1-a)` tends to :math:`x_0'\\gamma_0''/b`, the shift
  :math:`p_2 = p_1 - \\varepsilon x_0'\\gamma_0''/b`.

The disk's resonant solution has no :math:`\\delta` at all: its amplitudes
:math:`\\beta = \\varepsilon v/(kM_3^2)` are fixed by the :math:`O(\\varepsilon^2)` detuning
:math:`D = \\tfrac12 kM_3^2` instead.
"""

from __future__ import annotations

import sympy as sp
from attrs import frozen

from problems.rigid_body.equations import a, b, z0p

__all__ = ["DELTA", "FirstOrderLaurent", "first_order_laurent"]

#: delta = a + b - 1 = a b (1 - omega**2): the distance from the disk.
DELTA = sp.Symbol("delta")


@frozen
class FirstOrderLaurent:
    """The first-order term of P near the disk, harmonic by harmonic.

    Attributes
    ----------
    residues : dict
        ``{harmonic j: coefficient of 1/delta}`` of the cos coefficient (sin coefficients are zero).
    regular : dict
        ``{harmonic j: value at delta = 0 of the cos coefficient minus its pole}``.
    regular_z0_zero : dict
        The same with z0' = 0 (then there is no pole).
    """

    residues: dict
    regular: dict
    regular_z0_zero: dict


def first_order_laurent(solution) -> FirstOrderLaurent:
    """Laurent expansion in :math:`\\delta` of the first-order term of P of a rigid-body solution."""
    index = solution.coordinates.index("P")
    term = solution.terms[index][1]
    residues, regular, regular_z0 = {}, {}, {}
    for j, (cos_c, sin_c) in sorted(term.terms.items()):
        if sp.simplify(sin_c) != 0:
            raise AssertionError(f"unexpected sin coefficient at harmonic {j}: {sin_c}")
        in_delta = sp.factor(sp.cancel(cos_c.subs(a, 1 - b + DELTA)))
        residue = sp.factor(sp.limit(in_delta * DELTA, DELTA, 0))
        residues[j] = residue
        regular[j] = sp.factor(sp.limit(sp.cancel(in_delta - residue / DELTA), DELTA, 0))
        regular_z0[j] = sp.factor(sp.limit(in_delta.subs(z0p, 0), DELTA, 0))
    return FirstOrderLaurent(residues=residues, regular=regular, regular_z0_zero=regular_z0)
