"""A :class:`~perturb.method.families.FamilyList` as JSON-ready data or as a text table.

JSON contract (``perturb families PROBLEM --format json``)::

    {"problem": str, "order": int,
     "families": [{"name": str, "kind": "isolated" | "continuum",
                   "amplitudes": {"a_x": value, "b_y": value, ...},
                   "frequency": [Ω0, Ω1, ...],
                   "status": "SUCCESS" | "INCONSISTENT" | "UNDETERMINED" | ...,
                   "message": str, "outside": str, "beyond": str,
                   "Omega": float | null}],
     "why": str}   # only when there is no family and the search could not list them

A value (amplitude or frequency coefficient) is a JSON number when it is a number (exact integers
stay integers, other exact numbers such as 3/8 or √3/3 are given as the nearest double), else the
string of the sympy expression (``"3*a_x**2/8"``: it depends on a free amplitude or a parameter).
``frequency`` lists the coefficients Ω_k of Ω = Ω0 + εΩ1 + ε²Ω2 + … as far as they are determined.
``status`` is the name of :class:`~perturb.solution.Status`; ``message`` says at which order and why
a construction stopped (``INCONSISTENT``), which unknowns stay open (``UNDETERMINED``), or, on
success, the status's own sentence. ``outside`` says why a family's series is outside its domain
at the problem's values (``perturb solve``'s check), ``beyond`` why it is beyond its estimated
validity; each is empty when it is not (and when it was not checked). ``Omega`` is the frequency
at the problem's values (null where a free amplitude or parameter leaves it a formula, or when no
values were given); the table prints that number beside the formula.
"""

from __future__ import annotations

import sympy as sp
from attrs import frozen

__all__ = ["FamiliesOutput", "as_dict", "as_table", "jsonable"]


@frozen
class FamiliesOutput:
    """What ``perturb families`` prints: the families, the problem's label and, per family, its
    ``(outside, beyond)`` domain flags and the values of the names the table prints as numbers
    (a driven problem's Ω)."""

    families: object
    problem: str
    flags: object = None
    values: dict | None = None


def jsonable(value) -> int | float | str:
    """A number when ``value`` is one (int if integer), else the string of the expression."""
    expr = sp.sympify(value)
    if expr.is_Integer:
        return int(expr)
    if expr.is_number and expr.is_real is not False:
        try:
            return float(expr)
        except TypeError:
            pass
    return str(expr)


def _omega(family, values: dict | None):
    """``(formula, number or None)`` of a family's frequency Ω = Ω0 + εΩ1 + …, the number at
    ``values`` (names -> floats, ``epsilon`` among them) when they fix every symbol."""
    eps = sp.Symbol("epsilon")
    omega = sp.Add(*(w * eps**k for k, w in enumerate(family.frequency)))
    if values is None:
        return omega, None
    subs = {s: values[s.name] for s in omega.free_symbols if s.name in values}
    try:
        number = float(omega.xreplace(subs))
    except (TypeError, ValueError):
        return omega, None
    return omega, number


def as_dict(families, problem: str, flags=None, values: dict | None = None) -> dict:
    """The JSON contract above for ``families`` (a FamilyList) of ``problem``; ``flags`` are
    ``(outside, beyond)`` of each family (:func:`perturb.domain.series_domain`), if checked;
    ``values`` the problem's values by name (``epsilon`` among them) for ``Omega``."""
    flags = list(flags) if flags is not None else [("", "")] * len(families.families)
    return {
        "problem": problem,
        "order": families.order,
        **({"why": families.why} if families.why else {}),
        "families": [
            {
                "name": f.name,
                "kind": f.kind,
                "amplitudes": {k: jsonable(v) for k, v in f.amplitudes.items()},
                "frequency": [jsonable(w) for w in f.frequency],
                "status": f.status.name,
                "message": f.message,
                "outside": outside,
                "beyond": beyond,
                "Omega": _omega(f, values)[1],
            }
            for f, (outside, beyond) in zip(families, flags, strict=True)
        ],
    }


def as_table(families, problem: str, flags=None, values: dict | None = None) -> str:
    """One block per family: name, kind (free amplitudes), amplitudes, frequency (its number at
    ``values`` first, when they fix it), status (and ``flags``, as for :func:`as_dict`)."""
    flags = list(flags) if flags is not None else [("", "")] * len(families.families)
    count = len(families.families)
    noun = "family" if count == 1 else "families"
    head = f"# {problem}: {count} {noun}, carried to order {families.order}"
    if families.family_order is not None:
        head += f" (selected by the conditions of order {families.family_order})"
    lines = [head]
    if not families.families:
        why = families.why or "the amplitude equations have only the trivial root"
        lines.append(f"no family: {why}")
    for f, (outside, beyond) in zip(families, flags, strict=True):
        kind = f.kind + (f" in {', '.join(f.free)}" if f.free else "")
        amplitudes = ", ".join(f"{k} = {v}" for k, v in f.amplitudes.items())
        omega, number = _omega(f, values)
        if number is not None and omega.free_symbols:
            frequency = f"{number:.12g}  (= {omega})"
        else:
            frequency = str(omega)
        lines += [
            "",
            f"{f.name}  ({kind})",
            f"  amplitudes: {amplitudes}",
            f"  Omega = {frequency}",
            f"  status: {f.status.name}: {f.message}",
        ]
        if outside:
            lines.append(f"  OUTSIDE the series' domain at these values: {outside}")
        elif beyond:
            lines.append(f"  {beyond}")
    return "\n".join(lines)
