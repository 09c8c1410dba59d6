"""No message, page or file advises installing the taken distribution name ``perturb`` (issue 27).

``perturb`` on the package registry is an unrelated project; perturb's distribution is
:data:`perturb._install.DISTRIBUTION`. A hint such as ``pip install 'perturb[plot]'`` or
``pip install perturb`` would install the other project, so none may appear in the tree.
"""

import re
from pathlib import Path

from perturb._install import DISTRIBUTION, install_hint

ROOT = Path(__file__).resolve().parents[1]
#: The folders and top-level files a user reads or runs.
SCANNED = ("perturb", "problems", "docs", "examples", "benchmarks", "tests", "README.md", ".ci")
SUFFIXES = {".py", ".md", ".rst", ".toml", ".txt", ".cfg", ".ipynb", ""}
#: ``pip install`` followed by the bare name, optionally quoted, optionally with extras or a version.
TAKEN = re.compile(r"pip3?\s+install\s+(?:-U\s+|--upgrade\s+)?['\"]?perturb(?![-\w])")
SKIPPED_DIRS = {"_build", ".venv", "__pycache__", ".git"}


def _files():
    for entry in SCANNED:
        path = ROOT / entry
        if path.is_file():
            yield path
        elif path.is_dir():
            for file in path.rglob("*"):
                if (
                    file.is_file()
                    and file.suffix in SUFFIXES
                    and not SKIPPED_DIRS & set(file.parts)
                ):
                    yield file


def test_no_hint_names_the_taken_distribution():
    offenders = []
    for file in _files():
        text = file.read_text(encoding="utf-8", errors="replace")
        offenders += [
            f"{file.relative_to(ROOT)}:{text.count(chr(10), 0, m.start()) + 1}: {m.group(0)}"
            for m in TAKEN.finditer(text)
            if file.name != Path(__file__).name
        ]
    assert not offenders, "install hints naming the taken distribution:\n" + "\n".join(offenders)


def test_the_pattern_catches_the_forms_users_copy():
    for hint in (
        "pip install 'perturb[plot]'",
        "pip install perturb",
        'pip install "perturb[fast]"',
    ):
        assert TAKEN.search(hint), hint
    assert not TAKEN.search(install_hint("plot"))
    assert not TAKEN.search('pip install -e ".[plot]"')


def test_the_distribution_is_the_one_pyproject_builds():
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(rf'^name = "{re.escape(DISTRIBUTION)}"$', pyproject, re.M)
