"""The house rules that keep the code's data path one-way (docs/architecture.md).

Every import is scanned, at module level and inside functions, by parsing the source with ``ast``:

1. ``perturb`` never imports ``problems`` (problems depend on the engine, never the reverse);
2. nothing imports the leaves ``perturb.report`` and ``perturb.cli`` except the CLI itself (and tests);
3. no source file of the package grows past a size that signals two concerns in one room;
4. the analytic rooms (the series, its steady states, continuation, roots) never import the rooms
   that check them (oracle, validation, the response curve with its true orbits), and validation
   never imports the response curve: no arrow runs back up;
5. no two files of the package import each other (a circle hidden by a function-level import).
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


# One test per rule, each listing every offender (a rule x file parametrization made ~590 tests).
def _relative(path: Path) -> str:
    try:
        return str(path.relative_to(ROOT))
    except ValueError:  # a planted file, outside the tree
        return path.name


def _imports_of(paths, module=None):
    """(path, line, imported name) for every import of every file."""
    for path in paths:
        for line, name in _imports(path, module):
            yield path, line, name


def problems_importers(paths, module=None) -> list[str]:
    """Files of ``perturb`` (but the CLI, a leaf) that import ``problems``."""
    return [
        f"{_relative(path)}:{line} imports {name}"
        for path, line, name in _imports_of(paths, module)
        if _is_under(name, "problems")
        and not _is_under(module or _module_name(path), "perturb.cli")
    ]


def leaf_importers(paths, module=None) -> list[str]:
    """Files other than the CLI that import the leaves ``perturb.report`` or ``perturb.cli``."""
    return [
        f"{_relative(path)}:{line} imports {name}"
        for path, line, name in _imports_of(paths, module)
        if not any(_is_under(module or _module_name(path), leaf) for leaf in LEAF_IMPORTERS)
        and (_is_under(name, "perturb.report") or _is_under(name, "perturb.cli"))
    ]


#: Files long for one concern: the table of every named tolerance and limit, each with the reason
#: for its value (issue 28 put them all in one place; splitting it by room would scatter them again).
LONG_BY_DESIGN = ("perturb/_defaults.py",)


def long_files(paths) -> list[str]:
    """Files past MAX_LINES lines (but LONG_BY_DESIGN)."""
    paths = [path for path in paths if _relative(path) not in LONG_BY_DESIGN]
    lengths = ((path, len(path.read_text(encoding="utf-8").splitlines())) for path in paths)
    return [f"{_relative(path)} has {n} lines" for path, n in lengths if n > MAX_LINES]


def sweep_extra_importers(paths, module=None) -> list[str]:
    """Files outside SWEEP_EXTRA_IMPORTERS that import Dask, xarray or Zarr."""
    return [
        f"{_relative(path)}:{line} imports {name}"
        for path, line, name in _imports_of(paths, module)
        if (module or _module_name(path)) not in SWEEP_EXTRA_IMPORTERS
        and any(_is_under(name, extra) for extra in SWEEP_EXTRA)
    ]


def _perturb_sources():
    return [p for p in _sources() if _module_name(p).startswith("perturb")]


def test_perturb_never_imports_problems():
    offenders = problems_importers(_perturb_sources())
    assert not offenders, "perturb must not import problems:\n" + "\n".join(offenders)


def test_only_the_cli_imports_the_leaves():
    offenders = leaf_importers(_sources())
    assert not offenders, "only the CLI may import the leaves:\n" + "\n".join(offenders)


def test_no_file_holds_two_rooms():
    offenders = long_files(_sources())
    assert not offenders, f"files past {MAX_LINES} lines:\n" + "\n".join(offenders)


#: The extra ``perturb[sweep]``: imported by the sweep room only (docs/architecture.md).
SWEEP_EXTRA = ("dask", "distributed", "xarray", "zarr", "cloudpickle")
#: Inside the sweep room, the modules that talk to Dask and the stores.
SWEEP_EXTRA_IMPORTERS = (
    "perturb.sweep.driver",
    "perturb.sweep.packing",
    "perturb.sweep.store",
    "perturb.sweep.memory",
)


def test_only_the_sweep_room_imports_dask_xarray_zarr():
    offenders = sweep_extra_importers(_sources())
    assert not offenders, "only the sweep room imports its extra:\n" + "\n".join(offenders)


#: Rooms that derive by the series alone, and the rooms above them they must never import.
ANALYTIC_ROOMS = ("perturb.steady", "perturb.method", "perturb.continuation", "perturb.algebra")
CHECKING_ROOMS = ("perturb.oracle", "perturb.validation", "perturb.response")


def upward_importers(paths, module=None) -> list[str]:
    """Files of an analytic room that import a checking room, and validation importing the
    response curve (rule 4)."""
    out = []
    for path, line, name in _imports_of(paths, module):
        own = module or _module_name(path)
        analytic = any(_is_under(own, room) for room in ANALYTIC_ROOMS)
        if (analytic and any(_is_under(name, room) for room in CHECKING_ROOMS)) or (
            _is_under(own, "perturb.validation") and _is_under(name, "perturb.response")
        ):
            out.append(f"{_relative(path)}:{line} imports {name}")
    return out


def mutual_importers(paths) -> list[str]:
    """Pairs of files that import each other (rule 5); a package and its own modules aside (an
    ``__init__`` re-exports them)."""
    modules = {_module_name(path): path for path in paths}
    imported = {
        module: {name for _, name in _imports(path)} & set(modules)
        for module, path in modules.items()
    }
    pairs = []
    for first, names in imported.items():
        for second in sorted(names):
            if first < second and first in imported.get(second, ()):
                if not (_is_under(second, first) or _is_under(first, second)):
                    pairs.append(f"{first} <-> {second}")
    return pairs


def test_no_arrow_runs_back_up():
    offenders = upward_importers(_perturb_sources())
    assert not offenders, "an analytic room imports a checking room:\n" + "\n".join(offenders)


def test_no_two_files_import_each_other():
    offenders = mutual_importers(_perturb_sources())
    assert not offenders, "files that import each other:\n" + "\n".join(offenders)


def test_every_rule_lists_every_offender_it_is_shown(tmp_path):
    """Each rule, given planted offenders, names each of them (a rule that finds nothing finds
    nothing wrong either)."""
    first, second = tmp_path / "first.py", tmp_path / "second.py"
    first.write_text("import problems\nimport xarray\n" + "x = 1\n" * MAX_LINES)
    second.write_text("def f():\n    from perturb.report import text\n    import dask.array\n")
    planted = [first, second]
    module = "perturb.oracle.sample"
    assert problems_importers(planted, module) == ["first.py:1 imports problems"]
    assert leaf_importers(planted, module) == [
        "second.py:2 imports perturb.report",
        "second.py:2 imports perturb.report.text",
    ]
    assert long_files(planted) == [f"first.py has {MAX_LINES + 2} lines"]
    assert sweep_extra_importers(planted, module) == [
        "first.py:2 imports xarray",
        "second.py:3 imports dask.array",
    ]
    assert upward_importers([second], "perturb.steady.sample") == []
    third = tmp_path / "third.py"
    third.write_text("def f():\n    from perturb.oracle import shoot\n")
    assert upward_importers([third], "perturb.steady.sample") == [
        "third.py:2 imports perturb.oracle",
        "third.py:2 imports perturb.oracle.shoot",
    ]
    assert upward_importers([third], "perturb.response.sample") == []
    # the exemptions: the CLI may use problems, the sweep driver its extra
    assert problems_importers(planted, "perturb.cli.main") == []
    assert sweep_extra_importers(planted, "perturb.sweep.driver") == []


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


# ---------------------------------------------------------------------------------------------
# The seam's rules: one door (a case) below the CLI, the frame asked rarely, no probing.


def _graph(paths) -> dict[str, set[str]]:
    """module -> the modules of the tree it imports (not its own packages, nor its children: a
    package's face hands its children's names on)."""
    modules = {_module_name(path): path for path in paths}
    graph = {}
    for module, path in modules.items():
        targets = {name for _, name in _imports(path)} & set(modules)
        graph[module] = {
            t for t in targets if not (_is_under(module, t) or _is_under(t, module)) and t != module
        }
    return graph


def circles(paths) -> list[str]:
    """Every circle of imports (a strongly connected set of two files or more), of any length."""
    graph = _graph(paths)
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(node):  # Tarjan's strongly connected components
        index[node] = low[node] = len(index)
        stack.append(node)
        on.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(" -> ".join(sorted(component)))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_no_circle_in_the_whole_house():
    """Neither perturb nor problems has files that reach each other through imports, however
    long the way (the rigid body's equations hand no name to numeric; the paper's report is read
    by its formatter without being imported by it)."""
    found = circles(list(_sources()))
    assert not found, "circles of imports:\n" + "\n".join(found)


def _calls(paths, attribute: str):
    """(path, line) of every call ``x.attribute(...)`` in ``paths``."""
    for path in paths:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr == attribute
            ):
                yield path, node.lineno


#: The one place below the CLI a model is made at other values by its own hook: the adapter that
#: gives a model that is not a problem its case (``Model.case``); everything else asks the case.
WITH_PARAMETERS_DOOR = ("perturb/validation/model.py",)


def test_below_the_door_every_point_comes_from_the_case():
    """No room of perturb re-creates a problem at other values (``with_parameters``): the
    response, the phase diagram and the sweep take their points from the case
    (``case.at(...)``, its ``model``)."""
    found = [
        f"{_relative(path)}:{line}"
        for path, line in _calls(_perturb_sources(), "with_parameters")
        if _relative(path) not in WITH_PARAMETERS_DOOR
    ]
    assert not found, "with_parameters called below the door:\n" + "\n".join(found)
    door = [line for _, line in _calls([ROOT / WITH_PARAMETERS_DOOR[0]], "with_parameters")]
    assert len(door) == 1  # the adapter itself


def test_no_attribute_probe_of_a_problem():
    """A problem is asked through its typed hooks, never with ``hasattr``/``getattr`` probes."""
    found = []
    for path in _sources():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Call)
                and getattr(node.func, "id", "") in ("hasattr", "getattr")
                and node.args
                and isinstance(node.args[0], ast.Name)
                and node.args[0].id in ("problem", "model")
            ):
                found.append(f"{_relative(path)}:{node.lineno}")
    assert not found, "a problem probed by attribute:\n" + "\n".join(found)


def test_only_the_plotting_modules_import_matplotlib():
    """matplotlib is imported by ``perturb/report/plots/`` alone; a check that it is installed
    finds it without importing it (``perturb._install.installed``)."""
    found = [
        f"{_relative(path)}:{line} imports {name}"
        for path, line, name in _imports_of(_sources())
        if _is_under(name, "matplotlib")
        and not _is_under(_module_name(path), "perturb.report.plots")
    ]
    assert not found, "matplotlib imported outside the plots:\n" + "\n".join(found)


#: The frame's answers (free or driven) asked outside the frame, counted where they are read.
FRAME_ANSWERS = ("frequency_given", "one_solution_for_all_points", "energy_may_be_conserved")
#: How many places ask them: what a free and a driven case solve, check and print is one table
#: keyed by frame type (perturb/validation/frames.py); the four left are the rooms below it that
#: need one answer each (the case's columns, projective scaling, the backbone, the energy). The
#: seam aimed at 6; this ceiling keeps the number from growing back.
MAX_FRAME_QUESTIONS = 4


def test_the_frame_is_asked_in_few_places():
    found = []
    for path in _sources():
        if _relative(path) == "perturb/frame.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr in FRAME_ANSWERS:
                found.append(f"{_relative(path)}:{node.lineno} {node.attr}")
            elif isinstance(node, ast.keyword) and node.arg == "driven":
                found.append(f"{_relative(path)}:{node.value.lineno} driven=")
    assert len(found) <= MAX_FRAME_QUESTIONS, "\n".join(found)


#: Public members of ``problems.Problem`` (the subclass contract plus what clients call). 44
#: before the optional physics became declared capabilities and the synonyms went, 30 before
#: what only perturb called left the class (the family and the derivation flag are private
#: fields read from the case; the map, the parameters in force and whether a sweep evaluates the
#: solution directly are the case's; the own parameter's value is ``parameter_value_of(model)``;
#: the symbolic derivation is the sweep's capability), 23 before the hooks with a generic answer
#: left it (``integrals_of_motion`` and ``label``: capabilities asked through
#: ``integrals_of_motion(model)`` and ``label_of(model)``; ``parameter_map``: a declaration with
#: no value on the base, as ``name``), 20 before the last five went with a deprecation path
#: (``original_rhs``, ``original_equations``, ``with_epsilon``: functions of
#: ``perturb.validation`` that read a class's own hook; ``steady_state``:
#: ``perturb.response.steady_state_of``; ``with_family``: ``create(family=...)``). What stays:
#: the contract's hooks (``build_system``, ``method_options``, ``epsilon``, ``symbol_values``,
#: ``state``, ``period``, ``check_values`` — users' files call ``super().check_values``) and the
#: calls the docs make (``create``, ``solve``, ``families``, ``state_names``, ``system``,
#: ``with_parameters``, ``case``, ``values``): the seam's target.
MAX_PROBLEM_MEMBERS = 15


def test_the_problem_surface_does_not_grow():
    from problems.base import Problem

    public = [name for name in dir(Problem) if not name.startswith("_")]
    assert len(public) <= MAX_PROBLEM_MEMBERS, sorted(public)


def test_the_seam_rules_see_what_they_are_shown(tmp_path):
    """Each new rule, given planted offenders, names them."""
    a, b, c = (tmp_path / f"{n}.py" for n in "abc")
    a.write_text("import perturb.b_mod\n")
    b.write_text("def f():\n    import perturb.c_mod\n")
    c.write_text("from perturb import a_mod\n")
    graph_paths = {a: "perturb.a_mod", b: "perturb.b_mod", c: "perturb.c_mod"}

    def module_name(path, _real=_module_name):
        return graph_paths.get(path) or _real(path)

    import tests.test_architecture as rules

    original = rules._module_name
    rules._module_name = module_name
    try:
        assert circles([a, b, c]) == ["perturb.a_mod -> perturb.b_mod -> perturb.c_mod"]
    finally:
        rules._module_name = original
    d = tmp_path / "d.py"
    d.write_text("problem.with_parameters(a=1)\nhasattr(problem, 'x')\n")
    assert [line for _, line in _calls([d], "with_parameters")] == [1]


def private_calls(paths) -> list[str]:
    """Calls of another object's private member (``other._step()``): a template is driven
    through its public steps, never its privates, from outside."""
    found = []
    for path in paths:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                continue
            name, owner = node.func.attr, node.func.value
            if not name.startswith("_") or name.startswith("__"):
                continue
            if isinstance(owner, ast.Name) and owner.id in ("self", "cls"):
                continue
            if isinstance(owner, ast.Call) and getattr(owner.func, "id", "") == "super":
                continue
            found.append(f"{_relative(path)}:{node.lineno} calls {ast.unparse(node.func)}")
    return found


def test_no_private_member_is_called_from_outside(tmp_path):
    found = private_calls(_perturb_sources())
    assert not found, "private members called from outside:\n" + "\n".join(found)
    planted = tmp_path / "driver.py"
    planted.write_text("runner._generating()\nself._own()\nsuper()._hook()\nrunner.step(1)\n")
    assert private_calls([planted]) == ["driver.py:1 calls runner._generating"]


# ---------------------------------------------------------------- one orbit record, one corrector

#: The one true periodic orbit (state, period, multipliers, how it was found, status): every
#: route to a true orbit returns it (docs/architecture.md, "One orbit record, one corrector").
TRUE_ORBIT_TYPE = "perturb/oracle/orbit.py:PeriodicOrbit"
#: Records whose multipliers are the series' (Magnus along the order-N orbit, the amplitude
#: equations' eigenvalues): analytic numbers, not a true orbit's.
SERIES_MULTIPLIERS = {
    "perturb/method/driven.py:SlowFlow",
    "perturb/steady/floquet.py:Stability",
    "perturb/steady/point.py:ResponsePoint",
    "perturb/steady/continued.py:SpecialResponse",
    "perturb/steady/continued.py:ResponseCurve",
    "perturb/response/model.py:TrueResponse",  # multipliers_analytic; its true orbit is held
}
#: Records that copy a true orbit's multipliers under a contract of their own, beside the orbit:
#: the validation report's row (users and tests build it field by field) and a catalogue's
#: steady state (stored on disk and read back without its orbit). A ceiling: it only falls.
ORBIT_MULTIPLIER_COPIES = {
    "perturb/validation/report.py:OrbitCheck",
    "perturb/dynamics/attractors.py:SteadyOrbit",
}


def _holds_multipliers(name: str) -> bool:
    """A field that holds Floquet multipliers (not one critical ``multiplier`` or an error)."""
    return name in ("multipliers", "floquet", "floquet_multipliers") or name.startswith(
        ("multipliers_", "floquet_")
    )


def multiplier_records(paths) -> dict[str, list[str]]:
    """``path:Class`` -> the names of its class-level annotated fields that hold multipliers."""
    found = {}
    for path in paths:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if not isinstance(node, ast.ClassDef):
                continue
            names = [
                item.target.id
                for item in node.body
                if isinstance(item, ast.AnnAssign)
                and isinstance(item.target, ast.Name)
                and _holds_multipliers(item.target.id)
            ]
            if names:
                found[f"{_relative(path)}:{node.name}"] = names
    return found


def test_one_true_orbit_record():
    found = multiplier_records(_sources())
    assert found.get(TRUE_ORBIT_TYPE) == ["multipliers"], found  # the scan sees the one type
    allowed = {TRUE_ORBIT_TYPE} | SERIES_MULTIPLIERS | ORBIT_MULTIPLIER_COPIES
    extra = sorted(set(found) - allowed)
    assert not extra, (
        "a new record holds an orbit's multipliers: hold a perturb.oracle.PeriodicOrbit "
        f"instead: {extra}"
    )


def test_multipliers_are_named_one_way():
    """``multipliers`` (or ``multipliers_<whose>``); older names live on as read-only properties."""
    found = multiplier_records(_sources())
    other = sorted(
        f"{where}.{name}"
        for where, names in found.items()
        for name in names
        if not (name == "multipliers" or name.startswith("multipliers_"))
    )
    assert not other, other


#: What a Newton loop solves with: a linear solve or a step function.
_SOLVES = {"solve", "lstsq", "qr_solve", "lu_solve", "_solve", "newton_step", "step"}
#: The Newton loops on systems of equations, each with why it is its own: the shooting's damped
#: loop down to the precision floor (perturb/oracle/newton.py), the continuation's one loop whose
#: step is a function (its bordered, fixed-λ and least-norm correctors, and the true curve's
#: minimally augmented systems), the disk's second route in 40-digit mpmath arithmetic (its
#: independence is the point), and the certified roots' polish in mpmath (a root, not an orbit).
NEWTON_LOOPS = {
    "perturb/oracle/newton.py:damped_newton",
    "perturb/continuation/newton.py:newton",
    "problems/rigid_body/true_orbit_mp.py:mp_true_orbit",
    "perturb/algebra/msolve.py:_refined",
}


def _inside(node):
    """The nodes under ``node``, not entering nested functions, lambdas or classes."""
    stack = list(ast.iter_child_nodes(node))
    while stack:
        item = stack.pop()
        if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda | ast.ClassDef):
            continue
        yield item
        stack.extend(ast.iter_child_nodes(item))


def _name(node) -> str:
    if isinstance(node, ast.Attribute):
        return node.attr
    return node.id if isinstance(node, ast.Name) else ""


def newton_loops(paths) -> list[str]:
    """``path:function`` of every loop that evaluates a Jacobian (a name holding ``jac``, or a
    ``linearised`` call) and solves with it (:data:`_SOLVES`) in one iteration."""
    found = []
    for path in paths:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for function in ast.walk(tree):
            if not isinstance(function, ast.FunctionDef | ast.AsyncFunctionDef):
                continue
            for loop in _inside(function):
                if not isinstance(loop, ast.For | ast.While):
                    continue
                body = list(_inside(loop))
                calls = {_name(n.func) for n in body if isinstance(n, ast.Call)}
                names = {_name(n) for n in body if isinstance(n, ast.Name | ast.Attribute)}
                derivative = any("jac" in n.lower() for n in names) or "linearised" in calls
                if derivative and calls & _SOLVES:
                    found.append(f"{_relative(path)}:{function.name}")
    return found


def test_one_newton_loop_per_arithmetic():
    found = newton_loops(_sources())
    assert len(found) == len(set(found)), found  # one loop a function
    assert set(found) == NEWTON_LOOPS, sorted(set(found) ^ NEWTON_LOOPS)


def test_the_orbit_rules_see_what_they_are_shown(tmp_path):
    planted = tmp_path / "copy.py"
    planted.write_text(
        "class Found:\n    floquet: tuple\n    multiplier: complex\n\n"
        "def polish(f, x):\n    for _ in range(8):\n        jac = f.jacobian(x)\n"
        "        x = x - np.linalg.solve(jac, f(x))\n    while True:\n        break\n"
    )
    assert multiplier_records([planted]) == {"copy.py:Found": ["floquet"]}
    assert newton_loops([planted]) == ["copy.py:polish"]
