"""Mode-shape names of standing waves of three or more coordinates (issue 22; family_names rule 4).

The amplitude vectors are written by hand, so each name follows from the rule alone: signs and
zeros in the coordinates' order, and the participation number (Σa²)²/Σa⁴ against (n + 1)/2.
"""

import pytest
import sympy as sp

from perturb.method.family_names import LOCALISED_BELOW, name_families


def _standing(*amplitudes):
    """A chain-like amplitude dict: x1's cosine amplitude, then (a, b = 0) per coordinate."""
    out = {"a_x1": sp.sympify(amplitudes[0])}
    for i, a in enumerate(amplitudes[1:], start=2):
        out[f"a_x{i}"] = sp.sympify(a)
        out[f"b_x{i}"] = sp.S.Zero
    return out


@pytest.mark.parametrize(
    ("amplitudes", "name"),
    [
        ((1, 2, 1), "in-phase"),
        ((1, -1, 1, -1), "anti-phase"),  # participation 4: spread over every coordinate
        ((1, 0, -1), "shape-p0n"),
        ((1, 1, -1, -1), "shape-ppnn"),
        ((1, -6, 6, -1), "anti-phase-localised-x2"),  # participation 5476/2594 = 2.11 < 2.5
        ((1, -1, sp.Rational(1, 100)), "anti-phase"),  # 2.0 (not below 2.0 for n = 3)
    ],
)
def test_a_standing_wave_is_named_by_its_signs_and_its_localisation(amplitudes, name):
    assert name_families([(_standing(*amplitudes), ())]) == [name]


def test_the_localisation_threshold_is_the_named_constant():
    """(1, -6, 6, -1) has participation 2.111; it is localised exactly while the threshold times
    n + 1 = 5 exceeds that."""
    squares = [1, 36, 36, 1]
    participation = sum(squares) ** 2 / sum(q * q for q in squares)
    assert participation < LOCALISED_BELOW * 5
    assert participation > 2  # and not below the threshold of a chain of 3 (2.0)


def test_a_sine_amplitude_is_not_a_standing_wave_and_ties_get_numbers():
    """A sine amplitude makes a motion phase-shifted, not a standing wave (issue 30: named, no
    longer ``family-1``)."""
    elliptic = _standing(1, 1, 1)
    elliptic["b_x2"] = sp.Rational(1, 2)
    names = name_families([(elliptic, ()), (_standing(1, -2, 1), ()), (_standing(1, -3, 2), ())])
    assert names[0] == "phase-shifted"
    assert sorted(names[1:]) == ["anti-phase-1", "anti-phase-2"]


def test_a_wave_of_equal_amplitudes_and_equal_lags_travels():
    """x_j = cos(s - j 2 pi/3) on a ring of three: every coordinate lags its neighbour by 120
    degrees (travelling-right); the mirror image travels left; unequal amplitudes do not travel."""
    root3 = sp.sqrt(3) / 2
    right = {"a_x1": 1, "a_x2": -sp.Rational(1, 2), "b_x2": root3, "a_x3": -sp.Rational(1, 2),
             "b_x3": -root3}  # fmt: skip
    left = {**right, "b_x2": -root3, "b_x3": root3}
    uneven = {**right, "a_x3": -1}
    assert name_families([(right, ()), (left, ()), (uneven, ())]) == [
        "travelling-right",
        "travelling-left",
        "phase-shifted",
    ]
