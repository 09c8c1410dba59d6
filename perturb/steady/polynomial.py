"""Polynomials compiled to arrays: values and gradients of many rows at once, in microseconds.

The displacement function of a driven system and the harmonic coefficients of its series are
polynomials in the amplitudes, the parameters and ε (expanded by the construction). Written as
one table of exponents (a row per monomial, a column per variable) and a matrix of float
coefficients (a row per polynomial), their values at x are ``C @ prod(x ** E)`` and their
gradients come from the same table, one power lower: no code is generated, nothing is
differentiated symbolically, and a row of hundreds of terms costs tens of microseconds.
:func:`compile_polynomials` returns None for rows that are not polynomial in the variables with
numeric coefficients (the caller then lambdifies).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import GENERATED_MAX_TERMS

__all__ = ["CompiledPolynomials", "compile_polynomials"]


@frozen
class CompiledPolynomials:
    """Rows of polynomials in ``k`` variables as an exponent table and a coefficient matrix.

    Attributes
    ----------
    names : tuple of str
        The variables, in the order of the columns of ``exponents``.
    exponents : ndarray of int, shape (T, k)
        One monomial a row.
    coefficients : ndarray of float, shape (rows, T)
    """

    names: tuple = field(converter=tuple)
    exponents: np.ndarray = field(eq=False)
    coefficients: np.ndarray = field(eq=False)

    @property
    def degree(self) -> int:
        return int(self.exponents.max(initial=0))

    def values(self, x) -> np.ndarray:
        """The rows at ``x`` (shape (k,) or (P, k)): shape (rows,) or (P, rows)."""
        x = np.asarray(x, dtype=float)
        monomials = np.prod(x[..., None, :] ** self.exponents, axis=-1)  # (..., T)
        return monomials @ self.coefficients.T

    def values_and_gradient(self, x) -> tuple[np.ndarray, np.ndarray]:
        """The rows and their gradients at one point ``x`` (shape (k,)): (rows,), (rows, k)."""
        x = np.asarray(x, dtype=float)
        e = self.exponents
        factors = x**e  # (T, k)
        lower = e * x ** np.maximum(e - 1, 0)  # d/dx_j of x_j^e_j (0 where e_j = 0)
        # the product of the other factors by prefix and suffix products (no division by x_j)
        prefix = np.ones_like(factors)
        suffix = np.ones_like(factors)
        np.cumprod(factors[:, :-1], axis=1, out=prefix[:, 1:])
        np.cumprod(factors[:, :0:-1], axis=1, out=suffix[:, -2::-1])
        monomials = prefix[:, -1] * factors[:, -1]
        return self.coefficients @ monomials, self.coefficients @ (prefix * suffix * lower)

    def function(self):
        """``f(x) -> (values, gradient)`` at one point, as generated Python arithmetic on floats.

        Small rows (at most ``GENERATED_MAX_TERMS`` monomial-variable pairs) are written out as
        straight-line code: on a handful of unknowns Python's float arithmetic beats numpy's
        per-call cost several times. Larger ones use :meth:`values_and_gradient`.
        """
        e, c = self.exponents, self.coefficients
        k = e.shape[1]
        if e.shape[0] * k > GENERATED_MAX_TERMS:
            return self.values_and_gradient
        return _generate(e, c)

    def specialized(self, fixed: dict, moving: dict, name: str = "lam") -> CompiledPolynomials:
        """The rows with the variables of ``fixed`` set to numbers and those of ``moving`` on a
        line, ``v = v0 + dv * lam`` (``moving``: name -> (v0, dv)), in the remaining variables
        and ``lam`` (last): the binomial expansion done on the arrays.

        Examples
        --------
        >>> import sympy as sp
        >>> x, p, q = sp.symbols("x p q")
        >>> compiled = compile_polynomials([x * p**2 + q], [x, p, q])
        >>> line = compiled.specialized({"q": 1.0}, {"p": (1.0, 2.0)})
        >>> line.names, line.values([3.0, 0.5]).tolist()  # x (1 + 2 lam)^2 + 1 at x = 3, lam = 0.5
        (('x', 'lam'), [13.0])
        """
        from math import comb

        unknown = [n for n in self.names if n not in fixed and n not in moving]
        keep = [self.names.index(n) for n in unknown]
        terms: dict[tuple, np.ndarray] = {}
        for t, row in enumerate(self.exponents):
            scale = 1.0
            for n, v in fixed.items():
                if n in self.names:
                    scale *= _power(v, int(row[self.names.index(n)]))
            if scale == 0.0:
                continue
            # the polynomial in lam of this monomial's moving factors
            in_lam = np.array([scale])
            for n, (v0, dv) in moving.items():
                e = int(row[self.names.index(n)])
                factor = np.array([comb(e, i) * _power(v0, e - i) * _power(dv, i)
                                   for i in range(e + 1)])  # fmt: skip
                in_lam = np.convolve(in_lam, factor)
            base = tuple(int(row[j]) for j in keep)
            for i, c in enumerate(in_lam):
                if c != 0.0:
                    key = (*base, i)
                    add = self.coefficients[:, t] * c
                    terms[key] = terms[key] + add if key in terms else add
        exponents = np.array(list(terms) or [(0,) * (len(keep) + 1)], dtype=np.int64)
        coefficients = (
            np.array(list(terms.values())).T if terms else np.zeros((len(self.coefficients), 1))
        )
        if not np.all(np.isfinite(coefficients)):
            raise OverflowError(
                "the amplitude equations' coefficients are past the floats at these values "
                f"({', '.join(f'{n} = {float(v):g}' for n, v in fixed.items())})"
            )
        return CompiledPolynomials((*unknown, name), exponents, coefficients)


def _power(value, exponent: int) -> float:
    """``value ** exponent`` in floats, infinite past them (Python's ``**`` raises there: eps =
    1e308 at order 3), so that the check of the coefficients says so in words."""
    try:
        return float(value) ** exponent
    except OverflowError:
        return math.copysign(math.inf, float(value)) if exponent % 2 else math.inf


def compile_polynomials(rows, variables) -> CompiledPolynomials | None:
    """``rows`` (sympy expressions) as :class:`CompiledPolynomials` in ``variables``, or None when
    a row is not a polynomial in them with numeric coefficients.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> compiled = compile_polynomials([x**2 * y + 3, sp.pi * y], [x, y])
    >>> compiled.values([2.0, 1.0]).round(6).tolist()
    [7.0, 3.141593]
    >>> compiled.values_and_gradient([2.0, 1.0])[1].round(6).tolist()
    [[4.0, 4.0], [0.0, 3.141593]]
    """
    variables = list(variables)
    monomials: dict[tuple, int] = {}
    entries = []
    for r, row in enumerate(rows):
        try:
            poly = sp.Poly(sp.expand(row), *variables)
        except sp.PolynomialError:
            return None
        for monomial, c in poly.terms():
            if not c.is_number:
                return None
            value = complex(c)
            if value.imag != 0:
                return None
            index = monomials.setdefault(monomial, len(monomials))
            entries.append((r, index, value.real))
    exponents = np.zeros((max(len(monomials), 1), len(variables)), dtype=np.int64)
    for monomial, index in monomials.items():
        exponents[index] = monomial
    coefficients = np.zeros((len(rows), exponents.shape[0]))
    for r, index, value in entries:
        coefficients[r, index] += value
    return CompiledPolynomials(tuple(v.name for v in variables), exponents, coefficients)


def _generate(e: np.ndarray, c: np.ndarray):
    """Straight-line Python for the rows and their gradient (see ``function``)."""
    terms, k = e.shape
    lines = [
        "def evaluate(x):",
        "    " + "".join(f"x{j}, " for j in range(k)) + "= list(map(float, x))",
    ]
    for j in range(k):
        for power in range(2, int(e[:, j].max(initial=0)) + 1):
            previous = f"x{j}" if power == 2 else f"x{j}_{power - 1}"
            lines.append(f"    x{j}_{power} = {previous} * x{j}")

    def power(j, p):
        return f"x{j}" if p == 1 else f"x{j}_{p}"

    for t in range(terms):
        factors = [power(j, int(p)) for j, p in enumerate(e[t]) if p > 0]
        lines.append(f"    m{t} = {' * '.join(factors) or '1.0'}")
    rows = []
    for i in range(c.shape[0]):
        parts = [f"{float(c[i, t])!r} * m{t}" for t in range(terms) if c[i, t] != 0.0]
        rows.append(" + ".join(parts) or "0.0")
    gradient = []
    for i in range(c.shape[0]):
        entries = []
        for j in range(k):
            parts = []
            for t in range(terms):
                p = int(e[t, j])
                if p == 0 or c[i, t] == 0.0:
                    continue
                factors = [power(q, int(r)) for q, r in enumerate(e[t]) if r > 0 and q != j]
                if p > 1:
                    factors.append(power(j, p - 1))
                parts.append(" * ".join([repr(float(c[i, t] * p)), *factors]))
            entries.append(" + ".join(parts) or "0.0")
        gradient.append("[" + ", ".join(entries) + "]")
    lines.append(f"    return array([{', '.join(rows)}]), array([{', '.join(gradient)}])")
    # a coefficient past the floats prints as inf or nan (eps = 1e308): kept as such, the values
    # then say so and the continuation stops with its reason
    namespace = {"array": np.array, "inf": math.inf, "nan": math.nan}
    exec(compile("\n".join(lines), "<compiled polynomials>", "exec"), namespace)  # noqa: S102
    return namespace["evaluate"]
