"""Families of a homogeneous system: the amplitude scaled out, every family a continuum in it.

When no amplitude is fixed, the amplitude equations of a system whose nonlinearity is
homogeneous have no isolated roots: every family is a continuum in its amplitude. Two facts turn
that into finitely many certified roots and an exact continuum.

1. **Weighted homogeneity of the amplitude equations.** Let every generating amplitude have
   weight 1. If the other unknowns (the frequency corrections :math:`\\Omega_k`) can be given
   weights :math:`w_j` such that every equation is weighted-homogeneous, the roots are invariant
   under :math:`a \\mapsto \\lambda a`, :math:`\\Omega_k \\mapsto \\lambda^{w}\\Omega_k` (cubic
   springs: :math:`\\Omega_1` has weight 2). On a pass whose phase amplitude p is non-zero
   (:mod:`perturb.method.families`), the roots are then those of the equations with p = 1 —
   finitely many for a system whose families are lines through the origin, each certified
   (:func:`perturb.algebra.certified_real_roots`) — scaled back: :math:`u = r_u\\,p^{w_u}`.
   Exact zeros stay zeros, so a family on which the nonlinearity vanishes identically (the
   in-phase mode of a chain whose only nonlinearity is in its springs: :math:`\\Omega_1 = 0` at
   every amplitude) is found as any other (:func:`projective_components`).
2. **Scaling of the motion.** If the right-hand side is :math:`\\sum_k \\varepsilon^k f_k` with
   :math:`f_k` homogeneous of degree :math:`1 + k(d-1)` in the state (one d), then
   :math:`x(t; A, \\varepsilon) = A\\,\\tilde x(t; 1, \\varepsilon A^{d-1})`: a family carried at
   amplitude 1 gives the whole continuum, its term of order k times :math:`A^{1+k(d-1)}` and its
   frequency correction :math:`\\Omega_k` times :math:`A^{k(d-1)}` (:func:`scaling_degree`,
   :func:`rescaled`) — exactly, whatever the order, and as fast as one numeric amplitude.
3. **Exact solutions.** Where the right-hand side vanishes identically on the generating solution
   at the reference frequency (a linear normal mode on which the nonlinear springs do not stretch,
   an invariant subspace), the generating solution is an exact periodic solution: every later
   term and frequency correction is zero, at any order. The order-by-order construction cannot
   see it when the neighbouring motions are degenerate (the corrections of such a mode are left
   open); :func:`exact_on` proves it (the right-hand side reduced to zero modulo
   cos² + sin² = 1) and :func:`exact_solution` writes it.
"""

from __future__ import annotations

from fractions import Fraction

import attrs
import sympy as sp

from perturb.system import EPS

__all__ = [
    "exact_modes",
    "exact_on",
    "exact_or",
    "exact_solution",
    "is_exact",
    "projective_components",
    "quasi_weights",
    "rescaled",
    "scaling_degree",
]


def quasi_weights(eqs, unknowns, amplitudes) -> dict | None:
    """Weights making every equation weighted-homogeneous, amplitudes of weight 1; None if none.

    The weights of the other unknowns are the solution of the linear conditions that two
    monomials of one equation have the same weighted degree; it must be unique and made of
    non-negative integers.

    Examples
    --------
    >>> import sympy as sp
    >>> w, a, b = sp.symbols("Omega1 a b")
    >>> quasi_weights([2*w*a - a**3 - a*b**2, 2*w*b - b**3], [w, a, b], [a, b])
    {Omega1: 2, a: 1, b: 1}
    >>> quasi_weights([w*a - a**3 + a], [w, a], [a]) is None
    True
    """
    unknowns = list(unknowns)
    others = [u for u in unknowns if u not in set(amplitudes)]
    index = {u: i for i, u in enumerate(unknowns)}
    rows, rhs = [], []
    for eq in eqs:
        eq = sp.expand(eq)
        if eq == 0:
            continue
        monomials = sp.Poly(eq, *unknowns).monoms()
        first = monomials[0]
        for m in monomials[1:]:
            amplitude_degree = sum(m[index[a]] - first[index[a]] for a in amplitudes)
            row = [m[index[o]] - first[index[o]] for o in others]
            if not any(row):
                if amplitude_degree:
                    return None  # two monomials of different amplitude degree, no other unknown
                continue
            rows.append(row)
            rhs.append(-amplitude_degree)
    weights = {a: 1 for a in amplitudes}
    if not others:
        return weights
    if not rows:
        return None  # the other unknowns appear in no constraint: nothing fixes their weight
    matrix = sp.Matrix(rows)
    if matrix.rank() < len(others):
        return None
    solution = matrix.solve_least_squares(sp.Matrix(rhs))
    if matrix * solution != sp.Matrix(rhs):
        return None
    for other, value in zip(others, solution, strict=True):
        if not (value.is_Integer and value >= 0):
            return None
        weights[other] = int(value)
    return {u: weights[u] for u in unknowns if u in weights}


