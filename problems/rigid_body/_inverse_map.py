"""Series of the reduction, with numbers put in, as a fast numpy map (the inverse map's numerics).

The inverse map (reduced state -> full state) is a series with 400–1100 terms a component while it
is symbolic in the body's parameters; with the parameters and epsilon put in, exactly, it is a short
polynomial in the reduced state :math:`Z = (P, \\dot P, G, \\dot G)` and the initial values
:math:`Z_0`. Along one solution :math:`Z_0` is a constant, so each component is

.. math:: y_i(Z) = \\sum_m c_{im}(Z_0)\\, Z^m ,

a matrix :math:`C(Z_0)` (components x monomials, a few dozen numbers computed per call) times the
monomials :math:`Z^m` at every point (each one product of a smaller monomial and one variable). The
sample points thus cost one multiplication per distinct monomial and one matrix product, instead of
the several hundred array operations of a compiled expression.
"""

from __future__ import annotations

import operator
from collections.abc import Mapping, Sequence
from fractions import Fraction

import numpy as np
import sympy as sp
from sympy.polys.rings import PolyElement

from problems.rigid_body._series_ring import SeriesRing

__all__ = ["PolynomialMap", "compile_polynomials"]

#: Points evaluated at a time: the monomial table (a few hundred rows) then stays in the CPU cache
#: instead of being written to and read back from memory.
CHUNK = 2048


class PolynomialMap:
    """``f(Z, Z0) -> array (n, ...)``: polynomials in ``Z`` whose coefficients are polynomials in ``Z0``.

    Parameters
    ----------
    terms : sequence of dict
        One per component: ``(exponents of Z, exponents of Z0) -> coefficient`` (floats).
    """

    def __init__(self, terms: Sequence[Mapping[tuple[tuple[int, ...], tuple[int, ...]], float]]):
        self.size = len(terms)
        monomials = sorted(
            {mz for component in terms for mz, _ in component},
            key=lambda m: (sum(m), m),
        )
        self.width = len(monomials[0]) if monomials else 0
        index = {m: i for i, m in enumerate(monomials)}
        # each monomial (but the constant) = a lower one times one variable
        self.steps = []
        for m in monomials:
            if not any(m):
                continue
            var = next(i for i, e in enumerate(m) if e)
            lower = tuple(e - (i == var) for i, e in enumerate(m))
            if lower not in index:  # complete the chain of divisors
                raise AssertionError(f"monomial {m} without its divisor {lower}")
            self.steps.append((index[m], index[lower], var))
        self.count = len(monomials)
        self.constant = index.get((0,) * self.width)
        rows, cols, coeffs, exps = [], [], [], []
        for i, component in enumerate(terms):
            for (mz, m0), c in component.items():
                rows.append(i)
                cols.append(index[mz])
                coeffs.append(c)
                exps.append(m0)
        self.rows = np.array(rows, dtype=np.intp)
        self.cols = np.array(cols, dtype=np.intp)
        self.coeffs = np.array(coeffs, dtype=float)
        self.exponents = np.array(exps, dtype=float).reshape(len(coeffs), -1)

    def _coefficients(self, z0: np.ndarray) -> np.ndarray:
        values = self.coeffs * np.prod(z0**self.exponents, axis=1)
        matrix = np.zeros((self.size, self.count))
        np.add.at(matrix, (self.rows, self.cols), values)
        return matrix

    def __call__(self, z, z0) -> np.ndarray:
        z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in z))
        shape = z[0].shape
        z0 = [np.asarray(v, dtype=float) for v in z0]
        if any(v.ndim for v in z0):  # initial values varying from point to point: term by term
            return self._pointwise(z, z0)
        flat = [v.ravel() for v in z]
        n = flat[0].size if flat else 1
        matrix = self._coefficients(np.array([float(v) for v in z0]))
        out = np.empty((self.size, n))
        columns = np.empty((self.count, min(n, CHUNK)))
        if self.constant is not None:
            columns[self.constant] = 1.0
        for start in range(0, n, CHUNK):
            stop = min(start + CHUNK, n)
            block = columns[:, : stop - start]
            for target, lower, var in self.steps:
                np.multiply(block[lower], flat[var][start:stop], out=block[target])
            # einsum's own loop, not BLAS: threaded BLAS on a busy machine costs more than it saves
            out[:, start:stop] = np.einsum("im,mn->in", matrix, block)
        return out.reshape((self.size, *shape))

    def _pointwise(self, z, z0) -> np.ndarray:
        z = np.broadcast_arrays(*z, *z0)
        base, initial = z[: self.width], z[self.width :]
        shape = base[0].shape
        out = np.zeros((self.size, *shape))
        columns = [None] * self.count
        if self.constant is not None:
            columns[self.constant] = np.ones(shape)
        for target, lower, var in self.steps:
            columns[target] = columns[lower] * base[var]
        for row, col, c, e in zip(self.rows, self.cols, self.coeffs, self.exponents, strict=True):
            factor = c * np.prod([v**p for v, p in zip(initial, e, strict=True) if p], axis=0)
            out[row] += factor * columns[col]
        return out


