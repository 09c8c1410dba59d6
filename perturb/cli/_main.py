"""The entry point: run a command, map what went wrong to an exit code, draw progress."""

from __future__ import annotations

import argparse
import contextlib
import gc
import importlib
import io
import os
import sys
import time
import warnings
from collections.abc import Iterator, Sequence

from perturb.cli._errors import (
    _INPUT_ERRORS,
    EXIT_FAILED,
    EXIT_USAGE,
    PRESSED,
    _RunFailed,
    _UsageError,
    pressed,
)
from perturb.cli._parser import _build_parser
from perturb.errors import PerturbError
from perturb.progress import listening


def _format_warning(message, category, filename, lineno, line=None) -> str:
    """Warnings on one line, as the CLI's errors are: ``perturb: warning: ...``."""
    return f"perturb: warning: {message}\n"


class _ProgressBar:
    """A one-line bar on stderr, redrawn in place: ``perturb: work-precision [#####.....] 12/24``,
    with the rate and the time left once there is a rate to tell
    (``perturb: sweep disk      85.3/s ETA  1m43s [###.....] 1200/10000``)."""

    WIDTH = 30

    def __init__(self, stream, clock=time.monotonic):
        self.stream = stream
        self.drawn = False
        self.clock = clock
        self.start: tuple[str, int, float] | None = None

    def _rate(self, label: str, done: int, total: int | None) -> str:
        now = self.clock()
        if self.start is None or self.start[0] != label or done < self.start[1]:
            self.start = (label, done, now)  # counted from here: work done before is not timed
            return ""
        count, seconds = done - self.start[1], now - self.start[2]
        if count <= 0 or seconds <= 0:
            return ""
        rate = count / seconds
        eta = _duration((total - done) / rate) if total and done < total else ""
        return f"{rate:9.3g}/s ETA {eta:>6s} "  # fixed width: the line never shrinks

    def __call__(self, label: str, done: int, total: int | None) -> None:
        rate = self._rate(label, done, total)
        if total:
            filled = self.WIDTH * done // total
            bar = f"[{'#' * filled}{'.' * (self.WIDTH - filled)}] {done}/{total}"
        else:
            bar = f"{done} done"
        self.stream.write(f"\rperturb: {label} {rate}{bar}")
        self.stream.flush()
        self.drawn = True
        if total and done >= total:
            self.close()

    def close(self) -> None:
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()
            self.drawn = False
        self.start = None


def _duration(seconds: float) -> str:
    """``42s``, ``3m07s``, ``2h05m``."""
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"


@contextlib.contextmanager
def _progress(args) -> Iterator[None]:
    """Show what a long run is doing on stderr unless ``--quiet`` was given: a bar on a terminal,
    periodic lines on a file or a pipe (:mod:`perturb.cli._progress`)."""
    from perturb.cli._progress import reporter_for

    reporter = None if getattr(args, "quiet", False) else reporter_for(sys.stderr, _ProgressBar)
    with listening(reporter):
        try:
            yield
        finally:
            if reporter is not None:
                reporter.close()


#: Commands whose ``--output`` is their own (a folder of report files, a sweep's store): not a
#: redirection of what they print.
_FOLDER_OUTPUT = ("reproduce", "report", "sweep", "phase-diagram", "basins")


@contextlib.contextmanager
def _to_file(args) -> Iterator[None]:
    """With ``--output PATH`` (a file), what the command prints goes into PATH instead.

    PATH is checked before the run (:func:`perturb.report.written.check_file`): an existing file
    perturb did not write is refused unless ``--force``; it is written atomically at the end.
    """
    path = getattr(args, "output", None)
    if path is None or args.command in _FOLDER_OUTPUT:
        yield
        return
    from perturb.report.written import check_file, write_file

    target = check_file(path, "--output", force=getattr(args, "force", False))
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        try:
            yield
        finally:  # a failed run's output (e.g. its JSON failure record) is written too
            if buffer.getvalue():
                # looked at again: a file the user saved there during the run is theirs
                check_file(path, "--output", force=getattr(args, "force", False))
                write_file(target, buffer.getvalue())


def _same_path(a: str, b: str) -> bool:
    """Whether the paths ``a`` and ``b`` name one file (resolved: links, ``..``; the same
    inode when both exist: hard links)."""
    first, second = os.path.expanduser(a), os.path.expanduser(b)
    try:
        if os.path.exists(first) and os.path.exists(second):
            return os.path.samefile(first, second)
    except OSError:
        pass
    return os.path.realpath(first) == os.path.realpath(second)


def _inside(path: str, folder: str) -> bool:
    """Whether ``path`` lies inside ``folder`` (both resolved)."""
    inner = os.path.realpath(os.path.expanduser(path))
    outer = os.path.realpath(os.path.expanduser(folder))
    return inner != outer and inner.startswith(outer.rstrip(os.sep) + os.sep)


