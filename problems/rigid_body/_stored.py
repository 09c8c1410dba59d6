"""The rigid body's symbolic derivations kept on disk, so that a warm run does not redo them.

:func:`stored` wraps :func:`perturb.cache.cached` (signed entries; the key covers perturb's engine,
sympy and Python) and adds to the key the source of the modules the derivation runs, listed by
each caller: an edited derivation never reads the results of an older one.  The inputs go into
the key as ``sympy.srepr`` (exact: a float is keyed by its full binary value), so a different body
never hits another body's entry.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import TypeVar

import sympy as sp

from perturb.cache import cached

__all__ = ["source_fingerprint", "stored"]

T = TypeVar("T")

_HERE = Path(__file__).parent


@cache
def source_fingerprint(names: tuple[str, ...]) -> str:
    """Hash of the named source files of this package (``("equations.py", ...)``)."""
    digest = hashlib.sha256()
    for name in names:
        digest.update(name.encode() + b"\0" + (_HERE / name).read_bytes())
    return digest.hexdigest()[:16]


def stored(kind: str, sources: tuple[str, ...], inputs: tuple, compute: Callable[[], T]) -> T:
    """``compute()``, kept on disk under ``kind`` for these ``inputs`` and ``sources``.

    Parameters
    ----------
    kind : str
        The entry's label (a file-name prefix of letters, digits, ``-``, ``_``).
    sources : tuple of str
        The files of :mod:`problems.rigid_body` whose code ``compute`` runs.
    inputs : tuple
        Everything else the result depends on (sympy objects, numbers, strings).
    compute : callable
        Builds the result when there is no valid entry.
    """

    def parts() -> tuple:  # built only when the disk cache is in use
        return source_fingerprint(tuple(sources)), tuple(sp.srepr(value) for value in inputs)

    return cached(kind, parts, compute)
