"""The named, inspectable steps of a Poincaré construction.

Each step is a frozen value object a user can print and export to LaTeX; together they mirror the
classical write-up (generating solution, quadratures :math:`g_k`, :math:`h_k`, periodicity
conditions, period correction).
"""

from __future__ import annotations

import re

import sympy as sp
from attrs import field, frozen

from perturb.trig import TrigPoly

__all__ = ["Condition", "GeneratingSolution", "OrderStep", "PeriodicityCondition", "S", "as_trig"]

S = sp.Symbol("s", real=True)  #: strained time s = Omega t


@frozen
class GeneratingSolution:
    """The ε = 0 solution :math:`x_i = a_i \\cos m_i s + b_i \\sin m_i s` (zero for non-resonant :math:`x_i`).

    Attributes
    ----------
    coordinates : tuple of str
    harmonics : tuple of int or None
        ``m_i = omega_i / omega_ref`` for resonant coordinates, ``None`` for non-resonant ones.
    cos_amplitudes, sin_amplitudes : tuple of sympy expressions
        The generating amplitudes (symbols still unknown, or given values).
    phase_coordinate : str
        The coordinate whose velocity vanishes at ``s = 0``.
    reference_frequency : sympy expression
        :math:`\\omega_{ref}`, the frequency of the phase coordinate.
    """

    coordinates: tuple[str, ...]
    harmonics: tuple[int | None, ...]
    cos_amplitudes: tuple[sp.Expr, ...]
    sin_amplitudes: tuple[sp.Expr, ...]
    phase_coordinate: str
    reference_frequency: sp.Expr

    def expressions(self) -> dict[str, sp.Expr]:
        out = {}
        for name, m, a, b in zip(
            self.coordinates, self.harmonics, self.cos_amplitudes, self.sin_amplitudes, strict=True
        ):
            out[name] = sp.S.Zero if m is None else a * sp.cos(m * S) + b * sp.sin(m * S)
        return out

    def latex(self) -> str:
        return r" \\ ".join(f"{name}_0 = {sp.latex(e)}" for name, e in self.expressions().items())

    def __str__(self) -> str:
        lines = [f"generating solution (phase fixed by d{self.phase_coordinate}/dt = 0 at t = 0):"]
        lines += [f"  {k}_0(s) = {v}" for k, v in self.expressions().items()]
        return "\n".join(lines)


@frozen
class PeriodicityCondition:
    """One periodicity condition: ``name`` must vanish (e.g. ``g_x,2(2pi)`` or ``dg_x,2/ds(2pi)``).

    Attributes
    ----------
    name : str
        ``g_<coordinate>,<k>(2pi)`` (position) or ``dg_<coordinate>,<k>/ds(2pi)`` (slope).
    expression : sympy expression
        What must vanish, in the unknowns of the construction.
    imposed : bool
        ``False`` for a condition a first integral makes dependent (kept as a check, not solved).
    """

    name: str
    expression: sp.Expr
    imposed: bool = True  #: False for a condition a first integral makes dependent (not solved)

    def latex(self) -> str:
        match = re.fullmatch(r"(d?)g_(\w+),(\d+)(/ds)?\(2pi\)", self.name)
        if match:
            dot = r"\dot " if match.group(1) else ""
            name = f"{dot}g_{{{match.group(2)},{match.group(3)}}}(2\\pi)"
        else:
            name = self.name
        return f"{name} = {sp.latex(self.expression)} = 0"


@frozen
class OrderStep:
    """Everything computed at order ``k``.

    Attributes
    ----------
    order : int
    forcing : dict
        ``R_{i,k}(s)``: the ε^k coefficient of the right-hand side, including the terms the strained time
        adds, on the solutions of lower order (as :class:`TrigPoly`).
    quadratures : dict
        ``g_{i,k}(s)``, the periodic part of :math:`\\int_0^s R_{i,k}(u)\\sin m(s-u)\\,du/m` (the particular
        solution with zero initial data for resonant coordinates, the periodic forced response for
        non-resonant ones).
    conditions : tuple of PeriodicityCondition
        The periodicity conditions of this order, before any unknown was solved for.
    solved : dict
        The unknowns this order determined (symbol -> value).
    branches : tuple of dict
        When the conditions were nonlinear (amplitude equations): every admissible root found.
    """

    order: int
    forcing: dict = field(eq=False)
    quadratures: dict = field(eq=False)
    conditions: tuple[PeriodicityCondition, ...] = ()
    solved: dict = field(factory=dict, eq=False)
    branches: tuple = ()

    def __str__(self) -> str:
        lines = [f"order {self.order}:"]
        for name, r in self.forcing.items():
            lines.append(f"  R_{name},{self.order}(s) = {as_trig(r)}")
        for name, g in self.quadratures.items():
            lines.append(f"  g_{name},{self.order}(s) = {as_trig(g)}")
        for c in self.conditions:
            lines.append(f"  condition {c.name} = {c.expression}")
        for k, v in self.solved.items():
            lines.append(f"  solved {k} = {v}")
        if len(self.branches) > 1:
            lines.append(f"  {len(self.branches)} branches: {list(self.branches)}")
        return "\n".join(lines)

    def latex(self) -> str:
        parts = [
            f"R_{{{n},{self.order}}}(s) = {sp.latex(as_trig(r))}" for n, r in self.forcing.items()
        ]
        parts += [
            f"g_{{{n},{self.order}}}(s) = {sp.latex(as_trig(g))}"
            for n, g in self.quadratures.items()
        ]
        parts += [c.latex() for c in self.conditions]
        parts += [f"{sp.latex(k)} = {sp.latex(v)}" for k, v in self.solved.items()]
        return r" \\ ".join(parts)


#: The name the periodicity condition had before ``perturb.method`` (kept importable).
Condition = PeriodicityCondition


def as_trig(poly: TrigPoly) -> sp.Expr:
    """A :class:`TrigPoly` as an expression in the strained time ``s``."""
    return poly.as_expr(S)
