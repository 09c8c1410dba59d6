"""The excitation of a driven system: what makes a :class:`~perturb.QuasilinearSystem` forced.

A driven quasilinear system

.. math:: \\ddot x_i + \\omega_i^2 x_i = \\varepsilon f_i(x, \\dot x, \\Omega t, \\varepsilon)

has a right-hand side :math:`2\\pi`-periodic in its third argument, written with a symbol
:math:`\\theta` that stands for :math:`\\Omega t` (``phase``). Near a resonance the excitation
frequency is :math:`\\Omega = (p/q)\\,\\omega_{ref} + \\varepsilon\\sigma` (``ratio`` = p/q,
``detuning`` = σ, ``reference`` the coordinate whose ω is :math:`\\omega_{ref}`): p/q = 1 primary, 2
parametric, 3 subharmonic (the response at Ω/3), 1/3 superharmonic (the response at 3Ω). The sought
response then has the period :math:`T = 2\\pi p/\\Omega` (p forcing periods) and the construction
runs in :math:`s = \\Omega t/p`, where :math:`\\theta = p s` (:mod:`perturb.method.driven`).

``phase`` may appear only through cosines and sines of integer multiples of itself (plus constant
phases), possibly multiplied by the state (parametric excitation): anything else is not periodic
in t and is refused. :meth:`Excitation.polynomial_form` rewrites such a right-hand side as a
polynomial in two symbols standing for :math:`\\cos\\theta` and :math:`\\sin\\theta`, which the
exact harmonic arithmetic of the engine expands like the state.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp
from attrs import field, frozen

from perturb._defaults import MAX_RESONANCE_INTEGER
from perturb.errors import InvalidSystemError, bad_value

__all__ = ["Excitation", "time_forcing"]


def _as_phase(value) -> sp.Symbol:
    if isinstance(value, str):
        if not value or any(c.isspace() for c in value):
            raise bad_value("phase", value, "give a name without spaces", InvalidSystemError)
        value = sp.Symbol(value)
    if not isinstance(value, sp.Symbol):
        raise bad_value(
            "phase", value, "give the sympy Symbol that stands for Omega*t", InvalidSystemError
        )
    return value


def _as_ratio(value) -> sp.Rational:
    """p/q exactly: an int, a sympy Rational, a Fraction, a string "p/q", or a float that is one."""
    fix = (
        f"give p/q exactly with p, q <= {MAX_RESONANCE_INTEGER}: an integer, "
        "sympy.Rational(1, 3) or the string '1/3'"
    )
    if isinstance(value, bool):
        raise bad_value("ratio", value, fix, InvalidSystemError)
    if isinstance(value, float):
        exact = Fraction(value).limit_denominator(MAX_RESONANCE_INTEGER) if value == value else None
        if exact is None or float(exact) != value:
            raise bad_value(
                "ratio", value, "it is not an exact ratio of small integers; " + fix,
                InvalidSystemError,
            )  # fmt: skip
        value = exact
    try:
        ratio = sp.Rational(str(value)) if isinstance(value, str | Fraction) else sp.sympify(value)
    except (sp.SympifyError, TypeError, ValueError):
        raise bad_value("ratio", value, fix, InvalidSystemError) from None
    if not isinstance(ratio, sp.Expr):  # a list, a matrix...: no number at all
        raise bad_value("ratio", value, fix, InvalidSystemError)
    if not ratio.is_Rational:
        raise bad_value("ratio", value, "an irrational ratio is no resonance; " + fix,
                        InvalidSystemError)  # fmt: skip
    if not ratio > 0:
        raise bad_value("ratio", value, "the ratio must be positive; " + fix, InvalidSystemError)
    if ratio.p > MAX_RESONANCE_INTEGER or ratio.q > MAX_RESONANCE_INTEGER:
        raise bad_value(
            "ratio", value,
            f"resonances p/q with p or q above {MAX_RESONANCE_INTEGER} are not supported; " + fix,
            InvalidSystemError,
        )  # fmt: skip
    return ratio


def _as_detuning(value) -> sp.Expr:
    try:
        expr = sp.sympify(value)
    except (sp.SympifyError, TypeError):
        raise bad_value(
            "detuning", value, "give a symbol (a declared parameter) or a number",
            InvalidSystemError,
        ) from None  # fmt: skip
    if expr.is_number and not expr.is_real:
        raise bad_value("detuning", value, "give a real number or a parameter", InvalidSystemError)
    return expr


def _check_reference(instance, attribute, value) -> None:
    if value is not None and not isinstance(value, str):
        raise bad_value(
            "reference", value, "give a coordinate's name (str) or None", InvalidSystemError
        )


@frozen
class Excitation:
    """The periodic excitation of a driven system (see the module docstring).

    Parameters
    ----------
    phase : sympy.Symbol or str
        The symbol standing for :math:`\\Omega t` in the right-hand sides.
    ratio : int, str or sympy.Rational
        p/q in :math:`\\Omega = (p/q)\\omega_{ref} + \\varepsilon\\sigma` (1 primary, 2 parametric,
        3 subharmonic, 1/3 superharmonic), p and q at most ``MAX_RESONANCE_INTEGER``.
    detuning : sympy expression
        σ: a declared parameter of the system (or a number).
    reference : str, optional
        The coordinate whose frequency is :math:`\\omega_{ref}` (default: the first).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem
    >>> x, v, th, s, F = sp.symbols("x v theta sigma F")
    >>> drive = Excitation(phase=th, ratio=1, detuning=s)
    >>> system = QuasilinearSystem([x], [v], [1], [EPS * (F * sp.cos(th) - x**3)],
    ...                            parameters=[s, F], excitation=drive)
    >>> drive.p, drive.q
    (1, 1)
    """

    phase: sp.Symbol = field(converter=_as_phase)
    ratio: sp.Rational = field(default=1, converter=_as_ratio)
    detuning: sp.Expr = field(default=0, converter=_as_detuning)
    reference: str | None = field(default=None, validator=_check_reference)

    @property
    def p(self) -> int:
        """The numerator: the response's period is p forcing periods."""
        return int(self.ratio.p)

    @property
    def q(self) -> int:
        """The denominator: the reference coordinate responds at harmonic q of Ω/p."""
        return int(self.ratio.q)

    @property
    def cos_symbol(self) -> sp.Symbol:
        """The symbol standing for :math:`\\cos\\theta` in :meth:`polynomial_form`."""
        return sp.Symbol(f"cos_{self.phase.name}")

    @property
    def sin_symbol(self) -> sp.Symbol:
        """The symbol standing for :math:`\\sin\\theta` in :meth:`polynomial_form`."""
        return sp.Symbol(f"sin_{self.phase.name}")

    def polynomial_form(self, expr: sp.Expr, label: str = "rhs") -> sp.Expr:
        """``expr`` with every cos/sin of ``k θ + c`` as a polynomial in cos θ and sin θ.

        Raises
        ------
        InvalidSystemError
            When θ appears otherwise (``θ x``, ``cos(θ/2)``, ``cos(√2 θ)``): not periodic in t with
            the forcing period.
        """
        theta, cos_t, sin_t = self.phase, self.cos_symbol, self.sin_symbol
        expr = sp.sympify(expr)
        if not expr.has(theta):
            return expr
        replaced = {}
        for atom in expr.atoms(sp.cos, sp.sin):
            argument = atom.args[0]
            if not argument.has(theta):
                continue
            slope = sp.simplify(sp.diff(argument, theta))
            offset = sp.simplify(argument - slope * theta)
            if not (slope.is_Integer and not offset.has(theta)):
                raise bad_value(
                    label, expr,
                    f"{atom} is not periodic in t with the forcing period 2*pi/Omega: the phase "
                    f"{theta} may appear only as cos/sin(k*{theta} + c) with an integer k",
                    InvalidSystemError,
                )  # fmt: skip
            k = int(slope)
            unit = sp.cos(k * theta) if isinstance(atom, sp.cos) else sp.sin(k * theta)
            shifted = sp.expand_trig(atom.func(k * theta + offset)) if offset != 0 else unit
            expanded = sp.expand(sp.expand_trig(shifted.subs(k * theta, k * theta)))
            expanded = sp.expand(sp.expand_trig(expanded))
            replaced[atom] = expanded.subs({sp.cos(theta): cos_t, sp.sin(theta): sin_t})
        result = sp.expand(expr.xreplace(replaced))
        if result.has(theta):
            raise bad_value(
                label, expr,
                f"the phase {theta} appears outside cos/sin: not periodic in t; write the "
                f"excitation with cos(k*{theta}) and sin(k*{theta})",
                InvalidSystemError,
            )  # fmt: skip
        return result


