"""The problem registry (issue 8 item 6): ``@register`` alone makes a built-in problem known."""

from __future__ import annotations

import importlib
import pkgutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import problems
from perturb.cli import main
from perturb.errors import ProblemLoadError, UnknownNameError
from problems import ALL_PROBLEMS, Problem, get_problem, problem_names, register
from problems._registry import _registered_names, builtin_index, check_problem_class
from problems.base import ParameterSpec


@pytest.fixture
def clean_registry(monkeypatch):
    """Registrations and the static index made by a test do not outlive it."""
    monkeypatch.setattr(ALL_PROBLEMS, "_loaded", dict(ALL_PROBLEMS._loaded))
    builtin_index.cache_clear()
    yield
    builtin_index.cache_clear()


def test_static_scan_agrees_with_importing_every_module():
    """The names the ast scan reads are exactly those the decorators register on import."""
    for info in pkgutil.walk_packages(problems.__path__, "problems."):
        importlib.import_module(info.name)
    registered = {name: f"{c.__module__}:{c.__qualname__}" for name, c in ALL_PROBLEMS.items()}
    assert builtin_index() == registered
    assert {"duffing", "van-der-pol", "disk", "rigid-body"} <= set(registered)


def test_listing_names_imports_no_problem_module():
    code = (
        "import sys, problems; names = problems.problem_names(); "
        "print(len(names), [m for m in sys.modules if m.startswith('problems.')])"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    out = run.stdout
    count, modules = out.split(" ", 1)
    assert int(count) >= 6
    assert "problems.duffing" not in modules and "problems.rigid_body.disk" not in modules
    assert "problems.rigid_body" not in modules  # no sub-package imported to walk it either


def test_the_file_walk_finds_the_modules_pkgutil_finds():
    from problems._registry import _module_files

    walked = {info.name for info in pkgutil.walk_packages(problems.__path__, "problems.")}
    found = {name for name, _ in _module_files(Path(problems.__path__[0]), "problems.")}
    assert found == walked
    assert "problems.rigid_body.paper.reproduction" in found


def test_scan_reads_literal_names_and_both_decorator_spellings():
    source = textwrap.dedent(
        """
        @register
        class A(Problem):
            name = "a-name"

        @problems.register
        class B(Problem):
            name: str = "b-name"

        @register
        class C(Problem):
            name = "c" + "-name"

        class D(Problem):
            name = "not-registered"
        """
    )
    assert _registered_names(source) == [("A", "a-name"), ("B", "b-name"), ("C", None)]


def test_a_decorator_alone_adds_a_builtin(tmp_path, monkeypatch, capsys, clean_registry):
    """A module dropped into the package (here: a folder added to its path) is listed and solved."""
    (tmp_path / "zz_extra.py").write_text(
        textwrap.dedent(
            """
            import sympy as sp
            from perturb import EPS, QuasilinearSystem
            from problems import register
            from problems.base import ParameterSpec, Problem

            X, XDOT = sp.symbols("x xdot")

            @register
            class Extra(Problem):
                name = "zz-extra"
                summary = "an extra built-in: x'' + x = eps (x' - x'^3/3)"
                parameter_specs = (ParameterSpec("eps", 0.1, "small parameter"),)

                @classmethod
                def build_system(cls):
                    return QuasilinearSystem([X], [XDOT], [1], [EPS * (XDOT - XDOT**3 / 3)])
            """
        )
    )
    monkeypatch.setattr(problems, "__path__", [*problems.__path__, str(tmp_path)])
    monkeypatch.delitem(sys.modules, "problems.zz_extra", raising=False)
    assert builtin_index()["zz-extra"] == "problems.zz_extra:Extra"
    assert main(["list"]) == 0
    assert "zz-extra" in capsys.readouterr().out
    assert main(["solve", "zz-extra", "--times", "0"]) == 0
    assert get_problem("zz-extra").__module__ == "problems.zz_extra"
    sys.modules.pop("problems.zz_extra")
    vars(problems).pop("zz_extra")


def test_mapping_interface():
    names = problem_names()
    assert names == sorted(names) == list(ALL_PROBLEMS)
    assert "duffing" in ALL_PROBLEMS and "nope" not in ALL_PROBLEMS
    assert len(ALL_PROBLEMS) == len(names)
    assert ALL_PROBLEMS["duffing"] is get_problem("duffing")
    assert ALL_PROBLEMS.get("nope") is None


def test_unknown_name_suggests_the_closest():
    with pytest.raises(UnknownNameError, match=r"did you mean 'van-der-pol'\?.*choose from"):
        get_problem("van-der-poll")
    with pytest.raises(UnknownNameError) as info:
        get_problem("qqqq")
    assert "did you mean" not in str(info.value) and "duffing" in str(info.value)


def _problem(name="tmp-problem", **attributes):
    body = {
        "name": name,
        "summary": "s",
        "parameter_specs": (ParameterSpec("eps", 0.1, "e"),),
        "build_system": classmethod(lambda cls: None),
        **attributes,
    }
    return type("Tmp", (Problem,), {k: v for k, v in body.items() if v is not None})


@pytest.mark.parametrize(
    ("attributes", "fragment"),
    [
        ({"summary": None}, "does not define summary"),
        ({"name": None}, "does not define name"),
        ({"parameter_specs": None}, "does not define parameter_specs"),
        ({"build_system": None}, "does not define build_system"),
        (
            {"parameter_specs": (ParameterSpec("mu", 1.0, "m"),)},
            "epsilon (or a parameter named eps, or 'epsilon' in parameter_map)",
        ),
        ({"name": ""}, "non-empty str"),
        ({"parameter_specs": ("eps",)}, "tuple of ParameterSpec"),
    ],
)
def test_incomplete_classes_are_refused(attributes, fragment, clean_registry):
    cls = _problem(**attributes)
    with pytest.raises(ProblemLoadError, match=fragment.replace("(", r"\(").replace(")", r"\)")):
        check_problem_class(cls)
    with pytest.raises(ProblemLoadError):
        register(cls)
    assert "tmp-problem" not in ALL_PROBLEMS


def test_register_refuses_a_taken_name(clean_registry):
    with pytest.raises(ProblemLoadError, match="already registered by problems.duffing:Duffing"):
        register(_problem("duffing"))
    mine = register(_problem("tmp-problem"))
    assert register(mine) is mine and get_problem("tmp-problem") is mine  # idempotent
    with pytest.raises(ProblemLoadError, match="give the class another name"):
        register(type("Other", (mine,), {}))
