"""A scene's ``[response]`` section: a driven problem's frequency response in a report (issue 18)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from perturb.errors import SceneError
from perturb.scene import parse_scene

ROOT = Path(__file__).resolve().parents[2]

SCENE = """
[problem]
name = "{problem}"

[parameters]
eps = 0.05

[response]
{response}

[outputs]
{outputs}
"""


def _scene(
    problem="forced-duffing", response='sweep = "Omega=1.0:1.1:5"', outputs="response = true"
):
    return SCENE.format(problem=problem, response=response, outputs=outputs)


@pytest.mark.parametrize(
    ("response", "outputs", "words"),
    [
        ('sweep = "Omega=1.1:1.0:5"', "response = true", "START must be below STOP"),
        ('sweep = "Omega=1.0:1.1:1"', "response = true", "between 2 and"),
        ('sweep = "Omega=1.0:1.1"', "response = true", "NAME=START:STOP:N"),
        ("sweep = 1.0", "response = true", "in quotes"),
        ('sweep = "Omega=1.0:1.1:5"\nvalidate = -1', "response = true", "validate = -1"),
        ('sweep = "Omega=1.0:1.1:5"\nshots = 2', "response = true", "unknown key 'shots'"),
        ("validate = 1", "response = true", 'give sweep = "NAME=START:STOP:N"'),
    ],
)
def test_bad_response_sections_say_the_key_the_value_and_the_fix(response, outputs, words):
    with pytest.raises(SceneError) as info:
        parse_scene(_scene(response=response, outputs=outputs), "s.toml")
    message = str(info.value)
    assert words in message and "\n" not in message and message.startswith("s.toml")


def test_a_response_output_without_the_section_is_refused():
    text = '[problem]\nname = "forced-duffing"\n[outputs]\nplots = ["frequency_response"]\n'
    with pytest.raises(SceneError, match="needs a \\[response\\] section"):
        parse_scene(text, "s.toml")


@pytest.mark.parametrize(
    ("problem", "response", "words"),
    [
        ("duffing", 'sweep = "eps=0.1:0.2:3"', "is not driven"),
        ("forced-duffing", 'sweep = "Omga=1.0:1.1:3"', "did you mean 'Omega'"),
    ],
)
def test_a_response_the_problem_cannot_give_fails_before_any_work(
    problem, response, words, tmp_path, capsys
):
    from perturb.cli import main

    scene = tmp_path / "scene.toml"
    scene.write_text(_scene(problem=problem, response=response))
    code = main(["report", str(scene), "--output", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and words in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "out" / "summary.md").exists()


def test_the_report_holds_the_same_curve_as_perturb_response(tmp_path, capsys):
    """The scene's response.json is the command's JSON for the same arguments, and its summary
    names the branches and folds; the plots asked for are written, no other."""
    pytest.importorskip("matplotlib")
    from perturb.cli import main

    scene = tmp_path / "scene.toml"
    scene.write_text(
        _scene(
            response='sweep = "Omega=1.0:1.1:6"',
            outputs='response = true\nplots = ["frequency_response"]',
        )
    )
    folder = tmp_path / "report"
    assert main(["report", str(scene), "--output", str(folder)]) == 0
    summary = capsys.readouterr().out
    assert main(
        ["response", "forced-duffing", "--set", "eps=0.05", "--sweep", "Omega=1.0:1.1:6",
         "--format", "json"]  # no order in the scene nor here: the one default of its kind
    ) == 0  # fmt: skip
    command = json.loads(capsys.readouterr().out)
    written = json.loads((folder / "response.json").read_text())
    assert written == command
    rows = (folder / "response.csv").read_text().splitlines()
    assert len(rows) == 1 + len(command["points"])
    assert "- response: " in summary and "branches" in summary
    for fold in command["folds"]:
        assert f"fold at Omega = {fold['value']:.6g}" in summary
    assert (folder / "frequency_response.png").stat().st_size > 0
    assert not (folder / "floquet_multipliers.png").exists()
    assert not (folder / "solution.csv").exists()


def test_a_scene_that_asks_for_no_response_computes_none(tmp_path, capsys):
    """The section alone computes nothing: only an output that needs the response does."""
    from perturb.cli import main

    scene = tmp_path / "scene.toml"
    scene.write_text(_scene(outputs="table = true"))
    assert main(["report", str(scene), "--output", str(tmp_path / "out")]) == 0
    summary = capsys.readouterr().out
    assert "response" not in summary.split("## files")[0]
    assert "computed: solve" in summary and "response " not in summary.split("computed:")[1]


@pytest.mark.slow
def test_the_example_response_scene_runs_and_its_true_orbits_agree(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    from perturb.cli import main

    folder = tmp_path / "report"
    path = ROOT / "examples" / "scenes" / "forced-duffing-response.toml"
    assert main(["report", str(path), "--output", str(folder)]) == 0
    summary = capsys.readouterr().out
    data = json.loads((folder / "response.json").read_text())
    assert len(data["folds"]) >= 1 and data["true"]
    assert "DISAGREE" not in summary
    for shot in data["true"]:
        assert shot["stable_true"] == shot["stable_analytic"]
    assert (folder / "floquet_multipliers.png").stat().st_size > 0
