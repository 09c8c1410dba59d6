"""Many initial states of a driven system integrated together; only their stroboscopic returns.

:func:`ensemble` gives an :class:`Ensemble` whose :meth:`~Ensemble.returns` advances M states of
the section (all at the drive phase φ) by k drive periods and gives the k returns of each,
shape ``(k, M, m)`` — never a dense trajectory. Two routes:

* ``"heyoka"``: heyoka's batch Taylor integrator (``taylor_adaptive_batch``, one compiled
  integrator of :data:`~perturb._defaults.ENSEMBLE_LANES` lanes, SIMD across the lanes) with
  ``propagate_grid`` at the drive periods, tolerance :data:`~perturb._defaults.ENSEMBLE_TOL`;
* ``"numpy"``: the classical Runge–Kutta method vectorised over all M states at once,
  :data:`~perturb._defaults.ENSEMBLE_RK4_STEPS` steps a drive period (the fallback without
  heyoka).

θ is reset to φ at the start of every call (the equations are 2π-periodic in it, exactly), so a
long run loses no digits of the phase. A state that becomes non-finite (a blow-up) returns NaN
from then on.
"""

from __future__ import annotations

import copy
import functools
import math
import threading

import numpy as np
from attrs import field, frozen

from perturb._defaults import ENSEMBLE_LANES, ENSEMBLE_RK4_STEPS, ENSEMBLE_TOL
from perturb.errors import InvalidParameterError, bad_value
from perturb.oracle import heyoka_available

__all__ = ["BACKENDS", "Ensemble", "ensemble"]

#: The routes, by name.
BACKENDS = ("heyoka", "numpy")


@frozen
class Ensemble:
    """The stroboscopic map of a driven motion, applied to many states at once.

    Attributes
    ----------
    motion : DrivenMotion
    phase : float
        The section's drive phase φ (θ at every return, mod 2π).
    backend : str
        ``"heyoka"`` or ``"numpy"``.
    """

    motion: object = field(eq=False)
    phase: float
    backend: str

    @property
    def name(self) -> str:
        """The route and its settings, for reports."""
        if self.backend == "heyoka":
            return f"heyoka batch Taylor ({ENSEMBLE_LANES} lanes, tol {ENSEMBLE_TOL:g})"
        return f"numpy RK4 ({ENSEMBLE_RK4_STEPS} steps a drive period)"

    def returns(self, states, count: int) -> np.ndarray:
        """The ``count`` stroboscopic returns of each of ``states``.

        Parameters
        ----------
        states : array_like, shape (M, m)
            States on the section (θ = φ).
        count : int
            Drive periods (>= 1).

        Returns
        -------
        ndarray, shape (count, M, m)
            ``[k, j]`` is state j after k + 1 drive periods (NaN once it blew up).
        """
        y = np.array(states, dtype=float, ndmin=2)
        if y.shape[1:] != (self.motion.m,):
            raise bad_value(
                "states", y.shape, f"give an array of shape (M, {self.motion.m})",
                InvalidParameterError,
            )  # fmt: skip
        if count < 1 or y.shape[0] == 0:
            return np.empty((max(count, 0), y.shape[0], self.motion.m))
        if self.backend == "heyoka":
            return _heyoka_returns(self.motion, self.phase, y, int(count))
        return _rk4_returns(self.motion, self.phase, y, int(count))


def ensemble(motion, phase: float = 0.0, backend: str | None = None) -> Ensemble:
    """The ensemble integrator of ``motion`` on the section at drive phase ``phase``.

    Parameters
    ----------
    motion : DrivenMotion
    phase : float
        φ, radians.
    backend : {"heyoka", "numpy"}, optional
        Default: heyoka when installed, else numpy.

    Raises
    ------
    InvalidParameterError
        An unknown backend, heyoka asked for but not installed, a phase not finite.
    """
    if not math.isfinite(phase):
        raise bad_value("phase", phase, "give a finite drive phase (radians)",
                        InvalidParameterError)  # fmt: skip
    if backend is None:
        backend = "heyoka" if heyoka_available() else "numpy"
    if backend not in BACKENDS:
        raise bad_value("backend", backend, f"give one of {list(BACKENDS)}", InvalidParameterError)
    if backend == "heyoka" and not heyoka_available():
        from perturb._install import install_hint

        raise bad_value("backend", backend, f"heyoka is not installed ({install_hint('fast')}); "
                        "use 'numpy'", InvalidParameterError)  # fmt: skip
    return Ensemble(motion, float(phase), backend)


# ------------------------------------------------------------------------------ heyoka
@functools.lru_cache(maxsize=8)
def _compiled(rhs, lanes: int):
    """The batch integrator of ``rhs``, compiled once per process."""
    import heyoka as hy

    from perturb.dynamics.motion import heyoka_equations

    return hy.taylor_adaptive_batch(
        heyoka_equations(rhs), np.zeros((rhs.n, lanes)), tol=ENSEMBLE_TOL
    )


_THREAD = threading.local()


def _batch_integrator(rhs, lanes: int):
    """This thread's copy of the compiled integrator (an integrator holds its state: two threads
    of one process, e.g. Dask's threaded workers, must not share one)."""
    cache = getattr(_THREAD, "integrators", None)
    if cache is None:
        cache = _THREAD.integrators = {}
    key = (rhs, lanes)
    if key not in cache:
        cache[key] = copy.copy(_compiled(rhs, lanes))
    return cache[key]


def _heyoka_returns(motion, phase: float, y: np.ndarray, count: int) -> np.ndarray:
    lanes = ENSEMBLE_LANES
    integrator = _batch_integrator(motion.rhs, lanes)
    m, total = motion.m, y.shape[0]
    grid = np.repeat((motion.drive_period * np.arange(count + 1))[:, None], lanes, axis=1)
    out = np.empty((count, total, m))
    start = np.zeros((m + 1, lanes))
    for first in range(0, total, lanes):
        block = y[first : first + lanes]
        used = block.shape[0]
        start[:m, :used] = block.T
        start[:m, used:] = block[-1][:, None]  # idle lanes repeat a state (discarded)
        start[m, :] = phase
        integrator.set_time(0.0)
        integrator.state[:] = start
        _, samples = integrator.propagate_grid(grid)
        out[:, first : first + used, :] = np.transpose(samples[1:, :m, :used], (0, 2, 1))
    return out


# ------------------------------------------------------------------------------ numpy
def _rk4_returns(motion, phase: float, y: np.ndarray, count: int) -> np.ndarray:
    f = motion.vector_field()
    steps = ENSEMBLE_RK4_STEPS
    h = motion.drive_period / steps
    w = motion.omega
    state = y.T.copy()  # (m, M)
    out = np.empty((count, y.shape[0], motion.m))
    with np.errstate(all="ignore"):  # a blow-up becomes NaN, reported by the caller
        for k in range(count):
            for j in range(steps):
                theta = np.full(state.shape[1], phase + w * h * j)
                k1 = f(state, theta)
                k2 = f(state + 0.5 * h * k1, theta + 0.5 * h * w)
                k3 = f(state + 0.5 * h * k2, theta + 0.5 * h * w)
                k4 = f(state + h * k3, theta + h * w)
                state = state + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4)
            out[k] = state.T
    return out
