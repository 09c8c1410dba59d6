"""The problem registry: every problem name, where its class comes from, and the decorator that adds one.

Three sources feed one table, in this order of precedence:

1. **built-in problems** — the modules of the ``problems`` package whose classes carry
   ``@register``.  They are found without importing them: :func:`builtin_index` walks the package's
   folders (not :func:`pkgutil.walk_packages`, which imports every sub-package) and reads each
   module's source with :mod:`ast`, taking the
   ``name = "..."`` of every class decorated with ``@register``.  A module is imported only when one
   of its problems is asked for, so ``perturb list`` does not pay for the rigid-body machinery of
   a problem it does not print and a new built-in problem needs nothing but its decorator.
2. **classes registered at run time** — any :func:`register` call (a user's module, a test).
3. **installed problems** — other distributions declare them in the entry-point group
   ``perturb.problems`` (``name = "package.module:Class"``); they are loaded on first use.

A name is looked up in that order, so an installed problem cannot shadow a built-in one.
"""

from __future__ import annotations

import ast
import difflib
import functools
import hashlib
import importlib
import importlib.metadata
import re
import sys
from collections.abc import Iterator, MutableMapping
from pathlib import Path

from perturb.errors import InvalidSystemError, ProblemLoadError, UnknownNameError
from problems._declared import declared_map
from problems.base import ParameterSpec, Problem

__all__ = [
    "ALL_PROBLEMS",
    "ENTRY_POINT_GROUP",
    "builtin_index",
    "check_problem_class",
    "did_you_mean",
    "entry_point_index",
    "get_problem",
    "problem_names",
    "register",
]

#: Entry-point group through which other distributions contribute problems (``name = "mod:Class"``).
ENTRY_POINT_GROUP = "perturb.problems"

#: The decorator's name as the static scan recognises it (``@register`` or ``@problems.register``).
_DECORATOR = "register"

#: Cheap text test run before parsing a module: a line that applies the decorator.
_DECORATOR_LINE = re.compile(rf"^[ \t]*@(?:\w+\.)*{_DECORATOR}\b", re.MULTILINE)

#: Class attributes every concrete problem must define (see the contract in :mod:`problems.base`).
_REQUIRED_ATTRIBUTES = ("name", "summary", "parameter_specs")

#: Closeness (difflib ratio) above which an unknown name gets a "did you mean" suggestion.
_SUGGESTION_CUTOFF = 0.6


# ---------------------------------------------------------------------------------- the contract
def check_problem_class(cls: type, label: str | None = None) -> None:
    """Raise :class:`ProblemLoadError` unless ``cls`` is a complete, concrete :class:`Problem`.

    Parameters
    ----------
    cls : type
        The candidate class.
    label : str, optional
        How the message names the class (default: ``module:Class``).

    Raises
    ------
    ProblemLoadError
        ``cls`` is not a subclass of :class:`problems.base.Problem`, or it leaves part of the
        subclass contract undefined (the message lists what is missing).
    """
    label = label or f"{cls.__module__}:{cls.__qualname__}"
    if not (isinstance(cls, type) and issubclass(cls, Problem)):
        raise ProblemLoadError(
            f"`{label}` is not a subclass of problems.base.Problem: derive it from Problem "
            "(from problems.base import Problem)"
        )
    missing = [a for a in _REQUIRED_ATTRIBUTES if not hasattr(cls, a)]
    missing += sorted(getattr(cls, "__abstractmethods__", ()))
    if not missing:
        if not isinstance(cls.name, str) or not cls.name.strip():
            raise ProblemLoadError(
                f"`{label}.name` = {cls.name!r} is invalid: give a non-empty str"
            )
        if not isinstance(cls.summary, str):
            raise ProblemLoadError(f"`{label}.summary` = {cls.summary!r} is invalid: give a str")
        specs = cls.parameter_specs
        if not isinstance(specs, tuple | list) or not all(
            isinstance(s, ParameterSpec) for s in specs
        ):
            raise ProblemLoadError(
                f"`{label}.parameter_specs` = {specs!r} is invalid: give a tuple of ParameterSpec"
            )
        try:
            mapping = declared_map(cls)
        except InvalidSystemError as exc:
            raise ProblemLoadError(str(exc)) from None
        declared = "epsilon" in mapping
        if cls.epsilon is Problem.epsilon and not declared and "eps" not in {s.name for s in specs}:
            missing.append("epsilon (or a parameter named eps, or 'epsilon' in parameter_map)")
    if missing:
        raise ProblemLoadError(
            f"`{label}` is incomplete: it does not define {', '.join(missing)}: add them "
            "(the subclass contract is in the docstring of problems.base)"
        )


def _origin(cls: type) -> tuple[str | None, str]:
    """Where a class was defined: its file and qualified name (equal across reloads of one file)."""
    module = sys.modules.get(cls.__module__)
    return getattr(module, "__file__", None) or cls.__module__, cls.__qualname__


