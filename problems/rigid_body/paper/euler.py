"""The seed paper's Euler angles (28)–(29), transcribed as a CLAIM UNDER TEST, and their check.

This module is the one place where the paper's formulas (28)–(29) are reproduced. They are not used
by any solver: :func:`paper_euler_angles` exists only so that the claim can be compared with

1. the angles of the TRUE motion (:func:`true_euler_angles`: the full Euler–Poisson system
   integrated from the analytic initial state, with :math:`\\psi` integrated along the trajectory
   from the kinematic equation :math:`\\dot\\psi = (p\\gamma + q\\gamma')/(\\gamma^2 + \\gamma'^2)`),
2. the angles of the corrected first-order solution (``disk`` problem,
   :meth:`~problems.rigid_body._body.FastSpinBody.euler_angles`), and
3. the leading-order angles derived here from the corrected solution
   (:func:`leading_order_euler_angles`), which is what (28)–(29) should have been.

Conventions the paper evidently uses (checked against its own (26)): z–x–z Euler angles,
:math:`\\theta` the nutation (:math:`\\cos\\theta = \\gamma''`, :math:`\\gamma_0'' = \\cos\\theta_0`),
:math:`\\psi` the precession, :math:`\\varphi` the proper rotation, with
:math:`\\gamma = (\\sin\\theta\\sin\\varphi, \\sin\\theta\\cos\\varphi, \\cos\\theta)`: the generating motion
:math:`\\gamma = \\cos\\tau`, :math:`\\gamma' = -\\sin\\tau` of (26) is :math:`\\varphi = \\pi/2 + \\tau`, and
(28) has :math:`\\varphi - \\varphi_0 \\approx r_0 t`. These are the conventions of
:mod:`problems.rigid_body.euler_angles`.

Transcription of (28)–(29) (our copy is a PDF extraction; :math:`V_i = v_i k^*`, :math:`\\tau = r_0 t`):

.. math::

    \\theta &= \\theta_0 - \\mu^{-2}\\cot\\theta_0\\,[\\theta_2(t+t_0) - \\theta_2(t_0)],\\\\
    r_0(\\psi - \\psi_0) &= \\tfrac12 c\\csc\\theta_0\\,\\{c\\cot\\theta_0 (V_1^2 + V_2^2)\\,t
        + \\csc\\theta_0\\,[k\\gamma_0'' r_0 t + \\psi_1(t+t_0) - \\psi_1(t_0)]
        + 2\\mu^{-1}\\cot\\theta_0\\,[\\psi_2(t+t_0) - \\psi_2(t_0)]\\},\\\\
    \\varphi - \\varphi_0 &= [r_0 - \\tfrac12 c\\,(k\\cot^2\\theta_0 - c r_0^{-1}(V_1^2 + V_2^2))]\\,t
        - \\mu^{-1}\\cot\\theta_0\\csc\\theta_0\\,[\\varphi_1(t+t_0) - \\varphi_1(t_0)],

with :math:`\\theta_2 = -b^{-1}x_0'\\cos\\tau + a^{-1}y_0'\\sin\\tau + \\tfrac14 k\\cos2\\tau`,
:math:`\\psi_1 = 2a^{-1}y_0'\\gamma_0''\\cos\\tau - V_2\\cos2\\tau + (V_1 - \\tfrac12k\\gamma_0'')\\sin2\\tau`,
:math:`\\psi_2 = x_0'(1-a)^{-1}\\sin\\tau + \\tfrac12C_1V_1V_2\\cos2\\tau - \\tfrac14C_1(V_1^2 - V_2^2)\\sin2\\tau`,
:math:`\\varphi_1 = a^{-1}y_0'\\gamma_0''\\cos\\tau - \\tfrac12V_2\\cos2\\tau + \\tfrac12(V_1 - \\tfrac12k\\gamma_0'')\\sin2\\tau`.

Ambiguities of the garbled text, and the reading chosen (the most favourable to the paper):

* The :math:`\\psi` braces: ``n`` / ``o`` are ``{`` / ``}`` and the displaced ``h i`` is the ``[ ]``
  around :math:`k\\gamma_0''r_0t + \\psi_1(t+t_0) - \\psi_1(t_0)`. This is the only grouping in which every
  term of the brace has the dimension of :math:`c` (so that both sides are rates).
* ``0:5 c cot2θ0 k − c r−10 k∗2 (υ21 + υ22)`` followed by three closing brackets: read as
  :math:`[r_0 - \\tfrac12c(k\\cot^2\\theta_0 - (c/r_0)k^{*2}(v_1^2+v_2^2))]t`, again the only dimensionally
  consistent grouping. ``cot2θ0`` is read as :math:`\\cot^2\\theta_0` (the paper writes squares as
  trailing digits, e.g. ``k∗2``); :math:`\\cot 2\\theta_0` would be :math:`\\approx -1/(2\\gamma_0'')` at
  the paper's :math:`\\gamma_0'' \\approx 0`, which is far worse.
* ``k∗2 υ21`` is :math:`k^{*2}v_1^2`; the plain ``k`` is the field parameter :math:`k = 3C/(RMl)`
  ((27) restates :math:`k = 1/(bk^*)`, an identity for :math:`M_3 = 1`).
* :math:`t_0` is an arbitrary phase; :math:`t_0 = 0` matches the phase of (26) and of the corrected
  solution (:math:`\\dot\\gamma(0) = 0`). The argument of the periodic functions is :math:`r_0 t`
  (as printed in (29); E11: the :math:`\\tau = r_0^{-1}t` of (27) is a typo).
* :math:`V_1, V_2` are the paper's (21)–(23) as in
  :meth:`~problems.rigid_body.disk.DiskInNewtonianField.paper_amplitudes` (:math:`\\gamma_0'^2` read
  as :math:`y_0'^2`, E5a, with :math:`M_3 = \\sin\\theta_0`). ``amplitudes="corrected"`` replaces them
  by the true :math:`\\beta_1/\\varepsilon = bV_1`, :math:`\\beta_2/\\varepsilon = -bV_2` (E7), to separate
  that error from the structure of (28)–(29).
* :math:`\\mu`: ``mu="eps"`` reads :math:`\\mu^{-1} = \\varepsilon = c/r_0` (the consistent expansion
  parameter, E1/E2); ``mu="definition"`` uses the printed definition (4),
  :math:`\\mu = c\\sqrt{\\gamma_0''}/r_0`. The explicit :math:`c`, :math:`c/r_0` factors are kept as printed.

References
----------
.. [1] The seed paper, equations (21)–(23), (26)–(29).
.. [2] ``docs/paper-errata.md``, section "Euler angles (28)–(29)" (E12).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from attrs import frozen

from perturb.errors import InvalidParameterError
from perturb.oracle import Scipy

__all__ = [
    "ANGLES",
    "EULER_CASES",
    "EULER_EPSILONS",
    "PaperEulerInputs",
    "compare_euler_angles",
    "euler_angle_study",
    "fast_disk",
    "leading_order_euler_angles",
    "paper_euler_angles",
    "paper_euler_inputs",
    "true_euler_angles",
]

#: The three Euler angles, in the order of the report.
ANGLES = ("theta", "psi", "phi")
#: Readings of the paper's mu: mu^-1 = eps = c/r0, or the printed definition (4).
MU_READINGS = ("eps", "definition")
#: Amplitude readings: the paper's v_i k* of (21)–(23), or the true beta_i/eps (E7).
AMPLITUDE_READINGS = ("paper", "corrected")
#: Fast-spin test cases: (k, gamma0''). The first is the project's witness set; the second is the
#: paper's own gamma0'' = 7e-6 (theta0 ~ pi/2) with a field k = 0.4.
EULER_CASES = {"k0.5_g0.3": (0.5, 0.3), "paper_g7e-6_k0.4": (0.4, 7e-6)}
#: eps = c/r0 values of the scaling study (one decade).
EULER_EPSILONS = (0.04, 0.02, 0.01, 0.004)
#: Periods compared and output samples per period.
EULER_PERIODS = 3
SAMPLES_PER_PERIOD = 64
#: Relative tolerance of the true-motion integration (integrals then drift by ~1e-11).
TRUTH_RTOL = 1e-12
#: Body of the study: the paper's A, B, C, M, x0, y0 (31); g and R are set so that c = 1 and k is
#: the case's field (the reference's fast-spin test set).
_BODY = {"A": 9.0, "B": 11.0, "C": 20.0, "M": 200.0, "x0": 1.0, "y0": 6.0, "z0": 0.0}
#: Comparisons reported: (name, first, second).
PAIRS = (
    ("true_vs_ours", "true", "ours"),
    ("true_vs_paper", "true", "paper"),
    ("ours_vs_paper", "ours", "paper"),
    ("true_vs_paper_corrected_amplitudes", "true", "paper_corrected_amplitudes"),
    ("true_vs_paper_mu_definition", "true", "paper_mu_definition"),
    ("true_vs_leading_order", "true", "leading_order"),
)
_TWO_PI = 2 * math.pi


@frozen
class PaperEulerInputs:
    """Every symbol of (28)–(29), as numbers.

    Attributes
    ----------
    theta0, psi0, phi0 : float
        Initial Euler angles (:math:`\\cos\\theta_0 = \\gamma_0''`).
    r0, c : float
        Initial spin and :math:`c = \\sqrt{Mgl/C}` (both s^-1).
    mu_inv : float
        The paper's :math:`\\mu^{-1}` under the chosen reading.
    a, b, k, x0p, y0p : float
        :math:`A/C`, :math:`B/C`, the field parameter, :math:`x_0/l`, :math:`y_0/l`.
    v1k, v2k : float
        :math:`V_1 = v_1k^*`, :math:`V_2 = v_2k^*`.
    t0 : float
        The phase constant :math:`t_0` (s).
    """

    theta0: float
    psi0: float
    phi0: float
    r0: float
    c: float
    mu_inv: float
    a: float
    b: float
    k: float
    x0p: float
    y0p: float
    v1k: float
    v2k: float
    t0: float = 0.0


def paper_euler_angles(t, inputs: PaperEulerInputs) -> dict[str, np.ndarray]:
    """The paper's (28)–(29) AS PRINTED (our reading; a claim under test, not a result).

    Parameters
    ----------
    t : array_like
        Physical times (s).
    inputs : PaperEulerInputs
        The symbols of (28)–(29).

    Returns
    -------
    dict
        ``{"theta", "psi", "phi"}`` arrays, shaped like ``t``.
    """
    s = inputs
    t = np.asarray(t, dtype=float)
    g3 = math.cos(s.theta0)
    cot, csc = g3 / math.sin(s.theta0), 1 / math.sin(s.theta0)
    c1 = s.b - s.a
    v1, v2 = s.v1k, s.v2k
    amp2 = v1**2 + v2**2

    def theta2(x):
        return -s.x0p / s.b * np.cos(x) + s.y0p / s.a * np.sin(x) + 0.25 * s.k * np.cos(2 * x)

    def psi1(x):
        return (
            2 * s.y0p * g3 / s.a * np.cos(x)
            - v2 * np.cos(2 * x)
            + (v1 - 0.5 * s.k * g3) * np.sin(2 * x)
        )

    def psi2(x):
        return (
            s.x0p / (1 - s.a) * np.sin(x)
            + 0.5 * c1 * v1 * v2 * np.cos(2 * x)
            - 0.25 * c1 * (v1**2 - v2**2) * np.sin(2 * x)
        )

    def phi1(x):
        return (
            s.y0p * g3 / s.a * np.cos(x)
            - 0.5 * v2 * np.cos(2 * x)
            + 0.5 * (v1 - 0.5 * s.k * g3) * np.sin(2 * x)
        )

    x, x0 = s.r0 * (t + s.t0), s.r0 * s.t0
    theta = s.theta0 - s.mu_inv**2 * cot * (theta2(x) - theta2(x0))
    brace = (
        s.c * cot * amp2 * t
        + csc * (s.k * g3 * s.r0 * t + psi1(x) - psi1(x0))
        + 2 * s.mu_inv * cot * (psi2(x) - psi2(x0))
    )
    psi = s.psi0 + 0.5 * s.c * csc * brace / s.r0
    rate = s.r0 - 0.5 * s.c * (s.k * cot**2 - s.c / s.r0 * amp2)
    phi = s.phi0 + rate * t - s.mu_inv * cot * csc * (phi1(x) - phi1(x0))
    return {"theta": theta, "psi": psi, "phi": phi}


def leading_order_euler_angles(t, inputs: PaperEulerInputs) -> dict[str, np.ndarray]:
    """What (28)–(29) should be: the leading-order angles of the corrected solution (derived here).

    With :math:`\\varepsilon = c/r_0`, :math:`\\tau = r_0t`, :math:`M_3 = \\sin\\theta_0`,
    :math:`\\gamma_0'' = \\cos\\theta_0` and the true amplitudes :math:`u_1 = \\beta_1/\\varepsilon`,
    :math:`u_2 = \\beta_2/\\varepsilon` (pass ``v1k, v2k`` = :math:`u_1, u_2`, i.e. the
    ``amplitudes="corrected"`` inputs), the first-order state (P = :math:`\\varepsilon(u_1\\cos\\tau +
    u_2\\sin\\tau)`, :math:`p_1 = P + \\varepsilon x_0'\\gamma_0''/b`, :math:`q_1 = -\\dot P +
    \\varepsilon(y_0'\\gamma_0''/a + k\\gamma'\\gamma_0'')`, :math:`\\gamma = M_3\\cos\\tau`,
    :math:`\\gamma' = -M_3\\sin\\tau`) in :math:`\\dot\\gamma'' = \\varepsilon(q_1\\gamma - p_1\\gamma')` and
    :math:`d\\psi/d\\tau = \\varepsilon(p_1\\gamma + q_1\\gamma')/M_3^2` gives, to :math:`O(\\varepsilon^3)`,

    .. math::

        \\theta - \\theta_0 &= -\\varepsilon^2[\\tfrac12u_1(1-\\cos2\\tau) - \\tfrac12u_2\\sin2\\tau
            + \\gamma_0''(a^{-1}y_0'\\sin\\tau + b^{-1}x_0'(1-\\cos\\tau))
            - \\tfrac14kM_3\\gamma_0''(1-\\cos2\\tau)],\\\\
        \\psi - \\psi_0 &= \\varepsilon^2\\{\\tfrac12k\\gamma_0''\\tau - \\tfrac14k\\gamma_0''\\sin2\\tau
            + M_3^{-1}[\\tfrac12u_1\\sin2\\tau + \\tfrac12u_2(1-\\cos2\\tau)
            + b^{-1}x_0'\\gamma_0''\\sin\\tau - a^{-1}y_0'\\gamma_0''(1-\\cos\\tau)]\\},

    and :math:`\\varphi - \\varphi_0 = (2\\pi/T)t` up to an :math:`O(\\varepsilon^2)` periodic part, with
    the period :math:`T` of the corrected solution:
    :math:`2\\pi/T = r_0[1 - \\tfrac12\\varepsilon^2(2M_3x_0' + k\\gamma_0''^2 + \\tfrac12kC_1M_3^2)]`.

    Parameters
    ----------
    t : array_like
        Physical times (s).
    inputs : PaperEulerInputs
        As for :func:`paper_euler_angles`, with the corrected amplitudes; ``mu_inv`` is not used.

    Returns
    -------
    dict
        ``{"theta", "psi", "phi"}``.
    """
    s = inputs
    t = np.asarray(t, dtype=float)
    eps = s.c / s.r0
    g3, m3 = math.cos(s.theta0), math.sin(s.theta0)
    u1, u2 = s.v1k, s.v2k
    x = s.r0 * (t + s.t0)
    one_c1, one_c2 = 1 - np.cos(x), 1 - np.cos(2 * x)
    theta = s.theta0 - eps**2 * (
        0.5 * u1 * one_c2
        - 0.5 * u2 * np.sin(2 * x)
        + g3 * (s.y0p / s.a * np.sin(x) + s.x0p / s.b * one_c1)
        - 0.25 * s.k * m3 * g3 * one_c2
    )
    psi = s.psi0 + eps**2 * (
        0.5 * s.k * g3 * x
        - 0.25 * s.k * g3 * np.sin(2 * x)
        + (
            0.5 * u1 * np.sin(2 * x)
            + 0.5 * u2 * one_c2
            + s.x0p * g3 / s.b * np.sin(x)
            - s.y0p * g3 / s.a * one_c1
        )
        / m3
    )
    c1 = s.b - s.a
    rate = s.r0 * (1 - 0.5 * eps**2 * (2 * m3 * s.x0p + s.k * g3**2 + 0.5 * s.k * c1 * m3**2))
    return {"theta": theta, "psi": psi, "phi": s.phi0 + rate * t}


# ---------------------------------------------------------------------------- the comparison
def fast_disk(eps: float, k_value: float, gamma3: float):
    """The ``disk`` problem with the paper's body, c = 1, field ``k_value`` and r0 = 1/eps.

    Parameters
    ----------
    eps : float
        :math:`\\varepsilon = c/r_0` (c = 1, so r0 = 1/eps).
    k_value : float
        The field parameter :math:`k = 3C/(RMl)` (sets R).
    gamma3 : float
        :math:`\\gamma_0'' = \\cos\\theta_0`.

    Returns
    -------
    DiskInNewtonianField
    """
    from problems import get_problem

    arm, C, M = math.hypot(_BODY["x0"], _BODY["y0"]), _BODY["C"], _BODY["M"]
    return get_problem("disk").create(
        **_BODY, g=C / (M * arm), R=3 * C / (k_value * M * arm), r0=1 / eps, gamma3_0=gamma3
    )


def paper_euler_inputs(
    problem, initial: dict, *, mu: str = "eps", amplitudes: str = "paper"
) -> PaperEulerInputs:
    """The symbols of (28)–(29) for a ``disk`` problem and the initial angles ``initial``.

    Parameters
    ----------
    problem : DiskInNewtonianField
        The body.
    initial : dict
        ``{"theta", "psi", "phi"}`` at t = 0 (the arbitrary constants of (28)).
    mu : {"eps", "definition"}
        Reading of the paper's :math:`\\mu^{-1}` (see the module docstring).
    amplitudes : {"paper", "corrected"}
        :math:`V_i = v_ik^*` of (21)–(23), or the true :math:`\\beta_1/\\varepsilon = bV_1`,
        :math:`\\beta_2/\\varepsilon = -bV_2`.

    Returns
    -------
    PaperEulerInputs
    """
    if mu not in MU_READINGS:
        raise InvalidParameterError(f"`mu` = {mu!r} is invalid: choose from {list(MU_READINGS)}")
    if amplitudes not in AMPLITUDE_READINGS:
        raise InvalidParameterError(
            f"`amplitudes` = {amplitudes!r} is invalid: choose from {list(AMPLITUDE_READINGS)}"
        )
    v = problem.symbol_values()
    eps, c, r0 = problem.epsilon(), problem.scale_c(), problem.values["r0"]
    mu_inv = eps if mu == "eps" else 1 / (eps * math.sqrt(v["gamma3_0"]))
    v1k, v2k = problem.paper_amplitudes()
    if amplitudes == "corrected":
        v1k, v2k = v["b"] * v1k, -v["b"] * v2k
    return PaperEulerInputs(
        theta0=float(initial["theta"]), psi0=float(initial["psi"]), phi0=float(initial["phi"]),
        r0=r0, c=c, mu_inv=mu_inv, a=v["a"], b=v["b"], k=v["k"], x0p=v["x0p"], y0p=v["y0p"],
        v1k=v1k, v2k=v2k,
    )  # fmt: skip


def true_euler_angles(problem, y0: np.ndarray, t: np.ndarray) -> dict[str, np.ndarray]:
    """Euler angles of the true motion from the physical state ``y0`` at t = 0.

    The full Euler–Poisson system is integrated (scipy DOP853, ``rtol = TRUTH_RTOL``, per-component
    absolute tolerances) together with :math:`\\dot\\psi = (p\\gamma + q\\gamma')/(\\gamma^2 + \\gamma'^2)`,
    :math:`\\psi(0) = 0`; :math:`\\theta = \\arccos\\gamma''`, :math:`\\varphi = \\operatorname{atan2}(\\gamma,
    \\gamma')`.

    Parameters
    ----------
    problem : FastSpinBody
        The body (its :meth:`original_rhs`, c and r0).
    y0 : numpy.ndarray
        Physical state (p, q, r, gamma, gamma', gamma'') at t = 0.
    t : numpy.ndarray
        Increasing output times from 0 (s).

    Returns
    -------
    dict
        ``{"theta", "psi", "phi"}`` at ``t``.

    Raises
    ------
    perturb.errors.IntegrationError
        If the integration fails.
    """
    rhs6 = problem.original_rhs()

    def rhs(y):
        rate = (y[0] * y[3] + y[1] * y[4]) / (y[3] ** 2 + y[4] ** 2)
        return np.append(rhs6(0.0, y[:6]), rate)

    c, r0 = problem.scale_c(), problem.values["r0"]
    integrator = Scipy(rtol=TRUTH_RTOL, y_scale=[c, c, r0, 1.0, 1.0, 1.0, 1.0])
    traj = integrator.integrate(rhs, (0.0, float(t[-1])), np.append(y0, 0.0), t_eval=t)
    y = traj.raise_for_status().y
    return {
        "theta": np.arccos(np.clip(y[5], -1.0, 1.0)),
        "psi": y[6],
        "phi": np.arctan2(y[3], y[4]),
    }


def _wrapped(x: np.ndarray) -> np.ndarray:
    return (x + math.pi) % _TWO_PI - math.pi


def _max_differences(first: dict, second: dict) -> dict[str, float]:
    out = {"theta": float(np.max(np.abs(first["theta"] - second["theta"])))}
    for name in ("psi", "phi"):
        out[name] = float(np.max(np.abs(_wrapped(first[name] - second[name]))))
    return out


def compare_euler_angles(
    problem,
    periods: float = EULER_PERIODS,
    samples_per_period: int = SAMPLES_PER_PERIOD,
    order: int = 1,
) -> dict:
    """The Euler angles of the true motion, the corrected solution, (28)–(29) and the leading order.

    Parameters
    ----------
    problem : DiskInNewtonianField
        A fast-spin disk (eps = c/r0 small).
    periods : float
        Number of periods compared (from t = 0, the phase of (26)).
    samples_per_period : int
        Output samples per period.
    order : int
        Order of the corrected solution (2 takes about a minute the first time, then is cached).

    Returns
    -------
    dict
        ``"max_diff"``: pair name (:data:`PAIRS`) -> {angle: max |difference|} (psi, phi modulo 2 pi);
        ``"size"``: the true variation of each angle (max |theta - theta0|, max |psi|, and
        max |phi - phi0 - r0 t| modulo 2 pi); ``"eps"``, ``"period"``.
    """
    solution = problem.solve(order)
    period = problem.period(solution)
    t = np.linspace(0.0, periods * period, int(round(periods * samples_per_period)) + 1)
    angles = {"ours": problem.euler_angles(solution, t)}
    y0 = problem.state_vector(solution, [0.0])[:, 0]
    angles["true"] = true_euler_angles(problem, y0, t)
    start = {name: angles["true"][name][0] for name in ANGLES}
    angles["paper"] = paper_euler_angles(t, paper_euler_inputs(problem, start))
    corrected = paper_euler_inputs(problem, start, amplitudes="corrected")
    angles["paper_corrected_amplitudes"] = paper_euler_angles(t, corrected)
    angles["paper_mu_definition"] = paper_euler_angles(
        t, paper_euler_inputs(problem, start, mu="definition")
    )
    angles["leading_order"] = leading_order_euler_angles(t, corrected)
    true = angles["true"]
    r0 = problem.values["r0"]
    size = {
        "theta": float(np.max(np.abs(true["theta"] - start["theta"]))),
        "psi": float(np.max(np.abs(true["psi"] - start["psi"]))),
        "phi": float(np.max(np.abs(_wrapped(true["phi"] - start["phi"] - r0 * t)))),
    }
    return {
        "eps": problem.epsilon(),
        "period": period,
        "size": size,
        "max_diff": {name: _max_differences(angles[one], angles[two]) for name, one, two in PAIRS},
    }


def _slope(eps: Sequence[float], values: Sequence[float]) -> float:
    """Least-squares slope of log(values) against log(eps)."""
    return float(np.polyfit(np.log(eps), np.log(values), 1)[0])


def euler_angle_study(
    epsilons: Sequence[float] = EULER_EPSILONS,
    cases: dict | None = None,
    periods: float = EULER_PERIODS,
    order: int = 1,
) -> dict:
    """The check of (28)–(29): max differences per angle and pair, per eps, and their slopes in eps.

    Parameters
    ----------
    epsilons : sequence of float
        Values of eps = c/r0 (fast spin; slopes are fitted over them).
    cases : dict, optional
        ``name -> (k, gamma0'')``; default :data:`EULER_CASES`.
    periods : float
        Periods compared per run.
    order : int
        Order of the corrected solution ("ours").

    Returns
    -------
    dict
        ``case -> {"k", "gamma3_0", "eps", "size": {angle: [...]}, "max_diff": {pair: {angle:
        [...]}}, "slope": {"size" or pair: {angle: slope}}}``.

    Examples
    --------
    >>> study = euler_angle_study(epsilons=(0.02, 0.01))  # doctest: +SKIP
    >>> study["k0.5_g0.3"]["slope"]["true_vs_paper"]["psi"]  # doctest: +SKIP
    1.0...
    """
    cases = EULER_CASES if cases is None else cases
    out = {}
    for case, (k_value, gamma3) in cases.items():
        runs = [
            compare_euler_angles(fast_disk(eps, k_value, gamma3), periods, order=order)
            for eps in epsilons
        ]
        eps_list = [r["eps"] for r in runs]
        size = {a: [r["size"][a] for r in runs] for a in ANGLES}
        diffs = {
            name: {a: [r["max_diff"][name][a] for r in runs] for a in ANGLES}
            for name, _, _ in PAIRS
        }
        slopes = {"size": {a: _slope(eps_list, size[a]) for a in ANGLES}}
        for name, per_angle in diffs.items():
            slopes[name] = {a: _slope(eps_list, per_angle[a]) for a in ANGLES}
        out[case] = {
            "k": k_value,
            "gamma3_0": gamma3,
            "eps": eps_list,
            "size": size,
            "max_diff": diffs,
            "slope": slopes,
        }
    return out
