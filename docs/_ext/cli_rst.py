"""The command-line reference as reStructuredText, generated from perturb's argparse tree.

Pure Python (no Sphinx): ``perturb_docs.py`` parses what :func:`cli_reference` returns, and
``tests/docs/test_site.py`` checks that it names every subcommand and option of the parser.
"""

from __future__ import annotations

import argparse
import re

_CODE = re.compile(r"`([^`]+)`")
_RULES = "=-~^"  # the page title uses "#" (MyST); the parser's sections come under it


def _text(help_text: str | None) -> str:
    """A help string as reST: `code` as literal, nothing that reST would read as markup."""
    text = (help_text or "").replace("%%", "%").replace("*", r"\*").replace("|", r"\|")
    return _CODE.sub(r"``\1``", text)


def _heading(title: str, level: int) -> list[str]:
    return [title, _RULES[level] * len(title), ""]


def _subparsers(parser: argparse.ArgumentParser) -> argparse._SubParsersAction | None:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action
    return None


def _invocation(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    return parser._get_formatter()._format_action_invocation(action)


def _options(parser: argparse.ArgumentParser, *, with_help: bool) -> list[str]:
    lines: list[str] = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            continue
        if isinstance(action, argparse._HelpAction) and not with_help:
            continue
        lines += [f".. option:: {_invocation(parser, action)}", ""]
        details = _text(action.help).rstrip()
        if details and not details.endswith((".", ")")):
            details += "."
        if action.required and action.option_strings:
            details += " Required."
        if action.option_strings and action.nargs == 0:
            details += " (A flag: takes no value.)"
        elif isinstance(action, argparse._AppendAction):
            details += " Repeatable."
        lines += ["   " + details, ""]
    return lines


def _command(
    parser: argparse.ArgumentParser, name: str, help_text: str | None, level: int
) -> list[str]:
    lines = _heading(f"perturb {name}", level)
    lines += [f".. program:: perturb {name}", ""]
    if help_text:
        lines += [_text(help_text[0].upper() + help_text[1:]) + ".", ""]
    lines += [".. code-block:: text", "", "   " + parser.format_usage().strip(), ""]
    if parser.description:
        lines += [_text(parser.description), ""]
    lines += _options(parser, with_help=False)
    return lines


def cli_reference(parser: argparse.ArgumentParser) -> str:
    """reST for ``parser``: the program, then one section per subcommand, every option of each."""
    lines = [".. program:: perturb", ""]
    if parser.description:
        lines += [_text(parser.description), ""]
    lines += [".. code-block:: text", "", "   " + parser.format_usage().strip(), ""]
    lines += _options(parser, with_help=True)
    sub = _subparsers(parser)
    if sub is not None:
        helps = {action.dest: action.help for action in sub._choices_actions}
        lines += ["Every command also takes ``-h``/``--help`` (its own help, then exit).", ""]
        for name, command in sub.choices.items():
            lines += _command(command, name, helps.get(name), 0)
    if parser.epilog:
        lines += _heading("Examples", 0)
        body = (
            parser.epilog.split("\n", 1)[1]
            if parser.epilog.startswith("examples:")
            else parser.epilog
        )
        lines += (
            [".. code-block:: text", ""]
            + ["   " + line.strip() for line in body.splitlines()]
            + [""]
        )
    return "\n".join(lines) + "\n"