def _with_divisors(monomials: set[tuple[int, ...]]) -> set[tuple[int, ...]]:
    """``monomials`` and every monomial on the chains that build them one variable at a time."""
    out = set(monomials)
    stack = list(monomials)
    while stack:
        m = stack.pop()
        if not any(m):
            continue
        var = next(i for i, e in enumerate(m) if e)
        lower = tuple(e - (i == var) for i, e in enumerate(m))
        if lower not in out:
            out.add(lower)
            stack.append(lower)
    return out


#: Per polynomial (by id, the polynomial kept beside): its monomials split into (Z, Z0) exponents.
_SPLIT_KEYS: dict[int, tuple] = {}


def _picker(indices: list[int]):
    """``monom -> tuple(monom[i] for i in indices)``, fast (:func:`operator.itemgetter`)."""
    if not indices:
        return lambda monom: ()
    if len(indices) == 1:
        (index,) = indices
        return lambda monom: (monom[index],)
    return operator.itemgetter(*indices)


def compile_polynomials(
    ring: SeriesRing,
    polys: Sequence[PolyElement],
    numbers: Mapping[sp.Symbol, Fraction],
    first: Sequence[sp.Symbol],
    second: Sequence[sp.Symbol],
) -> PolynomialMap:
    """The ``polys`` with ``numbers`` put in, as a :class:`PolynomialMap` of ``(first, second)``.

    The coefficients are evaluated in exact rational arithmetic and rounded once to double
    precision. Every generator of ``ring`` must be given a number or be one of ``first``/``second``,
    except generators the series do not contain (checked).
    """
    keep = ring.free_generators(numbers)
    where = {s: i for i, s in enumerate(keep)}
    stray = [s for s in keep if s not in first and s not in second]
    split = []
    stray_of = _picker([where[s] for s in stray])
    first_of, second_of = _picker([where[s] for s in first]), _picker([where[s] for s in second])
    shape = (tuple(keep), tuple(first), tuple(second))
    for poly in polys:
        values = ring.evaluate_float(poly, numbers, keep)
        keys = _SPLIT_KEYS.get(id(poly))
        if keys is None or keys[0] is not poly or keys[1] != shape:
            keys = (poly, shape, {})
            _SPLIT_KEYS[id(poly)] = keys
        known = keys[2]
        for monom in values.keys() - known.keys():  # each monomial split once per polynomial
            if any(stray_of(monom)):
                raise AssertionError(f"the series still depends on one of {stray}")
            known[monom] = (first_of(monom), second_of(monom))
        split.append({known[monom]: coeff for monom, coeff in values.items()})
    needed = _with_divisors({mz for component in split for mz, _ in component})
    if needed:  # register the divisors as zero terms of the first component
        present = {mz for component in split for mz, _ in component}
        zero0 = (0,) * len(second)
        target = split[0] if split else {}
        for m in needed - present:
            target[m, zero0] = 0.0
    return PolynomialMap(split)
