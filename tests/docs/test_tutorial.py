"""docs/tutorial-new-problem.md is executed, so it cannot rot (issue 11 item 6).

The page marks its blocks: ``<!-- file: NAME -->`` before a block that is a file to save,
``<!-- run -->`` before a console block whose ``$ perturb ...`` lines are run (exit 0, and the output
begins with the lines the page shows), ``<!-- python -->`` before Python run in one namespace, in
order, in the folder where the files were saved (their own asserts check the numbers).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from perturb import cli

PAGE = Path(__file__).resolve().parents[2] / "docs" / "tutorial-new-problem.md"
BLOCK = re.compile(r"<!-- (file: (?P<file>\S+)|run|python) -->\n```\w*\n(?P<body>.*?)```", re.S)


def blocks():
    return [
        (m.group(1), m.group("file"), m.group("body")) for m in BLOCK.finditer(PAGE.read_text())
    ]


def test_the_page_has_every_kind_of_block():
    kinds = [kind.split(":")[0] for kind, _, _ in blocks()]
    assert kinds.count("file") == 1 and kinds.count("run") >= 3 and kinds.count("python") >= 3


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    path = tmp_path_factory.mktemp("tutorial")
    for kind, name, body in blocks():
        if kind.startswith("file"):
            (path / name).write_text(body)
    return path


def console_cases():
    cases = []
    for kind, _, body in blocks():
        if kind == "run":
            command, *shown = body.rstrip("\n").split("\n")
            cases.append(pytest.param(command, shown, id=command[:60]))
    return cases


@pytest.mark.parametrize("command, shown", console_cases())
def test_console_blocks(folder, monkeypatch, capsys, command, shown):
    assert command.startswith("$ perturb ")
    monkeypatch.chdir(folder)
    code = cli.main(shlex.split(command)[2:])
    out = capsys.readouterr().out.splitlines()
    assert code == 0
    assert [line.rstrip() for line in out[: len(shown)]] == [line.rstrip() for line in shown]


def test_python_blocks(folder, monkeypatch):
    monkeypatch.chdir(folder)
    namespace: dict = {"__name__": "tutorial"}
    for kind, _, body in blocks():
        if kind == "python":
            exec(compile(body, str(PAGE), "exec"), namespace)  # noqa: S102 - the page's own code
