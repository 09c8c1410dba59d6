"""The whole diagram of the true responses: branch switching at the pitchforks of a symmetric
oscillator, the asymmetric pair, its period doublings, located to 1e-8.

ẍ + 0.1ẋ + x + x³ = F cos 1.2t (the forced Duffing typed with ε = 1), continued in F: its symmetric
response (x(t + T/2) = −x(t)) loses its symmetry at pitchforks F ≈ 4.19 and 24.81, where a pair of
asymmetric responses is born (images of each other under x → −x, t → t + T/2), which period-double
at F ≈ 15.97 and 22.33. Each point is checked by a route that shares nothing with perturb's:
scipy's DOP853 at rtol 1e-12 for the orbit and its monodromy, Newton's method on the period
(or half-period) map for the orbit at each F, and Brent's method on F for the zero of the test
function (det(DH + I) for the pitchfork, H the half-period map; det(M + I) for the doubling).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from perturb.errors import InvalidParameterError
from perturb.response.model import problem_response
from problems import get_problem

OMEGA, DAMPING = 1.2, 0.1
#: Located to this in F (the issue's promise); the reference's own error is ~1e-11 (Brent's xtol
#: 1e-12 on a test function computed at rtol 1e-12).
LOCATED = 1e-8


def _field(force):
    def f(t, y):
        x, v = y[0], y[1]
        m = y[2:].reshape(2, 2)
        jac = np.array([[0.0, 1.0], [-1.0 - 3 * x * x, -DAMPING]])
        acc = -DAMPING * v - x - x**3 + force * math.cos(OMEGA * t)
        return [v, acc, *(jac @ m).ravel()]

    return f


def _map(y, force, half):
    """(image, Jacobian) of the period map, or of the half-period map H(y) = −φ_{T/2}(y)."""
    span = (math.pi if half else 2 * math.pi) / OMEGA
    sol = solve_ivp(_field(force), (0.0, span), [*y, 1.0, 0.0, 0.0, 1.0], method="DOP853",
                    rtol=1e-12, atol=1e-14)  # fmt: skip
    end, mono = sol.y[:2, -1], sol.y[2:, -1].reshape(2, 2)
    return (-end, -mono) if half else (end, mono)


def _orbit(y, force, half):
    y = np.array(y, dtype=float)
    for _ in range(30):
        image, jac = _map(y, force, half)
        step = np.linalg.solve(jac - np.eye(2), -(image - y))
        y = y + step
        if float(np.max(np.abs(step))) < 1e-12 * max(1.0, float(np.max(np.abs(y)))):
            return y, _map(y, force, half)[1]
    raise AssertionError(f"Newton did not converge at F = {force}")


def _reference(value, state, half, width=1e-4):
    """The zero of det(J + I) on the orbit family near (state, value), by Brent on F."""
    y = np.array(state, dtype=float)

    def test(force):
        nonlocal y
        y, jac = _orbit(y, force, half)
        return float(np.linalg.det(jac + np.eye(2)))

    return brentq(test, value - width, value + width, xtol=1e-13, rtol=1e-15)


@pytest.fixture(scope="module")
def diagram():
    problem = get_problem("forced-duffing").create(eps=1.0, zeta=0.05, Omega=OMEGA)
    grid = np.linspace(0.01, 26.0, 27)
    return problem_response(problem, "F", grid, order=1, true=1000, max_period=1).true_curve


def test_the_pitchforks_are_located_to_1e8_and_bear_the_asymmetric_pair(diagram):
    symmetric = diagram.curves[0]
    assert symmetric.birth == "seed" and symmetric.period == 1 and symmetric.parent is None
    pitchforks = [b for b in symmetric.bifurcations if b.kind == "branch-point"]
    assert [round(b.value, 2) for b in pitchforks] == [4.19, 24.81]
    for b in pitchforks:
        assert b.located
        assert abs(b.multiplier - 1) < 1e-9  # the full map's multiplier +1 (DH's -1, squared)
        reference = _reference(b.value, b.state, half=True)
        assert abs(b.value - reference) <= LOCATED, (b.value, reference)
    # the pair born at the first pitchfork: asymmetric responses, each the other's image
    pair = [c for c in diagram.curves if c.birth == "branch-point"]
    assert pair and all(c.parent == 0 and c.period == 1 for c in pair)
    assert any(abs(c.born_at - pitchforks[0].value) < 1e-12 for c in pair)
    point = next(p for p in pair[0].points if 8.0 < p.value < 12.0)
    y, _ = _orbit(point.state, point.value, half=False)
    assert float(np.max(np.abs(y - np.array(point.state)))) < 1e-8
    half_image, _ = _map(y, point.value, half=True)
    assert float(np.max(np.abs(half_image - y))) > 0.1  # not symmetric: H(y) != y
    mirror, _ = _orbit(half_image, point.value, half=False)  # its image is a response too
    assert float(np.max(np.abs(mirror - half_image))) < 1e-8


def test_no_period_doubling_is_followed_at_max_period_1(diagram):
    assert all(c.period == 1 for c in diagram.curves)
    assert diagram.max_period == 1


@pytest.mark.slow
def test_the_asymmetric_pair_period_doubles_and_its_doubled_orbits_are_followed():
    problem = get_problem("forced-duffing").create(eps=1.0, zeta=0.05, Omega=OMEGA)
    grid = np.linspace(0.01, 26.0, 27)
    curves = problem_response(problem, "F", grid, order=1, true=1000, max_period=2).true_curve
    pair = next(c for c in curves.curves if c.birth == "branch-point")
    doublings = [b for b in pair.bifurcations if b.kind == "period-doubling"]
    assert sorted({round(b.value, 3) for b in doublings}) == [15.965, 22.332]
    for b in doublings:
        assert b.located and abs(b.multiplier + 1) < 1e-9
        reference = _reference(b.value, b.state, half=False)
        assert abs(b.value - reference) <= LOCATED, (b.value, reference)
    doubled = [c for c in curves.curves if c.birth == "period-doubling"]
    assert doubled and all(c.period == 2 for c in doubled)
    index = curves.curves.index(pair)
    assert all(c.parent == index for c in doubled)
    # a period-2 response: the period map twice returns to it, once does not
    point = next(p for p in doubled[0].points if 17.0 < p.value < 20.0)
    once, _ = _map(point.state, point.value, half=False)
    twice, _ = _map(once, point.value, half=False)
    assert float(np.max(np.abs(twice - np.array(point.state)))) < 1e-8
    assert float(np.max(np.abs(once - np.array(point.state)))) > 1e-3


@pytest.mark.parametrize("bad", [0, -1, 17, 2.5, True])
def test_max_period_out_of_range_is_one_line(bad):
    problem = get_problem("forced-duffing").create()
    with pytest.raises(InvalidParameterError, match="max_period"):
        problem_response(problem, "Omega", [1.0, 1.1], true=10, max_period=bad)


def test_the_command_line_names_each_branch_its_parent_and_birth(capsys):
    import json

    from perturb.cli import main

    argv = [
        "response",
        "forced-duffing",
        "--set",
        "eps=1",
        "--set",
        "zeta=0.05",
        "--set",
        "Omega=1.2",
        "--order",
        "1",
        "--sweep",
        "F=0.01:6:7",
        "--true",
        "--max-period",
        "1",
    ]
    assert main([*argv, "--format", "json"]) == 0
    entry = json.loads(capsys.readouterr().out)["true_curve"]
    births = [(c["period"], c["parent"], c["birth"]) for c in entry["curves"]]
    assert births[0] == (1, None, "seed")
    assert (1, 0, "branch-point") in births
    (pitchfork,) = [b for b in entry["curves"][0]["bifurcations"] if b["kind"] == "branch-point"]
    assert abs(pitchfork["value"] - 4.1916738) < 1e-6 and pitchfork["located"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "born at the branch-point at F = 4.19167380" in out
    assert "amplitude: max |x| over a period" in out


@pytest.mark.parametrize(("extra", "words"), [
    (["--true", "--max-period", "0"], "--max-period 0: give a whole number from 1"),
    (["--true", "--max-period", "17"], "to 16"),
    (["--true", "--max-period", "two"], "give a whole number"),
    (["--max-period", "2"], "add --true"),
])  # fmt: skip
def test_max_period_on_the_command_line(capsys, extra, words):
    from perturb.cli import main

    code = main(["response", "forced-duffing", "--sweep", "Omega=1:1.1:3", *extra])
    err = capsys.readouterr().err
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_a_neimark_sacker_point_gives_the_rotation_number_of_its_torus():
    """At loss of entrainment (the forced van der Pol), the torus born has the rotation number
    arg(μ)/2π of the complex multiplier on the circle: in (0, 1/2), and a quasi-periodic motion
    beside the point turns by it per forcing period (checked against the multiplier's own
    argument, computed here)."""
    from tests.driven.published import ForcedVanDerPol

    problem = ForcedVanDerPol.create()
    result = problem_response(problem, "Omega", np.linspace(0.9, 1.1, 9), true=400, max_period=1)
    found = [b for b in result.true_curve.bifurcations if b.kind == "neimark-sacker"]
    assert len(found) == 2
    for b in found:
        assert 0 < b.rotation < 0.5
        z = b.multiplier
        assert b.rotation == pytest.approx(abs(math.atan2(z.imag, z.real)) / (2 * math.pi))


def test_the_true_curve_reaches_the_sweeps_ends_exactly(diagram):
    values = [p.value for p in diagram.curves[0].points]
    assert 0.01 in values and 26.0 in values


@pytest.mark.slow
def test_a_cascade_on_an_asymmetric_oscillator_period_2_then_4():
    """The twin-well Duffing about its right well (no x -> -x symmetry): the period-1 orbit
    doubles (Jordan & Smith: period 2 by Γ = 0.27), the period-2 orbit born there doubles in
    turn; each doubling against scipy's DOP853 on the well's own equation, Newton on the k-period
    map and Brent on det(M_k + I), to 1e-8; the period-4 orbit is followed."""
    from tests.driven.published import DAMPING, FREQUENCY, TwinWell

    zeta, omega = DAMPING / (2 * math.sqrt(2)), FREQUENCY / math.sqrt(2)

    def shot(y, gamma, periods):
        def f(t, z):
            x, v = z[0], z[1]
            m = z[2:].reshape(2, 2)
            jac = np.array([[0.0, 1.0], [-1.0 - 3 * x - 1.5 * x * x, -2 * zeta]])
            acc = -x - 2 * zeta * v - 1.5 * x**2 - 0.5 * x**3 + gamma / 2 * math.cos(omega * t)
            return [v, acc, *(jac @ m).ravel()]

        sol = solve_ivp(f, (0.0, 2 * math.pi * periods / omega), [*y, 1.0, 0.0, 0.0, 1.0],
                        method="DOP853", rtol=1e-12, atol=1e-14)  # fmt: skip
        return sol.y[:2, -1], sol.y[2:, -1].reshape(2, 2)

    def reference(b, periods):
        y = np.array(b.state, dtype=float)

        def test(gamma):
            nonlocal y
            for _ in range(30):
                end, mono = shot(y, gamma, periods)
                step = np.linalg.solve(mono - np.eye(2), -(end - y))
                y = y + step
                if float(np.max(np.abs(step))) < 1e-12:
                    break
            return float(np.linalg.det(shot(y, gamma, periods)[1] + np.eye(2)))

        return brentq(test, b.value - 1e-4, b.value + 1e-4, xtol=1e-13, rtol=1e-15)

    problem = TwinWell.create()
    curves = problem_response(problem, "Gamma", np.linspace(0.02, 0.4, 5), true=1000,
                              max_period=4).true_curve  # fmt: skip
    first = min((b for b in curves.curves[0].bifurcations if b.kind == "period-doubling"),
                key=lambda b: b.value)  # fmt: skip
    assert 0.20 < first.value < 0.27
    assert abs(first.value - reference(first, 1)) <= LOCATED
    doubled = [c for c in curves.curves if c.period == 2 and c.parent == 0]
    assert doubled and abs(doubled[0].born_at - first.value) < 1e-12
    second = min((b for b in doubled[0].bifurcations if b.kind == "period-doubling"),
                 key=lambda b: b.value)  # fmt: skip
    assert first.value < second.value
    assert abs(second.value - reference(second, 2)) <= LOCATED
    assert any(c.period == 4 and c.birth == "period-doubling" for c in curves.curves)
