"""The rigid-body elimination itself: the symbols of the reduced system and the series derivation.

:mod:`problems.rigid_body.reduction` is the public face (the :class:`~problems.rigid_body.reduction
.Reduction` result, caching, the numeric maps); this module holds what the reduction is *made of*:
the reduced and initial-value symbols, the body specs (disk and general body), the solved forms of
the eliminated variables and :class:`Builder`, which runs the elimination as truncated series in a
:class:`~problems.rigid_body._series_ring.SeriesRing`. See the reduction module's docstring for the
mathematics.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cache

import sympy as sp
from attrs import frozen
from sympy.polys.rings import PolyElement

from perturb.system import EPS
from problems.rigid_body._series_ring import SeriesRing
from problems.rigid_body.equations import (
    NONDIMENSIONAL_STATE,
    a,
    b,
    gamma1,
    gamma2,
    gamma3,
    inertia_ratio_values,
    k,
    nondimensional_equations,
    nondimensional_integrals,
    p1,
    q1,
    r1,
    x0p,
    y0p,
    z0p,
)

__all__ = [
    "DISK_PARAMETERS",
    "GENERAL_PARAMETERS",
    "INITIAL_VALUES",
    "REDUCED_STATE",
    "LIGHT_SPECS",
    "SPECS",
    "VARIABLES",
    "Builder",
    "derived",
    "gamma3_0",
]

# ---------------------------------------------------------------------------- symbols
P, G, dP, dG = sp.symbols("P G dP dG")
P0, G0, dP0, dG0 = sp.symbols("P0 G0 dP0 dG0")
#: Initial value of gamma'' (the paper's gamma0'').
gamma3_0 = sp.Symbol("gamma3_0")
#: Reduced state in the order (P, dP, G, dG).
REDUCED_STATE = (P, dP, G, dG)
#: Initial values in the engine's order: x(0)'s then xdot(0)'s.
INITIAL_VALUES = (P0, G0, dP0, dG0)
DISK_PARAMETERS = (a, b, k, x0p, y0p, gamma3_0)
GENERAL_PARAMETERS = (a, b, k, x0p, y0p, z0p, gamma3_0)

#: Placeholders for the constants of the energy and area integrals.
_H0, _K0 = sp.symbols("H_0 K_0")
#: Generators of the series ring besides the parameters (epsilon first: the truncation variable).
VARIABLES = (EPS, *NONDIMENSIONAL_STATE, *REDUCED_STATE, *INITIAL_VALUES, _H0, _K0)


_INITIAL_OF = {P: P0, dP: dP0, G: G0, dG: dG0}


# ---------------------------------------------------------------------------- derivation
@frozen
class _Spec:
    """What distinguishes the disk from the general body."""

    equations: tuple[sp.Expr, ...]  # dimensionless rhs (p1, q1, r1, gamma1..3)
    energy: sp.Expr
    area: sp.Expr
    shift_p: sp.Expr  # p1 = P + shift_p
    shift_g: sp.Expr  # gamma = G + shift_g * P
    omega_sq: sp.Expr  # frequency squared of P
    params: tuple[sp.Symbol, ...]
    fraction_field: bool  # coefficients in QQ(a, b) (general) or a, b, 1/a, 1/b generators (disk)


def _solve_linear(equation: sp.Expr, unknown: sp.Symbol) -> tuple[sp.Expr, sp.Expr]:
    """Solve ``equation = 0``, linear in ``unknown``: return (numerator, denominator).

    ``equation = alpha * unknown + beta`` gives ``unknown = -beta / alpha``; both are polynomials,
    so the series evaluation needs one series inversion (of alpha).
    """
    equation = sp.expand(equation)
    alpha = sp.diff(equation, unknown)
    if alpha == 0 or sp.diff(alpha, unknown) != 0:
        raise AssertionError(f"{equation} = 0 is not linear in {unknown}")
    beta = sp.expand(equation.xreplace({unknown: 0}))
    return -beta, alpha


@frozen
class _Eliminations:
    """Solved forms: each unknown as numerator/denominator (sympy), and r1**2 for the energy."""

    q1: tuple[sp.Expr, sp.Expr]
    gamma2: tuple[sp.Expr, sp.Expr]
    gamma3: tuple[sp.Expr, sp.Expr]
    r1_squared: tuple[sp.Expr, sp.Expr]


def _eliminations(spec: _Spec) -> _Eliminations:
    f_p, _, _, f_g, _, _ = spec.equations
    # p1 = P + const  =>  dp1/dtau = dP
    q_sol = _solve_linear(f_p - dP, q1)
    # gamma = G + s_G P  =>  dgamma/dtau = dG + s_G dP
    g2_sol = _solve_linear(f_g - dG - spec.shift_g * dP, gamma2)
    # area integral = its value at tau = 0
    g3_sol = _solve_linear(spec.area - _K0, gamma3)
    # energy: H = c2 r1**2 + H|_{r1=0} (no linear term), so r1**2 = (H0 - H|_{r1=0}) / c2
    poly = sp.Poly(spec.energy, r1)
    if poly.degree() != 2 or poly.coeff_monomial(r1) != 0:
        raise AssertionError("the energy integral is not of the form c2*r1**2 + rest")
    c2 = poly.coeff_monomial(r1**2)
    rest = poly.coeff_monomial(1)
    return _Eliminations(q_sol, g2_sol, g3_sol, (sp.expand(_H0 - rest), sp.expand(c2)))


def _accelerations(spec: _Spec) -> tuple[sp.Expr, sp.Expr]:
    """d/dtau of dp1/dtau and of dgamma/dtau along the full flow (exact, expanded)."""
    f = spec.equations
    return tuple(
        sp.expand(sum(sp.diff(f[i], y) * fy for y, fy in zip(NONDIMENSIONAL_STATE, f, strict=True)))
        for i in (0, 3)
    )


@cache
def derived(kind: str) -> tuple[_Spec, _Eliminations, tuple[sp.Expr, sp.Expr]]:
    """The body's spec, its solved eliminations and its accelerations (derived once a process)."""
    spec = SPECS[kind]()
    return spec, _eliminations(spec), _accelerations(spec)


