"""``sympy.lambdify(..., modules="numpy")`` without the cost of its first call.

The first numpy lambdify of a process runs ``from numpy import *``, which makes numpy import every
submodule it loads lazily (``f2py``, ``testing``, ``random``, ``ma``, ``polynomial`` ...): about
0.1 s of CPU that a warm ``perturb validate`` would otherwise spend on nothing the generated code
calls.  :func:`numpy_lambdify` gives sympy the same printer and a namespace with the same
functions (numpy's loaded public names, then ``numpy.linalg``'s, then sympy's translations), so
the generated source, and hence every number it computes, is the one ``modules="numpy"`` gives.
"""

from __future__ import annotations

import builtins
import functools
import itertools
import linecache
import weakref
from collections.abc import Callable

from perturb._defaults import LAMBDIFIED_CACHE_ENTRIES
from perturb.cache import UNPICKLABLE, active, cached, digest

__all__ = ["mpmath_lambdify", "numpy_lambdify"]

#: The name sympy gives the generated function in its source.
_FUNCTION_NAME = "_lambdifygenerated"
#: Numbers the file names of generated sources (tracebacks and ``inspect`` show them, as sympy's).
_SOURCES = itertools.count()

#: The largest integer numpy's functions take as a Python ``int`` (int64): a larger literal becomes
#: an object array, on which ``sqrt``, ``exp``, ``cos`` ... fail ("no callable sqrt method").
INT64_MAX = 2**63 - 1


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


def _big_integers_as_floats(expr):
    """``expr`` with each integer beyond :data:`INT64_MAX` written as a float of all its digits.

    Exact results can hold such integers (``sqrt(847504615198858776185891631)`` in a specialised
    solution of the disk). As a Python ``int`` in the generated code, a ufunc fails on it; as a
    float literal of all its digits it is the double nearest to it, the very number Python's
    arithmetic makes of it where it worked (a product, a quotient). A complex infinity (``zoo``,
    a pole the parameter values fall on) becomes NaN: the function's value there is not a number,
    and its callers check for that, where numpy's printer would fail with a KeyError.
    """
    import sympy

    if isinstance(expr, list | tuple):
        return type(expr)(_big_integers_as_floats(e) for e in expr)
    if isinstance(expr, sympy.MatrixBase):
        return expr.applyfunc(_big_integers_as_floats)
    if not isinstance(expr, sympy.Basic):
        return expr
    if expr.has(sympy.zoo):  # a pole at these values: numpy's printer has no name for it
        expr = expr.xreplace({sympy.zoo: sympy.nan})
    big = [n for n in expr.atoms(sympy.Integer) if abs(int(n)) > INT64_MAX]
    if not big:
        return expr
    return expr.xreplace({n: sympy.Float(n, len(str(abs(int(n))))) for n in big})


