"""The tutorials are executed, so they cannot rot (issue 11 item 6, issue 20 item 2).

Each tutorial (``docs/tutorials/*.md``) is a MyST text notebook: Markdown with ``{code-cell}``
blocks. The documentation build executes them in a Jupyter kernel (``docs/conf.py``: a cell that
raises fails the build); this test runs the same cells without Jupyter, in order, in one namespace
and a fresh folder: a cell starting ``%%writefile NAME`` saves a file, one starting ``%%bash`` runs
its ``perturb ...`` lines through the CLI (each must exit 0), line magics (``%matplotlib``) are
dropped, and every other cell is Python whose own ``assert`` lines check the numbers against a
second route. The own-problem tutorial runs in the default suite; the others are slow (the site
build in ``tests/docs/test_site.py`` runs them too).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from perturb import cli

TUTORIALS = Path(__file__).resolve().parents[2] / "docs" / "tutorials"
CELL = re.compile(r"^```\{code-cell\}[^\n]*\n(?P<body>.*?)^```", re.S | re.M)
#: The tutorial kept in the default suite (seconds); the others take up to ~10 s each.
QUICK = ("new-problem.md",)


def notebooks() -> list[Path]:
    """Every tutorial that is a notebook (a MyST-NB header with a kernelspec)."""
    return sorted(p for p in TUTORIALS.glob("*.md") if "kernelspec:" in p.read_text()[:400])


def cells(page: Path) -> list[tuple[str, str, str]]:
    """``(kind, argument, body)`` for each code cell: kind ``file``, ``bash`` or ``python``."""
    found = []
    for match in CELL.finditer(page.read_text()):
        lines = [
            line for line in match.group("body").splitlines() if not line.startswith("%matplotlib")
        ]
        first = lines[0] if lines else ""
        if first.startswith("%%writefile "):
            found.append(("file", first.split()[1], "\n".join(lines[1:]) + "\n"))
        elif first == "%%bash":
            found.append(("bash", "", "\n".join(lines[1:])))
        else:
            assert not first.startswith("%"), f"{page.name}: a magic this test cannot run: {first}"
            found.append(("python", "", "\n".join(lines) + "\n"))
    return found


def test_every_tutorial_is_a_notebook_with_code():
    pages = notebooks()
    assert {p.name for p in pages} >= {
        "new-problem.md",
        "paper.md",
        "disk-euler.md",
        "work-precision.md",
    }
    for page in pages:
        assert sum(kind == "python" for kind, _, _ in cells(page)) >= 3, page.name


def test_the_own_problem_page_has_every_kind_of_cell():
    kinds = [kind for kind, _, _ in cells(TUTORIALS / "new-problem.md")]
    assert kinds.count("file") == 1 and kinds.count("bash") >= 3 and kinds.count("python") >= 3


def _params():
    return [
        pytest.param(page, id=page.stem, marks=() if page.name in QUICK else pytest.mark.slow)
        for page in notebooks()
    ]


@pytest.mark.parametrize("page", _params())
def test_tutorial_runs(page, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.syspath_prepend(str(tmp_path))
    namespace: dict = {"__name__": "tutorial"}
    for kind, argument, body in cells(page):
        if kind == "file":
            (tmp_path / argument).write_text(body)
        elif kind == "bash":
            for line in filter(None, (line.strip() for line in body.splitlines())):
                assert line.startswith("perturb "), (
                    f"{page.name}: a shell line that is not perturb: {line}"
                )
                code = cli.main(shlex.split(line)[1:])
                out = capsys.readouterr().out
                assert code == 0, f"{line} exited {code}"
                assert out.strip(), f"{line} printed nothing"
        else:
            exec(compile(body, str(page), "exec"), namespace)  # noqa: S102 - the page's own code
