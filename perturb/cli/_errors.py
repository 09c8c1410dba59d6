"""Errors the command line distinguishes: the user's input (exit 2) and a failed run (exit 1)."""

from __future__ import annotations

#: Exit codes: success, a valid run that failed (the reason is printed), bad input.
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2

_INPUT_ERRORS = (
    "InvalidParameterError",
    "InvalidSystemError",
    "UnknownNameError",
    "ProblemLoadError",
    "SceneError",
    "OutputError",
)


class _UsageError(Exception):
    pass


class _RunFailed(Exception):
    """A valid run that failed: exit 1 with the reason on one line."""


#: SIGINT signals that arrived during the run (Ctrl-C), told apart from a ``KeyboardInterrupt``
#: a user's code raised itself (:func:`perturb.cli._main.main` watches them).
PRESSED: list[int] = []


def pressed() -> bool:
    """Whether Ctrl-C was pressed during this run (False where signals cannot be watched and
    none was seen: then every ``KeyboardInterrupt`` outside a user's code is one)."""
    return bool(PRESSED)


def _tell(cost) -> None:
    """Say on stderr, in one line, how long a confirmed or unasked request will take when it is
    past :data:`perturb._defaults.NOTICE_SECONDS` (:func:`perturb.cost.notice`)."""
    import sys

    from perturb.cost import notice

    line = notice(cost)
    if line is not None:
        print(f"perturb: warning: {line}", file=sys.stderr)  # a warning: never an error line
