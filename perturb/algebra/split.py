"""Cutting a polynomial system into smaller ones before it is solved, without losing a real root.

A system's real roots are the union of the real roots of its *pieces*; each cut is exact, each
piece is disjoint from the others (a later alternative carries the earlier ones as "non-zero"),
so the roots of the pieces add up to the roots of the system, none counted twice:

1. **Linear pivots.** An unknown that appears linearly with a constant coefficient is solved for
   and put in: short ones (``v = c``, ``v = c·w + d``) at once, the others (the frequency
   correction Ω₁) in each leaf before it is solved (msolve on the chain of 6: 13 s → 2 s).
2. **Factors, read over the reals.** An equation (or a member of the ideal the caller names, see
   :func:`frequency_eliminants`) that factors over ℚ splits the piece into one piece per factor.
   A factor that is a positive semi-definite quadratic (a sum of squares, found by exact
   Gaussian elimination of its Gram matrix) vanishes at a real point only where each of its
   squared linear forms does, so it becomes linear equations; one with a positive constant part
   has no real zero and is dropped. A factor known to be non-zero on the piece is dropped.
3. **Sign symmetry.** If every equation is even or odd in a set S of unknowns (time reversal
   flips every sine amplitude), the roots are those with S = 0 (a smaller system) and, for each
   k, those whose first non-zero member of S is the k-th one.

The cuts are tried in the order symmetry, factors; what is left is a *leaf*, solved by msolve
or the exact route (:mod:`perturb.algebra.certified`), with its non-zero conditions imposed by
one more unknown (Rabinowitsch: ``t * prod(nonzero) = 1``).
"""

from __future__ import annotations

import time

import sympy as sp
from attrs import evolve, field, frozen

from perturb._defaults import SHORT_PIVOT, SPLIT_MAX_PIECES

__all__ = ["Piece", "cut", "frequency_eliminants", "psd_linear_forms", "sign_symmetry"]


class BudgetSpent(Exception):
    """The deadline passed while the system was being cut."""


@frozen
class Piece:
    """Part of a system's solution set: equations, unknowns, what is known not to vanish.

    Attributes
    ----------
    polys : tuple of sympy.Expr
        The equations ``p = 0`` (expanded, none zero).
    unknowns : tuple of sympy.Symbol
        The unknowns still open.
    nonzero : tuple of sympy.Expr
        Polynomials that do not vanish on the piece (the earlier alternatives of a cut).
    members : tuple of sympy.Expr
        Members of the ideal used for cutting only (they vanish wherever ``polys`` do).
    eliminated : tuple of (sympy.Symbol, sympy.Expr)
        Unknowns solved for, in order; each expression is in the unknowns open after it.
    path : tuple of str
        The cuts that led here: the certificate of the piece.
    """

    polys: tuple = field(converter=tuple)
    unknowns: tuple = field(converter=tuple)
    nonzero: tuple = field(default=(), converter=tuple)
    members: tuple = field(default=(), converter=tuple)
    eliminated: tuple = field(default=(), converter=tuple)
    path: tuple = field(default=(), converter=tuple)

    def put(self, var, value, note: str | None = None) -> Piece:
        """The piece with ``var = value`` put in (``value`` free of ``var``)."""
        sub = {var: value}

        def put_in(polys):
            return [sp.expand(p.xreplace(sub)) for p in polys]

        return evolve(
            self,
            polys=put_in(self.polys),
            unknowns=[u for u in self.unknowns if u != var],
            nonzero=put_in(self.nonzero),
            members=put_in(self.members),
            eliminated=[*self.eliminated, (var, value)],
            path=self.path if note is None else [*self.path, note],
        )


