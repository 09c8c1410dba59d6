"""Command-line interface: ``perturb list``, ``perturb solve`` (a leaf: nothing imports it).

Exit codes: 0 success, 1 a valid run whose construction or check failed (the reason is printed),
2 bad input (one line on stderr, no traceback). Only errors about the user's input exit 2: anything
else that goes wrong inside a run is a failed run (exit 1) with the reason on one line, never a
traceback. Options are never abbreviated (``--order`` is not ``--orders``).
"""

from perturb.cli._errors import EXIT_FAILED, EXIT_OK, EXIT_USAGE
from perturb.cli._main import _COMMANDS, _ProgressBar, main, run  # noqa: F401 (tests patch these)

__all__ = ["EXIT_FAILED", "EXIT_OK", "EXIT_USAGE", "main", "run"]
