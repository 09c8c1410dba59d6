"""The README's comments say what the commands beside them print: each commented command is run
and its comment checked against its JSON (a comment that drifts from the output fails here).

A README line ``perturb COMMAND ...   # comment`` is found by its command, so a comment edited in
the README is the one checked; every such line of a block the README runs is checked here (the
test fails on a commented command it does not know, so a new comment gets a check).
"""

from __future__ import annotations

import json
import re
import shlex
from pathlib import Path

import pytest

from perturb.cli import main

README = Path(__file__).resolve().parents[1] / "README.md"


def commented_lines() -> dict[str, str]:
    """``{command: comment}`` of every ``perturb ...  # comment`` line in a README bash block."""
    found, inside = {}, False
    for line in README.read_text().splitlines():
        if line.startswith("```"):
            inside = line.strip() == "```bash"
            continue
        if inside and line.startswith("perturb ") and "  #" in line:
            command, _, comment = line.partition("  #")
            found[command.strip()] = comment.strip()
    return found


def run_json(capsys, command: str) -> dict:
    argv = [*shlex.split(command)[1:], "--format", "json", "--quiet"]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)


def _stable(family: dict) -> bool:
    """A driven family's stability, as its message states it (``...; stable (Floquet)``)."""
    return bool(re.search(r"(?<!un)stable \(Floquet\)", family["message"]))


def check_families_count_and_stable(capsys, command: str, comment: str) -> None:
    match = re.fullmatch(r"(\d+) steady states of [^;]+; stable: (.+)", comment)
    assert match, comment
    families = run_json(capsys, command)["families"]
    assert len(families) == int(match.group(1))
    named = {name.strip() for name in match.group(2).split(",")}
    assert {f["name"] for f in families if _stable(f)} == named


def check_families_branches(capsys, command: str, comment: str) -> None:
    match = re.fullmatch(r"(\d+) branches: (.+?)(, \.\.\.)?", comment)
    assert match, comment
    names = {f["name"] for f in run_json(capsys, command)["families"]}
    assert len(names) == int(match.group(1))
    assert {name.strip() for name in match.group(2).split(",")} <= names


def check_unstable_by_both_routes(capsys, command: str, comment: str) -> None:
    assert comment == "unstable, by both routes"
    stability = run_json(capsys, command)["checks"]["stability"]
    assert stability["passed"] and stability["value"] > 1  # the true orbit's largest |mu|
    assert "multipliers say unstable" in stability["sentence"]


#: How each commented command's comment is checked (by the command's first words).
CHECKS = {
    "perturb families coupled-duffings": check_families_count_and_stable,
    "perturb families resonant-chain-4": check_families_branches,
    "perturb validate forced-duffing": check_unstable_by_both_routes,
}


def _check_of(command: str):
    return next((c for head, c in CHECKS.items() if command.startswith(head)), None)


def test_every_commented_command_has_a_check():
    commented = commented_lines()
    assert commented  # the README has commented commands: the parser found them
    unknown = [c for c in commented if _check_of(c) is None]
    assert not unknown, f"README comments without a check here: {unknown}"


@pytest.mark.parametrize("command", sorted(commented_lines()))
def test_the_comment_says_what_the_command_prints(capsys, command):
    comment = commented_lines()[command]
    _check_of(command)(capsys, command, comment)