def frequency_eliminants(eqs, unknowns, pairs) -> list:
    """Members of the ideal free of the frequency correction: each coordinate's balance and sums.

    ``w`` is an unknown that every equation contains at most linearly (the frequency correction
    Ω of amplitude equations). For each pair ``(u, v)`` of ``pairs`` (a coordinate's cosine and
    sine amplitudes) whose two equations have ``w``-coefficients ``c·u`` and ``c'·v`` with
    constants c, c', the combination ``c'·v·E_u − c·u·E_v`` is free of w (the coordinate's
    averaged power balance); sums of consecutive ones are returned too (for a chain they are the
    power carried by one spring, and factor). Every member is a combination of ``eqs`` with
    polynomial cofactors, so it vanishes wherever they do.

    Examples
    --------
    >>> import sympy as sp
    >>> w, a, b = sp.symbols("w a b")
    >>> frequency_eliminants([2*w*a + a**3 + a*b**2 - b, -2*w*b - b**3 - a**2*b], [w, a, b], [(a, b)])
    [2*b**2]
    """
    unknowns = list(unknowns)
    eqs = [sp.expand(e) for e in eqs]
    linear = [
        w
        for w in unknowns
        if all(sp.degree(e, w) <= 1 and not (e.coeff(w, 1).free_symbols & {w}) for e in eqs)
        and any(sp.degree(e, w) == 1 for e in eqs)
    ]
    if not linear:
        return []
    w = linear[0]
    balances = []
    for u, v in pairs:
        found = {}
        for e in eqs:
            c = e.coeff(w, 1)
            for s in (u, v):
                ratio = sp.cancel(c / s) if s != 0 else None
                if ratio is not None and ratio.is_number and ratio != 0 and s not in found:
                    found[s] = (e, ratio)
        if u in found and v in found:
            (eu, cu), (ev, cv) = found[u], found[v]
            balance = sp.expand(cv * v * eu - cu * u * ev)
            if balance != 0:
                balances.append(balance)
    members = list(balances)
    for start in range(len(balances)):
        for stop in range(start + 2, len(balances) + 1):
            members.append(sp.expand(sum(balances[start:stop])))
    return [m for m in members if m != 0]


def sign_symmetry(polys, unknowns) -> tuple:
    """Unknowns S such that every polynomial is even or odd in S jointly (empty: none).

    Found as the null space over GF(2) of the differences of the exponent vectors inside each
    polynomial; of its basis the vector with most unknowns is returned.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> sign_symmetry([x**2 + y**2 - 1, x*y - y], [x, y])
    (y,)
    """
    unknowns = list(unknowns)
    rows = []
    for p in polys:
        monomials = sp.Poly(p, *unknowns).monoms()
        first = monomials[0]
        for m in monomials[1:]:
            bits = sum(1 << i for i, (e, f) in enumerate(zip(m, first, strict=True)) if (e - f) % 2)
            if bits:
                rows.append(bits)
    basis = _gf2_nullspace(rows, len(unknowns))
    if not basis:
        return ()
    best = max(basis, key=lambda bits: bin(bits).count("1"))
    return tuple(u for i, u in enumerate(unknowns) if best >> i & 1)


def _gf2_nullspace(rows: list[int], n: int) -> list[int]:
    """A basis of ``{s : popcount(row & s) even for every row}`` (bit sets of ``n`` bits)."""
    pivots: dict[int, int] = {}  # pivot column -> reduced row
    for row in rows:
        for col, prow in pivots.items():
            if row >> col & 1:
                row ^= prow
        if not row:
            continue
        col = row.bit_length() - 1
        for other in list(pivots):
            if pivots[other] >> col & 1:
                pivots[other] ^= row
        pivots[col] = row
    free = [c for c in range(n) if c not in pivots]
    basis = []
    for f in free:
        s = 1 << f
        for col, prow in pivots.items():
            if prow >> f & 1:
                s |= 1 << col
        basis.append(s)
    return basis


