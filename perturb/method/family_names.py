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

3. A line whose direction is a fixed number (a continuum restricted by a later order, or an
   isolated root), when the solution tells whether it stays straight (``straight`` given by
   :func:`perturb.method.families.find_families`): ``line-θ`` for an orbit that stays on its line
   at every order, ``bowed-θ`` for one that leaves it (the higher harmonics bend it), θ the
   direction in degrees in [0, 180) in the plane of the first two resonant coordinates. The
   names above win where they apply: a straight orbit on an axis stays ``c-line``, a line with
   r = ±1 stays ``in-phase``/``anti-phase``. Hénon–Heiles: ``y-line`` (the axis, straight),
   ``line-30``, ``line-150`` (straight: 210° and 330° point the other way along them),
   ``bowed-0``, ``bowed-60``, ``bowed-120``, ``circle-ccw``, ``circle-cw``.

4. Three or more resonant coordinates, an isolated root with every sine amplitude zero (a
   standing wave: every coordinate passes through zero at the same instants), named by its mode
   shape, the signs and zeros of its amplitude vector in the coordinates' order (the phase
   coordinate's amplitude is positive):

   * no coordinate at rest, all of one sign: ``in-phase``; neighbours of opposite signs:
     ``anti-phase``; any other pattern: ``shape-`` and the signs (``p`` positive, ``n``
     negative, ``0`` at rest), e.g. ``shape-ppnn`` or ``shape-p0n``;
   * followed by ``-localised-c`` when the motion is concentrated on fewer than about half of the
     n coordinates: the participation number ``(Σ a²)² / Σ a⁴`` (1 for one coordinate, n for
     equal amplitudes) is below ``LOCALISED_BELOW`` · (n + 1), and c is the coordinate of
     largest amplitude (a chain of 4's ``(1, -6.03, 6.03, -1)`` is ``anti-phase-localised-x2``).

   The chain of 3's five branches: ``in-phase``, ``shape-p0n`` and three ``anti-phase-k``.

5. Anything else: ``family-1``, ``family-2``, … in canonical order.

Signs of expressions are read at generic positive values of the symbols (those of
:func:`perturb.method.exact.probe_values`). Two families that would get the same name are told
apart by a suffix ``-1``, ``-2``, … in canonical order. Canonical order: by the sorted text of the
amplitudes (``str`` of the items), which is deterministic.
"""

from __future__ import annotations

import math
from collections import Counter
from itertools import pairwise

import sympy as sp

from perturb._defaults import LOCALISED_BELOW
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


def _angle(coords: list, direction: dict) -> str | None:
    """The direction of a line in the plane of the first two coordinates, in degrees in [0, 180)
    (an integer when it is one to 1e-9, else one decimal); None off that plane."""
    if len(coords) < 2 or any(not is_zero(direction.get(c, 0)) for c in coords[2:]):
        return None
    u, v = (sp.sympify(direction.get(c, 0)) for c in coords[:2])
    free = (u.free_symbols | v.free_symbols) - set()
    point = probe_values(u + v) if free else {}
    x, y = (complex(sp.N(w.xreplace(point), 30)).real for w in (u, v))
    degrees = math.degrees(math.atan2(y, x)) % 180.0
    whole = round(degrees)
    if abs(degrees - whole) < 1e-9:
        return str(whole % 180)
    return f"{degrees:.1f}"


def _mode_shape(coords: list, value) -> str | None:
    """The name of a standing wave of three or more coordinates (module notes, rule 4)."""
    if any(not is_zero(value(f"b_{c}")) for c in coords):
        return None
    amplitudes = [value(f"a_{c}") for c in coords]
    if not all(a.is_number for a in amplitudes):
        return None
    signs = [0 if is_zero(a) else _sign(a) for a in amplitudes]
    if next((s for s in signs if s), 1) < 0:
        signs = [-s for s in signs]  # the phase coordinate's amplitude counts as positive
    if 0 not in signs and len(set(signs)) == 1:
        name = "in-phase"
    elif 0 not in signs and all(a != b for a, b in pairwise(signs)):
        name = "anti-phase"
    else:
        name = "shape-" + "".join({1: "p", -1: "n", 0: "0"}[s] for s in signs)
    squares = [float(sp.N(a, 30)) ** 2 for a in amplitudes]
    participation = sum(squares) ** 2 / sum(q * q for q in squares)
    if participation < LOCALISED_BELOW * (len(coords) + 1):
        peak = max(range(len(coords)), key=lambda i: squares[i])
        name += f"-localised-{coords[peak]}"
    return name


def _structural(amplitudes: dict, free: tuple, straight: bool | None = None) -> str | None:
    coords = _coordinates(amplitudes)

    def value(key):
        return sp.sympify(amplitudes.get(key, 0))

    if len(coords) >= 3 and not free:
        shape = _mode_shape(coords, value)
        if shape is not None:
            return shape

    moving = [c for c in coords if not (is_zero(value(f"a_{c}")) and is_zero(value(f"b_{c}")))]
    if len(moving) == 1:
        if len(coords) > 1:
            if straight is False and all(is_zero(value(f"b_{c}")) for c in coords):
                angle = _angle(coords, {c: value(f"a_{c}") for c in coords})
                if angle is not None:
                    return f"bowed-{angle}"
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
        if straight is None or (is_zero(ratio - 1) or is_zero(ratio + 1)) and straight:
            return "in-phase" if _sign(ratio) > 0 else "anti-phase"
        angle = _angle(coords, {c: value(f"a_{c}") for c in coords})
        if angle is None:
            return "in-phase" if _sign(ratio) > 0 else "anti-phase"
        return f"{'line' if straight else 'bowed'}-{angle}"
    if is_zero(a_c):
        shape = "circle" if is_zero(sp.expand(b_c**2 - a_p**2)) else "ellipse"
        return f"{shape}-ccw" if _sign(b_c / a_p) > 0 else f"{shape}-cw"
    radius = sp.simplify(a_c**2 + b_c**2)
    if free and not radius.free_symbols & {sp.Symbol(f) for f in free}:
        return "circle"
    return None


def _canonical(amplitudes: dict) -> str:
    return str(sorted((k, str(v)) for k, v in amplitudes.items()))


def name_families(described: list[tuple]) -> list[str]:
    """Names for families given as ``(amplitudes, free)`` or ``(amplitudes, free, straight)``
    (``straight``: whether the orbit stays on the line of its generating amplitudes at every
    order; None when unknown), in the same order (see module notes)."""
    raw = [_structural(*item) for item in described]
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
