"""A frequency response as JSON, CSV, a text table or LaTeX (``perturb response``)."""

from __future__ import annotations

import math

from perturb.report.latex import latex_comment
from perturb.report.marks import PointMark, point_mark, relative_error
from perturb.report.true_curve import true_curve_as_dict, true_curve_latex, true_curve_lines
from perturb.steady.measures import MEASURES

__all__ = [
    "flag_lines",
    "response_as_csv",
    "response_as_dict",
    "response_as_table",
    "response_latex",
]

_STABILITY = {True: "stable", False: "unstable", None: "marginal"}


def _number(value):
    value = float(value)
    return value if math.isfinite(value) else None


def _complex(z) -> list:
    return [_number(z.real), _number(z.imag)]


def response_as_dict(result) -> dict:
    """The JSON contract of ``perturb response --format json``.

    ``{"problem", "parameter", "order", "epsilon", "parameters", "points": [{"value", "branch",
    "amplitudes", "norms", "stable", "eigenvalues", "multipliers", "note", "peak",
    "first_harmonic", "error_estimate", "series_ok", "liouville", "curve", "mark"}], "folds":
    [{"value", "norms", "amplitudes", "peak", "first_order", "inside", "uncertainty",
    "true_value"}], "backbone": {"coordinate",
    "amplitudes", "values"} | null, "true": [{"value", "branch", "success", "amplitude",
    "amplitude_error", "floquet_max", "stable_true", "stable_analytic", "message",
    "true_amplitude", "measure", "within_tol", "reason", "multipliers_true",
    "multipliers_analytic", "curve"}], "failures": [str], "measure": {"name", "meaning"},
    "special": [{"kind", "value", "amplitudes", "norms", "peak", "inside", "multipliers"}],
    "curves": [{"values", "amplitudes": {measure: {coordinate: [...]}}, "stable", "series_ok",
    "max_multiplier", "status"}], "true_curve": {...} | null}``; complex numbers are
    ``[re, im]``. ``norms`` is the initial-value norm; ``measure`` names the amplitude the response is drawn by (``amplitude``
    and ``true_amplitude`` of the shot points are in it). ``true_curve`` (``--true``; null
    without it) is :func:`~perturb.report.true_curve.true_curve_as_dict`. A point's ``mark``
    is ``""`` when the series vouches for its labels, else ``outside``, ``beyond`` or
    ``uncertain`` (:mod:`perturb.report.marks`).
    """
    response = result.response
    points = [
        {
            "value": p.value,
            "branch": name,
            "amplitudes": {k: _number(v) for k, v in p.amplitudes.items()},
            "norms": {k: _number(v) for k, v in p.norms.items()},
            "stable": p.stable,
            "eigenvalues": [_complex(z) for z in p.eigenvalues],
            "multipliers": [_complex(z) for z in p.multipliers],
            "note": p.note,
            "peak": _numbers(p.peak),
            "first_harmonic": _numbers(p.first_harmonic),
            "error_estimate": _numbers(p.error),
            "series_ok": p.series_ok,
            "liouville": _number(p.liouville),
            "curve": p.branch,
            "mark": point_mark(p).code,
        }
        for p, name in zip(response.points, result.branches, strict=True)
    ]
    backbone = None
    if result.backbone is not None:
        backbone = {
            "coordinate": result.backbone.coordinate,
            "amplitudes": [_number(a) for a in result.backbone.amplitudes],
            "values": [_number(v) for v in result.backbone.values],
        }
    true = [
        {
            "value": t.value,
            "branch": t.branch,
            "success": t.success,
            "amplitude": _number(t.amplitude),
            "amplitude_error": _number(t.amplitude_error),
            "floquet_max": _number(t.floquet_max),
            "stable_true": t.stable_true,
            "stable_analytic": t.stable_analytic,
            "message": t.message,
            "true_amplitude": _number(t.true_amplitude),
            "measure": t.measure,
            "within_tol": t.within_tol,
            "reason": t.reason,
            "multipliers_true": [_complex(z) for z in t.multipliers_true],
            "multipliers_analytic": [_complex(z) for z in t.multipliers_analytic],
            "curve": t.curve,
        }
        for t in result.true
    ]
    return {
        "problem": result.problem,
        "parameter": result.parameter,
        "order": response.order,
        "epsilon": response.epsilon,
        "parameters": response.values,
        "points": points,
        "folds": [
            {
                "value": f.value,
                "norms": f.norms,
                "amplitudes": _numbers(f.amplitudes),
                "peak": _numbers(f.peak),
                "first_order": _number(f.first_order),
                "inside": f.inside,
                "uncertainty": _number(f.uncertainty),
                "true_value": _number(f.true_value),
            }
            for f in response.folds
        ],
        "backbone": backbone,
        "true": true,
        "failures": list(response.failures),
        "measure": {"name": response.measure, "meaning": MEASURES.get(response.measure, "")},
        "special": [
            {
                "kind": sp.kind,
                "value": sp.value,
                "amplitudes": _numbers(sp.amplitudes),
                "norms": _numbers(sp.norms),
                "peak": _numbers(sp.peak),
                "inside": sp.inside,
                "multipliers": [_complex(z) for z in sp.multipliers],
            }
            for sp in response.special
        ],
        "curves": [
            {
                "values": [_number(v) for v in c.values],
                "amplitudes": {
                    m: {k: [_number(v) for v in a] for k, a in by.items()}
                    for m, by in c.measures.items()
                },
                "stable": list(c.stable),
                "series_ok": list(c.series_ok),
                "max_multiplier": [_number(v) for v in c.largest],
                "status": c.status,
            }
            for c in response.curves
        ],
        "true_curve": true_curve_as_dict(result.true_curve),
    }