# ---------------------------------------------------------------------------------- built-ins
def _registered_names(source: str) -> list[tuple[str, str | None]]:
    """``(class name, problem name or None)`` for each class of ``source`` decorated ``@register``.

    The problem name is read from a literal ``name = "..."`` in the class body; ``None`` when the
    name is computed or inherited (the module must then be imported to learn it).
    """
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.ClassDef):
            continue
        decorators = [d.func if isinstance(d, ast.Call) else d for d in node.decorator_list]
        if not any(
            (isinstance(d, ast.Name) and d.id == _DECORATOR)
            or (isinstance(d, ast.Attribute) and d.attr == _DECORATOR)
            for d in decorators
        ):
            continue
        name = None
        for stmt in node.body:
            targets = stmt.targets if isinstance(stmt, ast.Assign) else [getattr(stmt, "target", 0)]
            value = getattr(stmt, "value", None)
            if (
                any(isinstance(t, ast.Name) and t.id == "name" for t in targets)
                and isinstance(value, ast.Constant)
                and isinstance(value.value, str)
            ):
                name = value.value
        found.append((node.name, name))
    return found


def _module_files(folder: Path, prefix: str) -> Iterator[tuple[str, Path]]:
    """``(module name, source file)`` of every module of the package in ``folder``, recursively.

    The walk of :func:`pkgutil.walk_packages`, on the file system only: that one imports each
    sub-package to find its path (``problems.rigid_body.paper`` and all it imports).  Sub-packages
    are the folders with an ``__init__.py``, as for the import system.
    """
    for path in sorted(folder.iterdir()):
        if path.is_dir() and (path / "__init__.py").is_file() and path.name.isidentifier():
            name = f"{prefix}{path.name}"
            yield name, path / "__init__.py"
            yield from _module_files(path, f"{name}.")
        elif path.suffix == ".py" and path.stem != "__init__" and path.stem.isidentifier():
            yield f"{prefix}{path.stem}", path


@functools.cache
def builtin_index() -> dict[str, str]:
    """The built-in problems, ``name -> "module:Class"``, found by a static scan of the package.

    Every module of the ``problems`` package (sub-packages included) whose source mentions
    ``@register`` is parsed with :mod:`ast`; nothing is imported unless a decorated class's
    ``name`` is not a string literal, in which case that module is imported to read it.  What
    the parse finds is kept in the disk cache (kind ``problem-index``) under the SHA-256 of every
    such module's name and source and of this module's (the parser): an edited, added or removed
    module parses them again.
    """
    import problems
    from perturb.cache import cached

    sources = {}
    for module, path in (
        found for folder in problems.__path__ for found in _module_files(Path(folder), "problems.")
    ):
        source = path.read_text(encoding="utf-8")
        if _DECORATOR_LINE.search(source):
            sources[module] = source
    found = cached(
        "problem-index",
        lambda: tuple(
            (m, hashlib.sha256(s.encode()).hexdigest())
            for m, s in {__name__: Path(__file__).read_text(encoding="utf-8"), **sources}.items()
        ),
        lambda: {module: _registered_names(source) for module, source in sources.items()},
    )
    index: dict[str, str] = {}
    for module in sources:
        for class_name, name in found[module]:
            if name is None:
                name = getattr(importlib.import_module(module), class_name).name
            index[name] = f"{module}:{class_name}"
    return index


# ---------------------------------------------------------------------------------- entry points
def entry_point_index() -> dict[str, importlib.metadata.EntryPoint]:
    """Problems installed by other distributions: entry points of :data:`ENTRY_POINT_GROUP`."""
    return {ep.name: ep for ep in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP)}


def _load_entry_point(ep: importlib.metadata.EntryPoint) -> type[Problem]:
    dist = getattr(getattr(ep, "dist", None), "name", None)
    where = f"entry point {ep.name!r} = {ep.value!r}" + (f" of {dist}" if dist else "")
    fix = f"fix or uninstall {dist}" if dist else "fix or uninstall the package that declares it"
    try:
        cls = ep.load()
    except Exception as exc:  # a broken third-party package: one line, never a traceback
        detail = " ".join(str(exc).split())
        raise ProblemLoadError(
            f"{where} cannot be loaded ({type(exc).__name__}: {detail}): {fix}"
        ) from None
    try:
        check_problem_class(cls, ep.value)
    except ProblemLoadError as exc:
        raise ProblemLoadError(f"{where}: {exc}; {fix}") from None
    return cls


