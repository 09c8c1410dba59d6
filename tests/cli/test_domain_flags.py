"""``response`` and ``families`` check the series' domain as ``solve`` does (issue 31, item 5):
outside its domain everywhere, a failed run with the reason (exit 1); a point outside or beyond
the series' estimated validity, flagged in the output."""

from __future__ import annotations

import json

import pytest

from perturb._defaults import VALIDITY_ESTIMATE_LIMIT
from perturb.cli import main
from perturb.domain import next_term, series_domain
from perturb.validation.model import parameter_value_of
from problems import get_problem


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_superharmonic_far_from_its_resonance_is_a_failed_run(capsys):
    code, out, err = run(capsys, "response", "superharmonic-duffing", "--sweep", "Omega=0.9:1.1:4")
    assert code == 1 and out == "", err
    assert err.startswith("perturb: failed:") and "outside its domain" in err
    solve = run(capsys, "solve", "superharmonic-duffing", "--set", "Omega=0.9")
    assert solve[0] == 1 and "outside its domain" in solve[2]  # the same check, the same answer


def test_superharmonic_at_the_primary_resonance_is_refused(capsys):
    code, out, err = run(capsys, "validate", "superharmonic-duffing", "--set", "Omega=1")
    assert code == 2 and "primary resonance" in err and err.count("\n") == 1


def test_eps_10_is_outside_the_domain_at_order_3_and_beyond_validity_at_order_1(capsys):
    argv = ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3", "--set", "eps=10"]
    code, out, err = run(capsys, *argv)  # order 3, the default: its terms grow
    assert code == 1 and out == "" and "outside its domain at every steady state" in err
    code, out, err = run(capsys, *argv, "--order", "1", "--format", "json")
    assert code == 0, err
    points = json.loads(out)["points"]
    assert points and all(p["series_ok"] for p in points)
    ratios = [p["error_estimate"]["x"] / p["peak"]["x"] for p in points]
    assert max(ratios) > VALIDITY_ESTIMATE_LIMIT  # the series' own estimate: not a motion
    assert "beyond the series' validity" in err  # said on stderr, the JSON kept clean
    code, out, _ = run(capsys, *argv, "--order", "1")
    assert code == 0 and "beyond the series' validity" in out  # the table says it itself


def test_a_sweep_past_the_resonance_flags_the_points_outside(capsys):
    argv = ["response", "superharmonic-duffing", "--sweep", "Omega=0.32:0.5:6", "--format", "json"]
    code, out, err = run(capsys, *argv)
    assert code == 0, err
    points = json.loads(out)["points"]
    outside = [p for p in points if not p["series_ok"]]
    assert outside and len(outside) < len(points)
    assert all("outside its domain" in p["note"] for p in outside)
    assert "outside the series' domain" in err


def test_near_the_resonance_nothing_is_flagged(capsys):
    code, out, err = run(capsys, "response", "forced-duffing", "--sweep", "Omega=0.95:1.1:4",
                         "--format", "json")  # fmt: skip
    assert code == 0, err
    assert all(p["series_ok"] for p in json.loads(out)["points"])
    assert "warning" not in err


def test_the_estimate_is_the_extrapolated_next_term():
    duffing = get_problem("forced-duffing").create(eps=10)
    solution = duffing.solve(1)
    check = series_domain(solution, parameter_value_of(duffing), duffing.symbol_values())
    expected = max(next_term(check.frequency_terms),
                   *(next_term(t) for t in check.coordinate_term_sizes.values()))  # fmt: skip
    assert check.estimate == expected > VALIDITY_ESTIMATE_LIMIT and check.beyond_validity
    near = get_problem("forced-duffing").create(Omega=1.05)
    check = series_domain(near.solve(1), parameter_value_of(near), near.symbol_values())
    assert check.ok and not check.beyond_validity


@pytest.mark.parametrize(("problem", "value"), [("duffing", "eps=5"), ("van-der-pol", "eps=3")])
def test_families_outside_the_domain_fail_as_solve_does(capsys, problem, value):
    code, out, err = run(capsys, "families", problem, "--set", value, "--format", "json")
    assert code == 1 and "outside its domain" in err, err
    families = json.loads(out)["families"]
    assert families and all(f["outside"] for f in families)
    assert run(capsys, "solve", problem, "--set", value)[0] == 1
