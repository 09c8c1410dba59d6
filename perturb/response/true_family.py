"""A driven problem as a family of true responses along its swept parameter (for
:mod:`perturb.response.true_curve`): the shooting map of :class:`perturb.oracle.DrivenFamily` built
from the problem's system with its parameters symbolic, the map from the swept value to the
system's parameters (the problem's :class:`perturb.case.Case`: its values and exact rates at any
λ, the problem's own checks refusing a value outside its domain), the measures of a true orbit,
the scaled equations the continuation follows, and the Floquet test functions."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from perturb._defaults import (
    MAX_STEP_FRACTION,
    TRUE_CURVE_MARGIN,
    TRUE_CURVE_MULTIPLIER_TOL,
    TRUE_CURVE_SAMPLES,
)
from perturb.errors import PerturbError
from perturb.response.true_results import NEIMARK_SACKER, PERIOD_DOUBLING, TruePoint
from perturb.system import Regime
from perturb.validation.capabilities import label_of

if TYPE_CHECKING:
    from perturb.oracle import PeriodicOrbit

__all__ = ["OutsideDomain", "ScaledEquations", "TrueFamily", "floquet_tests"]


class OutsideDomain(PerturbError):
    """A parameter value the problem refuses (the message is the problem's)."""


class TrueFamily:
    """The problem's driven family along ``parameter``: symbols, parameter map, measures."""

    def __init__(self, problem, parameter: str, grid: np.ndarray, order: int, integrator=None):
        from perturb._lambdify import numpy_lambdify
        from perturb.method.driven import amplitude_equations
        from perturb.oracle import DrivenFamily
        from perturb.validation._quasilinear import excitation_frequency, first_order_expressions

        system = problem.system()
        self.problem, self.parameter, self.system, self.order = problem, parameter, system, order
        if system.initial_values:
            raise OutsideDomain("the system's equations contain initial values")
        from perturb.validation import as_model, original_equations

        if not original_equations(as_model(problem)).quasilinear:
            raise OutsideDomain(
                f"{label_of(problem)} gives its own original equations, and the true curve follows "
                "its quasilinear system's orbits: compare them with `perturb validate` instead"
            )
        drive = system.excitation
        self.cycles = drive.p
        self.params = (*system.parameters, system.parameter)
        exprs = first_order_expressions(system, {})
        self.expressions = tuple(exprs)
        self.frequency = excitation_frequency(system, {})
        self.family = DrivenFamily.build(
            system.state_symbols, drive.phase, exprs, self.frequency, self.params, drive.p,
            integrator,
        )  # fmt: skip
        self._omega = numpy_lambdify(self.params, self.frequency)
        self.names = [c.name for c in system.coordinates]
        self.n = system.n
        self.amplitude_equations = amplitude_equations(system, order)
        index = {c.name: i for i, c in enumerate(system.coordinates)}
        self.harmonics = {
            c: (index[c], int(m))
            for c, m in zip(
                self.amplitude_equations.coordinates, self.amplitude_equations.harmonics,
                strict=True,
            )
        }  # fmt: skip
        self._case = problem.case()
        self._values: dict[float, np.ndarray] = {}
        self._directions: dict[float, np.ndarray] = {}
        self._last_case: tuple = (math.nan, None)
        self.range = (float(grid[0]), float(grid[-1]))

    def continuation_range(self) -> tuple[float, float, float]:
        """The sweep widened by ``TRUE_CURVE_MARGIN`` of its width at each end, and the largest
        step (``MAX_STEP_FRACTION`` of the widened width). An end is widened only where the
        problem accepts the values one largest step beyond it (a predictor may overshoot the
        range by a step); where it does not (a parameter's own bound, e.g. F > 0), the curve ends
        at the sweep."""
        lo, hi = self.range
        margin = TRUE_CURVE_MARGIN * (hi - lo)
        step = MAX_STEP_FRACTION * (hi - lo + 2 * margin)
        ends = []
        for end, sign in ((lo, -1.0), (hi, 1.0)):
            try:
                self.values(end + sign * (margin + step))
            except OutsideDomain:
                ends.append(end)
            else:
                ends.append(end + sign * margin)
        return ends[0], ends[1], step

    def case(self, lam: float):
        """The problem's :class:`perturb.case.Case` at λ; OutsideDomain if the problem refuses it
        (the last one kept: the values and the direction ask for the same λ)."""
        lam = float(lam)
        if self._last_case[0] != lam:
            try:
                self._last_case = (lam, self._case.at(**{self.parameter: lam}))
            except ValueError as exc:  # the problem's own check: InvalidParameterError and kin
                raise OutsideDomain(f"{self.parameter} = {lam:.10g}: {exc}") from None
        return self._last_case[1]

    def values(self, lam: float) -> np.ndarray:
        """The system's parameter values (and its own ε or μ last) at λ; OutsideDomain if
        refused."""
        lam = float(lam)
        if lam not in self._values:
            case = self.case(lam)
            named = case.symbol_values
            missing = [p.name for p in self.params[:-1] if p.name not in named]
            if missing:
                raise OutsideDomain(f"the problem gives no value for {missing}")
            vector = [named[p.name] for p in self.params[:-1]] + [case.parameter_value]
            if len(self._values) > 4096:
                self._values.clear()
            self._values[lam] = np.array(vector, dtype=float)
        return self._values[lam]

    def direction(self, lam: float) -> np.ndarray:
        """dp/dλ at λ: the case's exact derivatives (of μ = 1/ε too, in the large regime); kept
        per λ like :meth:`values` (a corrector asks at the same λ for every shot)."""
        lam = float(lam)
        if lam not in self._directions:
            case = self.case(lam)
            rates, eps_rate = case.rate(self.parameter)
            own = eps_rate
            if self.system.regime is Regime.LARGE:
                own = -eps_rate / case.epsilon**2
            if len(self._directions) > 4096:
                self._directions.clear()
            self._directions[lam] = np.array(
                [rates.get(p.name, 0.0) for p in self.params[:-1]] + [own], dtype=float
            )
        return self._directions[lam]

    def omega(self, lam: float) -> float:
        return float(self._omega(*self.values(lam)))

    def point(self, lam: float, y0) -> TruePoint:
        """The true point at (y0, λ): a shot with the orbit sampled, its measures."""
        shot = self.family.shoot(y0, self.values(lam), self.direction(lam), TRUE_CURVE_SAMPLES)
        return self.point_of(lam, shot)

    def point_of(self, lam: float, shot) -> TruePoint:
        y0 = np.asarray(shot.initial_state)
        mu = shot.multipliers
        largest = float(np.max(np.abs(mu))) if np.all(np.isfinite(mu)) else math.nan
        stable = None if abs(largest - 1.0) <= TRUE_CURVE_MULTIPLIER_TOL else largest < 1.0
        if not math.isfinite(largest):
            stable = None
        defect = shot.defect
        residual = float(np.max(np.abs(defect))) / max(1.0, float(np.max(np.abs(y0))))
        orbit = self.orbit_at(lam, y0, shot.monodromy, mu, residual, 1, shot.message)
        return TruePoint(
            lam, orbit, self.norms(lam, y0), self._peaks(shot), self._harmonics(shot), stable
        )

    def point_of_orbit(self, lam: float, y0, monodromy, orbit, periods: int) -> TruePoint:
        """The true point of a response of ``periods`` response periods from its composed
        monodromy and its orbit sampled over all of them."""
        from perturb.oracle.orbit import multipliers_of

        mono = np.asarray(monodromy, dtype=float)
        mu = multipliers_of(mono) if np.all(np.isfinite(mono)) else np.full(len(y0), math.nan)
        largest = float(np.max(np.abs(mu))) if np.all(np.isfinite(mu)) else math.nan
        stable = None if abs(largest - 1.0) <= TRUE_CURVE_MULTIPLIER_TOL else largest < 1.0
        if not math.isfinite(largest):
            stable = None
        orbit = np.asarray(orbit)
        peaks = {name: _peak(orbit[i]) for i, name in enumerate(self.names)}
        found = self.orbit_at(lam, y0, mono, mu, math.nan, periods, "")
        return TruePoint(
            lam, found, self.norms(lam, y0), peaks, self._harmonics_of(orbit, periods), stable
        )

    def orbit_at(
        self, lam, y0, monodromy, multipliers, residual, periods, failure
    ) -> PeriodicOrbit:
        """The true orbit of a point on a continued curve (``periods`` response periods; its
        ``residual`` relative to the state's size, NaN where the composed map does not give
        it; ``failure`` the integrator's message when its shot failed)."""
        from perturb.oracle import OrbitRoute, OrbitStatus, PeriodicOrbit

        finite = bool(np.all(np.isfinite(monodromy)))
        status = OrbitStatus.CONVERGED if finite else OrbitStatus.INTEGRATION_FAILED
        return PeriodicOrbit(
            period=self.family.period * periods / self.omega(lam),
            initial_state=y0,
            multipliers=multipliers,
            monodromy=monodromy,
            residual=residual,
            iterations=0,
            status=status,
            message=failure or status.value,
            integrator=getattr(self.family.integrator, "name", ""),
            found_by=OrbitRoute.CONTINUATION,
        )

    def norms(self, lam: float, y0) -> dict:
        """The analytic curve's measure of each resonant coordinate at (y0, λ)."""
        nu = self.omega(lam) / self.cycles
        out = {}
        for name, (i, m) in self.harmonics.items():
            out[name] = math.hypot(float(y0[i]), float(y0[self.n + i]) / (m * nu))
        return out

    def _peaks(self, shot) -> dict:
        orbit = np.asarray(shot.orbit)
        if orbit.size == 0:
            return {name: math.nan for name in self.names}
        return {name: _peak(orbit[i]) for i, name in enumerate(self.names)}

    def _harmonics(self, shot) -> dict:
        return self._harmonics_of(np.asarray(shot.orbit), 1)

    def _harmonics_of(self, orbit: np.ndarray, periods: int) -> dict:
        out = {}
        for name, (i, m) in self.harmonics.items():
            if orbit.size == 0:
                out[name] = math.nan
                continue
            samples = orbit[i]
            k = np.arange(samples.size)
            # resonant harmonic m of s = θ/p: exp(-i m θ_k/p), θ_k = 2πp k/n
            phase = np.exp(-2j * math.pi * m * periods * k / samples.size)
            out[name] = float(2.0 * abs(np.sum(samples * phase)) / samples.size)
        return out


def _peak(samples: np.ndarray) -> float:
    """max ``|x|`` over a period from equally spaced samples, refined by the parabola through the
    largest sample and its neighbours (periodic)."""
    a = np.abs(samples)
    k = int(np.argmax(a))
    y0, y1, y2 = a[k - 1], a[k], a[(k + 1) % a.size]
    curvature = y0 - 2 * y1 + y2
    if curvature >= 0:
        return float(y1)
    shift = 0.5 * (y0 - y2) / curvature
    return float(y1 - 0.25 * (y0 - y2) * shift)


class ScaledEquations:
    """G(x) = R(y0, λ)·W/U on x = (y0·W/U, λ): the state scaled to the sweep's width W (U the
    amplitudes' scale), so that a step moves state and parameter alike; shots cached."""

    def __init__(self, setup: TrueFamily, scale: float, width: float):
        self.setup, self.width = setup, width
        self.factor = width / scale
        self.shots = 0
        self._cache: dict[bytes, object] = {}
        self.last_failure = ""

    def unscale(self, x) -> tuple[np.ndarray, float]:
        x = np.asarray(x, dtype=float)
        return x[:-1] / self.factor, float(x[-1])

    def scaled(self, y0, lam) -> np.ndarray:
        return np.append(np.asarray(y0, dtype=float) * self.factor, float(lam))

    def shot(self, x):
        key = np.asarray(x, dtype=float).tobytes()
        if key not in self._cache:
            y0, lam = self.unscale(x)
            setup = self.setup
            try:
                shot = setup.family.shoot(y0, setup.values(lam), setup.direction(lam))
            except OutsideDomain as exc:
                self.last_failure = str(exc)
                shot = None
            else:
                self.shots += 1
                if not shot.success:
                    self.last_failure = f"integration at {self.setup.parameter} = {lam:.10g}: " + (
                        shot.message
                    )
            if len(self._cache) > 8:
                self._cache.clear()
            self._cache[key] = shot
        return self._cache[key]

    def residual(self, x) -> np.ndarray:
        shot = self.shot(x)
        if shot is None or not shot.success:
            return np.full(len(x) - 1, math.nan)
        return shot.defect * self.factor

    def jacobian(self, x) -> np.ndarray:
        shot = self.shot(x)
        m = len(x) - 1
        if shot is None or not shot.success:
            return np.full((m, m + 1), math.nan)
        jac = np.array(shot.jacobian)
        jac[:, -1] *= self.factor
        return jac

    def domain(self, x) -> str:
        _, lam = self.unscale(x)
        try:
            self.setup.values(lam)
        except OutsideDomain as exc:
            return str(exc)
        return ""


def _monodromy(jac) -> np.ndarray:
    m = jac.shape[0]
    return np.asarray(jac[:, :m], dtype=float) + np.eye(m)


def floquet_tests():
    """The period-doubling and Neimark–Sacker test functions on J = [M − I | ·]."""
    from perturb.continuation import TestFunction
    from perturb.oracle import is_neimark_sacker, neimark_sacker_test, period_doubling_test

    def ns_value(x, t, jac):
        value = neimark_sacker_test(_monodromy(jac))
        # a conservative map: every pair's product is 1 and the test is round-off (module notes)
        return 0.0 if abs(value) <= TRUE_CURVE_MULTIPLIER_TOL else value

    def ns_kind(x, t, jac):
        found, _ = is_neimark_sacker(_monodromy(jac), math.sqrt(TRUE_CURVE_MULTIPLIER_TOL))
        return NEIMARK_SACKER if found else None

    return (
        TestFunction(PERIOD_DOUBLING, lambda x, t, jac: period_doubling_test(_monodromy(jac))),
        TestFunction(NEIMARK_SACKER, ns_value, ns_kind),
    )
