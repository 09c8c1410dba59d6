"""Poincaré's method for periodic solutions of quasilinear systems, order by order.

The construction works in the strained time :math:`s = \\Omega t` with
:math:`\\Omega = \\omega_{ref} + \\sum_{k\\ge1}\\varepsilon^k\\Omega_k`, so that the sought solution is
:math:`2\\pi`-periodic in ``s`` and the period correction of the classical write-up,
:math:`\\alpha = T - 2\\pi/\\omega_{ref}`, becomes the frequency correction. With
:math:`x_i = \\sum_k \\varepsilon^k x_{i,k}(s)` the equations

.. math:: \\Omega^2 x_i'' + \\omega_i^2 x_i = f_i(x, \\Omega x', \\varepsilon)

give at order ``k``:  :math:`\\omega_{ref}^2 x_{i,k}'' + \\omega_i^2 x_{i,k} = R_{i,k}(s)`.

* For a resonant coordinate (:math:`\\omega_i = m_i\\omega_{ref}`) the solution is
  :math:`x_{i,k} = \\beta_{i,k}^c\\cos m_i s + \\beta_{i,k}^s\\sin m_i s + g_{i,k}(s)` where
  :math:`g_{i,k}` is the quadrature :math:`\\frac{1}{m_i\\omega_{ref}^2}\\int_0^s R_{i,k}(u)\\sin m_i(s-u)\\,du`
  (zero initial data) and :math:`\\beta_{i,k}` are the Maclaurin coefficients of the initial-value
  deviations.  :math:`g_{i,k}` is :math:`2\\pi`-periodic iff the periodicity conditions
  :math:`g_{i,k}(2\\pi) = 0`, :math:`\\dot g_{i,k}(2\\pi) = 0` hold, i.e. iff the harmonic
  :math:`m_i` of :math:`R_{i,k}` vanishes.
* For a non-resonant coordinate the forced response is the unique periodic solution.

The conditions are polynomial in the unknowns (generating amplitudes, their corrections, the
:math:`\\Omega_k`).  Nonlinear ones — the amplitude equations of the first non-zero order — are solved
for all roots and a branch is chosen; after that every correction enters linearly.  Unknowns left free
by an order are carried symbolically and fixed by a later one (this covers isolated roots, continuous
families with a user-chosen amplitude, and degenerate branches whose deviations scale as a power of ε
fixed by the balance of orders).

The concerns live in sibling modules: :mod:`perturb.method.expansion` (the forcing of each order),
:mod:`perturb.method.conditions` (solving the conditions, choosing a branch),
:mod:`perturb.steps` (the printable steps) and :mod:`perturb.method.exact` (zero tests).
This module holds the options (:class:`PoincareMethod`); the order-by-order template is
:class:`perturb.method.construction.OrderByOrder`.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from attrs import field, frozen

from perturb._checks import known_keywords
from perturb._defaults import SOLVE_SECONDS
from perturb.cache import Uncached, cached
from perturb.frame import DrivenFrame, FreeFrame
from perturb.method.options import (
    check_branch,
    check_cache,
    check_order,
    check_phase,
    check_seconds,
    check_system,
    one_of,
    to_amplitudes,
)
from perturb.progress import stage
from perturb.solution import PeriodicSolution, Status
from perturb.system import QuasilinearSystem
from perturb.trig import SympyRing

__all__ = ["PoincareMethod", "solve"]


@known_keywords
@frozen
class PoincareMethod:
    r"""Poincaré's method (small or large parameter) for a :class:`QuasilinearSystem`.

    Parameters
    ----------
    order : int
        Highest power of ε kept in the solution (>= 1).
    amplitudes : mapping, optional
        Fixed initial values ``{coordinate name: x_i(0)}``.  Values may be numbers or expressions in the
        system's parameters, ε (``perturb.system.EPS``) and its ``initial_values`` symbols (a
        constraint such as a first integral).  A coordinate listed here has exactly this initial value
        at every order (a member of a continuous family chosen by the user); the generating amplitudes
        of the others are unknowns found from the periodicity conditions.
    phase_coordinate : str, optional
        The coordinate whose velocity vanishes at ``t = 0`` (fixes the phase of an autonomous system).
        Default: the only coordinate in ``amplitudes`` if there is one, else the first coordinate.
    quadrature : {"auto", "exact", "numeric"}
        How the forcing of each order is expanded in harmonics: ``exact`` linearises products of
        trigonometric polynomials (polynomial right-hand sides only); ``numeric`` computes Fourier
        coefficients by FFT quadrature (any analytic right-hand side, numeric parameters and fixed
        generating amplitudes needed); ``auto`` (default) uses exact where it can.
    dependent_condition : {"auto", "phase-sine", "none"}
        A first integral makes one periodicity condition a consequence of the others: the one for the
        position of the phase coordinate, :math:`g_{ref,k}(2\pi) = 0` (the integral fixes
        :math:`x_{ref}(T)` once the other components have returned). ``phase-sine`` does not impose it
        (its residual is kept in ``solution.dependent_residuals``); ``none`` imposes every condition;
        ``auto`` (default) drops it when the system declares first integrals. Dropping it matters for
        reduced systems truncated in ε, where the integral holds only to the truncation order and
        imposing the dependent condition at the highest orders would make the conditions inconsistent.
    solve_seconds : float
        Time budget of sympy's solver on the nonlinear amplitude equations (run in a child process
        where the platform can fork) and of the certified real-root solver; past it the result has
        status ``SOLVER_BUDGET`` with the size of the system and says how to give the root instead.
        sympy's ``solve`` can run for hours on systems whose roots have no closed form.
    branch : mapping or int, optional
        Which root of the amplitude equations to follow: a mapping ``{symbol name: value}`` selects the
        root that has these values, and on a continuous family of roots fixes the generating
        amplitudes the family leaves free (``a_P0``: cosine amplitude of ``P`` at order 0, ``b_P0``:
        its sine amplitude); an integer indexes the admissible roots in the order listed in
        ``solution.steps[k].branches``.  Default: the isolated root with the largest phase amplitude.

    Examples
    --------
    Duffing's oscillator, a conservative system: its continuous family is pinned by the initial
    amplitude ``A`` (a symbol here, so the result holds for every amplitude):

    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot, A = sp.symbols("x xdot A")
    >>> duffing = QuasilinearSystem([x], [xdot], [1], [-EPS * x**3], parameters=[A])
    >>> solution = PoincareMethod(order=2, amplitudes={"x": A}).solve(duffing)
    >>> solution.frequency_series()
    -21*A**4*epsilon**2/256 + 3*A**2*epsilon/8 + 1
    """

    order: int = field(default=1, validator=check_order)
    amplitudes: dict = field(factory=dict, converter=to_amplitudes)
    phase_coordinate: str | None = field(default=None, validator=check_phase)
    branch: object = field(default=None, validator=check_branch)
    quadrature: str = field(default="auto", validator=one_of("auto", "exact", "numeric"))
    dependent_condition: str = field(default="auto", validator=one_of("auto", "phase-sine", "none"))
    solve_seconds: float = field(
        default=SOLVE_SECONDS, eq=False, repr=False, validator=check_seconds
    )

    # ------------------------------------------------------------------ public
    cache: bool = field(default=True, eq=False, repr=False, validator=check_cache)

    def solve(self, system: QuasilinearSystem) -> PeriodicSolution:
        """Construct the periodic solution of ``system``; see the module docstring.

        The result is read from / written to the disk cache (:mod:`perturb.cache`) unless
        ``cache=False``.

        Parameters
        ----------
        system : QuasilinearSystem
            The system to solve.

        Returns
        -------
        PeriodicSolution
            Its ``status`` says whether the construction succeeded (a failed construction is returned,
            not raised: see :meth:`PeriodicSolution.raise_for_status`).

        Raises
        ------
        perturb.errors.InvalidSystemError
            If ``system`` is not a :class:`QuasilinearSystem` or the options do not fit it.
        """
        check_system(system)

        def construct():  # the one step a run may wait on: told (a cache hit is not)
            with stage(f"deriving the order-{self.order} solution of {system.name}"):
                solution = _construct(self, system)
            # a spent budget is this run's, not the system's: a faster machine decides it
            return Uncached(solution) if solution.status is Status.SOLVER_BUDGET else solution

        if not self.cache:
            return Uncached.unwrap(construct())
        return cached("solution", lambda: self._cache_key(system), construct)

    def cache_key(self, system: QuasilinearSystem) -> tuple:
        """What a construction of ``system`` with these options is cached under (its options,
        the system and the frame's tag): clients caching what they derive from it key on it."""
        return self._cache_key(system)

    def _cache_key(self, system: QuasilinearSystem) -> tuple:
        def text(value):
            return (
                sp.srepr(sp.sympify(value))
                if isinstance(value, (sp.Basic, int, float))
                else repr(value)
            )

        amplitudes = sorted((k, text(v)) for k, v in self.amplitudes.items())
        branch = (
            sorted((str(k), text(v)) for k, v in self.branch.items())
            if isinstance(self.branch, Mapping)
            else repr(self.branch)
        )
        drive = system.frame.cache_tag()
        return (
            (system.content_digest, *drive),
            system.regime.value,
            system.name,
            system.truncation,
            self.order,
            amplitudes,
            self.phase_coordinate,
            branch,
            self.quadrature,
            self.dependent_condition,
        )


def solve(system: QuasilinearSystem, order: int = 1, **options) -> PeriodicSolution:
    """Shortcut for ``PoincareMethod(order=order, **options).solve(system)``.

    Parameters
    ----------
    system : QuasilinearSystem
        The system to solve.
    order : int, optional
        Highest power of ε kept (>= 1).
    **options
        Any other option of :class:`PoincareMethod` (``amplitudes``, ``branch``, ...).

    Returns
    -------
    PeriodicSolution

    Raises
    ------
    perturb.errors.InvalidSystemError
        On an order < 1 or an option that does not fit the system.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import solve
    >>> solve(vdp, order=2).frequency_series()
    1 - epsilon**2/16
    """
    return PoincareMethod(order=order, **options).solve(system)


def __getattr__(name: str):
    """``TEMPLATES``, the template of each frame (:attr:`perturb.QuasilinearSystem.frame`): free,
    or period given.  Made on first use, with the construction's modules: a run that reads its
    solutions from the cache never loads them."""
    if name != "TEMPLATES":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from perturb.method.construction import OrderByOrder
    from perturb.method.given_period import DrivenOrderByOrder

    templates = {FreeFrame: OrderByOrder, DrivenFrame: DrivenOrderByOrder}
    globals()["TEMPLATES"] = templates  # later lookups (and additions) use this one dict
    return templates


def _construct(method: PoincareMethod, system: QuasilinearSystem) -> PeriodicSolution:
    """One run on the native backend; again on sympy if an expression cannot be held natively.
    The template is the frame's (``TEMPLATES``)."""
    from perturb.native import NotNative

    templates = globals().get("TEMPLATES") or __getattr__("TEMPLATES")
    template = templates[type(system.frame)]
    try:
        return template(method, system).run()
    except NotNative:
        return template(method, system, SympyRing).run()
