"""The declared parameter map and the case (issue 28): user parameters -> system symbols and eps.

A problem declares how its parameters become the system's symbols and eps; every client reads
that (the response's Omega sweep, its folds and backbone, the order scan's eps moves, a sweep's
columns) instead of re-creating problems to find out. Checked here: the map's own checks (one
line each), that its numbers are the expressions' (one point, columns, inverses, another eps),
that a user's driven problem typed in one file sweeps Omega from the CLI with its backbone, and
that a problem written in physical parameters gives the same response whatever eps bookkeeping
its map chooses.
"""

from __future__ import annotations

import json
import math
import textwrap

import numpy as np
import pytest
import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from perturb.case import Case, ParameterMap
from perturb.cli import main
from perturb.errors import InvalidSystemError
from perturb.validation import with_epsilon
from perturb.validation.model import parameter_value_of
from problems import get_problem
from problems.base import ParameterSpec, Problem

X, XDOT, THETA = sp.symbols("x xdot theta")
ZETA, GAMMA, FORCE, SIGMA = sp.symbols("zeta gamma F sigma")
SYSTEM = QuasilinearSystem(
    [X], [XDOT], [1], [EPS * (-2 * ZETA * XDOT - GAMMA * X**3 + FORCE * sp.cos(THETA))],
    parameters=[ZETA, GAMMA, FORCE, SIGMA],
    excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
)  # fmt: skip
USER = ("eps", "zeta", "gamma", "F", "Omega")
POINT = {"eps": 0.05, "zeta": 0.1, "gamma": 1.0, "F": 1.0, "Omega": 1.08}


# ------------------------------------------------------------------------------ the map's checks
@pytest.mark.parametrize(
    ("declared", "words"),
    [
        ({}, "does not cover the system symbol 'sigma'"),
        ({"sigma": "(Omega - 1)/eps", "tau": "1"}, "declares 'tau', which is not a symbol"),
        ({"sigma": "(Omega - w)/eps"}, "uses ['w'], which are not user parameters"),
        ({"sigma": "(Omega - 1)/"}, "is not an expression"),
    ],
)
def test_a_map_that_does_not_fit_the_system_is_one_line(declared, words):
    with pytest.raises(InvalidSystemError) as info:
        ParameterMap.declare(SYSTEM.parameters, USER, declared)
    assert words in str(info.value) and "\n" not in str(info.value)


def test_eps_defaults_to_the_parameter_eps_and_may_be_declared():
    plain = ParameterMap.declare(SYSTEM.parameters, USER, {"sigma": "(Omega - 1)/eps"})
    assert plain.epsilon == sp.Symbol("eps", real=True)
    without = ParameterMap.declare(SYSTEM.parameters, ("zeta", "gamma", "F", "sigma"))
    assert without.epsilon is None


# ------------------------------------------------------------------------------ its numbers
@pytest.fixture(scope="module")
def mapping():
    return ParameterMap.declare(SYSTEM.parameters, USER, {"sigma": "(Omega - 1)/eps"})


def test_one_point_is_the_correctly_rounded_expression(mapping):
    symbols, eps = mapping.evaluate(POINT)
    exact = (sp.Rational(POINT["Omega"]) - 1) / sp.Rational(POINT["eps"])
    assert symbols["sigma"] == float(exact) and eps == POINT["eps"]
    assert symbols["zeta"] == POINT["zeta"]


def test_columns_are_the_points(mapping):
    omega = np.linspace(0.9, 1.2, 7)
    symbols, eps = mapping.columns({**POINT, "Omega": omega})
    one_by_one = [mapping.evaluate({**POINT, "Omega": w})[0]["sigma"] for w in omega]
    # numpy's (Omega - 1)/eps against the correctly rounded value: at most one rounding apart
    np.testing.assert_allclose(symbols["sigma"], one_by_one, rtol=4 * np.finfo(float).eps)
    assert eps.shape == omega.shape and np.all(eps == POINT["eps"])


def test_a_value_in_sigma_goes_back_to_omega(mapping):
    for sigma in (-3.0, 0.0, 2.5):
        omega = mapping.solve_user("Omega", "sigma", sigma, POINT)
        assert omega == pytest.approx(1 + POINT["eps"] * sigma, rel=1e-15)


def test_another_eps_keeps_every_symbol(mapping):
    for eps in (0.1, 0.025, 0.0125):
        moved = mapping.with_epsilon(POINT, eps)
        assert moved["eps"] == eps
        before, after = mapping.evaluate(POINT)[0], mapping.evaluate(moved)[0]
        assert after == pytest.approx(before, rel=1e-14)
        assert {k for k in POINT if moved[k] != POINT[k]} <= {"eps", "Omega"}


def test_the_disk_moves_r0_for_eps_and_keeps_its_body():
    disk = get_problem("disk").create(r0=0.755155, R=0.123299, gamma3_0=0.25)
    other = with_epsilon(disk, disk.epsilon() / 2)
    assert other.epsilon() == pytest.approx(disk.epsilon() / 2, rel=1e-15)
    assert {k for k in disk.values if disk.values[k] != other.values[k]} == {"r0"}
    assert other.symbol_values() == pytest.approx(disk.symbol_values(), rel=1e-15)


def test_the_disk_map_is_its_physics():
    """eps = c/r0 with c = sqrt(M g l / C), l = sqrt(x0^2 + y0^2), a = A/C, k = 3C/(R M l)."""
    disk = get_problem("disk").create()
    v = disk.values
    arm = math.hypot(v["x0"], v["y0"])
    assert disk.epsilon() == pytest.approx(math.sqrt(v["M"] * v["g"] * arm / v["C"]) / v["r0"])
    assert disk.symbol_values()["k"] == pytest.approx(3 * v["C"] / (v["R"] * v["M"] * arm))
    assert disk.symbol_values()["a"] == pytest.approx(v["A"] / v["C"])


