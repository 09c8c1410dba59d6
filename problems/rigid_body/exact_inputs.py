"""Exact inputs of the disk's true-orbit computations: rational parameters, equations, pins.

At the paper geometry (:math:`\\varepsilon = 10^{-4}`, :math:`k = 2.47\\times10^{-5}`) the P- and
G-frequencies of the reduced system differ by :math:`\\varepsilon^2 kM_3^2/2 \\approx 1.2\\times10^{-13}`,
so a relative error :math:`\\delta` in one coefficient of the resonant part of the equations (one that
breaks :math:`A + B = C`) moves the true amplitudes by about :math:`\\delta/10^{-13}`: a single
double-precision ulp (1e-16) shows in the third digit. The true orbit must therefore be computed from
the parameters *as given*, carried exactly (sympy ``Rational``) into the equations, each coefficient
rounded once to the working precision. This module supplies that, for both routes
(:mod:`problems.rigid_body.true_orbit`, heyoka in quadruple precision, and
:mod:`problems.rigid_body.true_orbit_mp`, an mpmath Taylor integrator):

* :func:`exact_values` — the problem's parameters as rationals (the shortest decimal of each float,
  i.e. the text the user typed; :math:`C = A + B` exactly for the disk);
* :func:`exact_equations` — the dimensional Euler–Poisson equations with rational coefficients;
* :class:`FamilyMember` — which orbit of the family is meant (the pins and the section), exactly;
* :func:`round_coefficients` — every coefficient of a polynomial rounded once to a binary precision.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cache

import mpmath
import sympy as sp
from attrs import frozen

from perturb.errors import bad_value
from problems.rigid_body import equations as eq

__all__ = [
    "FamilyMember",
    "exact_epsilon",
    "exact_equations",
    "exact_number",
    "exact_values",
    "round_coefficients",
]

#: Decimal digits to which an irrational pin (gamma(0) = sqrt(1 - gamma'**2 - gamma''**2)) is written
#: as a rational: 50 digits exceed quadruple precision (34) and the mpmath route's 40 digits.
PIN_DIGITS = 50


def exact_number(value) -> sp.Expr:
    """A parameter value as an exact sympy number.

    Parameters
    ----------
    value : float, int, str or sympy number
        A float becomes the rational of its *shortest* decimal representation,
        ``sympy.Rational(repr(value))``: the CLI parses ``--set r0=30.2062`` into the float
        30.2062, and ``repr`` gives back ``"30.2062"`` (for every text of at most 15 significant
        digits), so the rational is exactly what the user typed, not the binary neighbour
        30.20619999999999905...; a string is read as an exact decimal; ``inf`` becomes ``sympy.oo``.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If the value is NaN or not a number.
    """
    if isinstance(value, sp.Basic):
        number = exact_number(float(value)) if isinstance(value, sp.Float) else value
    elif isinstance(value, str):
        number = sp.Rational(value.strip())
    elif isinstance(value, bool):
        raise bad_value("value", value, "give a real number, not a bool")
    elif isinstance(value, int):
        number = sp.Integer(value)
    else:
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise bad_value("value", value, "give a real number") from None
        if math.isnan(number):
            raise bad_value("value", value, "give a finite real number (or inf for a distance)")
        if math.isinf(number):
            return sp.oo if number > 0 else -sp.oo
        number = sp.Rational(repr(number))
    if not (number.is_Rational or number in (sp.oo, -sp.oo)):
        raise bad_value("value", value, "give a rational number (a decimal)")
    return number


def exact_values(problem) -> dict[str, sp.Expr]:
    """The problem's parameter values as exact rationals (see :func:`exact_number`).

    The disk (problem ``disk``) accepts :math:`A + B - C` up to a relative round-off
    (:data:`problems.rigid_body.disk.DISK_RTOL`); here :math:`C = A + B` is imposed exactly, since
    the resonance :math:`(C-A)(C-B) = AB` that defines the disk must hold exactly (a violation of
    1e-16 already moves the true amplitudes in the third digit at the paper geometry).
    """
    values = {name: exact_number(v) for name, v in problem.values.items()}
    if problem.name == "disk":
        values["C"] = values["A"] + values["B"]
    return values


def exact_epsilon(values: Mapping[str, sp.Expr]) -> sp.Expr:
    """:math:`\\varepsilon = c/r_0`, :math:`c = \\sqrt{Mgl/C}`, :math:`l = \\sqrt{x_0^2 + y_0^2}` (exact)."""
    arm = sp.sqrt(values["x0"] ** 2 + values["y0"] ** 2)
    return sp.sqrt(values["M"] * values["g"] * arm / values["C"]) / values["r0"]


@cache
def _exact_equations(items: tuple) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Expr, ...]]:
    v = dict(items)
    rhs = eq.euler_poisson_equations(v["R"])
    subs = {
        eq.A: v["A"], eq.B: v["B"], eq.C: v["C"], eq.M: v["M"], eq.g: v["g"],
        eq.x0: v["x0"], eq.y0: v["y0"], eq.z0: v["z0"],
    }  # fmt: skip
    if v["R"] is not sp.oo:
        subs[eq.R] = v["R"]
    exprs = tuple(sp.expand(e.xreplace(subs)) for e in rhs)
    for e in exprs:
        for number in e.atoms(sp.Number):
            if not number.is_Rational:
                raise AssertionError(f"an inexact number {number} entered the exact equations")
    return eq.DIMENSIONAL_STATE, exprs


def exact_equations(
    values: Mapping[str, sp.Expr],
) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Expr, ...]]:
    """The dimensional Euler–Poisson equations :math:`\\dot y = f(y)` with rational coefficients.

    Parameters
    ----------
    values : mapping
        :func:`exact_values` (the names ``A B C M g R x0 y0 z0``; ``R = oo`` for no centre).

    Returns
    -------
    (state symbols, expressions)
        ``state`` = :data:`problems.rigid_body.equations.DIMENSIONAL_STATE`; each expression is a
        polynomial (degree 2) in the state with exact rational coefficients.
    """
    names = ("A", "B", "C", "M", "g", "R", "x0", "y0", "z0")
    return _exact_equations(tuple((n, values[n]) for n in names))


def _dyadic(value: sp.Rational, bits: int) -> sp.Rational:
    """``value`` correctly rounded to ``bits`` significant bits, as an exact (dyadic) rational."""
    if value == 0:
        return sp.Integer(0)
    mantissa, exponent = mpmath.libmp.from_rational(int(value.p), int(value.q), bits, "n")[1:3]
    sign = -1 if value < 0 else 1
    return sign * sp.Integer(mantissa) * sp.Integer(2) ** exponent


def round_coefficients(expr: sp.Expr, bits: int) -> sp.Expr:
    """Round every rational coefficient of a polynomial once, to ``bits`` significant bits.

    The result's coefficients are dyadic rationals :math:`m\\,2^e` with :math:`|m| < 2^{bits}`, so
    that :func:`perturb.oracle.symbolic.to_heyoka` converts them without a further rounding
    (``fp(str(m)) / fp(str(2**-e))`` is exact in a type of ``bits`` bits): each coefficient is the
    exact value rounded to nearest once, never through float64.

    Parameters
    ----------
    expr : sympy.Expr
        A polynomial with rational coefficients (expanded here).
    bits : int
        113 for quadruple precision (real128), 64 for the x86 80-bit long double.
    """
    out = []
    for term in sp.Add.make_args(sp.expand(expr)):
        coefficient, rest = term.as_coeff_Mul()
        if not coefficient.is_Rational:
            raise bad_value("expr", term, "only rational coefficients can be rounded")
        out.append(_dyadic(coefficient, bits) * rest)
    return sp.Add(*out)


@frozen
class FamilyMember:
    """Which periodic orbit of the disk's family is meant, in exact numbers.

    The true orbits form a family (energy, area and geometric integrals); the member is the one of
    the analytic solution: on the shooting section :math:`\\gamma'(0) =` ``section`` the spin is
    :math:`r(0) = r_0`, :math:`\\gamma''(0) = \\gamma_0''` and :math:`|\\boldsymbol\\gamma| = 1`. Both
    routes pin these same numbers; ``p_seed``, ``q_seed`` only start the search.

    Attributes
    ----------
    section, r0, gamma3_0 : sympy.Rational
    p_seed, q_seed : sympy.Rational
        The analytic solution's p(0), q(0) (exact values of the doubles).
    """

    section: sp.Rational
    r0: sp.Rational
    gamma3_0: sp.Rational
    p_seed: sp.Rational
    q_seed: sp.Rational

    @classmethod
    def of(cls, problem, seed) -> FamilyMember:
        """The member through the analytic solution's state ``seed`` (p, q, r, gammas at t = 0)."""
        values = exact_values(problem)
        return cls(
            section=sp.Rational(float(seed[4])),
            r0=values["r0"],
            gamma3_0=values["gamma3_0"],
            p_seed=sp.Rational(float(seed[0])),
            q_seed=sp.Rational(float(seed[1])),
        )

    @property
    def gamma1(self) -> sp.Rational:
        """:math:`\\gamma(0) = \\sqrt{1 - \\gamma'^2 - \\gamma''^2}` to :data:`PIN_DIGITS` digits."""
        exact = sp.sqrt(1 - self.section**2 - self.gamma3_0**2)
        return sp.Rational(str(sp.N(exact, PIN_DIGITS)))

    def reference_state(self) -> tuple[sp.Rational, ...]:
        """(p_seed, q_seed, r0, gamma(0), section, gamma3_0): the origin of the search."""
        return (self.p_seed, self.q_seed, self.r0, self.gamma1, self.section, self.gamma3_0)