def _numbers(mapping) -> dict:
    return {k: _number(v) for k, v in mapping.items()}


def response_as_csv(result) -> str:
    """One row per branch point: ``PARAMETER,branch,<coordinate>_amplitude...,stable`` (the
    amplitude the initial-value norm, as always), then ``<coordinate>_peak...,
    <coordinate>_first_harmonic..., max_multiplier, series_ok, mark`` (``mark`` empty when the
    series vouches for the point, else ``outside``, ``beyond`` or ``uncertain``)."""
    response = result.response
    coords = list(response.coordinates)
    header = [
        result.parameter, "branch", *(f"{c}_amplitude" for c in coords), "stable",
        *(f"{c}_peak" for c in coords), *(f"{c}_first_harmonic" for c in coords),
        "max_multiplier", "series_ok", "mark",
    ]  # fmt: skip
    rows = [",".join(header)]
    for p, name in zip(response.points, result.branches, strict=True):
        cells = [f"{p.value:.12g}", name, *(f"{p.norms[c]:.12g}" for c in coords)]
        largest = max((abs(z) for z in p.multipliers), default=math.nan)
        extra = [
            *(f"{p.peak.get(c, math.nan):.12g}" for c in coords),
            *(f"{p.first_harmonic.get(c, math.nan):.12g}" for c in coords),
            f"{largest:.12g}", str(p.series_ok).lower(), point_mark(p).code,
        ]  # fmt: skip
        rows.append(",".join([*cells, _STABILITY[p.stable], *extra]))
    return "\n".join(rows)


def response_as_table(result) -> str:
    """A readable table: the points, the special points, the shot points, what failed."""
    response = result.response
    coords = list(response.coordinates)
    measure = getattr(response, "measure", "initial")

    def size(p, c):
        if hasattr(p, "amplitude"):
            return p.amplitude(c, measure)
        table = {"peak": p.peak, "initial": p.norms}.get(measure) or p.norms
        return table.get(c, math.nan)

    lines = [
        f"# response {result.problem}  sweep {result.parameter}  order {response.order}  "
        f"epsilon {response.epsilon:g}  amplitude: {MEASURES.get(measure, measure)}",
        "# " + "  ".join(f"{k}={v:g}" for k, v in response.values.items()),
        f"{result.parameter:>12s} {'branch':>9s} "
        + " ".join(f"{'|' + c + '|':>12s}" for c in coords)
        + f" {'stability':>10s} {'max|lambda|':>12s} {'prod lambda':>12s}",
    ]
    for p, name in zip(response.points, result.branches, strict=True):
        largest = max((abs(z) for z in p.multipliers), default=math.nan)
        product = math.prod(p.multipliers).real if p.multipliers else math.nan
        lines.append(
            f"{p.value:12.6g} {name:>9s} "
            + " ".join(f"{size(p, c):12.6g}" for c in coords)
            + f" {_STABILITY[p.stable]:>10s} {largest:12.6f} {product:12.6f}"
            + (f"  [{point_mark(p).value}]" if point_mark(p) is not PointMark.NONE else "")
            + (f"  ({p.note})" if p.note else "")
        )
    if response.folds:
        lines.append("folds (saddle-node: the response jumps here in a slow sweep; * beside it):")
        for f in response.folds:
            amps = "  ".join(f"|{c}| = {size(f, c):.6g}" for c in coords)
            lines.append(
                f" {' ' if f.inside else '*'} {result.parameter} = {f.value:.8g}{_band(f)}   {amps}"
            )
    others = [s for s in response.special if s.kind != "fold"]
    if others:
        lines.append("branch points, Neimark-Sacker, period doubling (* beside the sweep):")
        for s in others:
            amps = "  ".join(f"|{c}| = {size(s, c):.6g}" for c in coords)
            mark = " " if s.inside else "*"
            lines.append(f" {mark}{s.kind:>15s} at {result.parameter} = {s.value:.8g}   {amps}")
    if result.backbone is not None:
        b = result.backbone
        lines.append(
            f"backbone ({b.coordinate}, free undamped system): {result.parameter} from "
            f"{b.values[0]:.6g} at amplitude 0 to {b.values[-1]:.6g} at {b.amplitudes[-1]:.4g}"
        )
    if result.true:
        lines.append("true motion (forced shooting, Floquet multipliers):")
        for t in result.true:
            agree = "agree" if t.stable_true == t.stable_analytic else "DISAGREE"
            within = {True: "", False: " > tol", None: ""}[t.within_tol]
            lines.append(
                f"  {result.parameter} = {t.value:.6g} {t.branch:>9s}: "
                + (
                    f"amplitude {t.amplitude:.6g} (true {t.true_amplitude:.6g}), orbit error "
                    f"{t.amplitude_error:.3g}{within}, max|lambda| {t.floquet_max:.6f} "
                    f"({_STABILITY[t.stable_true]}; analytic {_STABILITY[t.stable_analytic]}: "
                    f"{agree}) [{t.reason}]"
                    if t.success
                    else f"no true orbit found: {t.message}"
                )
            )
    for failure in response.failures:
        lines.append(f"not solved: {failure}")
    lines.extend(true_curve_lines(result.true_curve, result.parameter))
    lines.extend(flag_lines(result))
    return "\n".join(lines)


