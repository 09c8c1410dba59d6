"""What travels to the Dask workers: a sweep's job (or a map's calls) as cloudpickle bytes, with a
user's problem class by value when a worker could not import it (a problem from a file,
``perturb sweep path/file.py:Class``), and with the modules that file imported from its own folder.
"""

from __future__ import annotations

import os
import sys

from perturb.errors import InvalidParameterError
from perturb.sweep.spec import SweepJob

__all__ = ["pack", "pickled"]


def _importable_elsewhere(module_name: str) -> bool:
    """Whether a fresh interpreter could import ``module_name`` (its top-level package is found
    by the import system's finders, not merely present in this process's ``sys.modules``)."""
    top = module_name.partition(".")[0]
    if top in sys.builtin_module_names or top == "__main__":
        return top != "__main__"
    for finder in sys.meta_path:
        find = getattr(finder, "find_spec", None)
        if find is None:
            continue
        try:
            if find(top, None) is not None:
                return True
        except (ImportError, ValueError, AttributeError, TypeError):
            continue
    return False


def pack(job: SweepJob) -> bytes:
    """The job as cloudpickle bytes; the problem's class travels by value when a worker could
    not import it (a problem from a file, ``perturb sweep path/file.py:Class``).

    Raises
    ------
    perturb.errors.InvalidParameterError
        The problem cannot be pickled (an attribute holding a lock, an open file...): one line
        naming its class and file, and what to do.
    """
    return pickled(job, job.spec.model)


def pickled(payload, model) -> bytes:
    """``payload`` as cloudpickle bytes, ``model``'s class by value when a worker could not import
    it; a payload that cannot be pickled is one line about ``model`` (see :func:`pack`)."""
    import cloudpickle

    module = sys.modules.get(type(model).__module__)
    registered = []
    if module is not None and not _importable_elsewhere(module.__name__):
        registered = [module, *_siblings(module)]
        for each in registered:
            cloudpickle.register_pickle_by_value(each)
    try:
        return cloudpickle.dumps(payload)
    except Exception as exc:  # noqa: BLE001 - any reason pickle gives
        where = getattr(module, "__file__", None) or type(model).__module__
        detail = " ".join(f"{type(exc).__name__}: {exc}".split())[:200]
        raise InvalidParameterError(
            f"{where}: the problem {type(model).__name__} cannot be sent to the Dask workers "
            f"(pickling it failed: {detail}): make its attributes picklable (make a lock, an "
            "open file or a connection inside the method that needs it, not on the class or "
            "the instance)"
        ) from None
    finally:
        for each in registered:
            cloudpickle.unregister_pickle_by_value(each)


def _siblings(module) -> list:
    """The modules a problem file imported from its own folder (``import helpers`` at its top:
    :mod:`problems.loading` puts the folder on the path while it imports the file) that a worker
    could not import: they travel by value with the file's class."""
    file = getattr(module, "__file__", None)
    if not file:
        return []
    folder = os.path.dirname(os.path.abspath(file))
    found = []
    for name, other in list(sys.modules.items()):
        where = getattr(other, "__file__", None)
        if other is module or not where or name.partition(".")[0] in sys.builtin_module_names:
            continue
        inside = os.path.abspath(where).startswith(folder + os.sep)
        if inside and not _importable_elsewhere(name):
            found.append(other)
    return found