def projective_components(eqs, unknowns, scale, amplitudes, seconds: float, pairs=()):
    """The roots of weighted-homogeneous amplitude equations on which ``scale`` is not zero, as
    continua in ``scale`` (see the module notes, 1); None when the route does not apply (not
    weighted-homogeneous, parameters left in the coefficients, a continuum left at scale = 1).

    Parameters
    ----------
    eqs : sequence of sympy.Expr
    unknowns : sequence of sympy.Symbol
    scale : sympy.Symbol
        The amplitude that is not zero (the pass's phase amplitude), one of ``unknowns``.
    amplitudes : collection of sympy.Symbol
        The generating amplitudes (weight 1).
    seconds : float
    pairs : sequence of (sympy.Symbol, sympy.Symbol)
        Each coordinate's (cosine, sine) amplitudes, for the certified solver's cuts.

    Returns
    -------
    list of Component or None
        ``values`` ``{u: r_u * scale**w_u}``, ``free`` ``(scale,)``; a :class:`Partial` list when
        a piece is a continuum at scale = 1 (its caller writes that piece another way).

    Raises
    ------
    TimeoutError
        When the certified solver's budget is spent.

    Examples
    --------
    The free-ended chain of three with cubic springs, pass x1 (its amplitude a non-zero):

    >>> import sympy as sp
    >>> w, a1, a2, a3 = sp.symbols("Omega1 a1 a2 a3")
    >>> d1, d2 = a1 - a2, a2 - a3
    >>> eqs = [8*w*a1 - 3*d1**3, 8*w*a2 + 3*d1**3 - 3*d2**3, 8*w*a3 + 3*d2**3]
    >>> found = projective_components(eqs, [w, a1, a2, a3], a1, [a1, a2, a3], 30.0)
    >>> sorted(str(c.values) for c in found)  # doctest: +NORMALIZE_WHITESPACE
    ['{Omega1: 0, a2: a1, a3: a1}', '{Omega1: 3*a1**2/8, a2: 0, a3: -a1}',
     '{Omega1: 81*a1**2/8, a2: -2*a1, a3: a1}']
    """
    from perturb.algebra.certified import certified_real_roots
    from perturb.algebra.rootset import RootStatus
    from perturb.errors import InvalidSystemError
    from perturb.method.component import Component
    from perturb.method.exact import rational_form

    unknowns = list(unknowns)
    if scale not in unknowns:
        return None
    eqs = [rational_form(e) for e in eqs]
    if any(sp.sympify(e).free_symbols - set(unknowns) for e in eqs):
        return None
    weights = quasi_weights(eqs, unknowns, [a for a in amplitudes if a in set(unknowns)])
    if weights is None:
        return None
    rest = [u for u in unknowns if u != scale]
    fixed = [sp.expand(e.xreplace({scale: 1})) for e in eqs]
    fixed = [e for e in fixed if e != 0]
    if any(e.is_number for e in fixed):
        return []  # a non-zero constant: no root with this amplitude non-zero
    try:
        found = certified_real_roots(
            fixed, rest, seconds=seconds, pairs=[p for p in pairs if scale not in p]
        )
    except InvalidSystemError:
        return None
    if found.status is RootStatus.NO_REAL_ROOT:
        return []
    if found.status is RootStatus.BUDGET_EXCEEDED:
        raise TimeoutError(found.message)
    if found.status not in (RootStatus.SOLVED, RootStatus.POSITIVE_DIMENSIONAL):
        return None
    out = []
    for root in found.numbers():
        values = {u: sp.expand(root[u] * scale ** weights.get(u, 0)) for u in rest}
        out.append(Component(values=values, free=(scale,)))
    if found.status is RootStatus.POSITIVE_DIMENSIONAL:  # a family of several amplitudes too
        return Partial(out)
    return out