def response_latex(result) -> str:
    """The folds and a sample of points as a booktabs tabular (``--format latex``)."""
    response = result.response
    coords = list(response.coordinates)
    head = " & ".join([f"${result.parameter}$", "branch", *(f"$|{c}|$" for c in coords), "stable"])
    rows = [
        " & ".join(
            [f"{p.value:.6g}", name, *(f"{p.norms[c]:.6g}" for c in coords), _STABILITY[p.stable]]
        )
        + r" \\"
        for p, name in zip(response.points, result.branches, strict=True)
    ]
    folds = "".join(f"% fold at {result.parameter} = {f.value:.8g}\n" for f in response.folds)
    folds += true_curve_latex(result.true_curve, result.parameter)
    return (
        f"% {latex_comment(result.problem)}: frequency response, order {response.order}\n"
        + folds
        + "\\begin{tabular}{"
        + "r" * (len(coords) + 1)
        + "lr}\n\\toprule\n"
        + head
        + r" \\"
        + "\n\\midrule\n"
        + "\n".join(rows)
        + "\n\\bottomrule\n\\end{tabular}\n"
    )


def _band(fold) -> str:
    """`` ± δ`` (the series' own estimate of the fold's error), `` ± ?`` (it cannot tell), and
    the true fold with ``--true``."""
    band = f" ± {fold.uncertainty:.2g}" if math.isfinite(fold.uncertainty) else " ± ?"
    if math.isfinite(fold.true_value):
        band += f" (true {fold.true_value:.10g})"
    return band


def fold_lines(result) -> list[str]:
    """Sentences about the folds' uncertainty when the series stands alone (no true fold
    refines them): where the branch set may change, and the points there."""
    response = result.response
    lines = []
    for f in response.folds:
        if math.isfinite(f.true_value):
            continue
        marked = sum(1 for p in response.points if f.holds(p.value))
        if not math.isfinite(f.uncertainty):
            lines.append(f"{f.band_note(result.parameter)}; check it with --true")
        elif marked:
            lines.append(
                f"{f.band_note(result.parameter)} (the series' own estimate: orders "
                f"{response.order} and {response.order - 1} differ by that); {marked} point(s) "
                "there are marked; check them with --true"
            )
    return lines


def flag_lines(result) -> list[str]:
    """Sentences about the points whose series is outside its domain (``series_ok`` false),
    beyond its validity (the series' own estimate of its error, ``error`` per coordinate, more
    than :data:`perturb._defaults.VALIDITY_ESTIMATE_LIMIT` of the point's amplitude), or whose
    stability is within the series' error of 1 (:func:`perturb.report.marks.point_mark`)."""
    from perturb._defaults import VALIDITY_ESTIMATE_LIMIT

    points = result.response.points
    marks = [point_mark(p) for p in points]
    outside = [p for p, m in zip(points, marks, strict=True) if m is PointMark.OUTSIDE]
    beyond = [
        (p, relative_error(p)) for p, m in zip(points, marks, strict=True) if m is PointMark.BEYOND
    ]
    uncertain = [p for p, m in zip(points, marks, strict=True) if m is PointMark.UNCERTAIN]
    lines = []
    if outside:
        lines.append(
            f"{len(outside)} of {len(points)} steady states are outside the series' domain: their "
            f"amplitudes are not the motion's (e.g. at {result.parameter} = "
            f"{outside[0].value:.6g}: {outside[0].note})"
        )
    if beyond:
        point, ratio = max(beyond, key=lambda b: b[1])
        lines.append(
            f"{len(beyond)} of {len(points)} steady states are beyond the series' validity: its own "
            f"estimate of their error is more than {VALIDITY_ESTIMATE_LIMIT:g} of the amplitude "
            f"(up to {ratio:.2g} at {result.parameter} = {point.value:.6g}); check them with "
            "--validate"
        )
    if uncertain:
        lines.append(
            f"{len(uncertain)} of {len(points)} steady states have a stability within the series' "
            f"error of 1: their largest Floquet multiplier is not farther from the unit circle "
            f"than the estimated error of the orbit (e.g. at {result.parameter} = "
            f"{uncertain[0].value:.6g}), so stable or unstable is not certain there; check them "
            "with --validate"
        )
    return lines + fold_lines(result)
