"""The classical fast-spin heavy body in gravity and a Newtonian field: ``perturb solve rigid-body``.

General principal moments :math:`A, B, C` and centre of mass :math:`(x_0, y_0, z_0)`; the body spins
fast about :math:`z` (:math:`\\varepsilon = c/r_0 \\ll 1`). The reduction
(:func:`problems.rigid_body.reduction.general_body_reduction`) gives, with :math:`P = p_1`,
:math:`G = \\gamma`,

.. math::

    \\ddot P + \\omega^2 P = \\varepsilon F_1 + \\varepsilon^2 F_2 + \\dots, \\qquad
    \\ddot G + G = \\varepsilon \\Phi_1 + \\dots, \\qquad \\omega^2 = \\frac{(C-A)(C-B)}{AB}.

For :math:`\\omega` not an integer the :math:`P`-oscillation is non-resonant: its generating amplitude
vanishes and :math:`P` is the forced response, whose harmonic :math:`j` carries
:math:`1/(\\omega^2 - j^2)`. At :math:`\\omega = 1` (:math:`C = A + B`, the disk) the first-order
response has the small divisor :math:`1/(1-\\omega^2)` in its :math:`z_0` term; that case is the
problem ``disk``.
"""

from __future__ import annotations

import math

from perturb._defaults import NEAR_RESONANCE
from perturb.errors import InvalidParameterError
from problems import register
from problems.rigid_body._body import (
    ARM,
    BODY_PARAMETER_MAP,
    EPSILON_WARN,
    FastSpinBody,
    body_parameter_specs,
)
from problems.rigid_body.reduction import (
    GENERAL_PARAMETERS,
    Reduction,
    general_body_reduction,
    specialised_general_body_reduction,
)

__all__ = ["FastSpinRigidBody", "MAX_BODY_ORDER", "RESONANCE_TOL"]

#: |omega - 1| (or omega) below this is rejected: the forced response's divisor 1 - omega**2 (or
#: omega**2) would be smaller than ~2 * RESONANCE_TOL. (The triangle inequality gives omega <= 1, so
#: no other integer resonance j**2 - omega**2 = 0 can occur.)
RESONANCE_TOL = NEAR_RESONANCE
#: Highest solution order offered (order n uses the reduction of order n + 1).
MAX_BODY_ORDER = 2
#: The reduction order exceeds the solution order by one: the frequency correction of order n + 1
#: needs the forcing of that order.
_REDUCTION_EXTRA = 1
#: Default initial spin: with the default body, eps = c/r0 = 0.01.
_DEFAULT_R0 = 0.33772


def frequency_squared(A: float, B: float, C: float) -> float:
    """:math:`\\omega^2 = (C-A)(C-B)/(AB)`, the squared nutation frequency in units of the spin."""
    return (C - A) * (C - B) / (A * B)


@register
class FastSpinRigidBody(FastSpinBody):
    """A heavy body spinning fast about its z axis (Arkhangel'skii's fast-spin periodic motions).

    Defaults: A = 9, B = 11, C = 16 (omega = 0.595), centre of mass (1, 6, 0.5), gamma3_0 = 0.25
    and r0 giving eps = c/r0 = 0.01, in the paper's field (M = 200, g = 1.5e-7, R = 2000).

    Examples
    --------
    >>> from problems import get_problem
    >>> body = get_problem("rigid-body").create()
    >>> round(body.epsilon(), 6)
    0.01
    >>> solution = body.solve(1)
    >>> solution.success, round(body.period(solution), 4)
    (True, 18.6047)
    """

    name = "rigid-body"
    summary = (
        "heavy body about a fixed point, gravity + Newtonian centre, fast spin eps = c/r0, "
        "non-resonant omega**2 = (C-A)(C-B)/(AB) != 1"
    )
    parameter_specs = body_parameter_specs(
        A=9.0, B=11.0, C=16.0, z0=0.5, gamma3_0=0.25, r0=_DEFAULT_R0
    )
    uses_z0 = True
    parameter_map = {**BODY_PARAMETER_MAP, "z0p": f"z0/{ARM}"}
    parameter_symbols = GENERAL_PARAMETERS

    def check_values(self, values) -> None:
        super().check_values(values)
        A, B, C = values["A"], values["B"], values["C"]
        w2 = frequency_squared(A, B, C)
        if w2 <= 0:
            raise InvalidParameterError(
                f"`C` = {C:g} is invalid: spin about the intermediate (or a repeated) axis has "
                f"omega**2 = (C-A)(C-B)/(AB) = {w2:.3g} <= 0, no oscillation; give C larger or "
                "smaller than both A and B"
            )
        omega = math.sqrt(w2)  # the triangle inequality gives 0 < omega <= 1
        if omega < RESONANCE_TOL:
            raise InvalidParameterError(
                f"`C` = {C:g} is invalid: omega = {omega:.3g} is within {RESONANCE_TOL:g} of 0 (C "
                "nearly equal to A or B), where the constant response carries 1/omega**2; move C away"
            )
        if abs(omega - 1) < RESONANCE_TOL:
            raise InvalidParameterError(
                f"`C` = {C:g} is invalid: omega = {omega:.9g} is within {RESONANCE_TOL:g} of 1, "
                "where the forced response has the small divisor 1/(1 - omega**2); this is the "
                "disk C = A + B: use the problem `disk`"
            )

    @classmethod
    def reduction_for(cls, order: int) -> Reduction:
        return general_body_reduction(cls._reduction_order(order))

    @classmethod
    def specialised_reduction_for(cls, order: int, values: dict) -> Reduction:
        return specialised_general_body_reduction(cls._reduction_order(order), values)

    @classmethod
    def _reduction_order(cls, order: int) -> int:
        if (
            isinstance(order, bool)
            or not isinstance(order, int)
            or not 1 <= order <= MAX_BODY_ORDER
        ):
            raise InvalidParameterError(
                f"`order` = {order!r} is invalid: the fast-spin body is implemented to order "
                f"{MAX_BODY_ORDER}; pass order=1 or 2"
            )
        return order + _REDUCTION_EXTRA

    def _specific_conditions(self) -> list[tuple[str, float, bool, str]]:
        """The small divisor 1/(1 - omega**2) of the forced response must stay moderate."""
        eps = self.epsilon()
        divisor = abs(1 - self.omega() ** 2)
        ratio = eps / divisor
        ok = ratio <= EPSILON_WARN
        sentence = (
            f"the small divisor must stay moderate: eps/|1 - omega**2| = {eps:.4g}/{divisor:.4g} = "
            f"{ratio:.3g} <= {EPSILON_WARN:g}"
            if ok
            else f"the small divisor 1/(1 - omega**2) = {1 / divisor:.4g} is too large for eps = "
            f"{eps:.4g}: eps/|1 - omega**2| = {ratio:.3g} > {EPSILON_WARN:g}, so the forced "
            "response's O(eps/(1 - omega**2)) terms are not small (omega = "
            f"{self.omega():.6g} is too close to the resonance omega = 1; give a larger r0)"
        )
        return [("small divisor 1/(1 - ω²)", ratio, ok, sentence)]

    def omega(self) -> float:
        """The nutation frequency :math:`\\omega` (units of the spin :math:`r_0`)."""
        v = self.values
        return math.sqrt(frequency_squared(v["A"], v["B"], v["C"]))