def psd_linear_forms(quadratic, unknowns) -> list | None:
    """For a quadratic ``q >= 0`` on ℝⁿ: affine forms whose common zeros are q's real zeros.

    ``q = [1, x]ᵀ G [1, x]`` with G its Gram matrix; exact symmetric Gaussian elimination writes
    ``q = Σ dᵢ ℓᵢ²`` with every dᵢ > 0 when G is positive semi-definite. Returns None when it is
    not (q changes sign: no conclusion), ``[1]`` when q has no real zero (a form is a non-zero
    constant), else the forms.

    Examples
    --------
    >>> import sympy as sp
    >>> a, b = sp.symbols("a b")
    >>> psd_linear_forms((a - 1)**2 + b**2, [a, b])
    [a - 1, b]
    >>> psd_linear_forms(a**2 + 1, [a]), psd_linear_forms(a*b, [a, b])
    ([1], None)
    """
    poly = sp.Poly(quadratic, *unknowns)
    if poly.total_degree() != 2:
        return None
    x = [sp.S.One, *unknowns]
    n = len(x)
    gram = [[sp.S.Zero] * n for _ in range(n)]
    for monomial, c in poly.terms():
        idx = [i + 1 for i, e in enumerate(monomial) for _ in range(e)]
        i, j = ([0, 0] + idx)[-2:]  # x_i x_j, x_i (with the constant 1) or the constant
        if i == j:
            gram[i][i] += c
        else:
            gram[i][j] += sp.Rational(c) / 2
            gram[j][i] += sp.Rational(c) / 2
    # eliminate the unknowns first, the constant coordinate (index 0) last
    order = [*range(1, n), 0]
    g = [[gram[r][c] for c in order] for r in order]
    forms = []
    for k in range(n):
        if g[k][k] < 0:
            return None
        if g[k][k] == 0:
            if any(g[k][j] != 0 for j in range(k, n)):
                return None  # a zero pivot with a non-zero row: indefinite
            continue
        form = sum(g[k][j] / g[k][k] * x[order[j]] for j in range(k, n))
        forms.append(sp.expand(form))
        pivot_row = g[k][:]
        for r in range(k + 1, n):
            factor = pivot_row[r] / pivot_row[k]
            for c in range(k, n):
                g[r][c] -= factor * pivot_row[c]
    if any(f.is_number for f in forms):
        return [sp.S.One]
    return forms


def _same_up_to_constant(f, g) -> bool:
    """Whether ``f = c·g`` for a number c != 0 (same monomials, proportional coefficients)."""
    gens = sorted(sp.sympify(f).free_symbols | sp.sympify(g).free_symbols, key=str)
    if not gens:
        return sp.sympify(g) != 0 and sp.sympify(f) != 0
    p, q = sp.Poly(f, *gens), sp.Poly(g, *gens)
    if p.is_zero or q.is_zero or p.monoms() != q.monoms():
        return False
    ratio = p.LC() / q.LC()
    return all(a == ratio * b for a, b in zip(p.coeffs(), q.coeffs(), strict=True))


def _real_alternatives(poly, piece: Piece):
    """How ``poly = 0`` splits over the reals: a list of alternatives, each a list of equations.

    None: no split (one irreducible factor that is not a sum of squares). ``[]``: no real zero
    on the piece (every factor is non-zero there).
    """
    _, factors = sp.factor_list(poly, *piece.unknowns)
    alternatives = []
    for factor, _multiplicity in factors:
        if not factor.free_symbols & set(piece.unknowns):
            continue
        if any(_same_up_to_constant(factor, nz) for nz in piece.nonzero):
            continue
        forms = (
            psd_linear_forms(factor, piece.unknowns)
            if sp.Poly(factor, *piece.unknowns).total_degree() == 2
            else None
        )
        if forms == [sp.S.One]:
            continue  # a sum of squares plus a positive constant: no real zero
        alternatives.append((factor, forms))
    if (
        len(alternatives) == 1
        and alternatives[0][1] is None
        and _same_up_to_constant(alternatives[0][0], poly)
    ):
        return None
    return alternatives


def _normalise(piece: Piece) -> Piece | None:
    """Short linear pivots put in, zeros dropped; None when the piece is empty (proved).

    Only pivots whose value has at most :data:`SHORT_PIVOT` terms (``v = c``, ``v = c·w + d``)
    are put in while cutting; the others (the frequency correction) wait for the leaf, where
    :func:`~perturb.algebra.triangular.eliminate_linear` puts them in once.
    """
    while True:
        polys = [p for p in (sp.expand(q) for q in piece.polys) if p != 0]
        if any(p.is_number for p in polys):
            return None
        nonzero = [sp.expand(q) for q in piece.nonzero]
        if any(q == 0 for q in nonzero):
            return None
        nonzero = [q for q in nonzero if not q.is_number]
        members = [m for m in (sp.expand(q) for q in piece.members) if m != 0 and not m.is_number]
        piece = evolve(piece, polys=polys, nonzero=nonzero, members=members)
        pivot = _short_pivot(polys, piece.unknowns)
        if pivot is None:
            return piece
        piece = piece.put(*pivot)


