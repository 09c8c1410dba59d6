"""The true curves of a response (``perturb response --true``) as JSON, table lines and LaTeX."""

from __future__ import annotations

import math

__all__ = ["true_curve_as_dict", "true_curve_latex", "true_curve_lines"]

_STABILITY = {True: "stable", False: "unstable", None: "marginal"}


def _number(value):
    value = float(value)
    return value if math.isfinite(value) else None


def _complex(z) -> list:
    return [_number(z.real), _number(z.imag)]


def _numbers(mapping: dict) -> dict:
    return {k: _number(v) for k, v in mapping.items()}


def true_curve_as_dict(curves) -> dict | None:
    """The ``true_curve`` entry of ``perturb response --format json`` (None without ``--true``).

    ``{"budget", "tolerance", "measure", "integrator", "curves": [{"branches",
    "status", "success", "message", "shots", "period", "parent", "birth", "born_at", "points":
    [{"value", "state", "norms", "peaks", "harmonics", "multipliers", "stable"}],
    "bifurcations": [...]}], "bifurcations": [{"kind", "value", "curve", "norms", "peaks",
    "multiplier", "multipliers", "inside", "located", "note", "rotation", "state", "period"}],
    "partings": [{"branch", "value", "analytic", "true", "difference", "tolerance", "before",
    "after", "note"}], "failures": [str]}``; complex numbers are ``[re, im]``, non-finite numbers
    null (``difference`` is null where no true orbit is left). Each curve is one branch of the
    diagram: its ``period`` (in response periods), its ``parent`` (the index of the curve it was
    born on; null for a curve through the analytic branches), the kind of its ``birth``
    (``seed``, ``branch-point``, ``period-doubling``) and where (``born_at``), and its own
    special points (``bifurcations``, as in the list of all of them).
    """
    if curves is None:
        return None
    out_curves, bifurcations = [], []
    for index, curve in enumerate(curves.curves):
        own = [_bifurcation(b, index, curve.period) for b in curve.bifurcations]
        out_curves.append(
            {
                "branches": list(curve.branches),
                "status": curve.status,
                "success": curve.success,
                "message": curve.message,
                "shots": curve.shots,
                "period": curve.period,
                "parent": curve.parent,
                "birth": curve.birth,
                "born_at": _number(curve.born_at),
                "bifurcations": own,
                "points": [
                    {
                        "value": p.value,
                        "state": [_number(v) for v in p.state],
                        "norms": _numbers(p.norms),
                        "peaks": _numbers(p.peaks),
                        "harmonics": _numbers(p.harmonics),
                        "multipliers": [_complex(z) for z in p.multipliers],
                        "stable": p.stable,
                    }
                    for p in curve.points
                ],
            }
        )
        bifurcations.extend(own)
    return {
        "budget": curves.budget,
        "tolerance": curves.tolerance,
        "measure": curves.measure,
        "integrator": curves.integrator,
        "curves": out_curves,
        "bifurcations": sorted(bifurcations, key=lambda b: b["value"]),
        "partings": [
            {
                "branch": p.branch,
                "value": _number(p.value),
                "analytic": _number(p.analytic),
                "true": _number(p.true),
                "difference": _number(p.difference),
                "tolerance": p.tolerance,
                "before": _number(p.before),
                "after": _number(p.after),
                "note": p.note,
            }
            for p in curves.partings
        ],
        "failures": list(curves.failures),
    }


def _bifurcation(b, index: int, period: int) -> dict:
    return {
        "kind": b.kind,
        "value": b.value,
        "curve": index,
        "norms": _numbers(b.norms),
        "peaks": _numbers(b.peaks),
        "multiplier": _complex(b.multiplier),
        "multipliers": [_complex(z) for z in b.multipliers],
        "inside": b.inside,
        "located": b.located,
        "note": b.note,
        "rotation": _number(b.rotation),
        "state": [_number(v) for v in b.state],
        "period": period,
    }


def _amplitudes(point, measure: str) -> str:
    """Each resonant coordinate's amplitude in ``measure`` (the one the section's header names)."""
    return "  ".join(f"|{c}| = {point.amplitude(c, measure):.6g}" for c in point.norms)


