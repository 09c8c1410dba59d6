"""A frequency response as JSON, CSV, a text table or LaTeX (``perturb response``)."""

from __future__ import annotations

import math

from perturb.report.latex import latex_comment

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


def _flags(result) -> list[tuple[str, str]]:
    """``(outside, beyond)`` of each point (``""`` each for a result made without them)."""
    n = len(result.response.points)
    outside = tuple(getattr(result, "outside", ())) or ("",) * n
    beyond = tuple(getattr(result, "beyond", ())) or ("",) * n
    return list(zip(outside, beyond, strict=True))


def _flag(outside: str, beyond: str) -> str:
    """The CSV's ``flag`` column: ``outside`` (its domain), ``beyond`` (its validity) or empty."""
    return "outside" if outside else "beyond" if beyond else ""


def flag_lines(result) -> list[str]:
    """Sentences about the points outside the series' domain or beyond its validity."""
    parameter = result.parameter
    flags = _flags(result)
    lines = []
    for kind, index, what, meaning in (
        ("outside", 0, "outside the series' domain", "are not the motion's"),
        ("beyond", 1, "beyond the series' estimated validity", "may be far from the motion's"),
    ):
        marked = [(p, f[index]) for p, f in zip(result.response.points, flags, strict=True)
                  if f[index]]  # fmt: skip
        if marked:
            point, reason = marked[0]
            lines.append(
                f"{len(marked)} of {len(flags)} steady states are {what} (flag {kind}): their "
                f"amplitudes {meaning}; e.g. at {parameter} = {point.value:.6g}: {reason}"
            )
    return lines


def response_as_dict(result) -> dict:
    """The JSON contract of ``perturb response --format json``.

    ``{"problem", "parameter", "order", "epsilon", "parameters", "points": [{"value", "branch",
    "amplitudes", "norms", "stable", "eigenvalues", "multipliers", "note", "outside",
    "beyond"}], "folds": [{"value",
    "norms"}], "backbone": {"coordinate", "amplitudes", "values"} | null, "true": [{"value",
    "branch", "success", "amplitude", "amplitude_error", "floquet_max", "stable_true",
    "stable_analytic", "message"}], "failures": [str]}``; complex numbers are ``[re, im]``;
    ``outside`` says why a point's series is outside its domain, ``beyond`` why it is beyond its
    estimated validity (each empty when it is not).
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
            "outside": outside,
            "beyond": beyond,
        }
        for p, name, (outside, beyond) in zip(
            response.points, result.branches, _flags(result), strict=True
        )
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
        "backbone": backbone,
        "true": true,
        "failures": list(response.failures),
    }


def response_as_csv(result) -> str:
    """One row per branch point: ``PARAMETER,branch,<coordinate> amplitude...,stable,flag``
    (``flag``: ``outside`` its series' domain, ``beyond`` its estimated validity, or empty)."""
    response = result.response
    coords = list(response.coordinates)
    header = [result.parameter, "branch", *(f"{c}_amplitude" for c in coords), "stable", "flag"]
    rows = [",".join(header)]
    for p, name, flags in zip(response.points, result.branches, _flags(result), strict=True):
        cells = [f"{p.value:.12g}", name, *(f"{p.norms[c]:.12g}" for c in coords)]
        rows.append(",".join([*cells, _STABILITY[p.stable], _flag(*flags)]))
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
    for p, name, flags in zip(response.points, result.branches, _flags(result), strict=True):
        largest = max((abs(z) for z in p.multipliers), default=math.nan)
        flag = _flag(*flags)
        lines.append(
            f"{p.value:12.6g} {name:>9s} "
            + " ".join(f"{p.norms[c]:12.6g}" for c in coords)
            + f" {_STABILITY[p.stable]:>10s} {largest:12.6f}"
            + (f"  [{flag}]" if flag else "")
            + (f"  ({p.note})" if p.note else "")
        )
    lines += flag_lines(result)
    if response.folds:
        lines.append("folds (saddle-node: the response jumps here in a slow sweep):")
        for f in response.folds:
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
