"""``sympy.lambdify(..., modules="numpy")`` without the cost of its first call.

The first numpy lambdify of a process runs ``from numpy import *``, which makes numpy import every
submodule it loads lazily (``f2py``, ``testing``, ``random``, ``ma``, ``polynomial`` ...): about
0.1 s of CPU that a warm ``perturb validate`` would otherwise spend on nothing the generated code
calls.  :func:`numpy_lambdify` gives sympy the same printer and a namespace with the same
functions (numpy's loaded public names, then ``numpy.linalg``'s, then sympy's translations), so
the generated source, and hence every number it computes, is the one ``modules="numpy"`` gives.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

__all__ = ["numpy_lambdify"]


@functools.cache
def _namespace() -> dict:
    """What ``sympy.lambdify(..., "numpy")`` puts in scope, minus numpy's unloaded submodules."""
    import numpy
    import numpy.linalg
    from sympy.utilities.lambdify import NUMPY_DEFAULT, NUMPY_TRANSLATIONS

    namespace = dict(NUMPY_DEFAULT)
    namespace["numpy"] = numpy
    for module in (
        numpy,
        numpy.linalg,
    ):  # the order of "from numpy import *; from numpy.linalg ..."
        loaded = vars(module)  # a name of __all__ missing here is a submodule not imported yet
        namespace.update((name, loaded[name]) for name in module.__all__ if name in loaded)
    for sympy_name, numpy_name in NUMPY_TRANSLATIONS.items():
        namespace[sympy_name] = namespace[numpy_name]
    namespace.setdefault("Abs", abs)  # as sympy's _import does
    return namespace


def _printer():
    """The printer ``lambdify`` makes for ``modules="numpy"`` (a new one per call, as there)."""
    from sympy.printing.numpy import NumPyPrinter

    return NumPyPrinter(
        {
            "fully_qualified_modules": False,
            "inline": True,
            "allow_unknown_functions": True,
            "user_functions": {},
        }
    )


def numpy_lambdify(args, expr, cse: bool = False) -> Callable:
    """``sympy.lambdify(args, expr, "numpy", cse=cse)``: the same function, built more cheaply.

    Parameters
    ----------
    args : sympy.Symbol or (nested) sequence of them
        The arguments of the function, as for :func:`sympy.lambdify`.
    expr : sympy.Expr, sequence or Matrix
        What the function returns.
    cse : bool, optional
        Pull out common subexpressions (as :func:`sympy.lambdify`'s ``cse``).

    Returns
    -------
    callable
        The generated function (its source is that of ``modules="numpy"``).

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> float(numpy_lambdify(x, sp.sin(x) ** 2 + sp.cos(x) ** 2)(0.3))
    1.0
    """
    import sympy

    return sympy.lambdify(args, expr, modules=[_namespace()], printer=_printer(), cse=cse)
