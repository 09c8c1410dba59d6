"""Pickles of sympy expressions that read back without being evaluated again, and their digest.

sympy pickles a sum, product or power by its constructor, so reading one back sorts and collects
its terms again: most of the time of reading a large expression.  The pickles written here hold
such an expression as its canonical arguments and rebuild it as it was.  :mod:`perturb.cache`
writes its entries' payloads with :func:`dumps` and builds key parts with :func:`digest`.

A payload refers to :func:`_rebuilt_assoc` and :func:`_rebuilt_power` by their module path, so
moving them changes what old entries need to load; the cache's entries carry the engine's source
fingerprint in their key and header, so entries written by another layout are missed (a
different file name) and, if ever read, rejected as stale before they are unpickled.
"""

from __future__ import annotations

import hashlib
import io
import pickle

__all__ = ["UNPICKLABLE", "digest", "dumps"]

#: What pickling a value that cannot be pickled raises (a lambda, a module, a C object).
UNPICKLABLE = (pickle.PicklingError, TypeError, AttributeError, RecursionError)


def _rebuilt_assoc(cls: type, args: tuple, commutative: bool | None):
    """A sympy sum or product from the arguments it held (already canonical): no re-evaluation."""
    return cls._from_args(args, commutative)


def _rebuilt_power(cls: type, base, exponent):
    """A sympy power from the base and exponent it held (already canonical): no re-evaluation."""
    return cls(base, exponent, evaluate=False)


class _Pickler(pickle.Pickler):
    """A pickler that writes sympy's ``Add``, ``Mul`` and ``Pow`` as their canonical arguments.

    sympy pickles an expression by its constructor, so reading it back evaluates every sum and
    product again (sorting and collecting its terms): most of the time of reading a large
    expression.  The arguments of a stored expression are already in canonical form, so they are
    put back as they were (``_from_args``, ``evaluate=False``): the same object, equal and with
    the same ``srepr``, at a small fraction of the cost.  Only these exact classes are handled
    (not subclasses, which may evaluate differently); everything else pickles as usual.
    """

    def __init__(self, file, assoc: tuple[type, ...], power: type) -> None:
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self._assoc = assoc
        self._power = power

    def reducer_override(self, obj):
        kind = type(obj)
        if kind in self._assoc:
            return _rebuilt_assoc, (kind, obj.args, obj.is_commutative)
        if kind is self._power:
            return _rebuilt_power, (kind, *obj.args)
        return NotImplemented


def dumps(value: object, tree: bool = False) -> bytes:
    """``pickle.dumps`` of ``value``, sympy's sums, products and powers as canonical arguments;
    with ``tree``, every repeated object written out again (pickle's memo off: the bytes are then
    those of the value's tree, whichever of its equal parts are one object)."""
    from sympy import Add, Mul, Pow

    buffer = io.BytesIO()
    pickler = _Pickler(buffer, (Add, Mul), Pow)
    pickler.fast = tree
    pickler.dump(value)
    return buffer.getvalue()


def digest(value: object) -> str:
    """SHA-256 (hex) of ``value``'s pickle as the cache writes it: a key part for large sympy
    objects, a fraction of the cost of their ``srepr``.

    Raises one of :data:`UNPICKLABLE` for a value that cannot be pickled.  The bytes determine
    the value they read back as, so two values with one digest are equal and a key built on it
    never reads another value's entry.  The pickle is written as a tree (a repeated part written
    out again, as ``srepr`` prints it), so whether equal parts are one object or several (built
    afresh, or read back from the cache) does not change it.

    Parameters
    ----------
    value : object
        Anything the cache can pickle (sympy expressions, systems, solutions).

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> digest(x**2 + 1) == digest(x**2 + 1) != digest(x**2 + 2)
    True
    """
    try:
        data = dumps(value, tree=True)
    except ValueError as exc:  # pickle's memo-less mode refuses a value that holds itself
        raise pickle.PicklingError(str(exc)) from exc
    return hashlib.sha256(data).hexdigest()