def _check_distinct_outputs(args) -> None:
    """Refuse, before any work, two outputs that name one file (``--plot same.png --output
    same.png``: one would overwrite the other), or a plot inside the store ``--output`` writes."""
    output, plot = getattr(args, "output", None), getattr(args, "plot", None)
    if not output or not plot or not output.strip() or not plot.strip():
        return
    if _same_path(output, plot):
        raise _UsageError(
            f"--plot {plot!r} and --output {output!r} name the same file: one would overwrite the "
            "other; give two different paths"
        )
    if args.command in _FOLDER_OUTPUT and _inside(plot, output):
        raise _UsageError(
            f"--plot {plot!r} lies inside the store --output {output!r}: give a path outside it"
        )


def _command(name: str, module: str = "_commands"):
    """The command ``name`` of :mod:`perturb.cli.<module>`, imported when it runs (``--help`` and
    argument errors never load numpy, sympy or the engine)."""

    def run(args):
        commands = importlib.import_module(f"perturb.cli.{module}")
        return getattr(commands, name)(args)

    return run


#: Command name -> its function (tests may patch an entry).
_COMMANDS = {
    "list": _command("_cmd_list"),
    "solve": _command("_cmd_solve"),
    "validate": _command("_cmd_validate"),
    "reproduce": _command("_cmd_reproduce"),
    "work-precision": _command("_cmd_work_precision"),
    "families": _command("_cmd_families"),
    "response": _command("_cmd_response", "_response"),
    "report": _command("_cmd_report", "_report"),
    "sweep": _command("_cmd_sweep", "_sweep"),
    "phase-diagram": _command("_cmd_phase", "_phase"),
    "basins": _command("_cmd_basins", "_dynamics"),
    "transient": _command("_cmd_transient", "_dynamics"),
    "ramp": _command("_cmd_ramp", "_dynamics"),
}


def _is_input_error(exc: BaseException) -> bool:
    return isinstance(exc, PerturbError) and any(
        cls.__name__ in _INPUT_ERRORS for cls in type(exc).__mro__
    )


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text or type(exc).__name__


def _value_options(parser: argparse.ArgumentParser, argv: list[str]) -> dict:
    """The options of the command named in ``argv`` that take exactly one value, by their
    option strings (empty when no command is named)."""
    sub = next((a for a in parser._actions if isinstance(a, argparse._SubParsersAction)), None)
    command = next((a for a in argv if not a.startswith("-")), None)
    if sub is None or command not in sub.choices:
        return {}
    chosen = sub.choices[command]
    return {
        option: action
        for option, action in chosen._option_string_actions.items()
        if action.nargs is None and not isinstance(action, argparse._StoreConstAction)
    }


def _dashed_values(parser: argparse.ArgumentParser, argv: Sequence[str]) -> list[str]:
    """``argv`` with each value that starts with '-' joined to its option (``--times -1,0,1`` ->
    ``--times=-1,0,1``, ``--output -o.json``): argparse would take it for an option. A value that
    is itself one of the command's options is left alone (a forgotten value stays an error)."""
    argv = list(argv)
    options = _value_options(parser, argv)
    out: list[str] = []
    i = 0
    while i < len(argv):
        item = argv[i]
        if item == "--":
            out += argv[i:]
            break
        following = argv[i + 1] if i + 1 < len(argv) else None
        if (
            item in options
            and following is not None
            and following.startswith("-")
            and following != "--"
            and following.split("=", 1)[0] not in options
            and following not in ("-h", "--help")
        ):
            out.append(f"{item}={following}")
            i += 2
            continue
        out.append(item)
        i += 1
    return out


