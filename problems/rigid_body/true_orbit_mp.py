"""The disk's true periodic orbit by a second, independent route: mpmath Taylor series, 40 digits.

:func:`problems.rigid_body.true_orbit.conditioned_true_orbit` resolves the orbit with heyoka in
quadruple precision, in conditioned coordinates, by a Gauss–Newton shooting on the variational
equations. This module gets the same orbit with none of that: the same exact equations
(:func:`~problems.rigid_body.exact_inputs.exact_equations`) and the same family member
(:class:`~problems.rigid_body.exact_inputs.FamilyMember`) are integrated by a Taylor method written
here in mpmath at :data:`DIGITS` significant digits (the equations are quadratic polynomials, so
the Taylor coefficients follow from Cauchy products), and the shooting is a Newton iteration on the
period-map defect in the physical coordinates (nondimensionalised), with a finite-difference
Jacobian. At 40 digits no conditioning is needed: the P-defect :math:`\\varphi|P|\\delta`
(:math:`\\varphi = 7.7\\times10^{-13}`) of a relative error :math:`\\delta = 10^{-9}` is ~1e-25 of
the state, far above the integration error (~1e-36).

It takes about a minute at the paper geometry (pure Python arithmetic): a slow test
(``tests/rigid_body/test_disk_true_orbit_routes.py``) and ``benchmarks/bench_true_orbit.py`` run it.
The result is read on the analytic solution's section :math:`\\dot G = 0` by the same reader as the
fast route (:func:`problems.rigid_body.true_orbit._move_to_section`, a measurement in float64 on the
converged state).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import mpmath
import numpy as np
import sympy as sp
from attrs import frozen

from perturb.oracle import OrbitRoute, OrbitStatus, PeriodicOrbit
from problems.rigid_body.exact_inputs import (
    FamilyMember,
    exact_epsilon,
    exact_equations,
    exact_values,
)

__all__ = ["DIGITS", "PolynomialField", "mp_true_orbit", "taylor_flow"]

#: Working precision (decimal digits) of the mpmath route; the brief asks >= 30. 40 leaves ~15
#: digits of margin over what the P-defect needs (see the module docstring).
DIGITS = 40
#: Taylor order: the cost per unit time ~ N**2 10**(DIGITS / N) is smallest near N = DIGITS ln(10)/2.
TAYLOR_ORDER = 46
#: Relative finite-difference step of the Newton Jacobian (digits: DIGITS/3 lost to the difference,
#: the truncation error h/|P| ~ 1e-13 is far below what Newton's convergence needs).
FD_STEP = mpmath.mpf(10) ** -13
#: Newton stops when the relative P-correction is below this (the result's resolution)...
STEP_TOL = mpmath.mpf(10) ** -12
#: ...or after this many iterations (quadratic convergence from the 1 % seed needs 4-5).
MAX_ITER = 12


@frozen
class PolynomialField:
    """:math:`\\dot x_i = c_i + \\sum_j a_{ij} x_j + \\sum_{j \\le l} b_{ijl} x_j x_l` in mpmath numbers.

    Attributes
    ----------
    constant : tuple of mpf
    linear : tuple of tuple of (j, mpf)
    quadratic : tuple of tuple of (j, l, mpf)
    """

    constant: tuple
    linear: tuple
    quadratic: tuple

    @classmethod
    def from_sympy(cls, state: Sequence[sp.Symbol], exprs: Sequence[sp.Expr]) -> PolynomialField:
        """From polynomial expressions of degree <= 2 with exact coefficients (rounded here once)."""
        constant, linear, quadratic = [], [], []
        for e in exprs:
            c, lin, quad = mpmath.mpf(0), [], []
            for monomial, coeff in sp.Poly(e, *state).terms():
                value = mpmath.mpf(sp.Rational(coeff).p) / sp.Rational(coeff).q
                powers = [i for i, n in enumerate(monomial) for _ in range(n)]
                if len(powers) == 0:
                    c = value
                elif len(powers) == 1:
                    lin.append((powers[0], value))
                elif len(powers) == 2:
                    quad.append((powers[0], powers[1], value))
                else:
                    raise ValueError(
                        f"`exprs` has a term of degree {len(powers)}: degree <= 2 only"
                    )
            constant.append(c)
            linear.append(tuple(lin))
            quadratic.append(tuple(quad))
        return cls(tuple(constant), tuple(linear), tuple(quadratic))

    def __call__(self, x: Sequence) -> list:
        return [
            self.constant[i]
            + sum((a * x[j] for j, a in self.linear[i]), mpmath.mpf(0))
            + sum((b * x[j] * x[m] for j, m, b in self.quadratic[i]), mpmath.mpf(0))
            for i in range(len(self.constant))
        ]

    def taylor(self, x: Sequence, order: int) -> list[list]:
        """Taylor coefficients :math:`X_i[k]`, :math:`k = 0..` ``order``, of the solution through ``x``.

        :math:`X_i[k+1] = F_i[k]/(k+1)`, with the coefficients of a product
        :math:`(x_jx_l)[k] = \\sum_{m \\le k} X_j[m]X_l[k-m]` (Cauchy product).
        """
        n = len(x)
        coeffs = [[mpmath.mpf(v)] for v in x]
        pairs = sorted({(j, m) for quad in self.quadratic for j, m, _ in quad})
        products = {pair: [] for pair in pairs}
        for k in range(order):
            for j, m in pairs:
                xj, xm = coeffs[j], coeffs[m]
                products[(j, m)].append(mpmath.fsum(xj[i] * xm[k - i] for i in range(k + 1)))
            for i in range(n):
                value = self.constant[i] if k == 0 else mpmath.mpf(0)
                value += mpmath.fsum(a * coeffs[j][k] for j, a in self.linear[i])
                value += mpmath.fsum(b * products[(j, m)][k] for j, m, b in self.quadratic[i])
                coeffs[i].append(value / (k + 1))
        return coeffs


def taylor_flow(field: PolynomialField, x0: Sequence, t_end, order: int = TAYLOR_ORDER) -> list:
    """:math:`x(t_{end})` from :math:`x(0) = x_0` by the Taylor method, in the current mpmath precision.

    The step :math:`h` makes the last two terms :math:`|X[N-1]|h^{N-1}`, :math:`|X[N]|h^N` (largest
    component) at most :math:`10^{-dps}`; the state should be scaled to O(1).
    """
    tol = mpmath.mpf(10) ** (-mpmath.mp.dps)
    x, t, t_end = [mpmath.mpf(v) for v in x0], mpmath.mpf(0), mpmath.mpf(t_end)
    while t < t_end:
        coeffs = field.taylor(x, order)
        last = max(abs(c[order]) for c in coeffs)
        before = max(abs(c[order - 1]) for c in coeffs)
        h = min(
            (tol / last) ** (mpmath.mpf(1) / order) if last else mpmath.inf,
            (tol / before) ** (mpmath.mpf(1) / (order - 1)) if before else mpmath.inf,
            t_end - t,
        )
        x = [mpmath.polyval(c[::-1], h) for c in coeffs]
        t += h
    return x


@frozen
class MpTrueOrbit:
    """The second route's orbit: a :class:`~perturb.oracle.PeriodicOrbit` and its 40-digit numbers.

    Attributes
    ----------
    orbit : PeriodicOrbit
        The orbit in float64 (``found_by`` :attr:`~perturb.oracle.OrbitRoute.MPMATH`): the state
        below, rounded, its period, ``residual`` the largest component of the period-map defect
        (scaled state), the Newton ``iterations``. No multipliers: the route's Jacobian is the
        finite differences of its free columns, not the monodromy.
    state : tuple of mpf
        (p, q, r, gamma, gamma', gamma'') at t = 0 on the section gamma' = const.
    period : mpf
        Physical period.
    alpha : mpf
        :math:`(r_0T - 2\\pi)/\\varepsilon^2`.
    beta1, beta2 : float
        :math:`P/\\varepsilon`, :math:`\\dot P/\\varepsilon` on the analytic solution's section dG = 0.
    last_step : float
        Relative size of the last Newton correction of (p, q) (the result's resolution).
    """

    orbit: PeriodicOrbit
    state: tuple
    period: object
    alpha: object
    beta1: float
    beta2: float
    last_step: float

    @property
    def iterations(self) -> int:
        """Newton iterations."""
        return self.orbit.iterations

    @property
    def defect(self) -> float:
        """Largest component of the period-map defect (scaled state) at the result."""
        return self.orbit.residual


def mp_true_orbit(problem, solution=None, digits: int = DIGITS) -> MpTrueOrbit:
    """The disk's true periodic orbit by the mpmath route (see the module docstring).

    Parameters
    ----------
    problem : the ``disk`` problem; its parameters are used exactly
        (:func:`~problems.rigid_body.exact_inputs.exact_values`).
    solution : PeriodicSolution, optional
        Seed, period guess and section (default: order 1), as for the fast route.
    digits : int
        mpmath precision (decimal digits).

    Raises
    ------
    RuntimeError
        If the Newton iteration does not reach :data:`STEP_TOL` in :data:`MAX_ITER` iterations.
    """
    from problems.rigid_body.true_orbit import _move_to_section

    if solution is None:
        solution = problem.solve(1)
    values = exact_values(problem)
    seed = np.asarray(problem.state_vector(solution, 0.0), dtype=float)
    member = FamilyMember.of(problem, seed)
    state, exprs = exact_equations(values)
    with mpmath.workdps(digits):
        r0 = mpmath.mpf(member.r0.p) / member.r0.q
        eps = mpmath.mpf(sp.N(exact_epsilon(values), digits + 10))
        # x = y / w in time tau = r0 t: p, q in units of c = eps r0 (a rational near it: any scale
        # is exact), r in units of r0; the coefficients stay exact rationals until here
        c = sp.Rational(str(sp.N(exact_epsilon(values) * member.r0, 12)))
        w = (c, c, member.r0, sp.Integer(1), sp.Integer(1), sp.Integer(1))
        x = sp.symbols("x0:6")
        scaled = [
            sp.expand(e.xreplace({state[i]: w[i] * x[i] for i in range(6)}) / (w[k] * member.r0))
            for k, e in enumerate(exprs)
        ]
        field = PolynomialField.from_sympy(x, scaled)
        start = [mpmath.mpf(v.p) / v.q for v in member.reference_state()]
        x0 = [start[i] / (mpmath.mpf(w[i].p) / w[i].q) for i in range(6)]
        tau = mpmath.mpf(problem.period(solution)) * r0
        free = (0, 1)
        iterations, last_step = 0, math.inf
        while True:
            end = taylor_flow(field, x0, tau)
            defect = mpmath.matrix([end[i] - x0[i] for i in range(6)])
            if last_step < STEP_TOL:
                break
            if iterations >= MAX_ITER:
                raise RuntimeError(
                    f"mpmath shooting: no convergence in {MAX_ITER} iterations (last relative "
                    f"step {last_step:.1e} > {float(STEP_TOL):.0e})"
                )
            iterations += 1
            jacobian = mpmath.matrix(6, 3)
            amplitude = mpmath.sqrt(x0[0] ** 2 + x0[1] ** 2)
            for col, i in enumerate(free):
                h = FD_STEP * amplitude
                shifted = list(x0)
                shifted[i] += h
                moved = taylor_flow(field, shifted, tau)
                for row in range(6):
                    jacobian[row, col] = (moved[row] - shifted[row] - defect[row]) / h
            velocity = field(end)  # d(defect)/d(tau) = f(x(tau))
            for row in range(6):
                jacobian[row, 2] = velocity[row]
            step = mpmath.qr_solve(jacobian, -defect)[0]
            x0[0] += step[0]
            x0[1] += step[1]
            tau += step[2]
            last_step = float(max(abs(step[0]), abs(step[1])) / amplitude)
        y = tuple(x0[i] * mpmath.mpf(w[i].p) / w[i].q for i in range(6))
        period = tau / r0
        alpha = (tau - 2 * mpmath.pi) / eps**2
        largest = float(max(abs(d) for d in defect))
    forward = problem.reduction().forward_function(problem.symbol_values(), problem.epsilon())
    _, z = _move_to_section(problem, np.array([float(v) for v in y]), forward)
    eps_float = problem.epsilon()
    orbit = PeriodicOrbit(
        period=float(period),
        initial_state=[float(v) for v in y],
        multipliers=np.empty(0, dtype=complex),
        monodromy=np.full((6, 6), math.nan),
        residual=largest,
        iterations=iterations,
        status=OrbitStatus.CONVERGED,
        message=(
            f"mpmath Taylor shooting ({digits} digits) converged in {iterations} iterations: "
            f"last relative step {last_step:.1e}, defect {largest:.1e}"
        ),
        integrator=f"mpmath Taylor order {TAYLOR_ORDER}",
        found_by=OrbitRoute.MPMATH,
        resolution=last_step,
    )
    return MpTrueOrbit(
        orbit=orbit,
        state=y,
        period=period,
        alpha=alpha,
        beta1=float(z[0] / eps_float),
        beta2=float(z[1] / eps_float),
        last_step=last_step,
    )