#: Names a right-hand side's time goes by when a user writes a forcing in it (``F*cos(Omega*t)``).
TIME_NAMES = ("t", "time")


def time_forcing(rhs, symbols, declared=()) -> str:
    """How to declare a forcing written in the time, in one sentence ("" when there is none).

    A user writes a forcing as ``F*cos(Omega*t)``; perturb solves a driven system in its phase
    θ = Ωt, declared as an :class:`Excitation`. ``symbols`` are the right-hand side's symbols
    that are not state or small parameter and look like the time: undeclared ones, and declared
    parameters named as in :data:`TIME_NAMES`; the sentence names the first one found inside a
    cosine or a sine, the frequency it is multiplied by, and the declaration to write instead.
    A symbol of ``declared`` (a parameter the system declares) counts only when a frequency
    multiplies it (``cos(Omega*t)``): ``cos(t)`` of a parameter named t is a constant phase.

    Examples
    --------
    >>> t, Omega, F, x = sp.symbols("t Omega F x")
    >>> print(time_forcing(F * sp.cos(Omega * t) - x**3, {t}))  # doctest: +NORMALIZE_WHITESPACE
    the forcing is written in the time t (cos(Omega*t)): perturb solves a driven system in its
    phase theta = Omega*t declared as an Excitation -- write it with a symbol theta (F*cos(theta);
    cos(2*Omega*t) is cos(2*theta)), pass excitation=Excitation(theta, ratio=1, detuning=sigma)
    with sigma among the parameters, and keep Omega as your parameter with parameter_map =
    {'sigma': '(Omega - 1)/eps'} (docs/forced.md, 'Your own forced oscillator')
    """
    expr = sp.sympify(rhs)
    found = []  # (time, rate, the call): each cosine or sine whose argument moves with a time
    for call in sorted(expr.atoms(sp.cos, sp.sin), key=sp.default_sort_key):
        argument = call.args[0]
        for time in sorted(argument.free_symbols & set(symbols), key=sp.default_sort_key):
            rate = sp.simplify(sp.diff(argument, time))
            if rate != 0 and not rate.has(time) and (time not in declared or rate.free_symbols):
                found.append((time, rate, call))
    fundamental = [  # every other harmonic of this time a whole multiple of it
        (time, rate, call)
        for time, rate, call in found
        if all(sp.simplify(r / rate).is_integer for t, r, _ in found if t == time)
    ]
    for time, rate, call in fundamental[:1] or found[:1]:
        theta = rate * time
        return (
            f"the forcing is written in the time {time} ({call}): perturb solves a driven "
            f"system in its phase theta = {theta} declared as an Excitation -- write it with "
            f"a symbol theta (F*cos(theta); cos({2 * theta}) is cos(2*theta)), pass "
            "excitation=Excitation(theta, ratio=1, detuning=sigma) with sigma among the "
            f"parameters, and keep {rate} as your parameter with parameter_map = "
            f"{{'sigma': '({rate} - 1)/eps'}} (docs/forced.md, 'Your own forced oscillator')"
        )
    return ""
