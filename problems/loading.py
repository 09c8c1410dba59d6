"""Problems from anywhere: a registered name, a Python file or an importable module.

:func:`load_problem` is what the command line calls for its ``PROBLEM`` argument:

* ``NAME`` — a built-in, registered or installed problem (see :mod:`problems._registry`);
* ``path/to/file.py:ClassName`` — a class defined in a Python file (``:ClassName`` may be left out
  when the file defines exactly one concrete problem);
* ``package.module:ClassName`` — a class in an importable module (installed, or on ``PYTHONPATH``).

The class needs no ``@register``: subclassing :class:`problems.base.Problem` and filling in its
contract is enough.  A file is imported under a fresh module name (``_perturb_file_<n>_<stem>``);
while it is imported its folder is put first on ``sys.path``, so it may import a sibling module
(``import helpers``) at its top level (a sweep's workers get such a module with the class); its
own relative imports (``from . import x``) do not work.
Every failure is one :class:`perturb.errors.ProblemLoadError` line naming the file and the fix.
"""

from __future__ import annotations

import contextlib
import importlib
import importlib.util
import itertools
import os
import re
import signal
import sys
import traceback
from pathlib import Path
from types import ModuleType

from perturb._defaults import PROBLEM_FILE_MAX_BYTES
from perturb.errors import ProblemLoadError
from problems._checks import check_usable
from problems._registry import check_problem_class, did_you_mean, get_problem
from problems.base import Problem

__all__ = ["LOADED_FILES", "load_problem", "user_frame"]

#: Suffix that marks the part before ``:`` as a file rather than a module.
_PY_SUFFIX = ".py"

_counter = itertools.count(1)

#: The files of the problems loaded by path or module in this process (resolved paths): an
#: exception raised in one of them at run time is the user's code failing (:func:`user_frame`).
LOADED_FILES: set[str] = set()


def load_problem(spec: str) -> type[Problem]:
    """The problem class named by ``spec``: ``NAME``, ``file.py:Class`` or ``module:Class``.

    Parameters
    ----------
    spec : str
        A registered name (``duffing``), a file and a class (``path/to/rayleigh.py:Rayleigh``, the
        class optional when the file defines exactly one problem) or a module and a class
        (``mypackage.oscillators:Rayleigh``).

    Returns
    -------
    type[Problem]
        A complete, concrete subclass of :class:`problems.base.Problem`.

    Raises
    ------
    UnknownNameError
        ``spec`` is a name no problem has.
    ProblemLoadError
        The file or module cannot be imported, does not define the class, or the class is not a
        complete :class:`~problems.base.Problem` (one line: the file, what is wrong, the fix).

    Examples
    --------
    >>> load_problem("duffing").name
    'duffing'
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ProblemLoadError(
            f"`problem` = {spec!r} is invalid: give a name (see `perturb list`), "
            "path/to/file.py:ClassName or package.module:ClassName"
        )
    if spec.endswith(_PY_SUFFIX):
        return _from_file(spec, spec, None)
    target, sep, class_name = spec.rpartition(":")
    if not sep:
        return get_problem(spec)
    if not class_name.isidentifier() or not target:
        raise ProblemLoadError(
            f"`problem` = {spec!r} is invalid: write path/to/file.py:ClassName or "
            "package.module:ClassName, ClassName a Python identifier"
        )
    if target.endswith(_PY_SUFFIX) or "/" in target or os.sep in target:
        return _from_file(spec, target, class_name)
    return _from_module(spec, target, class_name)


# ---------------------------------------------------------------------------------- files
def _from_file(spec: str, target: str, class_name: str | None) -> type[Problem]:
    path = Path(target).expanduser()
    if not path.is_file():
        what = (
            "is a folder"
            if path.is_dir()
            else "is not a regular file (a FIFO, a device or a socket)"
            if path.exists()
            else "does not exist"
        )
        raise ProblemLoadError(
            f"`problem` = {spec!r}: the file {str(path)!r} {what}: give the path of a Python file "
            "(absolute, or relative to the current folder), then :ClassName"
        )
    path = path.resolve()
    size = path.stat().st_size
    if size > PROBLEM_FILE_MAX_BYTES:
        raise ProblemLoadError(
            f"{path}: the file holds {size / 2**20:.1f} MB, more than a problem file's "
            f"{PROBLEM_FILE_MAX_BYTES / 2**20:.0f} MB: give the Python file that defines the class"
        )
    stem = re.sub(r"\W", "_", path.stem)
    module_name = f"_perturb_file_{next(_counter)}_{stem}"
    module_spec = importlib.util.spec_from_file_location(module_name, path)
    if module_spec is None or module_spec.loader is None:
        raise ProblemLoadError(
            f"{path}: Python cannot load this file: give a Python source file ending in .py"
        )
    module = importlib.util.module_from_spec(module_spec)
    sys.modules[module_name] = module  # attrs and pickling look classes up by module name
    folder = str(path.parent)
    sys.path.insert(0, folder)
    try:
        with _interrupts_told_apart() as pressed:
            module_spec.loader.exec_module(module)
    except KeyboardInterrupt as exc:
        del sys.modules[module_name]
        if pressed():  # Ctrl-C while the file was imported: the run is interrupted
            raise
        raise _import_failure(exc, str(path)) from None
    except (Exception, SystemExit) as exc:
        del sys.modules[module_name]
        raise _import_failure(exc, str(path)) from None
    finally:
        if folder in sys.path:
            sys.path.remove(folder)
    cls = _pick_class(module, str(path), class_name)
    LOADED_FILES.add(str(path))
    check_usable(cls, f"{path}:{cls.__name__}")
    return cls


# ---------------------------------------------------------------------------------- modules
def _from_module(spec: str, target: str, class_name: str) -> type[Problem]:
    try:
        with _interrupts_told_apart() as pressed:
            module = importlib.import_module(target)
    except KeyboardInterrupt as exc:
        if pressed():
            raise
        raise _import_failure(exc, target) from None
    except ModuleNotFoundError as exc:
        if exc.name is not None and (target == exc.name or target.startswith(f"{exc.name}.")):
            raise ProblemLoadError(
                f"`problem` = {spec!r}: no module named {exc.name!r}: install it, add its folder "
                "to PYTHONPATH, or name the file instead (path/to/file.py:ClassName)"
            ) from None
        raise _import_failure(exc, target) from None
    except (Exception, SystemExit) as exc:
        raise _import_failure(exc, target) from None
    cls = _pick_class(module, target, class_name)
    origin = getattr(module, "__file__", None)
    if origin and not origin.startswith(str(Path(__file__).resolve().parent)):
        LOADED_FILES.add(str(Path(origin).resolve()))  # a user's module, not a built-in one
    check_usable(cls, spec)
    return cls


def user_frame(exc: BaseException) -> str | None:
    """``file:line`` of the deepest frame of ``exc``'s traceback in a problem file loaded by
    path or module (:data:`LOADED_FILES`), or None when the user's code is not on the path."""
    frames = traceback.extract_tb(exc.__traceback__) if exc.__traceback__ else []
    mine = [f for f in frames if f.filename in LOADED_FILES]
    return f"{mine[-1].filename}:{mine[-1].lineno}" if mine else None