def _short_pivot(polys: list, unknowns) -> tuple | None:
    """``(v, value)`` from an equation ``c·v + rest = 0`` with c constant and a short rest."""
    for p in sorted(polys, key=lambda q: len(sp.Add.make_args(q))):
        terms = sp.Add.make_args(p)
        if len(terms) > SHORT_PIVOT + 1:
            break
        for var in unknowns:
            if sp.degree(p, var) != 1:
                continue
            coefficient = p.coeff(var, 1)
            if coefficient.is_number:
                return var, sp.expand(-(p - coefficient * var) / coefficient)
    return None


def _cut_by_factors(piece: Piece) -> list[Piece] | None:
    """Pieces from the first equation or member that splits over the reals (None: none does)."""
    candidates = sorted(
        [(m, True) for m in piece.members] + [(p, False) for p in piece.polys],
        key=lambda item: len(sp.Add.make_args(item[0])),
    )
    for poly, is_member in candidates:
        alternatives = _real_alternatives(poly, piece)
        if alternatives is None:
            continue
        rest = [p for p in piece.polys if p is not poly]
        members = [m for m in piece.members if m is not poly]
        pieces = []
        earlier = []
        for factor, forms in alternatives:
            added = forms if forms is not None else [factor]
            how = (
                f"sum of squares {factor} = 0: {', '.join(map(str, forms))} = 0"
                if forms is not None
                else f"factor {factor} = 0"
            )
            pieces.append(
                evolve(
                    piece,
                    polys=[*rest, *added],
                    members=members,
                    nonzero=[*piece.nonzero, *earlier],
                    path=[*piece.path, how + (" (of an ideal member)" if is_member else "")],
                )
            )
            earlier.append(factor)
        return pieces
    return None


def _cut_by_symmetry(piece: Piece) -> list[Piece] | None:
    flipped = sign_symmetry(piece.polys, piece.unknowns) if piece.polys else ()
    if not flipped or any(q.free_symbols & set(flipped) for q in piece.nonzero):
        return None  # none, or already cut by it (a member of S is known non-zero)
    names = ", ".join(map(str, flipped))
    pieces = [
        _put_zeros(piece, flipped, f"sign symmetry in ({names}): all zero"),
    ]
    for k, s in enumerate(flipped):
        part = _put_zeros(piece, flipped[:k], f"sign symmetry in ({names}): {s} first non-zero")
        pieces.append(evolve(part, nonzero=[*part.nonzero, s]))
    return pieces


def _put_zeros(piece: Piece, variables, note: str) -> Piece:
    for var in variables:
        piece = piece.put(var, sp.S.Zero)
    return evolve(piece, path=[*piece.path, note])


def cut(eqs, unknowns, *, members=(), deadline: float | None = None) -> list[Piece]:
    """The leaves of the cuts of ``eqs = 0``: disjoint pieces whose real roots are the system's.

    Parameters
    ----------
    eqs : sequence of sympy.Expr
        Polynomials with rational coefficients.
    unknowns : sequence of sympy.Symbol
    members : sequence of sympy.Expr
        Members of the ideal of ``eqs`` (combinations with polynomial cofactors), used for cuts.
    deadline : float, optional
        ``time.monotonic()`` past which :class:`BudgetSpent` is raised.

    Returns
    -------
    list of Piece
        Empty when every piece was proved to have no real root.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> [p.path[-1] for p in cut([x*y - y, x**2 + y**2 - 4], [x, y])]
    ['factor x - 2 = 0', 'factor x + 2 = 0', 'factor x - 1 = 0']
    """
    root = Piece(polys=[sp.expand(e) for e in eqs], unknowns=list(unknowns), members=members)
    stack, leaves = [root], []
    while stack:
        if deadline is not None and time.monotonic() > deadline:
            raise BudgetSpent
        piece = _normalise(stack.pop())
        if piece is None:
            continue
        if len(leaves) + len(stack) >= SPLIT_MAX_PIECES:
            leaves.append(piece)
            continue
        pieces = _cut_by_symmetry(piece)
        if pieces is None:
            pieces = _cut_by_factors(piece)
        if pieces is None:
            leaves.append(piece)
        else:
            stack.extend(reversed(pieces))
    return leaves
