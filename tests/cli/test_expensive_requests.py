"""Every expensive request is bounded before it starts (issue 31, item 2): one rule
(:mod:`perturb.cost`) for a sweep's grid, a response's values, order and shots, and a scene's
sections; above its threshold a ``--yes`` question, refused in one line before any work."""

from __future__ import annotations

import pytest

from perturb._defaults import CONFIRM_SECONDS, SWEEP_CONFIRM_POINTS, SWEEP_MAX_POINTS
from perturb.cli import main
from perturb.cost import Cost, check_cost, response_cost, sweep_cost
from perturb.errors import InvalidParameterError


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_the_estimate_grows_with_what_is_asked():
    base = response_cost(values=50, order=1, shots=0).seconds
    assert response_cost(values=100, order=1, shots=0).seconds > base
    assert response_cost(values=50, order=3, shots=0).seconds > base
    assert response_cost(values=50, order=1, shots=5).seconds > base
    assert sweep_cost(1000, 1, validate=True).seconds > sweep_cost(1000, 1, validate=False).seconds


@pytest.mark.parametrize(
    "cost",
    [
        Cost("a grid", SWEEP_CONFIRM_POINTS + 1, 0.0),
        Cost("a long run", 0, 2 * CONFIRM_SECONDS),
        Cost("an overflow", 0, float("inf")),
    ],
)
def test_past_the_threshold_only_with_yes(cost):
    with pytest.raises(InvalidParameterError, match="--yes"):
        check_cost(cost, yes=False)
    check_cost(cost, yes=True)


def test_past_the_maximum_not_even_with_yes():
    with pytest.raises(InvalidParameterError, match="give fewer"):
        check_cost(Cost("a grid", SWEEP_MAX_POINTS + 1, 0.0), yes=True)


@pytest.fixture
def no_work(monkeypatch):
    """Fail the test if any response or sweep is computed."""
    import perturb.response.model
    import perturb.sweep.driver

    def computed(*args, **kwargs):
        raise AssertionError("work started before the request was bounded")

    monkeypatch.setattr(perturb.response.model, "problem_response", computed)
    monkeypatch.setattr(perturb.sweep.driver.Cluster, "__enter__", computed)


def _asked(code, out, err, *words):
    assert code == 2 and out == "" and err.count("\n") == 1, err
    for word in words:
        assert word in err, err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:200000"], ["h of work", "--yes"]),
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:5", "--order", "12"],
         ["order 12", "--yes"]),
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:5", "--validate", "1000000000"],
         ["--validate 1000000000", "at most 50"]),
        (["sweep", "duffing", "--grid", "eps=0.01:0.2:400", "--grid", "amplitude=0.5:2:400",
          "--validate", "--format", "csv"], ["validated sweep points", "--yes"]),
        (["sweep", "duffing", "--grid", "eps=0.01:0.2:100000", "--grid",
          "amplitude=0.5:2:100000", "--yes", "--format", "csv"], ["GiB in memory", "--output"]),
    ],
)  # fmt: skip
def test_the_cli_asks_before_any_work(capsys, no_work, argv, words):
    pytest.importorskip("distributed")
    _asked(*run(capsys, *argv), *words)


SCENE = """[problem]
name = "{problem}"
[{section}]
{body}
[outputs]
{output} = true
"""


@pytest.mark.parametrize(
    ("problem", "section", "body", "output"),
    [
        ("forced-duffing", "response", 'sweep = "Omega=0.9:1.1:10000000"', "response"),
        ("forced-duffing", "response", 'sweep = "Omega=0.9:1.1:1000000"\nvalidate = 10',
         "response"),
        ("duffing", "sweep", 'grid = ["eps=0.01:0.1:3000", "amplitude=0.5:2:3000"]\n'
         "validate = true", "sweep"),
    ],
)  # fmt: skip
def test_a_scene_asks_too(capsys, tmp_path, no_work, problem, section, body, output):
    pytest.importorskip("distributed")
    path = tmp_path / "s.toml"
    path.write_text(SCENE.format(problem=problem, section=section, body=body, output=output))
    code, out, err = run(capsys, "report", path, "--output", tmp_path / "rep")
    _asked(code, out, err, "perturb report --yes")
    assert not (tmp_path / "rep").exists()