# ---------------------------------------------------------------------------------- helpers
def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


@contextlib.contextmanager
def _interrupts_told_apart():
    """Tell a Ctrl-C pressed during an import (the run is interrupted) from a
    ``KeyboardInterrupt`` the imported code raised itself (a broken file): yields a function
    saying whether SIGINT arrived."""
    arrived = []

    def handler(signum, frame):
        arrived.append(signum)
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGINT, handler)
    except ValueError:  # not the main thread: signals cannot be watched, every one is a Ctrl-C
        yield lambda: True
        return
    try:
        yield lambda: bool(arrived)
    finally:
        signal.signal(signal.SIGINT, previous)


def _import_failure(exc: BaseException, where: str) -> ProblemLoadError:
    """One line for an exception raised while importing ``where`` (a file path or module name)."""
    if isinstance(exc, SystemExit):
        code = exc.code
        what = f"sys.exit({code!r})" if not isinstance(code, str) else f"exit({code!r})"
        return ProblemLoadError(
            f"{where}: importing it called {what}: a problem file is imported, not run; move "
            'the call under `if __name__ == "__main__":` or remove it'
        )
    if isinstance(exc, SyntaxError):
        location = f"{exc.filename}:{exc.lineno}" if exc.filename else where
        return ProblemLoadError(f"{location}: syntax error: {exc.msg}: fix the file")
    if isinstance(exc, ProblemLoadError):  # e.g. @register of a name already taken
        return ProblemLoadError(f"{where}: {exc}")
    frames = traceback.extract_tb(exc.__traceback__)
    # the user's file when named by path; for a module, the deepest frame outside the import system
    mine = [f for f in frames if f.filename == where] or [
        f for f in frames[1:] if not f.filename.startswith("<") and "importlib" not in f.filename
    ]
    location = f"{mine[-1].filename}:{mine[-1].lineno}" if mine else where
    if isinstance(exc, ModuleNotFoundError) and exc.name:
        return ProblemLoadError(
            f"{location}: importing it failed: no module named {exc.name!r}: install "
            f"{exc.name.partition('.')[0]} or fix the import"
        )
    detail = _one_line(exc)
    return ProblemLoadError(
        f"{location}: importing it raised {type(exc).__name__}{': ' + detail if detail else ''}: "
        "fix the file"
    )


def _pick_class(module: ModuleType, where: str, class_name: str | None) -> type[Problem]:
    own = sorted(
        name
        for name, obj in vars(module).items()
        if isinstance(obj, type)
        and issubclass(obj, Problem)
        and obj is not Problem
        and obj.__module__ == module.__name__
    )
    if class_name is None:
        concrete = [n for n in own if not getattr(vars(module)[n], "__abstractmethods__", ())]
        if len(concrete) != 1:
            raise ProblemLoadError(
                f"{where} defines {len(concrete)} concrete Problem subclasses {concrete}: "
                "name one as FILE.py:ClassName"
            )
        class_name = concrete[0]
    cls = getattr(module, class_name, None)
    if cls is None:
        if not own:
            raise ProblemLoadError(
                f"{where} defines no {class_name!r} and no subclass of problems.base.Problem: "
                "define one (class MyProblem(Problem): ...) and name it after the colon"
            )
        raise ProblemLoadError(
            f"{where} defines no class {class_name!r}{did_you_mean(class_name, own)}: "
            f"choose from the Problem subclasses it defines, {own}"
        )
    label = f"{where}:{class_name}"
    if not isinstance(cls, type):
        raise ProblemLoadError(
            f"`{label}` is a {type(cls).__name__}, not a class: name one of the Problem "
            f"subclasses {where} defines, {own}"
        )
    check_problem_class(cls, label)
    return cls
