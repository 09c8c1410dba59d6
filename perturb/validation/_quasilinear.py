"""Defaults of :class:`perturb.validation.Model` derived from the quasilinear system itself.

For a model whose original equations *are* its quasilinear system
:math:`\\ddot x_i + \\omega_i^2 x_i = f_i(x, \\dot x)` (with numbers put in), the first-order form,
its declared first integrals and, for conservative forces, its energy.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import sympy as sp

from perturb._lambdify import numpy_lambdify
from perturb.oracle import SymbolicRHS
from perturb.system import QuasilinearSystem

__all__ = [
    "conservative_energy",
    "excitation_frequency",
    "first_order_expressions",
    "first_order_form",
    "lambdify_integrals",
    "quasilinear_state_names",
    "state_along",
    "substitutions",
]


def quasilinear_state_names(system: QuasilinearSystem) -> tuple[str, ...]:
    """The state the oracle integrates: ``(x..., xdot...)``, and the phase θ = Ωt of a driven
    system last (its equations are made autonomous with θ' = Ω).

    Parameters
    ----------
    system : QuasilinearSystem

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> from problems import get_problem
    >>> from perturb.validation import quasilinear_state_names
    >>> quasilinear_state_names(get_problem("duffing").system())
    ('x', 'xdot')
    >>> quasilinear_state_names(get_problem("forced-duffing").system())
    ('x', 'xdot', 'theta')
    """
    return system.frame.state_names(system)


def state_along(solution, t, parameter_value: float, values: Mapping) -> dict[str, np.ndarray]:
    """The quasilinear state along ``solution`` at times ``t`` by name (θ = Ωt of a driven system
    included, in the order of :func:`quasilinear_state_names`).

    Parameters
    ----------
    solution : PeriodicSolution
    t : array_like
        Physical times.
    parameter_value : float
        ε (or μ in the large-parameter regime).
    values : mapping
        The system's parameter values.

    Returns
    -------
    dict of ndarray

    Examples
    --------
    >>> from problems import get_problem
    >>> from perturb.validation import state_along
    >>> duffing = get_problem("forced-duffing").create(Omega=1.05)
    >>> state = state_along(duffing.solve(1), [0.0, 1.0], duffing.epsilon(), duffing.symbol_values())
    >>> sorted(state), [round(float(v), 6) for v in state["theta"]]
    (['theta', 'x', 'xdot'], [0.0, 1.05])
    """
    system = solution.system
    y = solution.evaluate(t, parameter_value, values)
    state = dict(zip(solution.state_names, y, strict=True))
    subs = substitutions(system, values, parameter_value, None) or {}
    state.update(system.frame.phase_state(system, subs, t))  # a drive's phase θ = Ωt joins it
    return state


def excitation_frequency(system: QuasilinearSystem, subs: Mapping) -> sp.Expr:
    """Ω = (p/q) ω_ref + ε σ of a driven system, with ``subs`` put in (ε included)."""
    return system.frame.frequency(system, subs)


def substitutions(
    system: QuasilinearSystem,
    values: Mapping[str, float],
    parameter_value: float,
    y0: np.ndarray | None,
) -> dict | None:
    """Numbers for the system's symbols (parameters, its own small parameter, initial values).

    None when the system's equations need the initial values and ``y0`` is not given.
    """
    subs = {p: values[p.name] for p in system.parameters if p.name in values}
    subs[system.parameter] = parameter_value
    if system.initial_values:
        if y0 is None:
            return None
        subs.update(zip(system.initial_values, map(float, y0), strict=True))
    return subs


def first_order_expressions(system: QuasilinearSystem, subs: Mapping) -> list:
    """(ẋ, f(x, ẋ) − ω² x) of the quasilinear system on its state ``(x..., ẋ...)``, with ``subs``
    put in (a driven system's phase θ stays a symbol; parameters left out of ``subs`` too)."""
    n = system.n
    state = system.state_symbols
    forces = [sp.sympify(f).subs(subs) for f in system.rhs]
    w2 = [sp.sympify(w**2).subs(subs) for w in system.frequencies]
    return list(state[n:]) + [forces[i] - w2[i] * state[i] for i in range(n)]


def first_order_form(system: QuasilinearSystem, subs: Mapping) -> SymbolicRHS:
    """y' = (ẋ, f(x, ẋ) − ω² x) of the quasilinear system, with ``subs`` put in; a driven
    system's phase θ is appended with θ' = Ω (autonomous form)."""
    exprs = first_order_expressions(system, subs)
    return SymbolicRHS(*system.frame.autonomous(system.state_symbols, exprs, system, subs))


def conservative_energy(system: QuasilinearSystem, subs: Mapping) -> sp.Expr | None:
    """The energy of ẍ_i + ω_i² x_i = f_i(x) when the forces f derive from a potential, else None.

    With ``f = -grad V`` (velocity-free, symmetric Jacobian), :math:`H = \\sum \\dot x_i^2/2 +
    \\omega_i^2 x_i^2/2 + V` and :math:`V(x) = -\\int_0^1 f(s x)\\cdot x\\,ds`.
    """
    n = system.n
    if not system.frame.energy_may_be_conserved:
        return None  # a driven system exchanges energy with its drive
    xs, vs = system.state_symbols[:n], system.state_symbols[n:]
    forces = [sp.sympify(f).subs(subs) for f in system.rhs]
    if any(f.free_symbols & set(vs) for f in forces):
        return None
    jac = sp.Matrix(forces).jacobian(sp.Matrix(xs))
    if any(sp.simplify(jac[i, j] - jac[j, i]) != 0 for i in range(n) for j in range(i)):
        return None
    s = sp.Dummy("s")
    scaled = {x: s * x for x in xs}
    work = sp.integrate(
        sp.expand(
            sum(f.subs(scaled, simultaneous=True) * x for f, x in zip(forces, xs, strict=True))
        ),
        (s, 0, 1),
    )
    w2 = [sp.sympify(w**2).subs(subs) for w in system.frequencies]
    kinetic = sum(v**2 for v in vs) / 2
    return sp.expand(kinetic + sum(w2[i] * xs[i] ** 2 for i in range(n)) / 2 - work)


def lambdify_integrals(state, exprs) -> Callable:
    """``y -> array`` of the expressions ``exprs`` of the state symbols ``state``."""
    fn = numpy_lambdify(state, list(exprs), cse=True)

    def integrals(y):
        y = np.asarray(y, dtype=float)
        return np.array(np.broadcast_arrays(*fn(*y)), dtype=float)

    return integrals
