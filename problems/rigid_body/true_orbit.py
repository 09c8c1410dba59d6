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
   that a relative error :data:`RESOLUTION` in :math:`P(0)` shows as a residual :data:`TOL`; and
   the section component :math:`\\gamma'` with :math:`s_4 = \\varphi\\,` :data:`RESOLUTION` /
   :data:`TOL` (at most 1): the P-rows do not see a P-phase error :math:`a` offset by a time shift
   :math:`\\varphi a`, which shows only as the section's return :math:`\\gamma'(T) - \\gamma'(0)
   = \\varphi a` — at scale 1 that is 4e-15 for a 1 % error, below any residual the shooting can
   reach, and a Newton matrix whose singular value there (3e-19) is below the rounding of its
   monodromy (1e-16) converges anywhere along it (see :func:`amplitude_resolution`);
2. time :math:`\\tau = r_0 t` in units :math:`1/\\lambda`, so that the Newton column
   :math:`\\partial F/\\partial T` is of the size of the P columns;
3. a constant extra component :math:`w` with time rate :math:`1 + \\lambda w`: a float64 period has
   granularity :math:`10^{-16}T`, which alone moves the P-phase by :math:`10^{-16}\\cdot2\\pi`, i.e.
   :math:`10^{-3}` of :math:`\\varphi` — :math:`w` takes up that last bit of the period (the
   period and :math:`w` move the state alike: the shooting's minimum-norm step shares a time
   correction between them, and its rank cut at the monodromy's rounding keeps one ulp of noise on
   :math:`\\Phi_{ww} = 1` from deciding the share, which would put it all on the granular period);
4. heyoka in quadruple precision (real128; else 80-bit long double), from the parameters as exact
   rationals (:mod:`problems.rigid_body.exact_inputs`), each coefficient rounded once;
5. the origin re-centred on the orbit found and the shooting repeated, since the defect
   u(T) - u(0) is formed in float64 (see :data:`CENTRED`);
6. the resolution measured on the orbit found (:func:`amplitude_resolution`: the residual and the
   rounding of the defect through the pseudo-inverse of the Newton matrix), not inferred from the
   residual alone: an amplitude the defect does not determine is a failure, never a result.

The orbit is the family member of the analytic solution (:math:`r = r_0`, :math:`\\gamma'' =
\\gamma_0''`, :math:`|\\boldsymbol\\gamma| = 1` pinned), moved along the flow onto the analytic
solution's section :math:`\\dot G = 0`. About 3 s at the paper geometry (heyoka compiles the
conditioned system once per pass, three passes). An independent check:
:mod:`problems.rigid_body.true_orbit_mp`. Tests: ``tests/rigid_body/test_disk_shooting.py``,
``tests/rigid_body/test_disk_shooting_any_machine.py`` (the last bits of another machine, of the
monodromy as of the state).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb.errors import PerturbError
from perturb.oracle import (
    Heyoka,
    OrbitRoute,
    OrbitStatus,
    PeriodicOrbit,
    SymbolicRHS,
    find_periodic_orbit,
    heyoka_available,
)
from perturb.oracle.newton import defect_noise, rounding_norm
from problems.rigid_body._stored import stored
from problems.rigid_body.exact_inputs import (
    FamilyMember,
    exact_epsilon,
    exact_equations,
    exact_values,
    round_coefficients,
)

__all__ = ["RESOLUTION", "TOL", "TrueOrbit", "amplitude_resolution", "conditioned_true_orbit"]

#: Relative error of P(0) that shows as a shooting residual TOL (see the module docstring).
RESOLUTION = 1e-6
TOL = 1e-12
#: Trivial multipliers of the conditioned 7-D map: autonomy, the period component w, and the
#: three first integrals (energy, area, geometric); the remaining pair is e^{+-i phi}.
N_TRIVIAL = 5
#: Status when the conditioned shooting cannot run (heyoka missing) or was refused.
STATUS_UNAVAILABLE = -10
STATUS_REFUSED = -11
#: Status when the converged orbit's Newton matrix does not determine the amplitudes.
STATUS_UNRESOLVED = -12
#: Significant bits of heyoka's extended types: each coefficient is rounded once to these.
FP_BITS = {"real128": 113, "long double": 64}
#: Decimal digits of the final arithmetic (state from the conditioned coordinates, period term):
#: beyond quadruple precision, so that nothing is lost after the shooting.
WORK_DIGITS = 40
#: The P-defect u(T) - u(0) is formed in float64: with the origin ``ref`` a relative 1 % off the
#: orbit, |u| ~ 1e4 and its spacing 2e-12 exceeds TOL. The origin is therefore moved onto the orbit
#: found and the shooting repeated until the pass moved |u_p|, |u_q| by <= CENTRED, at most
#: MAX_CENTRINGS times (the last pass's resolution is then measured whatever it moved). The first
#: start is ~1e-6 off the orbit (|u| ~ 3 after it, spacing 4.4e-16), the second ~1e-10 (|u| ~
#: 1e-4): CENTRED = 1/8 (spacing 2.8e-17) asks for that third pass, whose defect's rounding then
#: puts the measured resolution (:func:`amplitude_resolution`, ~3e6 times the defect at the paper
#: geometry) near 1e-10 instead of 8e-9.
CENTRED = 0.125
MAX_CENTRINGS = 4
#: Tolerance of the re-centred passes: with |u| <= CENTRED the P-defect is resolved far below TOL;
#: 1e-16 is what the third pass reaches (its rounding 4 spacings of 1/8 is 1.1e-16, real128's
#: integration error far less); a pass above it stops at its precision floor (the shooting's
#: measured floor, the spacing of |u| ~ 3 in the second pass) and the next one goes on.
FINE_TOL = 1e-16
#: The unknowns of the conditioned shooting that move the defect: u_p, u_q and the period
#: component w (the period itself moves it exactly as w does).
_MOVING = [0, 1, 6]
#: The conditioned state: u0..u5 for (p, q, r, gamma, gamma', gamma''), u6 the period component w.
_CONDITIONED_STATE = sp.symbols("u0:7")
#: The sources the conditioned equations are derived by (their edits invalidate the disk entries).
_SOURCES = ("true_orbit.py", "exact_inputs.py", "equations.py")


@frozen
class TrueOrbit:
    """The disk's true periodic orbit (:class:`~perturb.oracle.PeriodicOrbit`, physical units) and
    what the disk reads off it, or why it was not found.

    Attributes
    ----------
    orbit : PeriodicOrbit
        The orbit (``found_by`` :attr:`~perturb.oracle.OrbitRoute.CONDITIONED`): ``initial_state``
        (p, q, r, gamma, gamma', gamma'') on the analytic solution's section dG = 0 (NaN on
        failure), the true ``period`` in physical time, the ``multipliers`` and ``monodromy`` of
        the conditioned (7-D) map (the first :data:`N_TRIVIAL` multipliers are trivial, the next
        pair is :math:`e^{\\pm i\\varphi}`), the conditioned ``residual`` (TOL corresponds to a
        relative error RESOLUTION of P(0)), the ``resolution``: the relative uncertainty of the
        amplitudes, :math:`|\\delta(\\beta_1, \\beta_2)| / |(\\beta_1, \\beta_2)|`, the bound
        :func:`amplitude_resolution` of the converged orbit, and the ``status`` and ``message``.
    beta1, beta2 : float
        :math:`P(0)/\\varepsilon`, :math:`\\dot P(0)/\\varepsilon` on that section.
    alpha : float
        :math:`(T_\\tau - 2\\pi)/\\varepsilon^2`.
    first_order : tuple
        The same three from the analytic solution.
    pin_mismatch : float
        :math:`|r_1 - 1| + |\\gamma'' - \\gamma_0''|` at dG = 0.

    The orbit's own numbers are read here by their earlier names too: ``success``,
    ``initial_state``, ``period``, ``floquet`` (the multipliers, a tuple), ``n_trivial``,
    ``trivial_multiplier_error``, ``residual``, ``resolution``, ``iterations``, ``message``,
    ``integrator`` and ``status`` (the integer code: 0 converged; the shooting's negative codes;
    STATUS_UNAVAILABLE, STATUS_REFUSED, STATUS_UNRESOLVED).
    """

    orbit: PeriodicOrbit
    beta1: float = field(converter=float)
    beta2: float = field(converter=float)
    alpha: float = field(converter=float)
    first_order: tuple
    pin_mismatch: float = field(converter=float)

    @property
    def success(self) -> bool:
        """Whether the conditioned shooting converged and resolved the amplitudes."""
        return self.orbit.success

    @property
    def initial_state(self) -> np.ndarray:
        """The orbit's state on the section dG = 0."""
        return self.orbit.initial_state

    @property
    def period(self) -> float:
        """The true period in physical time."""
        return self.orbit.period

    @property
    def floquet(self) -> tuple:
        """The orbit's multipliers, as a tuple of complex."""
        return tuple(complex(z) for z in self.orbit.multipliers)

    @property
    def n_trivial(self) -> int:
        """The trivial multipliers of the conditioned map (:data:`N_TRIVIAL`)."""
        return self.orbit.n_trivial_expected

    @property
    def trivial_multiplier_error(self) -> float:
        """The orbit's trivial-multiplier error."""
        return self.orbit.trivial_multiplier_error

    @property
    def residual(self) -> float:
        """The conditioned periodicity defect."""
        return self.orbit.residual

    @property
    def resolution(self) -> float:
        """The relative uncertainty of the amplitudes."""
        return self.orbit.resolution

    @property
    def iterations(self) -> int:
        """Newton iterations of the last pass."""
        return self.orbit.iterations

    @property
    def status(self) -> int:
        """The integer code of the orbit's status."""
        return self.orbit.status.code

    @property
    def message(self) -> str:
        """What ran, or why it failed."""
        return self.orbit.message

    @property
    def integrator(self) -> str:
        """The shooting's integrator."""
        return self.orbit.integrator


def _failed(
    status: int,
    message: str,
    first_order=(math.nan,) * 3,
    floquet=(),
    monodromy=None,
    trivial_multiplier_error=math.nan,
    residual=math.nan,
    iterations=0,
    integrator="",
) -> TrueOrbit:
    nan = math.nan
    orbit = PeriodicOrbit(
        period=nan,
        initial_state=np.full(6, nan),
        multipliers=np.array(floquet, dtype=complex),
        monodromy=np.full((7, 7), nan) if monodromy is None else monodromy,
        residual=residual,
        iterations=iterations,
        status=OrbitStatus.of_code(status),
        message=message,
        trivial_multiplier_error=trivial_multiplier_error,
        integrator=integrator,
        n_trivial_expected=N_TRIVIAL,
        found_by=OrbitRoute.CONDITIONED,
    )
    return TrueOrbit(orbit, nan, nan, nan, first_order, nan)


def _exact(value) -> sp.Rational:
    """A conditioning number as an exact rational: sympy numbers kept, a float's binary value."""
    return value if isinstance(value, sp.Basic) else sp.Rational(float(value))


def _conditioned_rhs(problem, ref, scales, lam, bits: int | None = None) -> SymbolicRHS:
    """d u / d(lambda tau): the original equations in tau = r0 t, relative to ``ref``, scaled.

    The equations are :func:`~problems.rigid_body.exact_inputs.exact_equations` of the problem's
    exact parameters; ``ref``, ``scales`` and ``lam`` (conditioning choices, any numbers) are taken
    at their exact values (a float's binary value), so every coefficient of the conditioned
    polynomial is an exact rational. With ``bits`` each is then rounded once to that precision
    (:func:`~problems.rigid_body.exact_inputs.round_coefficients`; heyoka then converts it
    exactly), else :func:`perturb.oracle.symbolic.to_heyoka` rounds ``p/q`` in the working type.
    The expressions are kept on disk (kind ``true-orbit-rhs``), keyed by all these exact inputs.
    """
    values = exact_values(problem)
    ref = tuple(_exact(x) for x in ref)
    scales = tuple(_exact(x) for x in scales)
    lam = _exact(lam)
    inputs = (tuple(sorted(values.items())), ref, scales, lam, bits)
    body = stored(
        "true-orbit-rhs",
        _SOURCES,
        inputs,
        lambda: _conditioned_body(values, ref, scales, lam, bits),
    )
    return SymbolicRHS(_CONDITIONED_STATE, [*body, sp.Integer(0)])


def _conditioned_body(values, ref, scales, lam, bits) -> tuple[sp.Expr, ...]:
    """The six conditioned right-hand sides of :func:`_conditioned_rhs` (exact inputs)."""
    state, exprs = exact_equations(values)
    u = _CONDITIONED_STATE
    shift = {state[i]: ref[i] + scales[i] * u[i] for i in range(6)}
    rate = (1 + lam * u[6]) * lam / values["r0"]
    body = [sp.expand(e.xreplace(shift) * rate / scales[i]) for i, e in enumerate(exprs)]
    if bits is not None:
        body = [round_coefficients(e, bits) for e in body]
    return tuple(body)


def _mp(value) -> mpmath.mpf:
    """An exact number (sympy Rational or float) in the current mpmath precision."""
    if isinstance(value, sp.Basic):
        value = sp.Rational(value)
        return mpmath.mpf(int(value.p)) / int(value.q)
    return mpmath.mpf(float(value))


def shot_period(orbit) -> mpmath.mpf:
    """The time the shooting integrated to: heyoka's adapter hands a double over to real128 as its
    shortest decimal (``str``), so that decimal, not the double's binary value, is the period."""
    return mpmath.mpf(str(np.float64(orbit.period)))


def extended_type() -> str:
    """The heyoka floating point type of the shooting: quadruple (real128) where heyoka has it.

    Quadruple precision (113 bits) leaves the resonance intact to 1e-34; the x86 80-bit long double
    (64 bits, 1e-19) would leave a mismatch ~1e-6 of the detuning at the paper geometry.
    """
    import heyoka

    return "real128" if hasattr(heyoka, "real128") else "long double"


def amplitude_resolution(orbit, unit: float) -> float:
    """The relative uncertainty of the amplitudes P(0), Q(0) of a converged conditioned orbit.

    Measured, not assumed: near the orbit the defect is linear in the unknowns that move it, P, Q
    and the period (the component w; the shooting's period moves the state exactly as w does),
    ``F = M (x - x*)`` with ``M`` the columns (0, 1, 6) of the monodromy minus the identity, so

    .. math:: |x - x^*| \\le |M^+|\\,(r + n) / (1 - \\|\\delta M\\| / \\sigma_{min})

    elementwise, where ``r`` is the defect of each component (:attr:`PeriodicOrbit.defect`; the
    residual, its largest, where it is not given), ``n`` the rounding of each component of
    ``u(T) - u(0)`` (:func:`perturb.oracle.newton.defect_noise`) and ``\\|\\delta M\\|`` the
    rounding of ``M`` (:func:`perturb.oracle.newton.rounding_norm`). The integration error is not in it:
    in quadruple precision it is ~1e-30 of the defect's size, and an integrator whose error the
    defect shows makes the shooting stall at its measured floor, a failure. A residual alone says
    nothing of a direction the defect hardly sees (a P-phase error offset by a time shift shows
    only in the section row); this bound sees it as a small singular value.

    Parameters
    ----------
    orbit : PeriodicOrbit
        The conditioned shooting's converged orbit (state ``u``, monodromy).
    unit : float
        The relative amplitude change of one conditioned unit of ``u_p``, ``u_q``
        (``s_p / |P|``).

    Returns
    -------
    float
        ``unit * hypot(du_p, du_q)`` of the bound, or inf when ``M`` is singular within its
        rounding (the amplitudes are then not determined).

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.oracle import OrbitStatus, PeriodicOrbit
    >>> phi = np.eye(7)
    >>> phi[0, 1], phi[1, 0], phi[4, 6] = -1e-12, 1e-12, 1e-12  # P, Q turned; w moves the section
    >>> def orbit(monodromy):  # converged at residual 1e-15, in every component
    ...     return PeriodicOrbit(1.0, np.zeros(7), np.ones(7), monodromy, 1e-15, 1,
    ...                          OrbitStatus.CONVERGED, "")
    >>> float(np.round(amplitude_resolution(orbit(phi), 1e-6), 12))  # 1e-15 / 1e-12 in u_p, u_q
    1.416e-09
    >>> phi[4, 6] = 1e-17  # the time within the monodromy's rounding: P, Q not determined
    >>> amplitude_resolution(orbit(phi), 1e-6)
    inf
    """
    phi = np.asarray(orbit.monodromy, dtype=float)[:, _MOVING]
    matrix = phi - np.eye(len(orbit.initial_state))[:, _MOVING]
    u, sv, vt = np.linalg.svd(matrix, full_matrices=False)
    rounding = rounding_norm(phi)
    if not sv[-1] > 2 * rounding:
        return math.inf
    state = np.asarray(orbit.initial_state, dtype=float)
    if orbit.defect is None:  # each component within the residual
        defect = np.full_like(state, orbit.residual)
    else:
        defect = np.abs(np.asarray(orbit.defect, dtype=float))
    defect = defect + defect_noise(state, defect)
    pseudo_inverse = vt.T @ (u.T / sv[:, None])
    bound = np.abs(pseudo_inverse) @ defect / (1 - rounding / sv[-1])
    return unit * math.hypot(bound[0], bound[1])


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


def conditioned_true_orbit(
    problem, solution=None, offset: float = 0.0, integrator=None
) -> TrueOrbit:
    """The true periodic orbit of the analytic solution's family member (see the module docstring).

    Parameters
    ----------
    problem : the ``disk`` problem (:class:`problems.rigid_body.disk.DiskInNewtonianField`).
        Its parameters are used exactly (:func:`~problems.rigid_body.exact_inputs.exact_values`:
        each float as its shortest decimal, ``C = A + B``).
    solution : PeriodicSolution, optional
        The analytic solution giving the seed, the period guess and the section (default: order 1).
    offset : float
        Relative offset of the seed's P, dP (to check that the result does not depend on it).
    integrator : perturb.oracle.IntegratorBase, optional
        The shooting's integrator; default heyoka in :func:`extended_type` at its epsilon. The
        result must not depend on it beyond its resolution (tests run it with other tolerances).

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
    member = FamilyMember.of(problem, seed)
    ref_exact = member.reference_state()
    ref = np.array([float(x) for x in ref_exact])
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
    scales[4] = min(1.0, phi * RESOLUTION / TOL)
    lam = phi / max(1.0, amplitude / scales[0])
    fp_name = extended_type()
    u0 = np.zeros(7)
    u0[:2] = offset * ref[:2] / scales[:2]
    guess = period * r0 / lam
    for centring in range(MAX_CENTRINGS):
        try:
            orbit = find_periodic_orbit(
                _conditioned_rhs(problem, ref_exact, scales, lam, bits=FP_BITS[fp_name]),
                u0,
                guess,
                section_index=4,
                fixed_indices=(2, 3, 5),
                direction=-1,
                n_trivial=N_TRIVIAL,
                integrator=Heyoka(fp_type=fp_name) if integrator is None else integrator,
                y_scale=1.0,
                tol=TOL if centring == 0 else FINE_TOL,
            )
        except PerturbError as exc:
            return _failed(STATUS_REFUSED, f"conditioned shooting refused: {exc}", first)
        if not orbit.success:
            break
        # heyoka received the doubles as their shortest decimals (the oracle's real128 hand-over):
        # read them back the same way, then move the origin onto the orbit found
        shot = [mpmath.mpf(str(np.float64(x))) for x in orbit.initial_state]
        offset_size = float(max(abs(shot[0]), abs(shot[1])))
        with mpmath.workdps(WORK_DIGITS):
            moved = [
                sp.Rational(mpmath.nstr(_mp(ref_exact[i]) + _mp(scales[i]) * shot[i], WORK_DIGITS))
                for i in range(2)
            ]
        if (offset_size <= CENTRED and centring > 0) or centring == MAX_CENTRINGS - 1:
            break  # the last pass's own defect measures what it resolves (amplitude_resolution)
        ref_exact = (*moved, *ref_exact[2:])
        u0 = np.zeros(7)
        u0[6] = orbit.initial_state[6]
        guess = orbit.period
    common = dict(
        floquet=orbit.multipliers,
        monodromy=orbit.monodromy,
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        residual=orbit.residual,
        iterations=orbit.iterations,
        integrator=orbit.integrator,
    )
    if not orbit.success:
        return _failed(orbit.status.code, f"conditioned shooting: {orbit.message}", first, **common)
    with mpmath.workdps(WORK_DIGITS):
        y = np.array([float(_mp(ref_exact[i]) + _mp(scales[i]) * shot[i]) for i in range(6)])
        # the shooting's time is tau / (lam (1 + lam w)), tau = r0 t: the period term in full
        mp_lam = _mp(lam)
        tau_period = shot_period(orbit) * mp_lam * (1 + mp_lam * shot[6])
        eps_exact = mpmath.mpf(sp.N(exact_epsilon(exact_values(problem)), WORK_DIGITS))
        alpha = float((tau_period - 2 * mpmath.pi) / eps_exact**2)
        t_true = float(tau_period / _mp(member.r0))
    forward = problem.reduction().forward_function(values, eps)
    y, z = _move_to_section(problem, y, forward)
    resolution = amplitude_resolution(orbit, scales[0] / math.hypot(y[0], y[1]))
    if not math.isfinite(resolution):
        return _failed(
            STATUS_UNRESOLVED,
            "conditioned shooting: the conditioned defect does not determine the amplitudes (the "
            "Newton matrix of P, Q and the period is singular within the rounding of the "
            f"monodromy); converged residual {orbit.residual:.2e}",
            first,
            **common,
        )
    found = PeriodicOrbit(
        period=t_true,
        initial_state=np.asarray(y, dtype=float),
        multipliers=orbit.multipliers,
        monodromy=orbit.monodromy,
        residual=orbit.residual,
        iterations=orbit.iterations,
        status=orbit.status,
        message=(
            f"conditioned extended-precision shooting ({orbit.integrator}, exact rational "
            f"parameters) converged in {orbit.iterations} iterations: conditioned residual "
            f"{orbit.residual:.2e}, amplitudes resolved to ~{resolution:.1e} (P-detuning phase "
            f"{phi:.3g} per period); true period {t_true:.12g}, beta1/eps = {z[0] / eps:.7g}, "
            f"beta2/eps = {z[1] / eps:.7g}"
        ),
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        integrator=orbit.integrator,
        n_trivial_expected=N_TRIVIAL,
        n_trivial_found=orbit.n_trivial_found,
        precision_floor=orbit.precision_floor,
        found_by=OrbitRoute.CONDITIONED,
        resolution=resolution,
    )
    return TrueOrbit(
        found,
        beta1=float(z[0] / eps),
        beta2=float(z[1] / eps),
        alpha=alpha,
        first_order=first,
        pin_mismatch=float(abs(y[2] / r0 - 1) + abs(y[5] - g3)),
    )
