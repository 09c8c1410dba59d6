"""Every public name has a numpydoc docstring with an example that runs (issue 20, item 3).

The public names are those of the packages' ``__all__`` and the registered problem classes; a new
public function or class without an ``Examples`` section, or whose example no longer gives the
output it shows, fails here. Each name must also be listed on a page of the API reference
(``docs/reference/*.rst``), which is generated from these docstrings.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import re
import sys
from pathlib import Path

import pytest

REFERENCE = Path(__file__).resolve().parents[2] / "docs" / "reference"
PACKAGES = (
    "perturb",
    "perturb.case",
    "perturb.continuation",
    "perturb.oracle",
    "perturb.validation",
    "perturb.validation.capabilities",
    "perturb.report.plots",
    "perturb.report.formats",
    "perturb.workprecision",
    "perturb.cache",
    "problems",
)
#: Modules whose examples draw figures: skipped without matplotlib (the ``plot`` extra).
NEEDS_MATPLOTLIB = ("perturb.report.plots",)
#: Examples of heyoka itself: skipped without it (the ``fast`` extra).
NEEDS_HEYOKA = ("perturb.oracle.Heyoka", "perturb.oracle.to_heyoka")


def public_names() -> dict[str, object]:
    """``full name -> object`` of every public name (package ``__all__`` and problem classes)."""
    names = {}
    for package in PACKAGES:
        module = importlib.import_module(package)
        for name in module.__all__:
            names[f"{package}.{name}"] = getattr(module, name)
    from problems import get_problem, problem_names

    for key in problem_names():
        cls = get_problem(key)
        names[f"{cls.__module__}.{cls.__qualname__}"] = cls
    return names


def documented_objects() -> dict[str, object]:
    """The classes and functions among the public names (constants are documented by comment)."""
    return {
        name: obj
        for name, obj in public_names().items()
        if inspect.isclass(obj)
        or inspect.isroutine(obj)
        or callable(getattr(obj, "__wrapped__", None))
    }


def _doc(obj) -> dict[str, list[str]]:
    """The numpydoc sections of ``obj``'s docstring, ``"Summary"`` its first line; read without
    numpydoc, so that the default suite checks them without the docs extra."""
    lines = (inspect.getdoc(obj) or "").splitlines()
    sections = {"Summary": lines[:1] if lines and lines[0].strip() else []}
    current = None
    for line, underline in zip(lines, [*lines[1:], ""], strict=True):
        rule = underline.strip()
        if line.strip() and len(rule) >= 3 and set(rule) == {"-"}:
            current = line.strip()
            sections[current] = []
        elif current is not None and line.strip() and set(line.strip()) != {"-"}:
            sections[current].append(line)
    return sections


def _takes_arguments(obj) -> bool:
    target = obj.__init__ if inspect.isclass(obj) else obj
    if inspect.isclass(obj) and target is object.__init__:
        return False
    try:
        signature = inspect.signature(target)
    except (TypeError, ValueError):
        return False
    return any(p.name not in ("self", "cls") for p in signature.parameters.values())


OBJECTS = documented_objects()


def test_the_public_names_are_found():
    assert "perturb.PoincareMethod" in OBJECTS and "perturb.validation.validate" in OBJECTS
    assert "problems.duffing.Duffing" in OBJECTS
    assert len(OBJECTS) >= 60


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_docstring_sections(name):
    obj = OBJECTS[name]
    doc = dict.fromkeys(("Parameters", "Attributes", "Returns", "Yields", "Examples"), [])
    doc.update(_doc(obj))
    assert doc["Summary"], f"{name}: no one-line summary"
    assert doc["Examples"], f"{name}: no Examples section"
    assert ">>>" in "\n".join(doc["Examples"]), f"{name}: its Examples have no doctest line"
    if inspect.isclass(obj):
        # a class documents its constructor's arguments, or (a value object) its fields; a
        # protocol is not constructed
        protocol = getattr(obj, "_is_protocol", False)
        if not protocol and _takes_arguments(obj) and "__init__" in vars(obj):
            assert doc["Parameters"] or doc["Attributes"], f"{name}: no Parameters section"
    elif _takes_arguments(obj):
        assert doc["Parameters"], f"{name}: no Parameters section"
    if inspect.isroutine(obj) or callable(getattr(obj, "__wrapped__", None)):
        if not inspect.isclass(obj):
            assert doc["Returns"] or doc["Yields"], f"{name}: no Returns section"


def _examples(name):
    obj = OBJECTS[name]
    finder = doctest.DocTestFinder(recurse=False)
    module = sys.modules[getattr(obj, "__module__", None) or "builtins"]
    globs = dict(vars(module))  # as pytest --doctest-modules: the defining module's names
    return [t for t in finder.find(obj, name, globs=globs) if t.examples]


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_examples_run(name, tmp_path, monkeypatch):
    if name.startswith(NEEDS_MATPLOTLIB):
        pytest.importorskip("matplotlib")
        monkeypatch.setenv("MPLBACKEND", "Agg")
    if name in NEEDS_HEYOKA:
        pytest.importorskip("heyoka")
    monkeypatch.chdir(tmp_path)  # an example that writes a file writes it here
    tests = _examples(name)
    assert tests, f"{name}: no doctest found"
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    runner = doctest.DocTestRunner(optionflags=flags)
    for test in tests:
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed"


def _listed_on_reference_pages() -> set[str]:
    listed = set()
    for page in REFERENCE.glob("*.rst"):
        module = None
        for line in page.read_text().splitlines():
            if m := re.match(r"\.\. currentmodule:: (\S+)", line):
                module = m.group(1)
            elif m := re.match(r"\.\. perturb-constants:: (\S+)", line):
                module = m.group(1)
                listed.add(f"{module}.*constants*")
            elif m := re.match(r"   :names: (.+)", line):
                listed.update(f"{module}.{n}" for n in m.group(1).split())
            elif m := re.match(r"   ([A-Za-z_][\w.]*)$", line):
                listed.add(f"{module}.{m.group(1)}")
            elif m := re.match(r"\.\. data:: (\w+)", line):
                listed.add(f"{module}.{m.group(1)}")
    return listed


def test_every_public_name_has_a_reference_entry():
    listed = _listed_on_reference_pages()
    missing = []
    for name in public_names():
        package = name.rsplit(".", 1)[0]
        if name in listed:
            continue
        is_constant = name not in OBJECTS
        if is_constant and f"{package}.*constants*" in listed:
            continue
        missing.append(name)
    assert not missing, f"not on any page of docs/reference: {missing}"


def test_the_section_reader_sees_a_missing_example():
    def documented(x):
        """Square.

        Parameters
        ----------
        x : float

        Returns
        -------
        float
        """

    sections = _doc(documented)
    assert sections["Summary"] == ["Square."] and sections["Parameters"] == ["x : float"]
    assert "Examples" not in sections