def numpy_lambdify(args, expr, cse: bool = False, *, key: str | None = None) -> Callable:
    """``sympy.lambdify(args, expr, "numpy", cse=cse)``: the same function, built more cheaply.

    Parameters
    ----------
    args : sympy.Symbol or (nested) sequence of them
        The arguments of the function, as for :func:`sympy.lambdify`.
    expr : sympy.Expr, sequence or Matrix, or a function returning one
        What the function returns; a function (with ``key``) is called only when the generated
        source is not in the disk cache: a warm run then builds no sympy expression.
    cse : bool, optional
        Pull out common subexpressions (as :func:`sympy.lambdify`'s ``cse``).
    key : str, optional
        What the source is kept under in place of the digest of ``args`` and ``expr``: it must
        determine both (a digest of what they are built from).

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
    if key is None or not active():
        expr = _big_integers_as_floats(expr() if key is not None and callable(expr) else expr)
        if not active():
            return _lambdified(args, expr, cse)
        try:
            parts = (digest((args, expr)), bool(cse))
        except UNPICKLABLE:  # an implemented function's own code: not kept
            return _lambdified(args, expr, cse)

        def built():
            return expr

    else:
        parts = ("given", key, bool(cse))

        def built():
            return _big_integers_as_floats(expr() if callable(expr) else expr)

    def made() -> Callable:
        return _lambdified(args, built(), cse)

    source = cached(
        "lambdified",
        parts,
        lambda: _portable_source(made(), _scope()),
        keep=LAMBDIFIED_CACHE_ENTRIES,
    )
    return made() if source is None else _from_source(*source)


def _lambdified(args, expr, cse: bool) -> Callable:
    import sympy

    return sympy.lambdify(
        args, expr, modules=[_namespace()], printer=_printer(), cse=cse, **_no_docstring()
    )


def _scope() -> dict:
    """The globals of a generated function: the namespace, with what ``lambdify`` adds."""
    return {**_namespace(), "builtins": builtins, "range": range}


def _portable_source(function: Callable, scope: dict) -> tuple[str, dict] | None:
    """The source of a function ``lambdify`` generated and the names it added to ``scope``
    (:func:`_scope` or :func:`_mpmath_scope`: the symbols of a sympy expression, each under its
    own name, as ``lambdify`` puts them), or None when it needs anything else (an implemented
    function, an import the printer added)."""
    import sympy

    names = {k: v for k, v in function.__globals__.items() if k != "__builtins__"}  # exec's own
    added = {k: v for k, v in names.items() if k not in scope or scope[k] is not v}
    if scope.keys() - names.keys() or not all(
        isinstance(v, sympy.Symbol) and str(v) == k for k, v in added.items()
    ):
        return None
    lines = linecache.cache.get(function.__code__.co_filename)
    return None if lines is None else ("".join(lines[2]), added)


def _from_source(source: str, added: dict, scope: dict | None = None) -> Callable:
    """The function of a generated ``source``, built as ``lambdify`` builds it (the same code in
    the same namespace, its source kept for tracebacks and :mod:`inspect`).

    The source is kept in the disk cache (kind ``lambdified``, keyed on a digest of the
    arguments and the expression, :func:`perturb.cache.digest`, and on ``cse``): printing it,
    and pulling out the common subexpressions, is most of the time of ``lambdify``.
    """
    filename = f"<lambdifygenerated-perturb-{next(_SOURCES)}>"
    local: dict = {}
    scope = _scope() if scope is None else scope
    exec(compile(source, filename, "exec"), {**scope, **added}, local)  # a signed entry of ours
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    function = local[_FUNCTION_NAME]
    weakref.finalize(function, linecache.cache.pop, filename, None)
    return function


def mpmath_lambdify(args, expr) -> Callable:
    """``sympy.lambdify(args, expr, "mpmath")``, its source kept in the disk cache.

    As :func:`numpy_lambdify` keeps numpy's: a warm run reads the source back (kind
    ``lambdified``, keyed on a digest of the arguments and the expression) and runs it in the
    namespace ``lambdify`` gives it, so neither the printer nor what it imports (sympy's code
    generation, ``sympy.codegen.ast``) is loaded.  A function that needs anything else is
    lambdified afresh every time.

    Examples
    --------
    >>> import mpmath
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> with mpmath.workdps(30):
    ...     print(mpmath_lambdify([x], [sp.sqrt(x) / 3])(mpmath.mpf(2))[0])
    0.471404520791031682933896241403
    """
    import sympy

    def made() -> Callable:
        return sympy.lambdify(args, expr, modules="mpmath", **_no_docstring())

    if not active():
        return made()
    try:
        key = (digest((args, expr)), "mpmath")
    except UNPICKLABLE:  # an implemented function's own code: not kept
        return made()
    source = cached(
        "lambdified",
        key,
        lambda: _portable_source(made(), _mpmath_scope()),
        keep=LAMBDIFIED_CACHE_ENTRIES,
    )
    return made() if source is None else _from_source(*source, _mpmath_scope())


@functools.cache
def _mpmath_namespace() -> dict:
    """What ``sympy.lambdify(..., "mpmath")`` puts in scope: mpmath's names, then sympy's
    translations (as sympy's ``_import("mpmath")`` makes them)."""
    from sympy.utilities.lambdify import MPMATH_DEFAULT, MPMATH_TRANSLATIONS

    namespace = dict(MPMATH_DEFAULT)
    exec("from mpmath import *", {}, namespace)  # noqa: S102 - sympy's own import command
    for sympy_name, mpmath_name in MPMATH_TRANSLATIONS.items():
        namespace[sympy_name] = namespace[mpmath_name]
    namespace.setdefault("Abs", abs)
    return namespace


def _mpmath_scope() -> dict:
    """The globals of a function generated for mpmath (see :func:`_scope`)."""
    return {**_mpmath_namespace(), "builtins": builtins, "range": range}


@functools.cache
def _no_docstring() -> dict:
    """``docstring_limit=0`` where sympy's ``lambdify`` takes it: the generated function's
    docstring then names no expression, where printing it (``str``) is a third of the cost of
    ``lambdify`` on the expressions a validation compiles.  The generated code is the same."""
    import inspect

    import sympy

    supported = "docstring_limit" in inspect.signature(sympy.lambdify).parameters
    return {"docstring_limit": 0} if supported else {}
