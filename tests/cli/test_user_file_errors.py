"""A user's problem file that is broken is named as such (issue 31, item 4): one line naming the
file, the cause and the fix, exit 2 — never an internal error, never an overflow, whatever the
command (the class is checked once when it is loaded: ``problems/_checks.py``)."""

from __future__ import annotations

import pytest

from perturb.cli import main
from tests.cli.hostile_files import DRIVEN_FILE, HEADER, PROBLEM_FILES, scene

BROKEN = sorted(name for name, (_, expect) in PROBLEM_FILES.items() if expect == "usage")


@pytest.fixture
def folder(tmp_path, monkeypatch):
    for name, (text, _) in PROBLEM_FILES.items():
        (tmp_path / name.split(":")[0]).write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _named(code, out, err, file):
    assert code == 2 and out == "", err
    lines = [line for line in err.splitlines() if not line.startswith("perturb: warning")]
    assert len(lines) == 1 and lines[0].startswith("perturb: error:"), err
    assert file.split(":")[0] in lines[0], err
    assert "internal error" not in err and "overflow" not in err


@pytest.mark.parametrize("name", BROKEN)
def test_solve_names_the_broken_file(capsys, folder, name):
    _named(*run(capsys, "solve", name), name)


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("no_values.py", "'k'"),
        ("recursive.py", "recursed without end"),
        ("unknown_function.py", "calls ['g']"),
        ("pole.py", "not polynomial in the state"),
        ("exit0.py", "sys.exit(0)"),
        ("exit3.py", "sys.exit(3)"),
        ("keyboard.py", "KeyboardInterrupt"),
        ("options_list.py", "method_options() returned list"),
        ("build_returns_none.py", "returned NoneType"),
        ("default_invalid.py", "default parameters are refused"),
    ],
)
def test_the_cause_is_said(capsys, folder, name, words):
    code, out, err = run(capsys, "solve", name)
    _named(code, out, err, name)
    assert words in err


@pytest.mark.parametrize(
    "argv",
    [
        ["validate", "no_values.py"],
        ["families", "recursive.py"],
        ["response", "exit3.py", "--sweep", "sigma=-1:1:3"],
        ["work-precision", "options_list.py", "--periods", "1", "--repeat", "1"],
    ],
)
def test_every_command_names_it(capsys, folder, argv):
    _named(*run(capsys, *argv), argv[1])


def test_a_scene_naming_a_broken_file(capsys, folder):
    (folder / "s.toml").write_text(scene(problem="pole.py", parameters="", outputs="table = true"))
    code, out, err = run(capsys, "report", "s.toml", "--output", "rep")
    _named(code, out, err, "pole.py")
    assert not (folder / "rep" / "summary.md").exists()


def test_an_error_in_the_users_code_at_run_time_names_the_line(capsys, folder):
    text = (
        HEADER
        + PROBLEM_FILES["good.py"][0].split(HEADER, 1)[1]
        + (
            "\n    def symbol_values(self):\n"
            "        if self.values['amplitude'] > 2:\n"
            "            raise RuntimeError('amplitudes above 2 are not modelled')\n"
            "        return super().symbol_values()\n"
        )
    )
    (folder / "late.py").write_text(text, encoding="utf-8")
    assert run(capsys, "solve", "late.py", "--times", "0")[0] == 0
    code, out, err = run(capsys, "solve", "late.py", "--set", "amplitude=3")
    _named(code, out, err, "late.py")
    assert "late.py:" in err and "amplitudes above 2 are not modelled" in err


def test_a_file_that_is_fine_still_runs(capsys, folder):
    code, out, err = run(capsys, "solve", "sine.py", "--times", "0", "--format", "json")
    assert code == 0, err
    code, out, err = run(capsys, "response", DRIVEN_FILE, "--sweep", "sigma=-1:1:3")
    assert code == 0, err