class Builder:
    """Runs the elimination as truncated series in one polynomial ring."""

    def __init__(self, kind: str, sr: SeriesRing):
        self.spec, elim, self.accelerations = derived(kind)
        self.sr = conv = sr
        self.q_num, self.q_den = map(conv, elim.q1)
        self.g2_num, self.g2_den = map(conv, elim.gamma2)
        self.g3_num, self.g3_den = map(conv, elim.gamma3)
        self.rs_num, self.rs_den = map(conv, elim.r1_squared)

    def _ratio(self, num, den, mapping):
        return self.sr.mul(
            self.sr.substitute(num, mapping), self.sr.inverse(self.sr.substitute(den, mapping))
        )

    def _iterate(self, state: dict, reduced: Mapping, constants: Mapping | None) -> dict:
        """Fixed-point iteration; ``constants`` None means r1 = 1, gamma'' = gamma3_0 (tau = 0)."""
        sr = self.sr
        for _ in range(sr.order + 3):
            previous = dict(state)
            mapping = {**state, **reduced, **(constants or {})}
            state[q1] = self._ratio(self.q_num, self.q_den, mapping)
            mapping[q1] = state[q1]
            state[gamma2] = self._ratio(self.g2_num, self.g2_den, mapping)
            mapping[gamma2] = state[gamma2]
            if constants is not None:
                state[gamma3] = self._ratio(self.g3_num, self.g3_den, mapping)
                mapping[gamma3] = state[gamma3]
                r_sq = self._ratio(self.rs_num, self.rs_den, mapping)
                state[r1] = sr.sqrt(r_sq)
            if state == previous:
                return state
        raise AssertionError("the elimination series did not converge")

    def _start(self, reduced: Mapping[sp.Symbol, PolyElement]) -> dict:
        sr = self.sr
        shift_p = sr(self.spec.shift_p)
        shift_g = sr(self.spec.shift_g)
        p_val = reduced[P]
        return {
            p1: sr.trunc(p_val + shift_p),
            gamma1: sr.trunc(reduced[G] + sr.mul(shift_g, p_val)),
            r1: sr.ring.one,
            gamma3: sr(gamma3_0),
            q1: sr.ring.zero,
            gamma2: sr.ring.zero,
        }

    def run(self) -> dict[str, PolyElement]:
        """The reduction's series by name (see :class:`Reduction` for their meaning)."""
        sr = self.sr
        # --- tau = 0: r1 = 1, gamma'' = gamma3_0, reduced state = initial values
        initial_reduced = {s: sr.gen(_INITIAL_OF[s]) for s in REDUCED_STATE}
        initial = self._iterate(self._start(initial_reduced), initial_reduced, None)
        h0 = sr.substitute(sr(self.spec.energy), initial)
        k0 = sr.substitute(sr(self.spec.area), initial)
        # --- any tau
        reduced = {s: sr.gen(s) for s in REDUCED_STATE}
        state = self._iterate(self._start(reduced), reduced, {_H0: h0, _K0: k0})
        # --- accelerations along the flow, on the series: P'' and G'' = gamma'''' - s_G P''
        ddp, ddgamma = (sr.substitute(sr(expr), state) for expr in self.accelerations)
        shift_g = sr(self.spec.shift_g)
        ddg = sr.trunc(ddgamma - sr.mul(shift_g, ddp))
        out = {
            "rhs_p": sr.trunc(ddp + sr(self.spec.omega_sq) * sr.gen(P)),
            "rhs_g": sr.trunc(ddg + sr.gen(G)),
            "geometric": sr.substitute(sr(gamma1**2 + gamma2**2 + gamma3**2), state),
            "energy": h0,
            "area": k0,
        }
        for s in NONDIMENSIONAL_STATE:
            out[f"state:{s.name}"] = state[s]
            out[f"initial:{s.name}"] = initial[s]
        return out


