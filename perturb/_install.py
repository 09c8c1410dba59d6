"""Where perturb comes from: its distribution name and the one way to advise installing an extra.

The import name is ``perturb``; the distribution on the package registry is :data:`DISTRIBUTION`,
because ``perturb`` there is an unrelated project (a planning ledger): a hint naming the bare
import name with an extra would install that. Every message that advises an install is built
by :func:`install_hint`, and ``tests/test_install_hints.py`` greps the tree for the taken name.
"""

#: The distribution name on the package registry (free when chosen: ``pip index versions`` found no
#: release under it; ``perturb`` itself is taken by another project).
DISTRIBUTION = "perturb-poincare"


def install_hint(extra: str) -> str:
    """The command that installs an optional extra, from the registry or from a clone.

    Examples
    --------
    >>> install_hint("plot")
    'pip install \\'perturb-poincare[plot]\\' (from a clone: pip install -e ".[plot]")'
    """
    return f"pip install '{DISTRIBUTION}[{extra}]' (from a clone: pip install -e \".[{extra}]\")"


def installed(module: str) -> bool:
    """Whether ``module`` can be imported, found without importing it (a check before any work
    must not load matplotlib or Dask: only the rooms that use them import them).

    Examples
    --------
    >>> installed("json"), installed("no_such_module_here")
    (True, False)
    """
    import importlib.util

    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # a parent missing, or a module set to None (tests)
        return False
