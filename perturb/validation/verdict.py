"""The verdict rule, in one place: the checks from the measurements, and the outcome from the checks.

VALID only when every check passed: a true periodic orbit exists near the analytic one (existence),
the analytic orbit is within ``tol`` of it at equal phase and its period within ``tol`` (accuracy),
and the error falls like ε^(N+1) along a scan of the problem's own small parameter (order).  A check
that failed makes the verdict INVALID, naming it with its figure; otherwise a check that could not
run makes it UNDECIDED, saying why. When the order check alone failed but the error still falls
like ε^(k+1) for some 1 <= k < N (a solution that cannot gain at order N), the verdict is
LOWER_ORDER: "accurate to O(ε^(k+1))", with the measured errors — not INVALID, which says the
solution does not describe the motion at all.  The trajectory over the horizon and the problem's own validity
estimates are reported, never decisive.
"""

from __future__ import annotations

import math

from perturb._defaults import SLOPE_TOLERANCE
from perturb.validation.report import Check, Condition, OrbitCheck, SlopeFit, Verdict

__all__ = ["accurate_order", "decide", "measurement_checks"]


def accurate_order(checks: tuple[Check, ...]) -> int | None:
    """The k of "accurate to O(eps^(k+1))", k >= 1, when the order check alone failed.

    The largest k whose slope k + 1 the measured slope reaches within the verdict's band
    (``SLOPE_TOLERANCE``), when that is below the order asked and at least 1; None when the
    outcome is not a lower order (another check failed or could not run, or even k = 1 fails).
    """
    order = next((c for c in checks if c.name == "order"), None)
    others = [c for c in checks if c.name != "order"]
    if order is None or order.passed is not False or any(c.passed is not True for c in others):
        return None
    if not math.isfinite(order.value):
        return None
    k = math.floor(order.value + SLOPE_TOLERANCE) - 1
    asked = round(order.tolerance + SLOPE_TOLERANCE) - 1
    return k if 1 <= k < asked else None


def _existence(orbit: OrbitCheck | None, why_missing: str) -> Check:
    limit = orbit.resolution_limit if orbit is not None else math.nan
    if orbit is None:
        return Check("existence", math.nan, limit, None, why_missing)
    if not orbit.success:
        return Check(
            "existence",
            math.nan,
            limit,
            None,
            f"no true periodic orbit was found near the analytic one ({orbit.message})",
        )
    if not orbit.resolved:
        return Check(
            "existence",
            orbit.resolution,
            limit,
            None,
            f"the shooting cannot resolve the true orbit at this precision (uncertainty "
            f"{orbit.resolution:.1e} of the amplitude > {limit:g}); {orbit.message}",
        )
    return Check(
        "existence",
        orbit.resolution,
        limit,
        True,
        f"a true periodic orbit exists near the analytic one (resolved to {orbit.resolution:.1e})",
    )


def _accuracy(orbit: OrbitCheck | None, tol: float, why_missing: str) -> tuple[Check, Check]:
    if orbit is None or not orbit.resolved:
        why = why_missing if orbit is None else "no resolved true orbit to measure against"
        return (
            Check("orbit_error", math.nan, tol, None, why),
            Check("period_error", math.nan, tol, None, why),
        )
    checks = []
    for name, value, what in (
        ("orbit_error", orbit.orbit_error, "distance from the true orbit"),
        ("period_error", abs(orbit.period_error), "relative period error"),
    ):
        if not math.isfinite(value):
            checks.append(Check(name, value, tol, None, f"the {what} could not be measured"))
        else:
            ok = value <= tol
            checks.append(
                Check(name, value, tol, ok, f"{what} {value:.3g} {'<=' if ok else '>'} tol {tol:g}")
            )
    return checks[0], checks[1]


def _order(fit: SlopeFit | None, why_missing: str) -> Check:
    if fit is None:
        return Check("order", math.nan, math.nan, None, why_missing, ">=")
    least = fit.expected - fit.band
    if fit.consistent is None:
        return Check(
            "order", fit.slope, least, None, f"the slope could not be measured ({fit.note})", ">="
        )
    if not math.isfinite(fit.slope):
        return Check("order", fit.slope, least, True, fit.note, ">=")
    ok = bool(fit.consistent)
    sentence = (
        f"the error falls like eps^{fit.slope:.2f} "
        f"({'>=' if ok else '<'} {least:g} = order + 1 - {fit.band:g})"
    )
    if not ok:
        sentence += ", so any agreement at this eps is accidental"
    return Check("order", fit.slope, least, ok, sentence, ">=")


def measurement_checks(
    orbit: OrbitCheck | None,
    fit: SlopeFit | None,
    tol: float,
    why_no_fit: str = "the order was not measured",
    why_no_orbit: str = "no true orbit was searched for",
) -> tuple[Check, ...]:
    """The four checks of the verdict: existence, orbit error, period error, order.

    ``why_no_fit`` and ``why_no_orbit`` say why a measurement is missing (``fit`` or ``orbit``
    None); the check is then undecided.
    """
    return (
        _existence(orbit, why_no_orbit),
        *_accuracy(orbit, tol, why_no_orbit),
        _order(fit, why_no_fit),
    )


def decide(
    checks: tuple[Check, ...],
    *,
    breakdown: str | None = None,
    failure: str | None = None,
    conditions: tuple[Condition, ...] = (),
    trajectory: str = "",
) -> tuple[Verdict, str]:
    """The outcome and its one-sentence reason.

    Parameters
    ----------
    checks : tuple of Check
    breakdown : str, optional
        Why the analytic solution itself is meaningless (non-positive period, non-finite state):
        INVALID whatever the checks.
    failure : str, optional
        Why the measurements could not be made (the true motion could not be computed): UNDECIDED.
    conditions : tuple of Condition
        The problem's validity estimates; failed ones are added as warnings.
    trajectory : str
        The trajectory information, appended to the sentence.
    """
    if breakdown is not None:
        outcome, body = Verdict.INVALID, f"The analytic solution breaks down: {breakdown}"
    elif failure is not None:
        outcome, body = Verdict.UNDECIDED, f"The true motion could not be computed: {failure}"
    else:
        failed = [c for c in checks if c.passed is False]
        open_ = [c for c in checks if c.passed is None]
        lower = accurate_order(checks)
        if lower is not None:
            outcome = Verdict.LOWER_ORDER
            asked = round(failed[0].tolerance + SLOPE_TOLERANCE) - 1
            body = (
                f"The analytic solution describes the true motion, but only to O(eps^{lower + 1}) "
                f"(accurate to order {lower} < {asked} asked): "
                + "; ".join(c.sentence for c in checks if c.name != "order")
                + f"; {failed[0].sentence.replace(', so any agreement at this eps is accidental', '')}"
            )
        elif failed:
            outcome = Verdict.INVALID
            body = "The analytic solution does not describe the true motion: " + "; ".join(
                f"{c.name}: {c.sentence}" for c in failed
            )
            if open_:
                body += " (not measured: " + ", ".join(c.name for c in open_) + ")"
        elif open_:
            outcome = Verdict.UNDECIDED
            body = "Undecided whether the analytic solution describes the true motion: " + (
                "; ".join(f"{c.name}: {c.sentence}" for c in open_)
            )
        else:
            outcome = Verdict.VALID
            body = "The analytic solution describes the true motion: " + "; ".join(
                c.sentence for c in checks
            )
    warnings = [c.sentence for c in conditions if not c.ok]
    if warnings:
        body += f". The problem's own estimate warns: {warnings[0]}"
    if trajectory:
        body += f". {trajectory}"
    return outcome, body.rstrip(".") + "."
