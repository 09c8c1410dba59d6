"""Shared machinery of the fast-spin rigid-body problems (``disk`` and ``rigid-body``).

Both problems take the same physical parameters, reduce the dimensionless Euler–Poisson system
(:math:`\\tau = r_0 t`, :math:`\\varepsilon = c/r_0`, :math:`c = \\sqrt{Mgl/C}`) to a quasilinear system
in :math:`(P, G)` with :mod:`problems.rigid_body.reduction`, and map the periodic solution back to the
physical state :math:`(p, q, r, \\gamma, \\gamma', \\gamma'')` in physical time.
"""

from __future__ import annotations

import math
import warnings
from abc import abstractmethod
from functools import cache, lru_cache

import attrs
import numpy as np
import sympy as sp

from perturb import PeriodicSolution, PoincareMethod
from perturb.errors import AccuracyWarning, InvalidParameterError
from perturb.oracle import SymbolicRHS
from perturb.validation import Condition, Equations, Integrals
from problems.base import (
    _SOLUTION_CACHE,
    ParameterSpec,
    Problem,
    _class_key,
    _options_key,
    positive,
)
from problems.rigid_body import equations as eq
from problems.rigid_body import numeric
from problems.rigid_body._stored import stored
from problems.rigid_body.euler_angles import angles_from_state, precession_by_quadrature
from problems.rigid_body.reduction import (
    INITIAL_VALUES,
    SPECIALISED_CACHE_SIZE,
    Reduction,
    check_gamma3_0,
)

__all__ = ["FastSpinBody", "INTEGRAL_NAMES", "STATE_NAMES", "geometric_constraint"]

#: Names of the physical state components, in the order of :func:`numeric.full_rhs`.
STATE_NAMES = ("p", "q", "r", "gamma1", "gamma2", "gamma3")
#: Names of the first integrals, in the order of :func:`numeric.integrals_function`.
INTEGRAL_NAMES = ("energy", "area", "geometric")
#: Above this value of eps = c/r0 the fast-spin expansion is not even qualitatively right
#: (reference section (f): at eps = 232 the motion is tumbling). It is also the limit of the
#: validity condition "eps = c/r0 small" (:meth:`FastSpinBody.validity_conditions`).
EPSILON_WARN = 0.1
#: Relative tolerance of the reference integration (the reference's oracle: integral drift <= 1e-11).
ORACLE_RTOL = 1e-12
#: Periods followed by :meth:`FastSpinBody.true_motion_errors` by default.
TRACK_PERIODS = 5
#: Reductions found for solutions (:meth:`FastSpinBody._reduction_of`), by solution, class and
#: (for a solution specialised to numbers) the body's values; at most REDUCTIONS_KEPT of them.
_REDUCTIONS: dict[tuple, tuple] = {}
REDUCTIONS_KEPT = 256
#: The values the Euler–Poisson equations contain (the initial state's r0, gamma3_0 do not).
_BODY_DATA = ("A", "B", "C", "M", "g", "R", "x0", "y0", "z0")


def _direction_cosine(value: float) -> str | None:
    return None if abs(value) <= 1 else "a direction cosine needs |gamma3_0| <= 1"


def _spin(value: float) -> str | None:
    if value > 0:
        return None
    return "give the initial spin r0 > 0 (the scaling tau = r0 t needs it; flip the body axes for r0 < 0)"


def _distance(value: float) -> str | None:
    return None if value > 0 else "give R > 0 (R = inf: no Newtonian centre, k = 0)"


def body_parameter_specs(
    A: float, B: float, C: float, z0: float, gamma3_0: float, r0: float
) -> tuple[ParameterSpec, ...]:
    """The common parameter list with problem-specific defaults for A, B, C, z0, gamma3_0, r0."""
    return (
        ParameterSpec("A", A, "principal moment of inertia about x at the fixed point", positive),
        ParameterSpec("B", B, "principal moment of inertia about y", positive),
        ParameterSpec("C", C, "principal moment of inertia about z (the spin axis)", positive),
        ParameterSpec("M", 200.0, "mass of the body", positive),
        ParameterSpec("g", 1.5e-7, "field strength at the fixed point", positive),
        ParameterSpec(
            "R", 2000.0, "distance of the Newtonian centre (inf: none)", _distance, allow_inf=True
        ),
        ParameterSpec("x0", 1.0, "centre of mass, x body coordinate"),
        ParameterSpec("y0", 6.0, "centre of mass, y body coordinate"),
        ParameterSpec("z0", z0, "centre of mass, z body coordinate"),
        ParameterSpec("r0", r0, "initial spin about the body z axis (fast: r0 >> c)", _spin),
        ParameterSpec(
            "gamma3_0",
            gamma3_0,
            "initial cosine between body z and the vertical",
            _direction_cosine,
        ),
    )


