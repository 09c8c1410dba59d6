"""Output formats as a registry: every ``--format`` choice list comes from it, and a format is one
module of ``perturb/report/formats/`` (a planted one is offered and used by the command line)."""

from __future__ import annotations

import sys

import pytest

import perturb.report.formats as formats
from perturb.cli import main

#: The choice lists the commands offered when they were written by hand (the ``--help`` contract).
CHOICES = {
    "problems": ["table", "json", "latex"],
    "solution": ["table", "csv", "json", "latex"],
    "validation": ["table", "json", "latex"],
    "work-precision": ["table", "csv", "json", "latex"],
    "reproduction": ["table", "json"],
    "response": ["table", "csv", "json", "latex"],
    "families": ["table", "json", "latex"],
    "phase": ["table", "json"],
    "sweep": ["zarr", "csv", "json"],
}


@pytest.mark.parametrize("kind", sorted(CHOICES))
def test_the_choices_are_the_commands_own(kind):
    assert formats.choices(kind) == CHOICES[kind]


def test_only_json_carries_the_warnings_and_writes_a_failure():
    assert [n for n in formats.FORMATS if formats.keeps_warnings(n)] == ["json"]
    assert formats.write("failure", "json", {"status": "failed"}) == '{"status": "failed"}\n'
    assert formats.write("failure", "csv", {"status": "failed"}) == ""


_ONE_LINE = """
from perturb.report.formats import Format

FORMAT = Format(
    "one-line", {"validation": lambda report: report.outcome.name.lower() + "\\n"}, rank=5
)
"""


def test_a_format_is_one_file(tmp_path, monkeypatch, capsys):
    (tmp_path / "one_line_format.py").write_text(_ONE_LINE)
    monkeypatch.setattr(formats, "__path__", [*formats.__path__, str(tmp_path)])
    monkeypatch.setattr(formats, "FORMATS", formats._found())
    monkeypatch.delitem(sys.modules, "perturb.report.formats.one_line_format", raising=False)
    assert formats.choices("validation") == [*CHOICES["validation"], "one-line"]
    assert formats.choices("solution") == CHOICES["solution"]  # it writes validations only
    code = main(["validate", "duffing", "--periods", "1", "--format", "one-line"])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert out == "valid\n"
    assert main(["solve", "duffing", "--format", "one-line"]) == 2  # not a choice there
    assert "invalid choice: 'one-line'" in capsys.readouterr().err
