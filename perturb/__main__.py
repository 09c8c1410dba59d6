"""``python -m perturb``: the same as the ``perturb`` command."""

import sys

from perturb.cli import main

sys.exit(main())
