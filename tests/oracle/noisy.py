"""An integrator that emulates another machine: its last bits differ from this one's.

A different CPU, BLAS or library version changes the last bits of every integration. The
:class:`NoisyIntegrator` wraps a real integrator and adds to each final state a reproducible
perturbation of a chosen absolute size (seeded by the start), so a test can ask what a machine
whose floor is higher than ours would get. Given the shooting's augmented state (the state and
its n x n variational matrix), only the state is perturbed: a machine's last bits move the
monodromy by its own float64 rounding, not by the state's noise. Its error model is the one the shooting's precision
floor assumes: :meth:`loosened` makes the noise ``factor`` times larger along with the inner
integrator's tolerance. The perturbation is :func:`perturb.oracle._noise.perturbed`, the one the
suite-wide test noise (``PERTURB_TEST_NOISE``) adds to every integration.
"""

from __future__ import annotations

import math

import numpy as np
from attrs import frozen

from perturb.oracle._noise import perturbed
from perturb.oracle.base import IntegratorBase, Run


@frozen
class NoisyIntegrator(IntegratorBase):
    """``inner`` with a perturbation on each final state: ``level`` (absolute, an integration
    error) plus ``ulps`` float64 spacings of each component (the last bits of the machine)."""

    inner: IntegratorBase
    level: float = 0.0
    ulps: float = 0.0

    @property
    def name(self) -> str:
        return f"{self.inner.name} + noise {self.level:g} + {self.ulps:g} ulp"

    def loosened(self, factor: float) -> NoisyIntegrator:
        inner = self.inner.loosened(factor) or self.inner
        return NoisyIntegrator(inner, self.level * factor, self.ulps * factor)

    def _accept_rhs(self, rhs) -> None:
        self.inner._accept_rhs(rhs)

    def _integrate_impl(self, rhs, t0, t1, y0, grid, jac) -> Run:
        run = self.inner._integrate_impl(rhs, t0, t1, y0, grid, jac)
        if len(run.states) == 0:
            return run
        # copies in the inner integrator's own type: the template's test noise (PERTURB_TEST_NOISE)
        # then moves them by ulps of that type, as it would the inner integrator's
        states = [np.array(state) for state in run.states]
        size = states[-1].size
        n = math.isqrt(4 * size + 1) // 2  # size = n + n**2 for the shooting's augmented state
        n = n if n + n * n == size else size
        # the same start gives the same noise: a machine is deterministic, only different
        start = np.asarray(y0, dtype=float)
        moved = perturbed(states[-1][:n].astype(float), self.ulps, start, level=self.level)
        states[-1][:n] = moved.astype(states[-1].dtype)
        return Run(run.t, states, run.t_reached, run.nfev, run.status, run.message)
