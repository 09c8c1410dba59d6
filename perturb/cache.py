"""On-disk cache of derived symbolic objects (solutions, reductions).

The folder is ``$PERTURB_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/perturb`` or ``~/.cache/perturb``.
Set ``PERTURB_CACHE_DIR=off`` to disable it.  Entries are pickles keyed by a hash of everything the
result depends on (the inputs' ``srepr``, the perturb version and the engine's source code), so a
change of input, version or engine never reads a stale entry; an unreadable entry is recomputed and overwritten.
"""

from __future__ import annotations

import functools
import hashlib
import os
import pickle
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

__all__ = ["cache_dir", "cached"]

T = TypeVar("T")

#: Environment variable naming the cache folder (``off`` disables the cache).
CACHE_ENV = "PERTURB_CACHE_DIR"
#: Bump when the pickled layout of cached objects changes.
CACHE_FORMAT = 1


def cache_dir() -> Path | None:
    """The cache folder, or ``None`` when caching on disk is disabled."""
    value = os.environ.get(CACHE_ENV)
    if value is not None:
        return None if value.strip().lower() in ("off", "0", "none", "") else Path(value)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "perturb"


@functools.cache
def _code_fingerprint() -> str:
    """Hash of the engine's source: an edited engine never reads results of an older one."""
    digest = hashlib.sha256()
    for path in sorted(Path(__file__).parent.rglob("*.py")):
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _key(parts: tuple) -> str:
    from perturb import __version__

    text = repr((CACHE_FORMAT, __version__, _code_fingerprint(), *parts))
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def cached(kind: str, parts: tuple, compute: Callable[[], T]) -> T:
    """Return ``compute()``, reading it from / writing it to the disk cache when enabled.

    Parameters
    ----------
    kind : str
        A label used as the file prefix (``solution``, ``reduction`` ...).
    parts : tuple
        Everything the result depends on, as text-representable values (use ``sympy.srepr``).
    compute : callable
        Builds the object when it is not cached.
    """
    folder = cache_dir()
    if folder is None:
        return compute()
    path = folder / f"{kind}-{_key(parts)}.pkl"
    try:
        with open(path, "rb") as fh:
            return pickle.load(fh)
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError, TypeError):
        pass
    value = compute()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=folder, suffix=".tmp")  # atomic replace: no torn entries
        with os.fdopen(fd, "wb") as fh:
            pickle.dump(value, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except (OSError, pickle.PicklingError, TypeError, AttributeError):
        pass  # an unwritable cache only costs time
    return value