def _run(argv: Sequence[str] | None) -> int:
    parser = _build_parser()
    try:
        args = parser.parse_args(_dashed_values(parser, sys.argv[1:] if argv is None else argv))
        if args.command is None and args.version:
            import perturb

            print(f"perturb {perturb.__version__}")
            return 0
        if args.command is None:
            parser.print_help()
            return EXIT_USAGE
        _check_distinct_outputs(args)
        with _progress(args), _to_file(args):
            return _COMMANDS[args.command](args)
    except _UsageError as exc:
        print(f"perturb: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except _RunFailed as exc:
        print(f"perturb: failed: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILED
    except BrokenPipeError:
        raise
    except Exception as exc:  # noqa: BLE001 - a run never ends in a traceback
        return _failure(exc)
    except BaseException as exc:
        # raised by a user's problem file (a hook that calls sys.exit, raises KeyboardInterrupt,
        # GeneratorExit or a bare BaseException): named in one line, exit 2; else what it is
        # (argparse's --help, a Ctrl-C pressed)
        user = None if isinstance(exc, KeyboardInterrupt) and pressed() else _user_code(exc)
        if user is not None:
            print(f"perturb: error: {user}", file=sys.stderr)
            return EXIT_USAGE
        if isinstance(exc, SystemExit | KeyboardInterrupt):
            raise
        return _failure(exc)


def _user_code(exc: BaseException) -> str | None:
    """The one-line error of an exception the user's problem file caused, if it did: raised in
    its code, or a recursion without end while a user's problem is in use."""
    loading = sys.modules.get("problems.loading")
    if loading is None or not loading.LOADED_FILES:
        return None
    where = loading.user_frame(exc)
    if where is not None:
        if isinstance(exc, SystemExit):
            what = f"called sys.exit({exc.code!r})"
        else:
            detail = " ".join(str(exc).split())
            what = f"raised {type(exc).__name__}" + (f": {detail}" if detail else "")
        return f"{where}: the problem's code {what}: fix the class"
    if isinstance(exc, RecursionError):
        files = ", ".join(sorted(loading.LOADED_FILES))
        return (
            f"{files}: the problem's equations make perturb recurse without end "
            "(RecursionError): fix the expressions (a function that rewrites itself, or one "
            "nested thousands of levels deep)"
        )
    return None


def _failure(exc: BaseException) -> int:
    """The exit code and the line of an exception that ended a run."""
    if not isinstance(exc, PerturbError) or not _is_input_error(exc):
        user = _user_code(exc)
        if user is not None:
            print(f"perturb: error: {user}", file=sys.stderr)
            return EXIT_USAGE
    if isinstance(exc, MemoryError):
        print(
            "perturb: failed: the run needs more memory than this machine gives it: ask for "
            "fewer values (times, points, an order lower)",
            file=sys.stderr,
        )
        return EXIT_FAILED
    if isinstance(exc, OverflowError | FloatingPointError | ZeroDivisionError):
        print(
            f"perturb: failed: the computation overflowed or divided by zero at these parameters "
            f"({_one_line(exc)}); try values closer to the problem's defaults",
            file=sys.stderr,
        )
        return EXIT_FAILED
    if _is_input_error(exc):
        print(f"perturb: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    if isinstance(exc, PerturbError):  # a valid run that failed (a construction, a sweep)
        print(f"perturb: failed: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILED
    print(
        f"perturb: failed: internal error ({type(exc).__name__}: {_one_line(exc)}); please "
        "report it with the command line",
        file=sys.stderr,
    )
    return EXIT_FAILED


#: Thread-count variables of the BLAS/OpenMP runtimes numpy may load, set to 1 by the command when
#: unset: perturb's linear algebra is on matrices of a few rows, and starting a pool of threads
#: costs a fresh process about 0.05 s of CPU (a tenth of a warm ``perturb validate``).
SINGLE_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")


#: The variable that puts every Python process the command starts (a Dask worker, its
#: multiprocessing bootstrap and resource tracker) in safe-path mode: no working folder first on
#: its ``sys.path``, so that a ``multiprocessing.py`` lying there is never run (Python >= 3.11).
SAFE_PATH_VARIABLE = "PYTHONSAFEPATH"


def _as_a_program() -> None:
    """What only the process running the ``perturb`` command does (not a caller of :func:`main`):
    single-threaded BLAS, and safe-path mode for the Python processes it starts."""
    for name in SINGLE_THREAD_VARIABLES:
        os.environ.setdefault(name, "1")
    os.environ[SAFE_PATH_VARIABLE] = "1"


def _before_exit() -> None:
    """The process is about to end: the objects left need no garbage collection.

    Freezing them spares the interpreter's final collection a walk over every sympy expression
    and module (0.1 to 0.2 s of CPU); they are still released as the interpreter shuts down.
    """
    gc.freeze()


#: numpy's floating-point warnings (np.errstate's "warn" messages).
FLOATING_POINT_NOTICES = r"(overflow|underflow|invalid value|divide by zero) encountered"


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``perturb`` command; returns the exit code.

    A closed output pipe (``perturb solve ... | head``) ends the run quietly, as other Unix tools do.
    Called without ``argv`` (as the program, reading ``sys.argv``), it also sets the variables of
    :data:`SINGLE_THREAD_VARIABLES` to 1 where they are unset, before numpy is imported.
    """
    warnings.formatwarning = _format_warning
    # numpy's floating-point notices ("overflow encountered in exp") are the arithmetic of a run
    # at extreme values, not news for the user: what comes of them (a non-finite result, a series
    # outside its domain) is reported by perturb's own checks, in one line
    warnings.filterwarnings("ignore", message=FLOATING_POINT_NOTICES, category=RuntimeWarning)
    program = argv is None
    if program:
        _as_a_program()
    try:
        with _watching_interrupts():
            code = _run(argv)
        sys.stdout.flush()
        if program:
            _before_exit()
        return code
    except BrokenPipeError:
        # Python's advice: point stdout at devnull so the interpreter's final flush cannot fail again.
        with contextlib.suppress(OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        return EXIT_FAILED
    except KeyboardInterrupt:  # pragma: no cover - Ctrl-C: said, with the shells' code
        print("\nperturb: interrupted", file=sys.stderr)
        return 130


@contextlib.contextmanager
def _watching_interrupts() -> Iterator[None]:
    """Record each SIGINT (Ctrl-C) that arrives during the run, then raise KeyboardInterrupt as
    Python does: a KeyboardInterrupt a user's code raised itself is told apart from one."""
    import signal

    PRESSED.clear()

    def handler(signum, frame):
        PRESSED.append(signum)
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGINT, handler)
    except ValueError:  # not the main thread: signals cannot be watched
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def run() -> None:  # pragma: no cover - console entry
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    run()
