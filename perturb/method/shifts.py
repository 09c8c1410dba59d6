"""Components of the amplitude equations that are one family: a shift by half a period."""

from __future__ import annotations

import sympy as sp

from perturb.method.exact import is_zero

__all__ = ["distinct_components"]


def distinct_components(components: list, generating, solved: dict) -> list:
    """Drop components that are another one shifted by half a period.

    ``s -> s + pi`` changes the sign of every amplitude of odd harmonic: van der Pol's roots
    ``a_x = 2`` and ``a_x = -2`` are one limit cycle. On a continuum the free amplitudes change sign
    with their harmonic, which is a change of parameter. Of two such components the one whose
    phase amplitude is positive (else: whose amplitudes read first) is kept.
    """
    symbols = (*generating.cos_amplitudes, *generating.sin_amplitudes)
    signs = [(-1) ** (m or 0) for m in generating.harmonics] * 2

    def amplitudes(component, shift):
        flip = {}
        if shift:
            flip = {
                f: -f
                for f in component.free
                for sym, sign in zip(symbols, signs, strict=True)
                if sym == f and sign < 0
            }
        values = []
        for sym, sign in zip(symbols, signs, strict=True):
            value = sp.sympify(sym).xreplace(solved).xreplace(component.values).xreplace(flip)
            values.append(sign * value if shift else value)
        return values

    def same(first, second):
        return all(is_zero(a - b) for a, b in zip(first, second, strict=True))

    phase = generating.coordinates.index(generating.phase_coordinate)

    def key(component):
        lead = amplitudes(component, False)[phase]
        negative = lead.is_number and bool(lead < 0)
        return (negative, str(amplitudes(component, False)))

    ordered = sorted(components, key=key)
    kept: list = []
    for component in ordered:
        shifted = amplitudes(component, True)
        if not any(same(shifted, amplitudes(other, False)) for other in kept):
            kept.append(component)
    return kept
