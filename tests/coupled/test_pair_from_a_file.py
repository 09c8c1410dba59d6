"""Issue 30's first failure, as a user meets it: two weakly coupled forced Duffings typed in one
file the way docs/forced.md shows (coordinates x1, x2; the detuning sigma a parameter).

It used to exit 2 with the solver's words ("a_x10/(10*b_x10) ... is invalid": the generating
amplitude a_x10 of x1 was parsed as a correction of a coordinate x and left in the equations) and
to answer "0 families: only the trivial root". Now every branch, each a true orbit of the same
stability (forced shooting from its state), and no true steady state beside them (shooting from
seeded random states)."""

from __future__ import annotations

import json
import textwrap

import numpy as np
import pytest

from perturb.cli import main
from perturb.oracle import heyoka_available
from problems import load_problem
from tests.coupled.census import add_orbit, census, seeded, shooting_setup

PAIR = textwrap.dedent(
    """
    import sympy as sp
    from perturb import EPS, Excitation, QuasilinearSystem
    from problems.base import ParameterSpec, Problem

    X1, X2, V1, V2, TH = sp.symbols("x1 x2 v1 v2 theta")
    ZETA, GAMMA, KAPPA, F, SIGMA = sp.symbols("zeta gamma kappa F sigma")


    class CoupledDuffings(Problem):
        name = "my-coupled-duffings"
        summary = "two weakly coupled forced Duffings in 1:1, the first forced"
        parameter_specs = (
            ParameterSpec("eps", 0.05, "small parameter"),
            ParameterSpec("zeta", 0.05, "damping"),
            ParameterSpec("gamma", 1.0, "cubic stiffness"),
            ParameterSpec("kappa", 0.1, "coupling"),
            ParameterSpec("F", 1.0, "forcing"),
            ParameterSpec("sigma", 0.0, "detuning"),
        )

        @classmethod
        def build_system(cls):
            return QuasilinearSystem(
                [X1, X2], [V1, V2], [1, 1],
                [
                    EPS * (-2 * ZETA * V1 - GAMMA * X1**3 - KAPPA * (X1 - X2) + F * sp.cos(TH)),
                    EPS * (-2 * ZETA * V2 - GAMMA * X2**3 - KAPPA * (X2 - X1)),
                ],
                parameters=[ZETA, GAMMA, KAPPA, F, SIGMA],
                excitation=Excitation(TH, ratio=1, detuning=SIGMA),
            )
    """
)


@pytest.fixture
def pair_file(tmp_path):
    path = tmp_path / "pair.py"
    path.write_text(PAIR)
    return path


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_the_response_of_a_pair_typed_in_a_file_runs(pair_file, capsys):
    code, out, err = _run(capsys, "response", f"{pair_file}:CoupledDuffings", "--sweep",
                          "sigma=-2:4:4", "--format", "json")  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert not data["failures"]
    assert {len(p["norms"]) for p in data["points"]} == {2}  # both coordinates, every point


@pytest.mark.skipif(not heyoka_available(), reason="the shootings take minutes without heyoka")
def test_the_families_of_a_pair_typed_in_a_file_are_the_true_steady_states(pair_file, capsys):
    code, out, err = _run(capsys, "families", f"{pair_file}:CoupledDuffings", "--set", "sigma=1",
                          "--format", "json")  # fmt: skip
    assert code == 0, err
    names = [f["name"] for f in json.loads(out)["families"]]
    problem = load_problem(f"{pair_file}:CoupledDuffings").create(sigma=1.0)
    rhs, _, shift = shooting_setup(problem)
    found = []
    rows = seeded(problem, 1)
    assert sorted(name for name, _, _ in rows) == sorted(names) and len(names) > 1
    for name, point, orbit in rows:
        assert orbit.success, name
        assert add_orbit(found, orbit, rhs, shift, 1), f"{name}: another branch's orbit"
        assert point.stable is bool(np.max(np.abs(orbit.floquet_multipliers)) < 1.0), name


@pytest.mark.slow
@pytest.mark.skipif(not heyoka_available(), reason="the shootings take minutes without heyoka")
def test_no_true_steady_state_of_the_pair_is_missing(pair_file):
    problem = load_problem(f"{pair_file}:CoupledDuffings").create(sigma=1.0)
    rhs, _, shift = shooting_setup(problem)
    found = []
    for _, _, orbit in seeded(problem, 1):
        add_orbit(found, orbit, rhs, shift, 1)
    analytic = len(found)
    random = census(problem, starts=120, box=3.0, seed=31)

    class _Orbit:
        def __init__(self, orbit):
            self.initial_state = orbit.state
            self.floquet_multipliers = [orbit.largest_multiplier]

    extra = [o for o in random if add_orbit(found, _Orbit(o), rhs, shift, 1)]
    assert random and not extra
    assert analytic == 5  # five steady states at sigma = 1, as the issue counted by shooting


def test_a_response_that_could_not_be_enumerated_is_never_no_root():
    """A driven problem whose roots were not enumerated says why: the families' table and JSON
    never read "only the trivial root" then (the issue's false answer)."""
    from perturb.method.driven import amplitude_equations
    from perturb.report.families import as_dict, as_table
    from perturb.steady.branches import SteadyState
    from problems import get_problem

    equations = amplitude_equations(get_problem("coupled-duffings").system(), 1)
    spent = SteadyState((), (), equations, "the solver ran out of its time budget")
    families = spent.families("coupled-duffings", 1)
    assert not families.families and "time budget" in families.why
    assert "only the trivial root" not in as_table(families, "coupled-duffings")
    assert as_dict(families, "coupled-duffings")["why"] == families.why
    proved = SteadyState((), (), equations, "").families("coupled-duffings", 1)
    assert "no real root" in proved.why
