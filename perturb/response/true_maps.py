"""The maps whose fixed points are the true responses of a driven system, and the Newton refinement
of their special points (for :mod:`perturb.response.true_branches`).

* :class:`MapEquations`: the shooting map of ``k`` response periods, R_k(y₀, λ) = φᵏ(y₀) − y₀, its
  Jacobian [M_k − I | s_k] composed from k shots of one period (M_k = M(y_{k−1})⋯M(y₀),
  s_k = M(y_{k−1}) s_{k−1} + s(y_{k−1})): a response of k periods, born at a period doubling
  (k = 2) and its cascade; or the **half-period map** of a symmetric system,
  H(y₀) = −φ_{T/2}(y₀), whose fixed points are the symmetric responses
  (x(t + T/2) = −x(t)) and whose multiplier −1 is the symmetry-breaking pitchfork of the full map
  (M = (DH)² then has a +1 with the symmetric curve crossing the asymmetric pair).
* :func:`half_period_symmetry`: whether the equations of motion are invariant under
  (y, θ) → (−y, θ + T/2) (a forced Duffing, any odd restoring force forced by a cosine).
* :func:`refine`: a special point located as a regular zero of the minimally augmented system
  {R(y, λ) = 0, ψ(y, λ) = 0} (ψ one scalar test function of the monodromy: det(M − I) at a fold,
  det(M + I) at a period doubling, det(DH + I) at a symmetric pitchfork), by Newton's method with
  ψ's gradient by central differences of shots: quadratic until the differences' error, ~1e-8
  relative, then linear at that rate; a located point is a zero of R to the corrector's tolerance
  and of ψ to its rounding.

The state is scaled as :class:`~perturb.response.true_family.ScaledEquations` scales it (the
unknowns of a continuation weigh alike).
"""

from __future__ import annotations

import math

import numpy as np

from perturb._defaults import (
    REFINE_MAX_ITER,
    REFINE_STEP,
    REFINE_TOL,
    SYMMETRY_PROBES,
    SYMMETRY_SEED,
    SYMMETRY_TOL,
)
from perturb.response.true_family import OutsideDomain

__all__ = ["MapEquations", "half_period_symmetry", "refine"]


def half_period_symmetry(setup) -> bool:
    """Whether f(−y, θ + πp) = −f(y, θ) for the driven family's field (p the forcing periods of a
    response), at ``SYMMETRY_PROBES`` random points (a field that is not invariant changes by
    O(1) at almost every point)."""
    from perturb._lambdify import numpy_lambdify

    system = setup.system
    state = list(system.state_symbols)
    phase = system.excitation.phase
    params = list(setup.params)
    f = numpy_lambdify([*state, phase, *params], list(setup.expressions))
    rng = np.random.default_rng(SYMMETRY_SEED)
    shift = math.pi * setup.cycles
    for _ in range(SYMMETRY_PROBES):
        y = rng.uniform(0.2, 0.6, len(state))
        theta = float(rng.uniform(0.0, 2 * math.pi))
        p = rng.uniform(0.2, 0.6, len(params))
        a = np.asarray(f(*y, theta, *p), dtype=float)
        b = np.asarray(f(*(-y), theta + shift, *p), dtype=float)
        if float(np.max(np.abs(a + b))) > SYMMETRY_TOL * (1.0 + float(np.max(np.abs(a)))):
            return False
    return True