def test_a_case_is_checked_as_the_problem_is():
    duffing = get_problem("forced-duffing").create(Omega=1.05)
    case = duffing.case()
    assert isinstance(case, Case) and case.symbol_values["sigma"] == pytest.approx(1.0)
    with pytest.raises(ValueError, match="Omega"):
        case.at(Omega=-1.0)
    assert case.with_epsilon(-0.01) is None  # eps must stay positive: no admissible move


# ------------------------------------------------------------------------------ a user's file
USER_FILE = """
import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, XDOT, THETA = sp.symbols("x xdot theta")
ZETA, GAMMA, FORCE, SIGMA = sp.symbols("zeta gamma F sigma")


class MyForcedDuffing(Problem):
    name = "my-forced-duffing"
    summary = "x'' + 2 zeta eps x' + x + gamma eps x^3 = F eps cos(Omega t)"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms"),
        ParameterSpec("zeta", 0.1, "scaled damping"),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness"),
        ParameterSpec("F", 1.0, "scaled forcing"),
        ParameterSpec("Omega", 1.0, "excitation frequency"),
    )
    parameter_map = {"sigma": "(Omega - 1)/eps"}

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [XDOT], [1], [EPS * (-2 * ZETA * XDOT - GAMMA * X**3 + FORCE * sp.cos(THETA))],
            parameters=[ZETA, GAMMA, FORCE, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
        )
"""


def _response(capsys, *argv) -> dict:
    code = main(["response", *argv, "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)


def test_a_users_driven_problem_sweeps_omega_and_gets_its_backbone(tmp_path, capsys):
    path = tmp_path / "my_duffing.py"
    path.write_text(textwrap.dedent(USER_FILE))
    mine = _response(capsys, f"{path}:MyForcedDuffing", "--sweep", "Omega=0.95:1.2:11")
    shipped = _response(capsys, "forced-duffing", "--sweep", "Omega=0.95:1.2:11")
    assert mine["backbone"] is not None
    # the backbone of x'' + x + eps x^3 = 0: Omega = 1 + 3 eps a^2 / 8 + O(eps^2)
    for a, omega in zip(mine["backbone"]["amplitudes"], mine["backbone"]["values"], strict=True):
        assert omega == pytest.approx(1 + 3 * 0.05 * a**2 / 8, abs=0.05**2 * a**4)
    assert mine["backbone"]["values"] == pytest.approx(shipped["backbone"]["values"], rel=1e-12)
    assert [f["value"] for f in mine["folds"]] == pytest.approx(
        [f["value"] for f in shipped["folds"]], rel=1e-12
    )
    assert len(mine["points"]) == len(shipped["points"])


# ------------------------------------------------------------------------------ physical units
class _Physical(Problem):
    """x'' + c x' + x + k3 x^3 = P cos(Omega t), written in the measured c, k3, P, Omega."""

    name = "physical-duffing"
    summary = "forced Duffing in physical parameters"
    parameter_specs = (
        ParameterSpec("c", 0.01, "damping coefficient"),
        ParameterSpec("k3", 0.05, "cubic stiffness"),
        ParameterSpec("P", 0.03, "forcing amplitude"),
        ParameterSpec("Omega", 1.05, "excitation frequency"),
    )

    @classmethod
    def build_system(cls):
        return SYSTEM


class _BookkeptByForce(_Physical):
    parameter_map = {  # eps = P: the forcing is the small term of reference
        "epsilon": "P", "zeta": "c/(2*P)", "gamma": "k3/P", "F": "1", "sigma": "(Omega - 1)/P",
    }  # fmt: skip


class _BookkeptByStiffness(_Physical):
    parameter_map = {  # eps = k3: the nonlinearity is
        "epsilon": "k3", "zeta": "c/(2*k3)", "gamma": "1", "F": "P/k3", "sigma": "(Omega - 1)/k3",
    }  # fmt: skip


@pytest.mark.parametrize("order", [1, 2])
def test_the_response_does_not_depend_on_the_eps_bookkeeping(order):
    """Every small term carries one eps, so the order-N series is one function of the physical
    products eps*zeta, eps*gamma, eps*F, eps*sigma: two maps give the same branches."""
    for omega in (1.0, 1.05, 1.1):
        by_force = _BookkeptByForce.create(Omega=omega)
        by_stiffness = _BookkeptByStiffness.create(Omega=omega)
        assert by_force.epsilon() != by_stiffness.epsilon()
        one = by_force.families(order)
        other = by_stiffness.families(order)
        assert [f.name for f in one] == [f.name for f in other]
        for f, g in zip(one, other, strict=True):
            x = f.solution.evaluate(
                [0.0, 1.0], parameter_value_of(by_force), by_force.symbol_values()
            )
            y = g.solution.evaluate(
                [0.0, 1.0], parameter_value_of(by_stiffness), by_stiffness.symbol_values()
            )
            np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-12)


def test_how_a_swept_parameter_moves_the_point(mapping):
    """Exact derivatives: d sigma/d Omega = 1/eps, d sigma/d eps = -(Omega - 1)/eps^2."""
    case = Case(SYSTEM, mapping, POINT)
    symbols, eps_rate = case.rate("Omega")
    assert symbols["sigma"] == pytest.approx(1 / POINT["eps"], rel=1e-15) and eps_rate == 0
    symbols, eps_rate = case.rate("eps")
    expected = -(POINT["Omega"] - 1) / POINT["eps"] ** 2
    assert symbols["sigma"] == pytest.approx(expected, rel=1e-14) and eps_rate == 1
    assert case.is_affine_in("Omega") and not case.is_affine_in("eps")
