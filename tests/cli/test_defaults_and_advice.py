"""A newcomer's first hour: one default order for every command (printed in each header), the
phase diagram's default map, numbers where a value is asked for, ``perturb --version``, and advice
that helps — a forcing written in the time, a swept name the parameter map sets."""

from __future__ import annotations

import importlib.metadata
import json
import textwrap

import numpy as np
import pytest

from perturb._defaults import DRIVEN_ORDER, FREE_ORDER
from perturb.cli import main
from perturb.cli._parser import _build_parser
from perturb.domain import series_domain
from perturb.steady.measures import series_estimate
from perturb.validation.model import parameter_value_of
from problems import get_problem
from tests.helpers import roundings


def run(capsys, *argv):
    code = main([*argv, "--quiet"] if argv and not argv[0].startswith("--") else list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ------------------------------------------------------------------ one default order
@pytest.mark.parametrize(
    ("problem", "order"), [("forced-duffing", DRIVEN_ORDER), ("duffing", FREE_ORDER)]
)
def test_every_command_takes_one_default_order_and_prints_it(capsys, problem, order):
    code, out, err = run(capsys, "solve", problem, "--times", "0", "--format", "json")
    assert code == 0, err
    assert json.loads(out)["order"] == order
    code, out, err = run(capsys, "solve", problem, "--times", "0")
    assert code == 0 and out.startswith(f"# {problem}  order {order}  "), out
    code, out, err = run(capsys, "families", problem, "--format", "json")
    assert code == 0, err
    assert json.loads(out)["order"] == order
    code, out, err = run(capsys, "validate", problem, "--format", "json")
    assert code == 0, err
    assert json.loads(out)["order"] == order


def test_validate_checks_the_series_the_response_drew(capsys):
    """``perturb response`` and ``perturb validate`` at a point of it use one order by default."""
    code, out, err = run(capsys, "response", "forced-duffing", "--sweep", "Omega=1:1.1:3",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    drawn = json.loads(out)["order"]
    code, out, err = run(capsys, "validate", "forced-duffing", "--set", "Omega=1.05", "--format",
                         "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["order"] == drawn == DRIVEN_ORDER


def test_an_explicit_order_still_wins(capsys):
    code, out, err = run(capsys, "solve", "forced-duffing", "--order", "1", "--times", "0",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["order"] == 1
    code, _, err = run(capsys, "solve", "duffing", "--order", "0")
    assert code == 2 and "--order 0" in err


def test_the_help_states_the_rule():
    parser = _build_parser()
    text = parser._subparsers._group_actions[0].choices["validate"].format_help()
    assert f"default {DRIVEN_ORDER} for a driven" in " ".join(text.split())


def test_the_phase_diagrams_default_map_is_the_continued_one():
    argv = ["phase-diagram", "forced-duffing", "--grid", "Omega=1:1.1:3", "--grid", "F=1:2:2"]
    assert _build_parser().parse_args(argv).map == "order-n"
    assert _build_parser().parse_args([*argv, "--map", "first-order"]).map == "first-order"


# ------------------------------------------------------------------ numbers, the version
def test_families_give_the_frequency_as_a_number(capsys):
    code, out, err = run(capsys, "families", "forced-duffing", "--set", "Omega=1.05",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    omegas = [f["Omega"] for f in json.loads(out)["families"]]  # lower, middle, upper
    assert len(omegas) == 3 and omegas == pytest.approx([1.05] * 3, rel=roundings(4))
    code, out, _ = run(capsys, "families", "forced-duffing", "--set", "Omega=1.05")
    assert "  Omega = 1.05  (= epsilon*sigma + 1)" in out
    code, out, _ = run(capsys, "families", "duffing", "--format", "json")
    (family,) = json.loads(out)["families"]
    assert family["Omega"] == pytest.approx(1 + 3 / 8 * 0.1, rel=roundings(4))  # A = 1, eps 0.1


def test_version(capsys):
    code = main(["--version"])
    out, _ = capsys.readouterr()
    assert code == 0 and out == f"perturb {importlib.metadata.version('perturb-poincare')}\n"


# ------------------------------------------------------------------ advice that helps
_TIMED = """
import sympy as sp
from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, V, t = sp.symbols("x xdot t")
ZETA, ALPHA, F, OMEGA = sp.symbols("zeta alpha F Omega")


class Timed(Problem):
    name = "timed"
    summary = "x'' + x = eps [-2 zeta x' - alpha x^2 - x^3 + forcing in t]"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter"),
        ParameterSpec("zeta", 0.1, "damping"),
        ParameterSpec("alpha", 0.5, "quadratic stiffness"),
        ParameterSpec("F", 1.0, "forcing"),
        ParameterSpec("Omega", 1.0, "excitation frequency"),
    )

    @classmethod
    def build_system(cls):
        forcing = {forcing}
        return QuasilinearSystem(
            [X], [V], [1], [EPS * (-2 * ZETA * V - ALPHA * X**2 - X**3 + forcing)],
            parameters=[ZETA, ALPHA, F, OMEGA{extra}],
        )
"""


@pytest.mark.parametrize(
    ("forcing", "extra"),
    [
        ("F * sp.cos(OMEGA * t)", ""),
        ("F * sp.cos(OMEGA * t) + F / 3 * sp.sin(3 * OMEGA * t)", ""),  # a sum of harmonics
        ("F * sp.cos(OMEGA * t)", ", t"),  # t declared: still the time
    ],
)
def test_a_forcing_written_in_the_time_says_how_to_declare_it(capsys, tmp_path, forcing, extra):
    path = tmp_path / "timed.py"
    path.write_text(textwrap.dedent(_TIMED.format(forcing=forcing, extra=extra)))
    code, out, err = run(capsys, "response", f"{path}:Timed", "--sweep", "Omega=0.9:1.1:5")
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert "Excitation(theta" in err and "theta = Omega*t" in err
    assert "'sigma': '(Omega - 1)/eps'" in err and "declare them in `parameters`" not in err


@pytest.mark.parametrize(
    "argv",
    [
        ["response", "forced-duffing", "--sweep", "sigma=-1:1:5"],
        ["sweep", "forced-duffing", "--grid", "sigma=-1:1:5", "--format", "csv"],
        ["solve", "forced-duffing", "--set", "sigma=1"],
    ],
)
def test_a_name_the_map_sets_gets_the_maps_advice(capsys, argv):
    if argv[0] == "sweep":
        pytest.importorskip("dask")
    code, _, err = run(capsys, *argv)
    assert code == 2 and "did you mean" not in err, err
    assert "sigma is set by Omega through the map sigma = (Omega - 1)/eps" in err
    assert ("; set Omega" if argv[0] == "solve" else "; sweep Omega") in err


# ------------------------------------------------------------------ the series check's scale
def test_a_coordinate_near_zero_cannot_put_a_right_answer_outside():
    """Terms of 5e-8 and 2e-7 in a coordinate beside an amplitude of 0.6: below the solution's
    scale (the check of the series' terms), inside; the same growth on the amplitude's scale:
    outside."""
    quiet = np.array([[0.6, 0.03, 0.0015], [0.0, 5e-8, 2e-7]])
    assert series_estimate(quiet)[1] == []
    loud = np.array([[0.6, 0.03, 0.0015], [0.0, 0.01, 0.04]])
    assert series_estimate(loud)[1] == ["order-2 term 0.04 >= order-1 term 0.01"]


def test_the_forced_pair_is_inside_its_domain_with_the_names_of_order_1():
    """coupled-duffings at its defaults: at order 3 no family is "outside its domain" for the
    tiny terms of its barely excited coordinate, none is ``beyond-series``, and each keeps the
    name of the order-1 orbit nearest it (the same orbit: within O(eps) of its amplitudes)."""
    problem = get_problem("coupled-duffings").create()
    eps = parameter_value_of(problem)
    first, third = problem.families(1), problem.families(3)
    for family in third:
        check = series_domain(family.solution, eps, problem.symbol_values())
        assert check.ok, (family.name, check.reasons)
        assert not family.name.startswith("beyond-series")

    def state(f):
        return np.array([float(v) for v in f.amplitudes.values()])

    for family in third:
        nearest = min(first, key=lambda g: np.linalg.norm(state(g) - state(family)))
        assert nearest.name == family.name
        assert np.linalg.norm(state(nearest) - state(family)) < 10 * eps * np.linalg.norm(
            state(family)
        )


def test_families_say_of_a_branch_what_the_response_marks(capsys):
    """The forced pair detuned to Omega = 1.25 (sigma = 5): the branches the response marks as
    not vouched for by the series are the ones ``families`` flags, and ``validate`` finds the
    unflagged one VALID (the flagged ones are what it measures as not described)."""
    argv = ["--set", "Omega=1.25", "--format", "json"]
    code, out, err = run(capsys, "families", "coupled-duffings", *argv)
    assert code == 0, err
    flagged = {f["name"] for f in json.loads(out)["families"] if f["outside"] or f["beyond"]}
    code, out, err = run(capsys, "response", "coupled-duffings", "--sweep", "Omega=1.24:1.26:3",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    at = [p for p in json.loads(out)["points"] if p["value"] == pytest.approx(1.25)]
    assert flagged == {p["branch"] for p in at if p["mark"]} != set()
    for point in at:
        if not point["mark"]:
            code, out, err = run(capsys, "validate", "coupled-duffings", "--family",
                                 point["branch"], *argv)  # fmt: skip
            assert code == 0, err
            assert json.loads(out)["outcome"] == "valid"


def test_a_parameter_named_t_in_a_constant_phase_is_no_time():
    """``cos(t)`` with t a declared parameter is a constant phase, accepted; ``cos(Omega*t)``
    is a forcing in the time, refused with the advice."""
    import sympy as sp

    from perturb import EPS, QuasilinearSystem
    from perturb.errors import InvalidSystemError

    x, v, t, omega = sp.symbols("x xdot t Omega")
    QuasilinearSystem([x], [v], [1], [EPS * (-(x**3) + sp.cos(t))], parameters=[t])
    with pytest.raises(InvalidSystemError, match="Excitation"):
        QuasilinearSystem([x], [v], [1], [EPS * (-(x**3) + sp.cos(omega * t))],
                          parameters=[t, omega])  # fmt: skip
