"""`perturb families` and `--family NAME` (issue 11, item 4): JSON contract, selection, bad names."""

import json

import pytest

from perturb.cli import main

#: The keys of one family in the JSON contract, exactly.
FAMILY_KEYS = {"name", "kind", "amplitudes", "frequency", "status", "message", "outside", "beyond"}
#: ... extended (never renamed): the frequency as a number at the problem's values.
FAMILY_KEYS |= {"Omega"}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_families_json_contract(capsys):
    code, out, _ = run(capsys, "families", "van-der-pol", "--order", "2", "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert set(data) == {"problem", "order", "families"}
    assert data["problem"] == "van-der-pol" and data["order"] == 2
    (family,) = data["families"]
    assert set(family) == FAMILY_KEYS
    assert family["name"] == "limit-cycle" and family["kind"] == "isolated"
    assert family["amplitudes"] == {"a_x": 2}
    # exact numbers become JSON numbers: Omega = 1 + 0 eps - eps²/16 + ...
    assert family["frequency"][:3] == [1, 0, -0.0625]
    assert family["status"] == "SUCCESS"


def test_families_json_expressions_are_strings(capsys):
    code, out, _ = run(capsys, "families", "resonant-pair", "--format", "json")
    assert code == 0
    families = {f["name"]: f for f in json.loads(out)["families"]}
    assert set(families) == {"in-phase", "anti-phase", "line"}
    in_phase = families["in-phase"]
    assert in_phase["kind"] == "continuum"
    assert in_phase["amplitudes"] == {"a_x": "amplitude", "a_y": "amplitude", "b_y": 0}
    assert in_phase["frequency"][:2] == [1, "3*amplitude**2/8"]
    assert families["anti-phase"]["amplitudes"]["a_y"] == "-amplitude"


def test_families_table_names_the_free_amplitude(capsys):
    code, out, _ = run(capsys, "families", "duffing")
    assert code == 0
    assert "continuum  (continuum in a_x)" in out
    assert "a_x = amplitude" in out


@pytest.mark.parametrize(("mode", "name"), [("1", "in-phase"), ("-1", "anti-phase")])
def test_family_option_equals_the_branch_the_problem_used(capsys, mode, name):
    common = ["solve", "resonant-pair", "--order", "2", "--times", "0,0.5,1", "--format", "json"]
    code, out, _ = run(capsys, *common, "--set", f"mode={mode}")
    assert code == 0
    before = json.loads(out)
    code, out, _ = run(capsys, *common, "--family", name)
    assert code == 0
    chosen = json.loads(out)
    assert chosen["state"] == before["state"]
    assert chosen["period"] == before["period"]


def test_validate_accepts_family(capsys):
    code, out, _ = run(
        capsys, "validate", "van-der-pol", "--family", "limit-cycle", "--format", "json"
    )
    assert code == 0
    assert json.loads(out)["valid"] is True


@pytest.mark.parametrize("command", ["solve", "validate"])
def test_unknown_family_exits_2_with_the_list(capsys, command):
    code, out, err = run(capsys, command, "resonant-pair", "--family", "sideways")
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "'sideways'" in err
    assert "['anti-phase', 'in-phase', 'line']" in err


def test_families_bad_order_exits_2(capsys):
    code, _, err = run(capsys, "families", "duffing", "--order", "0")
    assert code == 2 and "--order" in err


HENON_HEILES_FILE = """
import sympy as sp
from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem

X, Y, XD, YD = sp.symbols("x y xdot ydot")


class HenonHeiles(Problem):
    name = "henon-heiles"
    summary = "Henon-Heiles near the origin"
    parameter_specs = (ParameterSpec("eps", 0.05, "size of the cubic terms"),)

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X, Y], [XD, YD], [1, 1], [-2 * EPS * X * Y, -EPS * (X**2 - Y**2)]
        )
"""


def test_henon_heiles_from_a_users_file_lists_its_eight_families(capsys, tmp_path):
    """Issue 21.3: at the default order the degenerate line continuum is restricted by the
    order-4 conditions; 8 families, each fixed (SUCCESS) with one free amplitude."""
    path = tmp_path / "henon.py"
    path.write_text(HENON_HEILES_FILE)
    code, out, err = run(capsys, "families", f"{path}:HenonHeiles", "--format", "json")
    assert code == 0, err
    families = {f["name"]: f for f in json.loads(out)["families"]}
    assert set(families) == {
        "y-line", "line-30", "line-150", "bowed-0", "bowed-60", "bowed-120",
        "circle-ccw", "circle-cw",
    }  # fmt: skip
    assert all(f["status"] == "SUCCESS" for f in families.values())