class MapEquations:
    """R(x) of a response of ``multiple`` periods (or the half-period map with ``half``) in the
    scaled unknowns x = (y₀·factor, λ); shots cached (see the module notes).

    Parameters
    ----------
    base : ScaledEquations
        The one-period equations (their setup, scale and counter of shots).
    multiple : int
        k: response periods of the map (1, 2, 4…).
    half : bool
        The half-period map H = −φ_{T/2} of a symmetric system instead (``multiple`` 1).
    """

    def __init__(self, base, multiple: int = 1, half: bool = False):
        self.base, self.setup, self.factor = base, base.setup, base.factor
        self.multiple, self.half = int(multiple), bool(half)
        self._cache: dict[bytes, object] = {}
        self.last_failure = ""

    @property
    def shots(self) -> int:
        return self.base.shots

    def unscale(self, x):
        return self.base.unscale(x)

    def scaled(self, y0, lam):
        return self.base.scaled(y0, lam)

    def domain(self, x) -> str:
        return self.base.domain(x)

    def compose(self, y0, lam: float, samples: int = 0):
        """``(end, M, s, orbit)`` of the map at (y0, λ), unscaled; None when a shot fails or λ is
        refused. ``orbit`` the state at ``samples`` equally spaced phases of each period."""
        setup = self.setup
        try:
            values, direction = setup.values(lam), setup.direction(lam)
        except OutsideDomain as exc:
            self.last_failure = str(exc)
            return None
        family = setup.family
        if self.half:
            shot = family.shoot(y0, values, direction, samples, span=family.period / 2)
            self.base.shots += 1
            if not shot.success:
                self.last_failure = shot.message
                return None
            return -shot.final_state, -shot.monodromy, -shot.sensitivity, shot.orbit
        m = len(y0)
        y, mono, sens, orbits = np.asarray(y0, dtype=float), np.eye(m), np.zeros(m), []
        for _ in range(self.multiple):
            shot = family.shoot(y, values, direction, samples)
            self.base.shots += 1
            if not shot.success:
                self.last_failure = shot.message
                return None
            mono = shot.monodromy @ mono
            sens = shot.monodromy @ sens + shot.sensitivity
            y = shot.final_state
            if samples:
                orbits.append(np.asarray(shot.orbit))
        orbit = np.hstack(orbits) if orbits else np.empty((m, 0))
        return y, mono, sens, orbit

    def _at(self, x):
        key = np.asarray(x, dtype=float).tobytes()
        if key not in self._cache:
            y0, lam = self.unscale(x)
            if len(self._cache) > 8:
                self._cache.clear()
            self._cache[key] = self.compose(y0, lam)
        return self._cache[key]

    def monodromy(self, x) -> np.ndarray | None:
        """The map's Jacobian in the state at the scaled point x (None: a failed shot)."""
        at = self._at(x)
        return None if at is None else at[1]

    def residual(self, x) -> np.ndarray:
        at = self._at(x)
        if at is None:
            return np.full(len(x) - 1, math.nan)
        y0, _ = self.unscale(x)
        return (at[0] - y0) * self.factor

    def jacobian(self, x) -> np.ndarray:
        at = self._at(x)
        m = len(x) - 1
        if at is None:
            return np.full((m, m + 1), math.nan)
        return np.column_stack((at[1] - np.eye(m), at[2] * self.factor))


def refine(equations: MapEquations, test, x0) -> tuple[np.ndarray | None, float]:
    """The zero of {R(x) = 0, ψ(x) = 0} near x0 by Newton's method (module notes).

    Parameters
    ----------
    equations : MapEquations
    test : callable
        ψ(M): a scalar of the map's monodromy M (its value changes sign at the special point).
    x0 : ndarray
        A scaled point near it (the secant's location on the curve).

    Returns
    -------
    (x or None, ψ there)
        None when Newton does not converge to ``REFINE_TOL`` within ``REFINE_MAX_ITER`` steps
        (the secant's point is then kept).
    """
    from perturb.continuation import CurveEquations, newton

    def psi(y):
        mono = equations.monodromy(y)
        return math.nan if mono is None else float(test(mono))

    def residual(x):
        return np.append(equations.residual(x), psi(x))

    def jacobian(x):
        jac = equations.jacobian(x)  # before the probes: the shot at x is still cached
        gradient = np.empty(len(x))
        for i in range(len(x)):
            h = REFINE_STEP * max(1.0, abs(float(x[i])))
            up, down = x.copy(), x.copy()
            up[i] += h
            down[i] -= h
            gradient[i] = (psi(up) - psi(down)) / (2 * h)
        return np.vstack((jac, gradient))

    def square_step(x, g, jac):
        return np.linalg.solve(jac, -g)

    found = newton(
        CurveEquations(residual, jacobian), x0, square_step, REFINE_MAX_ITER, REFINE_TOL,
        contracting=False, jacobian_at_end=False,
    )  # fmt: skip
    if not (found.converged and found.finite):
        return None, math.nan
    return found.x, psi(found.x)
