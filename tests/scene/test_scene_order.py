"""A scene without ``[solve] order`` takes the one default order of every command (3 for a
driven problem, 1 for a free one) and its summary prints it; a scene that gives an order keeps
it."""

from __future__ import annotations

import pytest

from perturb.cli import main
from perturb.scene import parse_scene, run_scene
from perturb.validation.frames import work_of
from problems import get_problem


@pytest.mark.parametrize(("name", "expected"), [("forced-duffing", 3), ("duffing", 1)])
def test_a_scene_without_order_takes_the_default_of_its_kind(name, expected):
    problem = get_problem(name).create()
    assert work_of(problem.system()).default_order == expected  # the CLI's one rule
    scene = parse_scene(f'[problem]\nname = "{name}"\n')
    assert scene.order is None
    result = run_scene(scene, problem)
    assert result.scene.order == expected
    assert result.solution.success, result.solution.message
    assert result.solution.order == expected


def test_a_scene_that_gives_its_order_keeps_it():
    problem = get_problem("forced-duffing").create()
    result = run_scene(parse_scene('[problem]\nname = "forced-duffing"\n[solve]\norder = 1\n'),
                       problem)  # fmt: skip
    assert result.scene.order == 1 and result.solution.order == 1


def test_the_summary_prints_the_default_order(tmp_path, capsys):
    scene = tmp_path / "scene.toml"
    scene.write_text('[problem]\nname = "forced-duffing"\n[outputs]\ntable = true\n')
    code = main(["report", str(scene), "--output", str(tmp_path / "out"), "--quiet"])
    out = capsys.readouterr().out
    assert code == 0
    assert "# forced-duffing: order 3" in out
    assert "# forced-duffing: order 3" in (tmp_path / "out" / "summary.md").read_text()
