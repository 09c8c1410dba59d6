"""Excitation and driven systems: what is accepted, what is refused with one line (issue 18)."""

from __future__ import annotations

import pytest
import sympy as sp

from perturb import EPS, Excitation, InvalidSystemError, QuasilinearSystem

X, V, TH, S, F = sp.symbols("x v theta sigma F")


def _system(rhs, ratio=1, detuning=S, parameters=(S, F)):
    return QuasilinearSystem(
        [X], [V], [1], [rhs], parameters=list(parameters),
        excitation=Excitation(phase=TH, ratio=ratio, detuning=detuning),
    )  # fmt: skip


@pytest.mark.parametrize(
    ("rhs", "words"),
    [
        (EPS * TH * X, "outside cos/sin"),
        (EPS * sp.cos(TH / 2) * X, "not periodic in t"),
        (EPS * sp.cos(sp.sqrt(2) * TH), "not periodic in t"),
        (EPS * sp.exp(TH), "outside cos/sin"),
    ],
)
def test_a_forcing_not_periodic_in_t_is_refused(rhs, words):
    with pytest.raises(InvalidSystemError, match=words):
        _system(rhs)


@pytest.mark.parametrize(
    ("ratio", "words"),
    [(sp.sqrt(2), "irrational"), (0.3333, "exact ratio"), (sp.Rational(11, 1), "above 9"),
     (-1, "positive"), (True, "p/q exactly")],
)  # fmt: skip
def test_an_unsupported_ratio_is_refused(ratio, words):
    with pytest.raises(InvalidSystemError, match=words):
        Excitation(phase=TH, ratio=ratio, detuning=S)


@pytest.mark.parametrize(("ratio", "p", "q"), [(1, 1, 1), ("1/3", 1, 3), (0.5, 1, 2), (3, 3, 1)])
def test_exact_ratios_are_read(ratio, p, q):
    drive = Excitation(phase=TH, ratio=ratio, detuning=S)
    assert (drive.p, drive.q) == (p, q)


def test_the_detuning_must_be_a_parameter():
    with pytest.raises(InvalidSystemError, match="declare them in `parameters`"):
        _system(EPS * F * sp.cos(TH), parameters=(F,))


@pytest.mark.parametrize("k", [1, 2, 3])
def test_harmonics_of_the_phase_become_exact_polynomials(k):
    """cos(k theta + 1/5), sin(k theta) in cos theta, sin theta: equal at random angles."""
    drive = Excitation(phase=TH, ratio=1, detuning=S)
    expr = sp.cos(k * TH + sp.Rational(1, 5)) * X + sp.sin(k * TH) ** 2
    poly = drive.polynomial_form(expr)
    assert not poly.has(TH)
    for angle in (0.3, 1.7, -2.2):
        back = poly.subs({drive.cos_symbol: sp.cos(angle), drive.sin_symbol: sp.sin(angle)})
        assert float((back - expr.subs(TH, angle)).subs(X, 0.7)) == pytest.approx(0, abs=1e-12)


def test_a_free_system_is_unchanged_by_the_new_field():
    free = QuasilinearSystem([X], [V], [1], [-EPS * X**3])
    assert free.excitation is None
    assert free.rhs_in_epsilon == (-EPS * X**3,)