@lru_cache(maxsize=SPECIALISED_CACHE_SIZE)  # asked for by every solve and its frame
def geometric_constraint(reduction: Reduction) -> sp.Expr:
    """G(0) from the geometric integral :math:`|\\gamma(0)|^2 = 1` (phase fixed by dG(0) = 0).

    The reduction's ``initial_full_state`` gives :math:`\\gamma(0), \\gamma'(0), \\gamma''(0)` in the
    initial values; with :math:`\\dot G(0) = 0` the constraint is solved for :math:`G_0`, taking the
    root with :math:`\\gamma(0) > 0`. :math:`\\gamma(0) - G_0` does not contain :math:`G_0`.

    Kept on disk (kind ``geometric-constraint``) under the reduction's kind, order and values
    and the sources that derive it: a warm run builds no sympy expression for it.
    """
    return stored(
        "geometric-constraint",
        ("_body.py", "reduction.py", "_elimination.py", "_series_ring.py", "equations.py"),
        (reduction.kind, reduction.order, reduction.values),
        lambda: _geometric_constraint(reduction),
    )


def _geometric_constraint(reduction: Reduction) -> sp.Expr:
    """:func:`geometric_constraint`, derived."""
    p0, g0, dp0, dg0 = INITIAL_VALUES
    g1, g2, g3 = reduction.initial_full_state[3:]
    g2 = g2.subs(dg0, 0)
    shift = sp.expand(g1 - g0)
    if shift.has(g0) or g2.has(g0) or g3.has(g0):
        raise AssertionError("gamma(0) - G0, gamma'(0) or gamma''(0) depends on G0")
    return sp.sqrt(1 - g3**2 - g2**2) - shift


#: The arm l of gravity's torque: the centre of mass's distance from the spin axis.
ARM = "sqrt(x0**2 + y0**2)"
#: The body's user parameters -> the reduction's dimensionless symbols and ε.
BODY_PARAMETER_MAP = {
    "a": "A/C",
    "b": "B/C",
    "k": f"3*C/(R*M*{ARM})",
    "x0p": f"x0/{ARM}",
    "y0p": f"y0/{ARM}",
    "epsilon": f"sqrt(M*g*{ARM}/C)/r0",
}