class Partial(list):
    """The isolated roots of the equations at scale = 1 when another piece of them is a continuum
    (a family with more than one free amplitude): those are for the Groebner parts to write."""


def _frequency_sought(system) -> bool:
    """Whether the system's frequency is sought, not given by a drive: an amplitude can then be
    scaled out (the one question this module asks of the frame)."""
    return not system.frame.frequency_given


def scaling_degree(system) -> int | None:
    """d when the right-hand side is :math:`\\sum_k \\varepsilon^k f_k` with every :math:`f_k`
    homogeneous of degree :math:`1 + k(d - 1)` in the state (module notes, 2); None otherwise
    (a linear term at order ε, a forcing, initial values or frequencies that move).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> x, y, u, v = sp.symbols("x y u v")
    >>> chain = QuasilinearSystem([x, y], [u, v], [1, 1], [-EPS*(x - y)**3, EPS*(x - y)**3])
    >>> scaling_degree(chain)
    3
    >>> scaling_degree(QuasilinearSystem([x], [u], [1], [-EPS*x**3 - EPS*x]))
    """
    if not _frequency_sought(system) or system.initial_values:  # scaling needs a free frequency
        return None
    if any(sp.sympify(w).free_symbols for w in system.frequencies):
        return None
    state = list(system.state_symbols)
    degree = None
    for f in system.rhs:
        f = sp.expand(f)
        if f == 0:
            continue
        if not f.is_polynomial(*state, EPS):
            return None
        poly = sp.Poly(f, EPS, *state)
        for (k, *m), _ in poly.terms():
            if k == 0:
                return None  # an O(1) term: not quasilinear in this form
            total = sum(m)
            if total == 1:
                return None  # a linear term at order eps: the frequencies move
            d = Fraction(total - 1, k) + 1
            if d.denominator != 1 or (degree is not None and d != degree):
                return None
            degree = d
    return None if degree is None else int(degree)


def rescaled(solution, amplitude: sp.Symbol, degree: int, note: str):
    """The solution carried at amplitude 1 as the continuum in ``amplitude`` (module notes, 2).

    Every term of order k is multiplied by :math:`A^{1+k(d-1)}`, every frequency correction
    :math:`\\Omega_k` by :math:`A^{k(d-1)}`, the generating amplitudes by A; ``amplitude`` becomes
    a parameter of the solution's system. The construction's steps, made at amplitude 1, are not
    kept (``note`` says so in the message).
    """
    step = degree - 1
    terms = tuple(
        tuple(
            t.map(lambda c, k=k: sp.expand(c * amplitude ** (1 + k * step)))
            for k, t in enumerate(row)
        )
        for row in solution.terms
    )
    frequency = tuple(
        sp.expand(w * amplitude ** (k * step)) for k, w in enumerate(solution.frequency)
    )
    generating = attrs.evolve(
        solution.generating,
        cos_amplitudes=tuple(
            sp.expand(sp.sympify(a) * amplitude) for a in solution.generating.cos_amplitudes
        ),
        sin_amplitudes=tuple(
            sp.expand(sp.sympify(b) * amplitude) for b in solution.generating.sin_amplitudes
        ),
    )
    deviations = {
        name: tuple(
            sp.expand(sp.sympify(v) * amplitude ** (1 + (k + 1) * step)) for k, v in enumerate(vs)
        )
        for name, vs in solution.deviations.items()
    }
    system = attrs.evolve(solution.system, parameters=(*solution.system.parameters, amplitude))
    message = "; ".join(filter(None, [solution.message, note]))
    return attrs.evolve(
        solution,
        system=system,
        terms=terms,
        frequency=frequency,
        generating=generating,
        deviations=deviations,
        steps=(),
        dependent_residuals={},
        message=message,
    )