# ---------------------------------------------------------------------------- the two bodies
def _disk_spec() -> _Spec:
    ratios = inertia_ratio_values(disk=True)
    eqs = nondimensional_equations(True, ratios=True).subs(ratios).subs(z0p, 0)
    ints = nondimensional_integrals(True)
    return _Spec(
        equations=tuple(sp.expand(e) for e in eqs),
        energy=ints["energy"].subs(z0p, 0),
        area=ints["area"],
        shift_p=EPS * x0p * gamma3_0 / b,
        shift_g=EPS * a * gamma3_0,
        omega_sq=sp.S.One,
        params=DISK_PARAMETERS,
        fraction_field=False,
    )


def _general_omega_sq() -> sp.Expr:
    ratios = inertia_ratio_values(disk=False)
    return sp.factor(-ratios[sp.Symbol("A1")] * ratios[sp.Symbol("B1")])


def _general_spec() -> _Spec:
    ratios = inertia_ratio_values(disk=False)
    eqs = nondimensional_equations(True, ratios=True).subs(ratios)
    ints = nondimensional_integrals(True)
    return _Spec(
        equations=tuple(sp.expand(e) for e in eqs),
        energy=ints["energy"],
        area=ints["area"],
        shift_p=sp.S.Zero,
        shift_g=sp.S.Zero,
        omega_sq=_general_omega_sq(),
        params=GENERAL_PARAMETERS,
        fraction_field=True,
    )


SPECS = {"disk": _disk_spec, "general": _general_spec}
#: What a reduction needs of its body without deriving the equations (a cache hit skips them).
LIGHT_SPECS = {
    "disk": {
        "name": "disk-newtonian-fast-spin",
        "frequencies": lambda: (1, 1),
        "params": DISK_PARAMETERS,
        "fraction_field": False,
    },
    "general": {
        "name": "rigid-body-fast-spin",
        "frequencies": lambda: (sp.sqrt(_general_omega_sq()), 1),
        "params": GENERAL_PARAMETERS,
        "fraction_field": True,
    },
}
