"""Polynomial algebra the engine and the response share: certified real roots of polynomial systems.

A neutral room: it depends on sympy (and, with the extra ``roots``, on the msolve binary) only;
:mod:`perturb.method` and :mod:`perturb.response` both use it, never the reverse.
"""

from perturb.algebra.budget import solve_bounded, sympy_roots
from perturb.algebra.certified import BACKENDS, certified_real_roots
from perturb.algebra.msolve import msolve_binary
from perturb.algebra.rootset import RootSet, RootStatus
from perturb.algebra.size import SystemSize
from perturb.algebra.triangular import exact_real_roots

__all__ = [
    "BACKENDS",
    "RootSet",
    "RootStatus",
    "SystemSize",
    "certified_real_roots",
    "exact_real_roots",
    "msolve_binary",
    "solve_bounded",
    "sympy_roots",
]
