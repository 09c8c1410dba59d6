"""The true steady states of a driven problem found by shooting alone: the independent count.

Forced shooting (:func:`perturb.oracle.find_forced_orbit`, the period given) from seeded random
initial states in a box, every converged orbit kept once: an orbit of p forcing periods is the
same as its images shifted by whole forcing periods (the state at t = kT/p), so those are matched
too. Nothing of the analytic construction is used; the count is a lower bound (an orbit whose
basin no start hits is missed), so the tests check it against the certified count both ways: no
true orbit outside the analytic branches, every analytic branch reached from its own seed.
"""

from __future__ import annotations

import math

import numpy as np
from attrs import frozen

from perturb.oracle import find_forced_orbit
from perturb.response import steady_state_of
from perturb.validation import original_equations
from perturb.validation.model import parameter_value_of

#: Two true orbits are one when their initial states agree to this, relative to their size (the
#: shooting converges to 1e-10; distinct steady states of the shipped problems differ by > 1e-3).
SAME_ORBIT = 1e-6


@frozen
class TrueOrbit:
    """A converged true steady state: its initial state (positions, velocities) and largest
    |Floquet multiplier|."""

    state: tuple
    largest_multiplier: float

    @property
    def stable(self) -> bool:
        return self.largest_multiplier < 1.0


def shooting_setup(problem):
    """``(rhs, period, shift)`` of a driven problem: the autonomous right-hand side with the
    phase last, the response's period (p forcing periods) and one forcing period."""
    system = problem.system()
    rhs = original_equations(problem, None).rhs
    omega = 2 * math.pi / problem.period(problem.solve(1)) * system.excitation.p
    forcing_period = 2 * math.pi / omega
    return rhs, system.excitation.p * forcing_period, forcing_period


def _images(rhs, state, shift: float, p: int):
    """The state after each of the p - 1 forcing periods (the same orbit, shifted)."""
    from perturb.oracle.registry import choose

    out = [np.asarray(state, dtype=float)]
    if p == 1:
        return out
    integrator = choose()
    y = np.append(np.asarray(state, dtype=float), 0.0)
    for k in range(1, p):
        traj = integrator.integrate(rhs, (0.0, k * shift), y)
        out.append(np.asarray(traj.y_final, dtype=float)[:-1])
    return out


def add_orbit(found: list, orbit, rhs, shift: float, p: int) -> bool:
    """Keep ``orbit`` unless it is one of ``found`` (or a shift of one); True when new."""
    state = np.asarray(orbit.initial_state, dtype=float)
    scale = max(1.0, float(np.max(np.abs(state))))
    for image in _images(rhs, state, shift, p):
        for known in found:
            if np.max(np.abs(image - np.asarray(known.state))) <= SAME_ORBIT * scale:
                return False
    largest = float(np.max(np.abs(orbit.floquet_multipliers)))
    found.append(TrueOrbit(tuple(state.tolist()), largest))
    return True


def census(problem, *, starts: int, box: float, seed: int) -> list[TrueOrbit]:
    """Distinct true steady states from ``starts`` seeded random initial states, each position
    and velocity uniform in [-box, box]."""
    rhs, period, shift = shooting_setup(problem)
    p = problem.system().excitation.p
    rng = np.random.default_rng(seed)
    m = rhs.n - 1
    found: list[TrueOrbit] = []
    for _ in range(starts):
        orbit = find_forced_orbit(rhs, rng.uniform(-box, box, m), period)
        if orbit.success:
            add_orbit(found, orbit, rhs, shift, p)
    return found


def seeded(problem, order: int = 1) -> list[tuple[str, object, object]]:
    """Per analytic branch: ``(name, its BranchPoint, the true orbit shot from its state)``."""
    from perturb.validation import state_along

    rhs, period, _ = shooting_setup(problem)
    state = steady_state_of(problem, order)
    out = []
    for name in state.names:
        solution = state.solution(name)
        y0 = [
            float(v[0])
            for v in state_along(
                solution, [0.0], parameter_value_of(problem), problem.symbol_values()
            ).values()
        ][:-1]
        point = state.points[state.names.index(name)]
        out.append((name, point, find_forced_orbit(rhs, y0, period)))
    return out
