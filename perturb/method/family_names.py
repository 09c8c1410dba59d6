"""Stable user-facing names of the families of periodic solutions.

A name is derived from the family's generating amplitudes alone (``a_x``: cosine amplitude of
``x``, ``b_y``: sine amplitude of ``y``, relative to the phase coordinate's cosine), so it does not
depend on the order in which roots were found nor on internal symbols. "Oscillates" means that a
coordinate's generating amplitudes are not identically zero on the family.

1. One coordinate ``c`` oscillates:

   * in a system with several resonant coordinates: ``c-line`` (the others stay zero: Hénon–Heiles's
     ``y-line`` is the orbit on the y axis);
   * in a system with one resonant coordinate: ``limit-cycle`` (isolated) or ``continuum``.

2. Two coordinates oscillate, the phase coordinate ``p`` (``a_p``) and ``c`` (``a_c``, ``b_c``):


   * ``b_c ≡ 0`` (a straight line through the origin, ``c = r p``): ``in-phase`` (r a positive
     number), ``anti-phase`` (r a negative number), ``line`` (r depends on the amplitudes or the
     parameters: e.g. every direction at once);
   * ``a_c ≡ 0`` (quadrature): ``circle`` when ``b_c² = a_p²``, else ``ellipse``, followed by
     ``-ccw`` (``b_c/a_p > 0``: counter-clockwise in the (p, c) plane) or ``-cw``.

   * both non-zero on a continuum whose free amplitudes leave ``a_c² + b_c²`` unchanged: ``circle``
     (fixed amplitude, free phase of ``c``: the disk's second family ``M1² + M2² = k M3²``; sympy
     gives it as two halves, ``circle-1`` and ``circle-2``, one for each sign of the square root).

   The phase coordinate is the one with no sine amplitude (its velocity vanishes at t = 0).

3. Anything else: ``family-1``, ``family-2``, … in canonical order.

Signs of expressions are read at generic positive values of the symbols (those of
:func:`perturb.method.exact.probe_values`). Two families that would get the same name are told
apart by a suffix ``-1``, ``-2``, … in canonical order. Canonical order: by the sorted text of the
amplitudes (``str`` of the items), which is deterministic.
"""

from __future__ import annotations

from collections import Counter

import sympy as sp

from perturb.method.exact import is_zero, probe_values

__all__ = ["name_families"]


def _sign(expr: sp.Expr) -> int:
    expr = sp.sympify(expr)
    value = complex(sp.N(expr.xreplace(probe_values(expr)), 30)).real
    return 1 if value > 0 else -1


def _coordinates(amplitudes: dict) -> list[str]:
    """Coordinate names in the order of the amplitudes (``a_x``, ``a_y``, ``b_y`` -> x, y)."""
    out = []
    for key in amplitudes:
        name = key[2:]
        if name not in out:
            out.append(name)
    return out


def _structural(amplitudes: dict, free: tuple) -> str | None:
    coords = _coordinates(amplitudes)

    def value(key):
        return sp.sympify(amplitudes.get(key, 0))

    moving = [c for c in coords if not (is_zero(value(f"a_{c}")) and is_zero(value(f"b_{c}")))]
    if len(moving) == 1:
        if len(coords) > 1:
            return f"{moving[0]}-line"
        return "continuum" if free else "limit-cycle"
    if len(moving) != 2:
        return None
    phase = [m for m in moving if f"b_{m}" not in amplitudes]
    if len(phase) != 1:
        return None
    p, c = phase[0], next(m for m in moving if m != phase[0])
    a_p, a_c, b_c = value(f"a_{p}"), value(f"a_{c}"), value(f"b_{c}")
    if is_zero(b_c):
        ratio = sp.simplify(a_c / a_p)
        if not ratio.is_number:
            return "line"
        return "in-phase" if _sign(ratio) > 0 else "anti-phase"
    if is_zero(a_c):
        shape = "circle" if is_zero(sp.expand(b_c**2 - a_p**2)) else "ellipse"
        return f"{shape}-ccw" if _sign(b_c / a_p) > 0 else f"{shape}-cw"
    radius = sp.simplify(a_c**2 + b_c**2)
    if free and not radius.free_symbols & {sp.Symbol(f) for f in free}:
        return "circle"
    return None


def _canonical(amplitudes: dict) -> str:
    return str(sorted((k, str(v)) for k, v in amplitudes.items()))


def name_families(described: list[tuple[dict, tuple]]) -> list[str]:
    """Names for families given as ``(amplitudes, free)``, in the same order (see module notes)."""
    raw = [_structural(a, f) for a, f in described]
    order = sorted(range(len(described)), key=lambda i: _canonical(described[i][0]))
    counts = Counter(raw)
    seen: Counter = Counter()
    names: list[str] = [""] * len(described)
    generic = 0
    for i in order:
        if raw[i] is None:
            generic += 1
            names[i] = f"family-{generic}"
        elif counts[raw[i]] > 1:
            seen[raw[i]] += 1
            names[i] = f"{raw[i]}-{seen[raw[i]]}"
        else:
            names[i] = raw[i]
    return names
