"""Frequency responses of driven systems: every branch, its stability, its folds.

The steady states themselves are ``perturb.steady``'s (the series alone); this room adds the
response curve of a problem with its checks against the true motion (``model``,
``truth``, the true curve past the series) and slow sweeps (``hysteresis``). The names
below are ``perturb.steady``'s, kept here for the scripts that import them from
``perturb.response``, beside the one this room adds: :func:`steady_state_of`, the steady state
of a driven model at its own point.
"""

from perturb import steady as _steady
from perturb.response.steady_of import steady_state_of
from perturb.steady import *  # noqa: F403 - the same public names, one list (steady's __all__)

__all__ = [*_steady.__all__, "steady_state_of"]
