"""``python -m perturb``: the same as the ``perturb`` command.

``python -m`` puts the working folder first on ``sys.path`` (the ``perturb`` command does not): a
``struct.py`` or ``selectors.py`` lying there would then be imported in place of the standard
library's. The entry is dropped before anything else is imported, unless perturb itself was found
there (a checkout run from its own folder).
"""

import os
import sys


def _drop_working_folder() -> None:
    """Remove the working folder ``python -m`` put first on ``sys.path``."""
    if sys.flags.safe_path or not sys.path:
        return
    first = sys.path[0]
    try:
        here = os.path.realpath(first or os.curdir) == os.path.realpath(os.curdir)
    except OSError:  # pragma: no cover - a working folder removed under us
        here = True
    package = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    if here and os.path.realpath(first or os.curdir) != package:
        del sys.path[0]


_drop_working_folder()

from perturb.cli import main  # noqa: E402 - after the path is made safe

sys.exit(main())