def exact_on(system, generating) -> bool:
    """Whether the generating solution (numeric amplitudes) at the reference frequency solves the
    system exactly: every right-hand side, with :math:`x_i = a_i\\cos m_i s + b_i\\sin m_i s` and
    :math:`\\dot x_i = \\omega_{ref}\\,dx_i/ds`, is zero for every s and ε (proved: a polynomial
    in c = cos s, t = sin s reduced modulo :math:`c^2 + t^2 - 1`).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from perturb.steps import GeneratingSolution
    >>> x, y, u, v = sp.symbols("x y u v")
    >>> pair = QuasilinearSystem([x, y], [u, v], [1, 1], [-EPS*(x - y)**3, EPS*(x - y)**3])
    >>> def on(a, b):
    ...     return exact_on(pair, GeneratingSolution(("x", "y"), (1, 1), (a, b), (0, 0), "x", 1))
    >>> on(1, 1), on(1, -1)
    (True, False)
    """
    if not _frequency_sought(system):
        return False
    c, t = sp.Dummy("c"), sp.Dummy("t")
    amplitudes = [*generating.cos_amplitudes, *generating.sin_amplitudes]
    if any(sp.sympify(a).free_symbols for a in amplitudes):
        return False
    if any(not (sp.sympify(a).is_Rational or sp.sympify(a).is_algebraic) for a in amplitudes):
        return False  # floats: no proof
    w = sp.sympify(generating.reference_frequency)
    subs = {}
    for i, (x, v) in enumerate(zip(system.coordinates, system.velocities, strict=True)):
        m = generating.harmonics[i]
        a, b = sp.sympify(generating.cos_amplitudes[i]), sp.sympify(generating.sin_amplitudes[i])
        if m is None:
            if a != 0 or b != 0:
                return False
            subs[x], subs[v] = sp.S.Zero, sp.S.Zero
            continue
        cos_m = sp.chebyshevt(m, c)
        sin_m = t * sp.chebyshevu(m - 1, c)
        subs[x] = a * cos_m + b * sin_m
        subs[v] = w * m * (-a * sin_m + b * cos_m)
    for f in system.rhs:
        value = sp.expand(sp.sympify(f).xreplace(subs))
        if value == 0:
            continue
        remainder = sp.reduced(value, [c**2 + t**2 - 1], t, c)[1]
        if sp.expand(remainder) != 0:
            return False
    return True


def exact_solution(template, order: int, note: str):
    """The exact solution whose generating solution is ``template``'s (:func:`exact_on` holds):
    ``template`` with every term beyond order 0 and every frequency correction zero, to ``order``,
    status SUCCESS and ``note`` as its message."""
    from perturb.solution import Status
    from perturb.trig import TrigPoly

    terms = tuple((row[0], *(TrigPoly() for _ in range(order))) for row in template.terms)
    frequency = (sp.sympify(template.generating.reference_frequency), *([sp.S.Zero] * order))
    deviations = {name: (sp.S.Zero,) * order for name in template.deviations}
    return attrs.evolve(
        template,
        order=order,
        terms=terms,
        frequency=frequency,
        deviations=deviations,
        steps=(),
        dependent_residuals={},
        status=Status.SUCCESS,
        message=note,
    )


def is_exact(solution) -> bool:
    """Whether a successful solution is its generating solution alone (every later term and
    frequency correction zero): an exact periodic solution."""
    if not solution.success or len(solution.frequency) < 2:
        return False
    if any(sp.sympify(w) != 0 for w in solution.frequency[1:]):
        return False
    return all(t.is_zero() for row in solution.terms for t in row[1:])


def exact_or(solution, system, order: int):
    """``solution``, or the exact solution it is when its construction stopped on the degenerate
    corrections of a family the nonlinearity vanishes on (:func:`exact_on`)."""
    if solution.success or not exact_on(system, solution.generating):
        return solution
    return exact_solution(
        solution, order, "exact: the right-hand side vanishes on the generating solution, so it "
        "solves the system at every order (frequency exactly the linear one)",
    )  # fmt: skip


