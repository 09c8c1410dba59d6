"""A frequency response as JSON, CSV, a text table or LaTeX (``perturb response``)."""

from __future__ import annotations

import math

from perturb.report.latex import latex_comment

__all__ = ["response_as_csv", "response_as_dict", "response_as_table", "response_latex"]

_STABILITY = {True: "stable", False: "unstable", None: "marginal"}


def _number(value):
    value = float(value)
    return value if math.isfinite(value) else None


def _complex(z) -> list:
    return [_number(z.real), _number(z.imag)]


def response_as_dict(result) -> dict:
    """The JSON contract of ``perturb response --format json``.

    ``{"problem", "parameter", "order", "epsilon", "parameters", "points": [{"value", "branch",
    "amplitudes", "norms", "stable", "eigenvalues", "multipliers", "note"}], "folds": [{"value",
    "norms"}], "branch_points": [{"value", "norms"}], "backbone": {"coordinate", "amplitudes", "values"} | null, "true": [{"value",
    "branch", "success", "amplitude", "amplitude_error", "floquet_max", "stable_true",
    "stable_analytic", "message"}], "failures": [str]}``; complex numbers are ``[re, im]``.
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
        "folds": [{"value": f.value, "norms": f.norms} for f in response.folds],
        "branch_points": [{"value": f.value, "norms": f.norms} for f in response.branch_points],
        "backbone": backbone,
        "true": true,
        "failures": list(response.failures),
    }


def response_as_csv(result) -> str:
    """One row per branch point: ``PARAMETER,branch,<coordinate> amplitude...,stable``."""
    response = result.response
    coords = list(response.coordinates)
    header = [result.parameter, "branch", *(f"{c}_amplitude" for c in coords), "stable"]
    rows = [",".join(header)]
    for p, name in zip(response.points, result.branches, strict=True):
        cells = [f"{p.value:.12g}", name, *(f"{p.norms[c]:.12g}" for c in coords)]
        rows.append(",".join([*cells, _STABILITY[p.stable]]))
    return "\n".join(rows)


def response_as_table(result) -> str:
    """A readable table: the points, the folds, the shot points, what could not be solved."""
    response = result.response
    coords = list(response.coordinates)
    lines = [
        f"# response {result.problem}  sweep {result.parameter}  order {response.order}  "
        f"epsilon {response.epsilon:g}",
        "# " + "  ".join(f"{k}={v:g}" for k, v in response.values.items()),
        f"{result.parameter:>12s} {'branch':>9s} "
        + " ".join(f"{'|' + c + '|':>12s}" for c in coords)
        + f" {'stability':>10s} {'max|lambda|':>12s}",
    ]
    for p, name in zip(response.points, result.branches, strict=True):
        largest = max((abs(z) for z in p.multipliers), default=math.nan)
        lines.append(
            f"{p.value:12.6g} {name:>9s} "
            + " ".join(f"{p.norms[c]:12.6g}" for c in coords)
            + f" {_STABILITY[p.stable]:>10s} {largest:12.6f}"
            + (f"  ({p.note})" if p.note else "")
        )
    if response.folds:
        lines.append("folds (saddle-node: the response jumps here in a slow sweep):")
        for f in response.folds:
            amps = "  ".join(f"|{c}| = {v:.6g}" for c, v in f.norms.items())
            lines.append(f"  {result.parameter} = {f.value:.8g}   {amps}")
    if response.branch_points:
        lines.append("branch points (a branch crosses another and goes on):")
        for f in response.branch_points:
            amps = "  ".join(f"|{c}| = {v:.6g}" for c, v in f.norms.items())
            lines.append(f"  {result.parameter} = {f.value:.8g}   {amps}")
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
            lines.append(
                f"  {result.parameter} = {t.value:.6g} {t.branch:>9s}: "
                + (
                    f"amplitude error {t.amplitude_error:.3g}, max|lambda| {t.floquet_max:.6f} "
                    f"({_STABILITY[t.stable_true]}; slow flow {_STABILITY[t.stable_analytic]}: "
                    f"{agree})"
                    if t.success
                    else f"no true orbit found: {t.message}"
                )
            )
    for failure in response.failures:
        lines.append(f"not solved: {failure}")
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