class FastSpinBody(Problem):
    """Base of the fast-spin body problems (abstract: see :class:`problems.base.Problem`)."""

    #: Whether the reduced parameters include z0' (the general body).
    uses_z0 = False
    #: The dimensionless parameters of the reduction (:meth:`symbol_values` gives their values).
    parameter_symbols: tuple[sp.Symbol, ...] = ()
    #: The reduction's dimensionless parameters and ε = c/r0 (the paper's 1/μ), c = sqrt(Mgl/C)
    #: with the arm l = sqrt(x0² + y0²).
    parameter_map = BODY_PARAMETER_MAP

    # ------------------------------------------------------------------ to provide
    @classmethod
    @abstractmethod
    def reduction_for(cls, order: int) -> Reduction:
        """The reduction whose truncation suffices for a solution of ``order``."""

    @classmethod
    @abstractmethod
    def specialised_reduction_for(cls, order: int, values: dict) -> Reduction:
        """:meth:`reduction_for` with the parameters put in (exact ``values``) before the reduction."""

    @classmethod
    def reduction(cls) -> Reduction:
        """The reduction of the class's system (the one :meth:`system` returns)."""
        return cls.reduction_for(1)

    @classmethod
    def build_system(cls):
        return cls.reduction().system

    # ------------------------------------------------------------------ validation
    def check_values(self, values) -> None:
        if values["x0"] == 0 and values["y0"] == 0:
            raise InvalidParameterError(
                "`x0` = 0 is invalid together with y0 = 0: the centre of mass on the spin axis "
                "(l = 0) gives c = 0; give x0 or y0 != 0"
            )
        eq._check_triangle({"A": values["A"], "B": values["B"], "C": values["C"]})
        check_gamma3_0(values["gamma3_0"])
        if abs(values["gamma3_0"]) == 1:
            raise InvalidParameterError(
                f"`gamma3_0` = {values['gamma3_0']:g} is invalid: with the spin axis vertical the "
                "generating amplitude M3 = sqrt(1 - gamma3_0**2) vanishes; give |gamma3_0| < 1"
            )

    # ------------------------------------------------------------------ scales
    def body(self) -> eq.RigidBodyParameters:
        """The dimensional body data."""
        v = self.values
        return eq.RigidBodyParameters(
            A=v["A"], B=v["B"], C=v["C"], x0=v["x0"], y0=v["y0"], z0=v["z0"], M=v["M"], g=v["g"],
            R=v["R"],
        )  # fmt: skip

    def scale_c(self) -> float:
        """:math:`c = \\sqrt{Mgl/C}` (angular-velocity scale of gravity)."""
        v = self.values
        return math.sqrt(v["M"] * v["g"] * math.hypot(v["x0"], v["y0"]) / v["C"])

    # ------------------------------------------------------------------ solving
    def _selection_options(self) -> dict:
        """The method options besides the amplitude constraint (which root, which phase)."""
        return {"phase_coordinate": "G"}

    def method_options(self) -> dict:
        return {
            "amplitudes": {"G": geometric_constraint(self.reduction())},
            **self._selection_options(),
        }

    #: Orders up to which the solution is kept symbolic in the body's parameters (one derivation
    #: serves every body, and exports LaTeX); above it the parameters are put in first, as exact
    #: rationals, which keeps the construction to seconds instead of minutes.
    SYMBOLIC_MAX_ORDER: int = 1

    def symbolic_derivation(self) -> FastSpinBody:
        """This body with its solution derived symbolic in its parameters
        (``solve(symbolic=True)``): a sweep derives once with it (the capability
        :class:`perturb.sweep.derive.SymbolicDerivation`)."""
        return attrs.evolve(self, symbolic=True)

    def exact_values(self) -> dict[sp.Symbol, sp.Rational]:
        """The body's dimensionless parameters as exact rationals (the decimal values given)."""
        values = self.symbol_values()
        return dict(_exact(tuple((p, values[p.name]) for p in self.parameter_symbols)))

    def _solving_reduction(self, order: int, symbolic: bool | None = None) -> Reduction:
        """The reduction :meth:`solve` uses at ``order`` (see its ``symbolic``)."""
        if symbolic is None:
            symbolic = order <= self.SYMBOLIC_MAX_ORDER
        if not symbolic:
            return self.specialised_reduction_for(order, self.exact_values())
        return self.reduction_for(order)

    def _frame(self, order: int, symbolic: bool | None = None) -> tuple:
        """The reduction, its system, the method options and the exact values put in (if any)."""
        reduction = self._solving_reduction(order, symbolic)
        options = {
            "amplitudes": {"G": geometric_constraint(reduction)},
            **self._selection_options(),
        }
        return reduction, reduction.system, options, dict(reduction.values)

    def _family_options(self, order: int) -> tuple:
        """The frame of :meth:`families`: the reduced system and options of :meth:`solve`."""
        _, system, options, _ = self._frame(order)
        return system, {k: v for k, v in options.items() if k != "branch"}

    def solve(self, order: int = 1, *, symbolic: bool | None = None) -> PeriodicSolution:
        """The periodic solution of ``order`` (cached; higher orders use a longer reduction).

        Parameters
        ----------
        order : int
            Order of the solution in epsilon.
        symbolic : bool, optional
            ``True``: the solution symbolic in the body's dimensionless parameters, derived once
            and shared by every parameter set (memory and disk cache) — the route for a sweep
            over parameters, and for formulas in the parameters (disk order 2 about 3 s, order 3
            about 13 s of CPU, cold). ``False``: derived for this body's parameter values,
            converted to exact rationals (no rounding enters the construction; the result is
            exact for the decimal values given); the values are put in before the reduction
            (:func:`~problems.rigid_body.reduction.specialised_disk_reduction`), which gives the
            same system as putting them into the symbolic one, faster for one parameter set.
            ``None`` (default): symbolic up to :attr:`SYMBOLIC_MAX_ORDER`, specialised above.
            Either way :meth:`state` and :meth:`period` evaluate it at this body's values.
        """
        if symbolic is not None and not isinstance(symbolic, bool):
            raise InvalidParameterError(
                f"`symbolic` = {symbolic!r} is invalid: pass True (symbolic in the body's "
                "parameters), False (for this body's values) or None (the default choice)"
            )
        if self._family is not None:
            return self._family_solution(order, self._family)
        symbolic = self._symbolic if symbolic is None else symbolic
        reduction, system, options, values = self._frame(order, symbolic)
        key = (
            *_class_key(type(self)),
            order,
            reduction.order,
            _options_key(options),
            repr(sorted((str(k), v) for k, v in values.items())),
        )
        if key not in _SOLUTION_CACHE:
            method = PoincareMethod(order=order, **options)
            _SOLUTION_CACHE[key] = method.solve(system)
        return _SOLUTION_CACHE[key]

    def _reduction_of(self, solution: PeriodicSolution) -> Reduction:
        """The reduction whose system ``solution`` solves (kept per solution: the comparison of
        two systems is sympy's, and every state asks for it)."""
        symbolic = bool(solution.system.parameters)
        values = None if symbolic else tuple(sorted(self.symbol_values().items()))
        key = (id(solution), type(self), values)
        kept = _REDUCTIONS.get(key)
        if kept is not None and kept[0] is solution:
            return kept[1]
        reduction = self._find_reduction(solution, symbolic)
        if len(_REDUCTIONS) >= REDUCTIONS_KEPT:
            _REDUCTIONS.clear()
        _REDUCTIONS[key] = (solution, reduction)  # the solution kept: its id is not reused
        return reduction

    def _find_reduction(self, solution: PeriodicSolution, symbolic: bool) -> Reduction:
        orders = [solution.order, *range(1, solution.order)]
        for order in orders:
            if symbolic and order > self.SYMBOLIC_MAX_ORDER:
                # that candidate is specialised (no parameters left), so it cannot be this
                # solution's: skip deriving it (a sweep evaluates a symbolic solution everywhere)
                continue
            candidate = self._solving_reduction(order)
            if candidate.system == solution.system or candidate.system.rhs == solution.system.rhs:
                return candidate
        if solution.system.parameters:
            return self.reduction_for(solution.order)
        return self.specialised_reduction_for(solution.order, self.exact_values())

    # ------------------------------------------------------------------ physical state
    def state_names(self) -> tuple[str, ...]:
        return STATE_NAMES

    def nondimensional_state(self, solution: PeriodicSolution, tau) -> np.ndarray:
        """:math:`(p_1, q_1, r_1, \\gamma, \\gamma', \\gamma'')` at :math:`\\tau = r_0 t` (shape (6, ...))."""
        eps = self.epsilon()
        values = self.symbol_values()
        pv = _user_parameter(solution, eps)
        reduced = solution.evaluate(tau, pv, values)
        z0 = solution.initial_state(pv, values)
        names = solution.state_names
        z = {n: reduced[i] for i, n in enumerate(names)}
        z_start = dict(zip(names, z0, strict=True))
        inverse = self._reduction_of(solution).inverse_function(values, eps)
        return inverse(
            (z["P"], z["dP"], z["G"], z["dG"]),
            (z_start["P"], z_start["G"], z_start["dP"], z_start["dG"]),
        )

    def state(self, solution: PeriodicSolution, t) -> dict[str, np.ndarray]:
        """The physical state at physical times ``t``: p = c p1, q = c q1, r = r0 r1, gammas."""
        t = np.asarray(t, dtype=float)
        r0 = self.values["r0"]
        eps = self.epsilon()
        if eps >= EPSILON_WARN:
            warnings.warn(
                f"eps = c/r0 = {eps:.4g} is not small: the fast-spin series does not describe the "
                "motion (give a larger r0)",
                AccuracyWarning,
                stacklevel=2,
            )
        y = self.nondimensional_state(solution, r0 * t)
        c = self.scale_c()
        scales = (c, c, r0, 1.0, 1.0, 1.0)
        return {n: s * y[i] for i, (n, s) in enumerate(zip(STATE_NAMES, scales, strict=True))}

    def state_vector(self, solution: PeriodicSolution, t) -> np.ndarray:
        """:meth:`state` stacked as an array of shape (6, ...)."""
        s = self.state(solution, t)
        return np.array([s[n] for n in STATE_NAMES])

    def period(self, solution: PeriodicSolution) -> float:
        """The period in physical time, :math:`T_\\tau / r_0`."""
        pv = _user_parameter(solution, self.epsilon())
        return float(solution.period_at(pv, self.symbol_values())) / self.values["r0"]

    def report_extras(self) -> dict:
        eps = self.epsilon()
        sentence = (
            "fast-spin expansion in eps = c/r0 = 1/mu (the paper calls it a slow-spin, "
            "large-parameter technique, but it is the same series): valid only for eps << 1, "
            "i.e. r0 >> c"
        )
        if eps >= EPSILON_WARN:
            sentence += f"; here eps = {eps:.4g}, so the solution does NOT describe the motion"
        return {"mu": 1.0 / eps, "regime": sentence}

    def euler_angles(self, solution: PeriodicSolution, t) -> dict[str, np.ndarray]:
        """Euler angles (z-x-z) along the solution: theta, psi (psi(0) = 0), phi."""
        t = np.asarray(t, dtype=float)
        s = self.state(solution, t)
        theta, phi = angles_from_state(s["gamma1"], s["gamma2"], s["gamma3"])
        psi = precession_by_quadrature(
            lambda times: self.state(solution, times), t, self.period(solution)
        )
        return {"theta": theta, "psi": psi, "phi": phi}

    # ------------------------------------------------------------------ original equations
    def original_rhs(self, solution: PeriodicSolution | None = None):
        """The dimensional Euler–Poisson right-hand side ``f(t, y)`` on (p, q, r, gammas)."""
        return numeric.full_rhs(self.body())

    def original_jacobian(self):
        """Jacobian ``J(t, y)`` of :meth:`original_rhs`."""
        return numeric.full_jacobian(self.body())

    def original_symbolic(self) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Expr, ...]]:
        """(state symbols, rhs expressions with every number substituted), e.g. for heyoka."""
        # keyed by the body's data alone: r0 and gamma3_0 do not enter the equations, so every
        # point of a sweep over them shares one field (and its compiled integrators)
        return _symbolic_rhs(tuple(sorted((name, self.values[name]) for name in _BODY_DATA)))

    def true_motion_errors(
        self, solution: PeriodicSolution, periods: float = TRACK_PERIODS, samples: int = 200
    ) -> dict[str, float]:
        """Largest errors of the analytic state against the integrated Euler–Poisson motion.

        The full dimensional system is integrated (scipy DOP853, ``rtol = ORACLE_RTOL``, absolute
        tolerances scaled per component) from the analytic state at ``t = 0`` over ``periods``
        periods. Errors are in the natural scales: p, q over c, r over r0, the gammas as they are.

        Returns
        -------
        dict
            ``{name: max |analytic - true| / scale}`` and ``"integrals"``, the largest relative drift
            of the energy, area and geometric integrals along the integrated trajectory.
        """
        from scipy.integrate import solve_ivp

        period = self.period(solution)
        t = np.linspace(0.0, periods * period, samples)
        analytic = self.state_vector(solution, t)
        c, r0 = self.scale_c(), self.values["r0"]
        scales = np.array([c, c, r0, 1.0, 1.0, 1.0])
        result = solve_ivp(
            self.original_rhs(),
            (0.0, t[-1]),
            analytic[:, 0],
            method="DOP853",
            rtol=ORACLE_RTOL,
            atol=ORACLE_RTOL * scales,
            t_eval=t,
        )
        if not result.success:
            raise RuntimeError(f"the Euler–Poisson integration failed: {result.message}")
        errors = np.max(np.abs(analytic - result.y), axis=1) / scales
        out = dict(zip(STATE_NAMES, map(float, errors), strict=True))
        ints = self.integrals(result.y)
        drift = np.max(np.abs(ints - ints[:, :1]), axis=1) / np.maximum(np.abs(ints[:, 0]), 1e-300)
        out["integrals"] = float(np.max(drift))
        return out

    # ------------------------------------------------------------------ validation (Model)
    def original_equations(self, y0=None) -> Equations:
        """The dimensional Euler–Poisson equations on (p, q, r, gammas), symbolic (one field
        object per body, so that what is derived from it is derived once)."""
        return Equations(_body_field(tuple(sorted((n, self.values[n]) for n in _BODY_DATA))))

    def integrals_of_motion(self, y0=None) -> Integrals:
        """Energy, area and geometric integrals of the physical state."""
        return Integrals(numeric.integrals_function(self.body()), INTEGRAL_NAMES)

    def validity_estimates(self) -> tuple[Condition, ...]:
        """Estimates of the fast-spin expansion's domain (they warn; the verdict is measured)."""
        return tuple(Condition(*item) for item in self.validity_conditions())

    def validity_conditions(self) -> list[tuple[str, float, bool, str]]:
        """Conditions of the fast-spin expansion (read by :meth:`validity_estimates`).

        Returns
        -------
        list of (name, value, ok, sentence)
            ``"ε = c/r0 small"`` (:data:`EPSILON_WARN`) and the problem's own conditions
            (:meth:`_specific_conditions`).
        """
        eps = self.epsilon()
        ok = eps <= EPSILON_WARN
        sentence = (
            f"the spin must be fast: eps = c/r0 = {eps:.6g} <= {EPSILON_WARN:g}"
            if ok
            else f"eps = c/r0 = {eps:.6g} > {EPSILON_WARN:g}: the spin r0 = "
            f"{self.values['r0']:.6g} is not fast compared with c = sqrt(Mgl/C) = "
            f"{self.scale_c():.6g}, so the fast-spin series does not describe the motion (give "
            f"r0 >= c/{EPSILON_WARN:g} = {self.scale_c() / EPSILON_WARN:.6g})"
        )
        return [("ε = c/r0 small", eps, ok, sentence), *self._specific_conditions()]

    def _specific_conditions(self) -> list[tuple[str, float, bool, str]]:
        """Problem-specific validity conditions (none in the base class)."""
        return []

    def first_integrals_function(self):
        """``y -> (energy, area, geometric)`` of physical states ``y`` (shape (6,) or (6, n)).

        The returned callable carries ``.names`` = :data:`INTEGRAL_NAMES`.
        """
        return _NamedIntegrals(numeric.integrals_function(self.body()))

    def integrals(self, y) -> np.ndarray:
        """(energy, area, geometric) of physical states ``y`` (shape (6,) or (6, n))."""
        return numeric.integrals_function(self.body())(y)