def _listed(curves) -> list:
    """The special points to print: ``(point, "curve k[, j]", times)`` by value, one entry for
    a point met on several curves (where they meet) and for the two of a symmetric pair (the
    same kind, value and amplitude); a doubled orbit's meeting with its parent (``crossing``)
    is its parent's period doubling, printed there."""
    from perturb.response.true_results import same_point

    entries: list = []
    for index, curve in enumerate(curves.curves, start=1):
        seen_here: list = []
        for b in curve.bifurcations:
            if b.kind == "crossing":
                continue
            key = (b.kind, round(b.value, 9), round(max(b.peaks.values(), default=0.0), 6))
            here = next((e for e in entries if e[0] == key or same_point(b, e[1])), None)
            if here is None:
                entries.append([key, b, [index], 1])
                seen_here.append(key)
            elif key in seen_here:
                here[3] += 1
            else:
                if b.located and not here[1].located:  # the better location shown
                    here[1] = b
                if index not in here[2]:
                    here[2].append(index)
    entries.sort(key=lambda e: e[1].value)
    return [(b, "curve " + ", ".join(map(str, where)), times) for _, b, where, times in entries]


def _birth(curve, parameter: str) -> str:
    if curve.parent is None:
        return f"from {', '.join(curve.branches)}"
    return (
        f"period {curve.period}, born at the {curve.birth} at {parameter} = "
        f"{curve.born_at:.10g} on curve {curve.parent + 1}"
    )


def true_curve_lines(curves, parameter: str) -> list[str]:
    """The table's section on the true curves: each curve, its special points, the partings."""
    if curves is None:
        return []
    lines = [
        f"true curves (shooting with the period fixed, pseudo-arclength, Floquet multipliers; "
        f"{curves.integrator}; at most {curves.budget} points each):"
    ]
    for i, curve in enumerate(curves.curves, start=1):
        values = [p.value for p in curve.points]
        span = f"{parameter} {min(values):.6g}..{max(values):.6g}" if values else "no point"
        stable = sum(1 for p in curve.points if p.stable)
        lines.append(
            f"  curve {i} ({_birth(curve, parameter)}): {len(curve.points)} points "
            f"({stable} stable), {span}, {curve.shots} shots; "
            + ("" if curve.success else "STOPPED: ")
            + curve.message
        )
    found = _listed(curves)
    if found:
        from perturb.steady.measures import MEASURES

        lines.append(
            "  special points of the true curves (located on them; amplitude: "
            f"{MEASURES.get(curves.measure, curves.measure)}):"
        )
        for b, where_found, times in found:
            where = "" if b.inside else "  (outside the sweep)"
            z = b.multiplier
            torus = f", torus rotation number {b.rotation:.8g}" if math.isfinite(b.rotation) else ""
            pair = (
                f" x{times} (orbits that are images: x -> -x, or a period later)"
                if times > 1
                else ""
            )
            lines.append(
                f"    {b.kind:>15s} {parameter} = {b.value:.10g}   "
                f"{_amplitudes(b, curves.measure)}   "
                f"multiplier {z.real:+.6f}{z.imag:+.6f}i{torus}   on {where_found}{pair}{where}"
                + (f"  ({b.note})" if b.note else "")
            )
    if curves.partings:
        lines.append(
            f"  where the analytic and true curves part (relative difference > {curves.tolerance:g}):"
        )
        for p in curves.partings:
            true = "no true orbit" if not math.isfinite(p.true) else f"true {p.true:.6g}"
            diff = "none left" if not math.isfinite(p.difference) else f"{p.difference:.3g}"
            if p.note:
                lines.append(f"    {p.branch:>9s}: {p.note}")
                continue
            lines.append(
                f"    {p.branch:>9s}: {parameter} = {p.value:.6g} (amplitude analytic "
                f"{p.analytic:.6g}, {true}); agree at {p.before:.6g}, differ by {diff} at "
                f"{p.after:.6g}"
            )
    for failure in curves.failures:
        lines.append(f"  not continued: {failure}")
    return lines


def true_curve_latex(curves, parameter: str) -> str:
    """LaTeX comment lines: the true curves' special points and partings."""
    if curves is None:
        return ""
    out = [f"% true {b.kind} at {parameter} = {b.value:.10g}\n" for b in curves.bifurcations]
    out += [
        f"% analytic {p.branch} parts from the true curve at {parameter} = {p.value:.6g}\n"
        for p in curves.partings
    ]
    return "".join(out)
