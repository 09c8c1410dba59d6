"""The disk's true periodic orbit by a conditioned, extended-precision shooting.

The P-oscillation of the disk is detuned from the G-oscillation by only :math:`\\varepsilon^2 D`,
:math:`D = kM_3^2/2`: its Floquet multipliers are :math:`e^{\\pm i\\varphi}`,
:math:`\\varphi = 2\\pi\\varepsilon^2 D`, so an error :math:`\\delta` (relative) in :math:`P(0)` changes
the periodicity defect by only :math:`\\varphi\\delta|P|`. At the paper geometry
(:math:`\\varepsilon = 10^{-4}`, :math:`k = 2.47\\times10^{-5}`) :math:`\\varphi = 7.7\\times10^{-13}`,
below float64 round-off: a plain shooting accepts any seed within ~1 % as "converged".
:func:`conditioned_true_orbit` runs the same (full Euler–Poisson) equations in conditioned coordinates:

1. the state relative to the seed, :math:`y = y_{ref} + s\\,u` (no cancellation in
   :math:`u(T) - u(0)`), with :math:`s_p = s_q = \\varphi|P|\\,` :data:`RESOLUTION` / :data:`TOL`, so
   that a relative error :data:`RESOLUTION` in :math:`P(0)` shows as a residual :data:`TOL`;
2. time :math:`\\tau = r_0 t` in units :math:`1/\\lambda`, so that the Newton column
   :math:`\\partial F/\\partial T` is of the size of the P columns (the shooting's rank cut is 1e-9);
3. a constant extra component :math:`w` with time rate :math:`1 + \\lambda w`: a float64 period has
   granularity :math:`10^{-16}T`, which alone moves the P-phase by :math:`10^{-16}\\cdot2\\pi`, i.e.
   :math:`10^{-3}` of :math:`\\varphi` — :math:`w` takes up that last bit of the period;
4. heyoka in extended precision (80-bit long double, else quadruple).

The orbit is the family member of the analytic solution (:math:`r = r_0`, :math:`\\gamma'' =
\\gamma_0''`, :math:`|\\boldsymbol\\gamma| = 1` pinned), moved along the flow onto the analytic
solution's section :math:`\\dot G = 0`. About 0.5 s at the paper geometry (heyoka compiles the
conditioned system once per call). Tests: ``tests/rigid_body/test_disk_shooting.py``.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb.errors import PerturbError
from perturb.oracle import Heyoka, SymbolicRHS, find_periodic_orbit, heyoka_available

__all__ = ["RESOLUTION", "TOL", "TrueOrbit", "conditioned_true_orbit"]

#: Relative error of P(0) that shows as a shooting residual TOL (see the module docstring).
RESOLUTION = 1e-6
TOL = 1e-12
#: Trivial multipliers of the conditioned 7-D map: autonomy, the period component w, and the
#: three first integrals (energy, area, geometric); the remaining pair is e^{+-i phi}.
N_TRIVIAL = 5
#: Status when the conditioned shooting cannot run (heyoka missing) or was refused.
STATUS_UNAVAILABLE = -10
STATUS_REFUSED = -11


@frozen
class TrueOrbit:
    """The disk's true periodic orbit (physical units), or why it was not found.

    Attributes
    ----------
    success : bool
        Whether the conditioned shooting converged.
    initial_state : ndarray, shape (6,)
        (p, q, r, gamma, gamma', gamma'') on the analytic solution's section dG = 0 (NaN on failure).
    period : float
        The true period in physical time.
    beta1, beta2 : float
        :math:`P(0)/\\varepsilon`, :math:`\\dot P(0)/\\varepsilon` on that section.
    alpha : float
        :math:`(T_\\tau - 2\\pi)/\\varepsilon^2`.
    first_order : tuple
        The same three from the analytic solution.
    floquet : tuple of complex
        Multipliers of the conditioned (7-D) map sorted by distance from 1; the first
        :data:`N_TRIVIAL` are trivial, the next pair is :math:`e^{\\pm i\\varphi}`.
    n_trivial : int
    trivial_multiplier_error : float
    residual : float
        Conditioned periodicity defect (TOL corresponds to a relative error RESOLUTION of P(0)).
    resolution : float
        Relative uncertainty of the amplitudes implied by the residual: residual / TOL * RESOLUTION.
    pin_mismatch : float
        :math:`|r_1 - 1| + |\\gamma'' - \\gamma_0''|` at dG = 0.
    iterations : int
    status : int
        0 converged; the shooting's negative codes; STATUS_UNAVAILABLE, STATUS_REFUSED.
    message : str
    integrator : str
    """

    success: bool
    initial_state: np.ndarray = field(eq=False)
    period: float = field(converter=float)
    beta1: float = field(converter=float)
    beta2: float = field(converter=float)
    alpha: float = field(converter=float)
    first_order: tuple
    floquet: tuple = field(converter=tuple)
    n_trivial: int
    trivial_multiplier_error: float = field(converter=float)
    residual: float = field(converter=float)
    resolution: float = field(converter=float)
    pin_mismatch: float = field(converter=float)
    iterations: int
    status: int
    message: str
    integrator: str = ""


def _failed(status: int, message: str, first_order=(math.nan,) * 3, **extra) -> TrueOrbit:
    nan = math.nan
    values = dict(
        success=False,
        initial_state=np.full(6, nan),
        period=nan,
        beta1=nan,
        beta2=nan,
        alpha=nan,
        first_order=first_order,
        floquet=(),
        n_trivial=N_TRIVIAL,
        trivial_multiplier_error=nan,
        residual=nan,
        resolution=nan,
        pin_mismatch=nan,
        iterations=0,
        status=status,
        message=message,
    )
    values.update(extra)
    return TrueOrbit(**values)


def _conditioned_rhs(problem, ref, scales, lam):
    """d u / d(lambda tau): the original equations in tau = r0 t, relative to ``ref``, scaled."""
    state, exprs = problem.original_symbolic()
    u = sp.symbols("u0:7")
    r0 = problem.values["r0"]
    shift = {state[i]: sp.Float(ref[i], 30) + sp.Float(scales[i], 30) * u[i] for i in range(6)}
    rate = (1 + sp.Float(lam, 30) * u[6]) * sp.Float(lam, 30) / sp.Float(r0, 30)
    body = [e.xreplace(shift) * rate / sp.Float(scales[i], 30) for i, e in enumerate(exprs)]
    return SymbolicRHS(u, [*body, sp.Integer(0)])


def _move_to_section(problem, y, forward):
    """Slide along the flow to dG = 0 (the analytic solution's phase): second-order Taylor steps."""
    state, exprs = problem.original_symbolic()
    flow = SymbolicRHS(state, exprs)
    c, r0 = problem.scale_c(), problem.values["r0"]
    units = np.array([c, c, r0, 1.0, 1.0, 1.0])
    for _ in range(3):
        z = forward(y / units)
        dt = -z[3] / z[5] / r0  # dG/d2G in tau
        f = flow(y)
        y = y + dt * f + 0.5 * dt**2 * (flow.jacobian(y) @ f)
    return y, forward(y / units)


def conditioned_true_orbit(problem, solution=None, offset: float = 0.0) -> TrueOrbit:
    """The true periodic orbit of the analytic solution's family member (see the module docstring).

    Parameters
    ----------
    problem : the ``disk`` problem (:class:`problems.rigid_body.disk.DiskInNewtonianField`).
    solution : PeriodicSolution, optional
        The analytic solution giving the seed, the period guess and the section (default: order 1).
    offset : float
        Relative offset of the seed's P, dP (to check that the result does not depend on it).

    Failures (heyoka missing, no convergence) are returned as a status with a message.
    """
    from problems.rigid_body._body import _user_parameter

    if solution is None:
        solution = problem.solve(1)
    if not solution.success:
        return _failed(STATUS_REFUSED, f"no analytic solution to seed from: {solution.message}")
    eps, r0 = problem.epsilon(), problem.values["r0"]
    g3 = problem.values["gamma3_0"]
    values = problem.symbol_values()
    period = problem.period(solution)
    z0 = solution.initial_state(_user_parameter(solution, eps), values)
    start = dict(zip(solution.state_names, z0, strict=True))
    first = (
        float(start["P"]) / eps,
        float(start["dP"]) / eps,
        (period * r0 - 2 * math.pi) / eps**2,
    )
    if not heyoka_available():
        return _failed(
            STATUS_UNAVAILABLE,
            "the conditioned shooting needs heyoka (extended precision); install heyoka",
            first,
        )
    seed = np.asarray(problem.state_vector(solution, 0.0), dtype=float)
    # the family member: r = r0, gamma'' = gamma3_0, |gamma| = 1 on the section gamma' = seed's
    ref = seed.copy()
    ref[2], ref[5] = r0, g3
    ref[3] = math.sqrt(max(0.0, 1 - ref[4] ** 2 - g3**2))
    phi = 2 * math.pi * eps**2 * problem.detuning()
    amplitude = math.hypot(ref[0], ref[1])
    if not (phi > 0 and amplitude > 0 and math.isfinite(phi * amplitude)):
        return _failed(
            STATUS_REFUSED,
            f"no detuned P-oscillation to condition (phi = {phi:.3g}, |P| = {amplitude:.3g})",
            first,
        )
    scales = np.ones(6)
    scales[:2] = phi * amplitude * RESOLUTION / TOL
    scales[2] = r0
    lam = phi / max(1.0, amplitude / scales[0])
    rhs = _conditioned_rhs(problem, ref, scales, lam)
    u0 = np.zeros(7)
    u0[:2] = offset * ref[:2] / scales[:2]
    try:
        orbit = find_periodic_orbit(
            rhs,
            u0,
            period * r0 / lam,
            section_index=4,
            fixed_indices=(2, 3, 5),
            direction=-1,
            n_trivial=N_TRIVIAL,
            integrator=Heyoka(high_precision=True),
            y_scale=1.0,
            tol=TOL,
        )
    except PerturbError as exc:
        return _failed(STATUS_REFUSED, f"conditioned shooting refused: {exc}", first)
    floquet = tuple(complex(m) for m in orbit.floquet_multipliers)
    common = dict(
        floquet=floquet,
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        residual=orbit.residual,
        iterations=orbit.iterations,
        integrator=orbit.integrator,
    )
    if not orbit.success:
        return _failed(orbit.status.code, f"conditioned shooting: {orbit.message}", first, **common)
    y = ref + scales * np.asarray(orbit.initial_state[:6], dtype=float)
    t_true = orbit.period * lam * (1 + lam * float(orbit.initial_state[6])) / r0
    forward = problem.reduction().forward_function(values, eps)
    y, z = _move_to_section(problem, y, forward)
    resolution = max(orbit.residual, 0.0) / TOL * RESOLUTION
    return TrueOrbit(
        success=True,
        initial_state=np.asarray(y, dtype=float),
        period=t_true,
        beta1=float(z[0] / eps),
        beta2=float(z[1] / eps),
        alpha=(t_true * r0 - 2 * math.pi) / eps**2,
        first_order=first,
        n_trivial=N_TRIVIAL,
        resolution=resolution,
        pin_mismatch=float(abs(y[2] / r0 - 1) + abs(y[5] - g3)),
        status=orbit.status.code,
        message=(
            f"conditioned extended-precision shooting ({orbit.integrator}) converged in "
            f"{orbit.iterations} iterations: conditioned residual {orbit.residual:.2e}, amplitudes "
            f"resolved to ~{resolution:.1e} (P-detuning phase {phi:.3g} per period); true period "
            f"{t_true:.12g}, beta1/eps = {z[0] / eps:.7g}, beta2/eps = {z[1] / eps:.7g}"
        ),
        **common,
    )