class _NamedIntegrals:
    """A first-integrals function with the ``names`` attribute :func:`validate` reads."""

    names = INTEGRAL_NAMES

    def __init__(self, function):
        self._function = function

    def __call__(self, y) -> np.ndarray:
        return self._function(y)


@lru_cache(maxsize=256)
def _exact(pairs: tuple) -> tuple:
    """``(symbol, float)`` pairs as ``(symbol, Rational)`` (``nsimplify`` is slow: kept)."""
    return tuple((p, sp.nsimplify(value, rational=True)) for p, value in pairs)


def _user_parameter(solution: PeriodicSolution, eps: float) -> float:
    from perturb import Regime

    return 1.0 / eps if solution.system.regime is Regime.LARGE else eps


@lru_cache(maxsize=SPECIALISED_CACHE_SIZE)
def _body_field(body: tuple) -> SymbolicRHS:
    """The Euler–Poisson field of the body ``body`` ((name, value) pairs), one object per body."""
    return SymbolicRHS(*_symbolic_rhs(body))


@cache
def _symbolic_rhs(items: tuple) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Expr, ...]]:
    values = dict(items)
    body = tuple((name, values[name]) for name in _BODY_DATA)  # r0 and gamma3_0 do not enter
    rhs = stored("body-rhs", ("equations.py", "_body.py"), body, lambda: _rhs_with_values(body))
    return eq.DIMENSIONAL_STATE, rhs


def _rhs_with_values(items: tuple) -> tuple[sp.Expr, ...]:
    """The Euler–Poisson right-hand sides with the values ``items`` (name, float) put in."""
    v = dict(items)
    distance = sp.oo if math.isinf(v["R"]) else v["R"]
    rhs = eq.euler_poisson_equations(distance)
    subs = {
        eq.A: v["A"], eq.B: v["B"], eq.C: v["C"], eq.M: v["M"], eq.g: v["g"],
        eq.x0: v["x0"], eq.y0: v["y0"], eq.z0: v["z0"],
    }  # fmt: skip
    if not math.isinf(v["R"]):
        subs[eq.R] = v["R"]
    return tuple(sp.expand(e.subs(subs)) for e in rhs)
