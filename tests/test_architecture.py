"""The house rules that keep the code's data path one-way (docs/architecture.md).

Every import is scanned, at module level and inside functions, by parsing the source with ``ast``:

1. ``perturb`` never imports ``problems`` (problems depend on the engine, never the reverse);
2. nothing imports the leaves ``perturb.report`` and ``perturb.cli`` except the CLI itself (and tests);
3. no source file of the package grows past a size that signals two concerns in one room.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("perturb", "problems")

#: A file past this many lines is a sign that it holds two concerns (../shared/design/house.md, rule 6);
#: the margin over the ~600 of the design lets a file grow a docstring without being split for it.
MAX_LINES = 650

#: Modules allowed to import the report leaves: the CLI front end (and its package ``__main__``).
LEAF_IMPORTERS = ("perturb.cli", "perturb.__main__", "perturb.report")


def _sources():
    for package in PACKAGES:
        yield from sorted((ROOT / package).rglob("*.py"))


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _imports(path: Path, module: str | None = None) -> list[tuple[int, str]]:
    """Every module ``path`` imports, anywhere in the file, with the line number."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    module = _module_name(path) if module is None else module
    is_package = path.name == "__init__.py"
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: resolve against this module's package
                base = module.split(".")
                base = base if is_package else base[:-1]
                base = base[: len(base) - (node.level - 1)]
                target = ".".join([*base, node.module] if node.module else base)
            else:
                target = node.module or ""
            found.append((node.lineno, target))
            found.extend((node.lineno, f"{target}.{alias.name}") for alias in node.names)
        elif isinstance(node, ast.Call) and getattr(
            node.func, "attr", getattr(node.func, "id", "")
        ) in (
            "import_module",
            "__import__",
        ):
            if (
                node.args
                and isinstance(node.args[0], ast.Constant)
                and isinstance(node.args[0].value, str)
            ):
                found.append((node.lineno, node.args[0].value))
    return found


def _is_under(name: str, package: str) -> bool:
    return name == package or name.startswith(package + ".")


def test_the_scan_sees_imports_inside_functions(tmp_path):
    source = tmp_path / "sample.py"
    source.write_text(
        "def f():\n    from problems.base import Problem\n    import problems\n"
        "    from .report import text\n"
    )
    names = [name for _, name in _imports(source, module="perturb.sample")]
    assert "problems.base" in names and "problems" in names and "perturb.report.text" in names


@pytest.mark.parametrize(
    "path", [p for p in _sources() if _module_name(p).startswith("perturb")], ids=_module_name
)
def test_perturb_never_imports_problems(path):
    offending = [(line, name) for line, name in _imports(path) if _is_under(name, "problems")]
    if _is_under(_module_name(path), "perturb.cli"):  # the CLI is a leaf: it may use problems
        offending = []
    assert not offending, f"{path.relative_to(ROOT)} imports problems at {offending}"


@pytest.mark.parametrize("path", list(_sources()), ids=_module_name)
def test_only_the_cli_imports_the_leaves(path):
    module = _module_name(path)
    if any(_is_under(module, leaf) for leaf in LEAF_IMPORTERS):
        return
    offending = [
        (line, name)
        for line, name in _imports(path)
        if _is_under(name, "perturb.report") or _is_under(name, "perturb.cli")
    ]
    assert not offending, f"{path.relative_to(ROOT)} imports a leaf at {offending}"


@pytest.mark.parametrize("path", list(_sources()), ids=_module_name)
def test_no_file_holds_two_rooms(path):
    n_lines = len(path.read_text(encoding="utf-8").splitlines())
    assert n_lines <= MAX_LINES, f"{path.relative_to(ROOT)} has {n_lines} lines (limit {MAX_LINES})"


#: The extra ``perturb[sweep]``: imported by the sweep room only (docs/architecture.md).
SWEEP_EXTRA = ("dask", "distributed", "xarray", "zarr", "cloudpickle")
#: Inside the sweep room, the modules that talk to Dask and the stores.
SWEEP_EXTRA_IMPORTERS = ("perturb.sweep.driver", "perturb.sweep.store", "perturb.sweep.memory")


@pytest.mark.parametrize("path", list(_sources()), ids=_module_name)
def test_only_the_sweep_room_imports_dask_xarray_zarr(path):
    module = _module_name(path)
    offending = [
        (line, name)
        for line, name in _imports(path)
        if any(_is_under(name, extra) for extra in SWEEP_EXTRA)
    ]
    if module in SWEEP_EXTRA_IMPORTERS:
        offending = []
    assert not offending, f"{path.relative_to(ROOT)} imports the sweep extra at {offending}"


@pytest.mark.parametrize("argv", [["--help"], ["sweep", "--help"], ["list"]])
def test_the_command_line_loads_no_sweep_extra_unasked(argv):
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from perturb.cli import main\n"
        "try:\n"
        f"    main({argv!r})\n"
        "except SystemExit:\n"
        "    pass\n"
        f"loaded = sorted(m for m in sys.modules if m.split('.')[0] in {SWEEP_EXTRA!r})\n"
        "print(loaded)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]"
