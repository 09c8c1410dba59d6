"""Is a right-hand side analytic along the generating solution? (The numeric quadrature needs it.)

The numeric quadrature (:func:`perturb.series.evaluate_analytic`) expands a non-polynomial
right-hand side in a Taylor series about the generating solution,
:math:`f(V_0(s) + \\delta) = \\sum_\\alpha \\partial^\\alpha f(V_0(s))\\,\\delta^\\alpha/\\alpha!`, for
every ``s`` on the orbit. That series exists only where ``f`` is analytic: at a branch point
(``sqrt(x)``, ``x**(1/3)``, ``log(x)`` where ``x`` reaches 0), a pole (``1/x``, ``tan(x)`` at
:math:`\\pi/2`) or a kink (``Abs``, ``sign``, ``Heaviside``, ``Max``: dry friction, clipping) the
derivatives are infinite, undefined or carry Dirac masses, and sampling them would silently drop or
corrupt the forcing. :func:`singularity` finds such a point on the sampled orbit and says which.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from perturb._defaults import SINGULARITY_MARGIN
from perturb._lambdify import numpy_lambdify

__all__ = ["singularity"]

#: Functions analytic at every real argument (their singularities, if any, are off the real axis).
REAL_ANALYTIC = (sp.sin, sp.cos, sp.exp, sp.sinh, sp.cosh, sp.tanh, sp.atan, sp.asinh, sp.erf)

#: Functions analytic where a companion expression of their argument stays away from zero.
#: tan/sec have poles where cos vanishes, cot/csc where sin does; log a branch point at 0,
#: asin/acos at +-1 (and are complex beyond): the companion must stay positive or non-zero.
_NONZERO = {sp.tan: sp.cos, sp.sec: sp.cos, sp.cot: sp.sin, sp.csc: sp.sin}
_POSITIVE = {sp.log: lambda a: a, sp.asin: lambda a: 1 - a**2, sp.acos: lambda a: 1 - a**2}


def singularity(expr: sp.Expr, symbols, samples) -> str | None:
    """Why ``expr`` is not analytic along the sampled orbit, or ``None`` when it is.

    Parameters
    ----------
    expr : sympy.Expr
        A right-hand side coefficient, a function of ``symbols`` only.
    symbols : sequence of sympy.Symbol
        The state variables ``expr`` depends on.
    samples : sequence of numpy.ndarray
        Their values along the generating solution (same order), on the quadrature grid.
    """
    checks: list[tuple[sp.Expr, bool, str]] = []  # (companion, must be positive, what it is)
    for node in sp.preorder_traversal(expr):
        if isinstance(node, sp.Pow):
            exponent = node.exp
            if exponent.is_Integer and exponent >= 0:
                continue
            if exponent.is_Integer:
                checks.append((node.base, False, f"a pole of {node} where {node.base} = 0"))
            else:
                checks.append((node.base, True, f"a branch point of {node} at {node.base} = 0"))
        elif node.is_Function:
            func = type(node)
            if func in REAL_ANALYTIC:
                continue
            if func in _NONZERO:
                companion = _NONZERO[func](node.args[0])
                checks.append((companion, False, f"a pole of {node} where {companion} = 0"))
            elif func in _POSITIVE:
                companion = _POSITIVE[func](node.args[0])
                checks.append((companion, True, f"a branch point of {node} at {companion} = 0"))
            else:
                return (
                    f"{node} is not analytic (a kink, a jump or an unknown function), so the "
                    "right-hand side has no Taylor expansion about the generating solution"
                )
    for companion, positive, what in checks:
        values = np.broadcast_to(
            np.asarray(numpy_lambdify(symbols, companion)(*samples), dtype=complex),
            np.shape(samples[0]),
        )
        scale = max(1.0, float(np.max(np.abs(values))))
        if np.any(np.abs(values.imag) > 0):
            return f"{companion} is not real along the generating solution"
        reach = values.real if positive else np.abs(values.real)
        if float(np.min(reach)) <= SINGULARITY_MARGIN * scale:
            return (
                f"the generating solution reaches {what}, where the right-hand side has no "
                "Taylor expansion; choose amplitudes that keep the orbit away from it, or "
                "rewrite the right-hand side"
            )
    return None