# ---------------------------------------------------------------------------------- the table
class ProblemRegistry(MutableMapping):
    """``name -> Problem class`` over built-in, registered and installed problems, loaded lazily.

    Iterating, ``len`` and ``in`` only read names (cheap); reading a value imports its module.
    Assigning is what :func:`register` does.
    """

    def __init__(self) -> None:
        self._loaded: dict[str, type[Problem]] = {}

    def __getitem__(self, name: str) -> type[Problem]:
        if name in self._loaded:
            return self._loaded[name]
        builtin = builtin_index().get(name)
        if builtin is not None:
            module, _, attr = builtin.partition(":")
            cls = getattr(importlib.import_module(module), attr)  # importing registers it
            return self._loaded.setdefault(name, cls)
        ep = entry_point_index().get(name)
        if ep is None:
            raise KeyError(name)
        return self._loaded.setdefault(name, _load_entry_point(ep))

    def __setitem__(self, name: str, cls: type[Problem]) -> None:
        self._loaded[name] = cls

    def __delitem__(self, name: str) -> None:
        del self._loaded[name]

    def __contains__(self, name: object) -> bool:
        return name in self._names()

    def __iter__(self) -> Iterator[str]:
        return iter(sorted(self._names()))

    def __len__(self) -> int:
        return len(self._names())

    def _names(self) -> set[str]:
        return set(builtin_index()) | set(self._loaded) | set(entry_point_index())

    def loaded(self, name: str) -> type[Problem] | None:
        """The class already loaded or registered under ``name``, if any (imports nothing)."""
        return self._loaded.get(name)

    def __repr__(self) -> str:
        return f"ProblemRegistry({sorted(self._names())})"


#: Every known problem, ``name -> class`` (built-in, registered, installed); values load lazily.
ALL_PROBLEMS = ProblemRegistry()


def register(cls: type[Problem]) -> type[Problem]:
    """Class decorator adding a problem to :data:`ALL_PROBLEMS` under ``cls.name``.

    In a module of the ``problems`` package the decorator is all it takes for ``perturb list`` and
    ``perturb solve NAME`` to know the problem.  Elsewhere it registers the class for the running
    process; to reach it from the command line, name it as ``path/to/file.py:Class`` or declare
    an entry point in the group ``perturb.problems``.

    Raises
    ------
    ProblemLoadError
        The class is incomplete (see :func:`check_problem_class`) or its ``name`` is already taken
        by a class defined elsewhere.

    Parameters
    ----------
    cls : type[Problem]
        A complete :class:`Problem` subclass (``name``, ``summary``, ``parameter_specs``,
        ``build_system``).

    Returns
    -------
    type[Problem]
        ``cls`` itself, so that the decorator leaves the class unchanged.

    Examples
    --------
    Registering a class again is harmless; another class under a taken name is refused:

    >>> from problems import get_problem, register
    >>> Duffing = get_problem("duffing")
    >>> register(Duffing) is Duffing
    True
    >>> class Copy(Duffing):
    ...     pass
    >>> register(Copy)
    Traceback (most recent call last):
    ...
    perturb.errors.ProblemLoadError: `Copy.name` = 'duffing' is already registered by problems.duffing:Duffing: give the class another name
    """
    check_problem_class(cls)
    name = cls.name
    builtin = builtin_index().get(name)
    taken = ALL_PROBLEMS.loaded(name)
    if builtin is not None and builtin.partition(":")[0] != cls.__module__:
        owner = builtin
    elif taken is not None and taken is not cls and _origin(taken) != _origin(cls):
        owner = f"{taken.__module__}:{taken.__qualname__}"
    else:
        ALL_PROBLEMS[name] = cls
        return cls
    raise ProblemLoadError(
        f"`{cls.__qualname__}.name` = {name!r} is already registered by {owner}: "
        "give the class another name"
    )


def problem_names() -> list[str]:
    """Every known problem name, sorted (built-in, registered and installed).

    Returns
    -------
    list of str

    Examples
    --------
    >>> from problems import problem_names
    >>> {"duffing", "van-der-pol", "disk"} <= set(problem_names())
    True
    """
    return list(ALL_PROBLEMS)


def did_you_mean(name: str, names: list[str]) -> str:
    """`` (did you mean 'x'?)`` for the known name closest to ``name``, or ``""`` if none is close."""
    close = difflib.get_close_matches(name, names, n=1, cutoff=_SUGGESTION_CUTOFF)
    return f" (did you mean {close[0]!r}?)" if close else ""


def get_problem(name: str) -> type[Problem]:
    """The problem class registered as ``name`` (see :func:`problems.load_problem` for files).

    Raises
    ------
    UnknownNameError
        No problem has that name; the message lists the known names and the closest one.
    ProblemLoadError
        An installed problem of that name cannot be loaded.

    Parameters
    ----------
    name : str
        A name of :func:`problem_names` (``perturb list``).

    Returns
    -------
    type[Problem]
        The class; ``create(**values)`` makes a problem with its parameter values.

    Examples
    --------
    >>> from problems import get_problem
    >>> Duffing = get_problem("duffing")
    >>> Duffing.__name__, [spec.name for spec in Duffing.parameter_specs]
    ('Duffing', ['eps', 'amplitude'])
    """
    try:
        return ALL_PROBLEMS[name]
    except KeyError:
        names = problem_names()
        raise UnknownNameError(
            f"`problem` = {name!r} is unknown{did_you_mean(name, names)}: choose from {names}, "
            "or name a class as path/to/file.py:ClassName or package.module:ClassName"
        ) from None