def _on_generating(system, cos_amplitudes, harmonics, frequency):
    """The right-hand sides with :math:`x_i = a_i\\cos m_i s` put in, as polynomials in
    c = cos s, t = sin s reduced modulo :math:`c^2 + t^2 - 1` (``None`` where not polynomial)."""
    c, t = sp.Dummy("c"), sp.Dummy("t")
    subs = {}
    for x, v, a, m in zip(
        system.coordinates, system.velocities, cos_amplitudes, harmonics, strict=True
    ):
        if m is None:
            subs[x] = subs[v] = sp.S.Zero
            continue
        subs[x] = a * sp.chebyshevt(m, c)
        subs[v] = -frequency * m * a * t * sp.chebyshevu(m - 1, c)
    out = []
    for f in system.rhs:
        value = sp.expand(sp.sympify(f).xreplace(subs))
        if value != 0:
            value = sp.expand(sp.reduced(value, [c**2 + t**2 - 1], t, c)[1])
        out.append((value, (c, t)))
    return out


def exact_modes(system, generating, known: dict, scale, unknowns, eqs, seconds: float) -> list:
    """The standing waves on which the right-hand side vanishes identically, as continua in
    ``scale`` (module notes, 3): the cosine amplitudes d with d_scale = 1 that make every
    coefficient of :math:`f(d\\cos s, -\\omega d\\sin s)` zero, certified; every sine amplitude
    and frequency correction zero. Such a mode is a root of the amplitude equations that their
    solvers may not isolate (it can lie on the closure of a continuum: the ring of three's
    in-phase mode on its plane of zero mean); each is checked against ``eqs``.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from perturb.steps import GeneratingSolution
    >>> x, y, u, v, w, a, b = sp.symbols("x y u v Omega1 a_x0 a_y0")
    >>> pair = QuasilinearSystem([x, y], [u, v], [1, 1], [-EPS*(x - y)**3, EPS*(x - y)**3])
    >>> gen = GeneratingSolution(("x", "y"), (1, 1), (a, b), (0, 0), "x", 1)
    >>> eqs = [8*w*a - 3*(a - b)**3, 8*w*b + 3*(a - b)**3]
    >>> [c.values for c in exact_modes(pair, gen, {}, a, [w, a, b], eqs, 30.0)]
    [{Omega1: 0, a_y0: a_x0}]
    """
    from perturb.algebra.certified import certified_real_roots
    from perturb.algebra.rootset import RootStatus
    from perturb.errors import InvalidSystemError
    from perturb.method.component import Component
    from perturb.method.exact import vanishes

    if not _frequency_sought(system) or scale is None:
        return []
    cosines = [sp.sympify(a).xreplace(known) for a in generating.cos_amplitudes]
    free = [a for a in cosines if isinstance(a, sp.Symbol) and a != scale]
    if scale not in cosines or any(
        sp.sympify(a).free_symbols - set(free) - {scale} for a in cosines
    ):
        return []
    at_one = [a.xreplace({scale: 1}) for a in cosines]
    conditions = []
    for value, (c, t) in _on_generating(
        system, at_one, generating.harmonics, sp.sympify(generating.reference_frequency)
    ):
        if value == 0:
            continue
        if not value.is_polynomial(c, t, EPS, *free):
            return []
        conditions.extend(sp.Poly(value, c, t, EPS).coeffs())
    conditions = [sp.expand(q) for q in conditions if sp.expand(q) != 0]
    if any(q.free_symbols - set(free) for q in conditions):
        return []  # the system's parameters in the coefficients: not this route
    if not free:
        roots = [] if conditions else [{}]
    elif not conditions:
        roots = None  # a whole subspace exact: a continuum, not ours
    else:
        try:
            found = certified_real_roots(conditions, free, seconds=seconds)
        except InvalidSystemError:
            return []
        roots = found.numbers() if found.status is RootStatus.SOLVED else None
        if found.status is RootStatus.NO_REAL_ROOT:
            roots = []
    out = []
    for root in roots or []:
        values = {u: sp.S.Zero for u in unknowns if u != scale}
        values.update({a: sp.expand(root[a] * scale) for a in free if a in set(unknowns)})
        if all(vanishes(sp.expand(sp.sympify(e).xreplace(values))) for e in eqs):
            out.append(Component(values=values, free=(scale,)))
    return out
