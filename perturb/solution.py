"""The result of a Poincaré construction: :class:`PeriodicSolution`, and its :class:`Status`."""

from __future__ import annotations

import enum
import pickle
import warnings
from collections.abc import Mapping, Sequence
from functools import cached_property

import attrs
import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._checks import as_mapping, as_real_array
from perturb._defaults import (
    DISPLAY_SIMPLIFY_MAX_OPS,
    EVAL_BLOCK,
    NEAR_RESONANCE,
    RECENT_COEFFICIENTS,
)
from perturb._install import install_hint
from perturb._lambdify import numpy_lambdify
from perturb.cache import UNPICKLABLE, digest
from perturb.errors import AccuracyWarning, InvalidParameterError, PerturbError, bad_value
from perturb.steps import GeneratingSolution, OrderStep, S
from perturb.system import EPS, QuasilinearSystem, Regime

__all__ = ["PeriodicSolution", "SolutionFailed", "Status"]

T_SYM = sp.Symbol("t", real=True)


class Status(enum.Enum):
    """Outcome of a construction; the values are the messages shown to users.

    Examples
    --------
    >>> from perturb import Status
    >>> Status.SUCCESS.ok
    True
    >>> print(Status.UNDETERMINED.value)
    the periodicity conditions leave some amplitudes free (a continuous family): fix them with `amplitudes=`
    """

    SUCCESS = "the periodicity conditions were solved at every order"
    NO_ROOT = "the amplitude equations have no admissible (non-trivial) root"
    INCONSISTENT = (
        "the periodicity conditions are inconsistent at some order (no periodic solution)"
    )
    UNDETERMINED = (
        "the periodicity conditions leave some amplitudes free (a continuous family): fix them "
        "with `amplitudes=`"
    )
    SINGULAR = "a divisor of the solution vanishes at these parameter values (a degenerate detuning or a resonance)"
    TRUNCATED = (
        "the construction needs a power of epsilon the system's right-hand side does not contain "
        "(it was truncated): give a longer series"
    )
    NOT_POLYNOMIAL = (
        "the right-hand side is not polynomial in the state; give numeric parameter values"
    )
    SOLVER_BUDGET = (
        "the polynomial solver ran out of its time budget before it could decide whether the "
        "amplitude equations have a root (not a proof that none exists): raise `solve_seconds` "
        "(PoincareMethod(solve_seconds=...), or `solve_seconds` in a problem's method_options); "
        f"without the extra roots only the slower exact route runs ({install_hint('roots')})"
    )

    @property
    def ok(self) -> bool:
        return self is Status.SUCCESS


class SolutionFailed(PerturbError, RuntimeError):
    """Raised by :meth:`PeriodicSolution.raise_for_status` on a failed construction.

    Parameters
    ----------
    message : str
        The status and its detail.

    Examples
    --------
    Duffing's oscillator is conservative: without a chosen amplitude the conditions leave it free,
    and the construction does not succeed.

    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem, SolutionFailed, solve
    >>> x, xdot = sp.symbols("x xdot")
    >>> duffing = QuasilinearSystem([x], [xdot], [1], [-EPS * x**3])
    >>> try:
    ...     solve(duffing, order=1).raise_for_status()
    ... except SolutionFailed as error:
    ...     print(str(error)[:40])
    the periodicity conditions leave some am
    """


class _StoredSteps(Sequence):
    """A solution's construction steps as read from a pickle, unpickled on first use.

    The steps (each order's forcing, quadratures and conditions, for ``perturb solve --steps``
    and the method's pages) are most of a solution's pickle — three quarters of the disk's, 0.55
    of the 0.69 s it takes to read — and a run that evaluates or validates the solution never
    looks at them: a warm ``perturb validate disk`` reads its solution from the disk cache
    without them.
    """

    __slots__ = ("_blob", "_steps")

    def __init__(self, blob: bytes):
        self._blob = blob
        self._steps: tuple | None = None

    def _loaded(self) -> tuple:
        if self._steps is None:
            self._steps = tuple(pickle.loads(self._blob))  # noqa: S301 - our own pickle, read
            self._blob = None  # from a signed cache entry or a pickle the caller gave
        return self._steps

    @staticmethod
    def blob(steps) -> bytes:
        """``steps`` pickled (a stored sequence not yet read: its own bytes, unread)."""
        if isinstance(steps, _StoredSteps) and steps._steps is None:
            return steps._blob
        return pickle.dumps(tuple(steps), protocol=pickle.HIGHEST_PROTOCOL)

    def __getitem__(self, index):
        return self._loaded()[index]

    def __len__(self) -> int:
        return len(self._loaded())

    def __eq__(self, other) -> bool:
        return tuple(self) == (tuple(other) if isinstance(other, Sequence) else other)

    def __hash__(self) -> int:
        return hash(self._loaded())

    def __repr__(self) -> str:
        return repr(self._loaded())


@frozen
class PeriodicSolution:
    """A periodic solution :math:`x_i(t) = \\sum_k \\varepsilon^k x_{i,k}(\\Omega t)`, :math:`T = 2\\pi/\\Omega`.

    Attributes
    ----------
    system : QuasilinearSystem
        The system that was solved.
    order : int
        Highest power of ε kept in the state.
    terms : tuple
        ``terms[i][k]`` is :math:`x_{i,k}(s)` as a :class:`~perturb.trig.TrigPoly` in the strained time
        ``s = Omega t``.
    frequency : tuple of sympy expressions
        :math:`\\Omega_k`, the coefficients of :math:`\\Omega = \\sum_k \\varepsilon^k\\Omega_k`
        (every coefficient the conditions determined; ``frequency[0]`` is the reference frequency).
    generating : GeneratingSolution
    steps : tuple of OrderStep
        The construction, order by order.
    deviations : dict
        ``{coordinate name: (beta_1, beta_2, ...)}``: the Maclaurin coefficients of the initial-value
        deviations :math:`\\beta_i(\\varepsilon) = x_i(0) - M_i`; under the velocity's name the same for
        :math:`\\dot x_i(0)` (resonant coordinates).
    status : Status
    message : str
        Human-readable detail of the status.
    dependent_residuals : dict
        Periodicity conditions not imposed because a first integral makes them dependent, with the
        solved values put in: they vanish to the accuracy of the integral (a check, not an input).

    Examples
    --------
    Van der Pol's limit cycle to second order: its frequency, its period and its state at two times
    (rows ``x``, ``xdot``) at ε = 0.1:

    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> solution = PoincareMethod(order=2).solve(vdp)
    >>> solution.status
    <Status.SUCCESS: 'the periodicity conditions were solved at every order'>
    >>> solution.frequency_series()
    1 - epsilon**2/16
    >>> solution.period_series()
    pi*epsilon**2/8 + 2*pi
    >>> solution.evaluate([0.0, 1.0], 0.1).round(6)
    array([[ 2.000104,  1.138489],
           [ 0.      , -1.568746]])
    """

    system: QuasilinearSystem
    order: int
    terms: tuple = field(eq=False)
    frequency: tuple[sp.Expr, ...]
    generating: GeneratingSolution
    steps: tuple[OrderStep, ...] = field(eq=False)
    deviations: dict = field(eq=False)
    status: Status = Status.SUCCESS
    message: str = ""
    dependent_residuals: dict = field(factory=dict, eq=False)

    # ------------------------------------------------------------------ pickling
    def __getstate__(self) -> dict:
        """The fields, the steps as their own pickle (read when first used: :class:`_StoredSteps`);
        the compiled evaluators are rebuilt where the solution is read."""
        state = {f.name: getattr(self, f.name) for f in attrs.fields(type(self))}
        state["steps"] = _StoredSteps.blob(self.steps)
        return state

    def __setstate__(self, state) -> None:
        if not isinstance(state, dict):  # attrs' own state of a slotted class: values in order
            state = dict(zip((f.name for f in attrs.fields(type(self))), state, strict=False))
        for name, value in state.items():
            if name == "steps" and isinstance(value, bytes):
                value = _StoredSteps(value)
            object.__setattr__(self, name, value)

    # ------------------------------------------------------------------ status
    @property
    def success(self) -> bool:
        return self.status.ok

    def raise_for_status(self) -> PeriodicSolution:
        """The solution itself if its construction succeeded, else raise.

        Returns
        -------
        PeriodicSolution
            ``self``, so that ``method.solve(system).raise_for_status()`` chains.

        Raises
        ------
        SolutionFailed
            If :attr:`status` is not a success; the message is the status and its detail.
        """
        if not self.success:
            raise SolutionFailed(f"{self.status.value}: {self.message}")
        return self

    # ------------------------------------------------------------------ symbolic views
    @property
    def coordinates(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.system.coordinates)

    @property
    def state_names(self) -> tuple[str, ...]:
        return self.system.state_names

    @property
    def parameter(self) -> sp.Symbol:
        """The symbol the results are written in (ε, or μ in the large-parameter regime)."""
        return self.system.parameter

    def _in_user_parameter(self, expr: sp.Expr) -> sp.Expr:
        if self.system.regime is Regime.LARGE:
            return expr.subs(EPS, 1 / self.system.parameter)
        return expr.subs(EPS, self.system.parameter)

    def coordinate(self, name: str, *, in_time: bool = False, simplify: bool = False) -> sp.Expr:
        """:math:`x_i` as a sum over orders, in ``s`` (default) or in physical time ``t``.

        ``simplify=True`` writes every harmonic coefficient as one fraction with its common factors
        pulled out (for display; the engine keeps them expanded).
        """
        i = self._index(name)
        terms = self.terms[i]
        if simplify:
            terms = [term.map(_display) for term in terms]
        expr = sp.Add(*(EPS**k * term.as_expr(S) for k, term in enumerate(terms)))
        if in_time:
            expr = expr.subs(S, self.frequency_expr * T_SYM)
        return self._in_user_parameter(expr)

    @property
    def frequency_expr(self) -> sp.Expr:
        """:math:`\\Omega(\\varepsilon)` truncated where the conditions stopped."""
        return sp.Add(*(EPS**k * w for k, w in enumerate(self.frequency)))

    def frequency_series(self, *, simplify: bool = False) -> sp.Expr:
        """:math:`\\Omega` in the system's own parameter: powers of ε, or of 1/μ when ``LARGE``.

        (:attr:`frequency_expr` is the same series in the engine's ε.)
        """
        expr = self.frequency_expr
        if simplify:
            expr = sp.Add(*(EPS**k * _display(w) for k, w in enumerate(self.frequency)))
        return self._in_user_parameter(expr)

    def period_series(self, *, simplify: bool = False) -> sp.Expr:
        """The period :math:`T = 2\\pi/\\Omega` expanded to the order the frequency is known."""
        n = len(self.frequency)
        series = sp.expand(sp.series(2 * sp.pi / self.frequency_expr, EPS, 0, n).removeO())
        if simplify:
            series = sp.Add(*(EPS**k * _display(series.coeff(EPS, k)) for k in range(n)))
        return self._in_user_parameter(series)

    def latex(self, *, simplify: bool = True) -> str:
        """The solution as LaTeX: one line per coordinate and the period.

        With ``simplify`` (default) each harmonic coefficient is shown as one fraction.
        """
        lines = [
            f"{sp.latex(sp.Symbol(c))} = {sp.latex(self.coordinate(c, simplify=simplify))}"
            for c in self.coordinates
        ]
        lines.append(f"T = {sp.latex(self.period_series(simplify=simplify))}")
        if self.system.regime is Regime.LARGE:  # the series are in 1/mu: say so
            lines.append(
                f"\\Omega = {sp.latex(self.frequency_series(simplify=simplify))}, \\quad "
                f"{sp.latex(EPS)} = {sp.latex(1 / self.parameter)}"
            )
        return " \\\\\n".join(lines)

    def _repr_latex_(self) -> str | None:
        """Jupyter's rendering: the coordinates and the period as aligned equations (as sympy
        objects render), or None (plain text) for a failed construction."""
        if not self.success:
            return None
        rows = [row.replace(" = ", " &= ", 1) for row in self.latex().split(" \\\\\n")]
        return "$\\displaystyle \\begin{aligned}" + " \\\\ ".join(rows) + "\\end{aligned}$"

    def __str__(self) -> str:
        out = [f"PeriodicSolution of {self.system.name} to order {self.order}: {self.status.name}"]
        if self.message:
            out.append(f"  {self.message}")
        for c in self.coordinates:
            out.append(f"  {c} = {self.coordinate(c)}")
        out.append(f"  Omega = {self.frequency_series()}")
        if self.system.regime is Regime.LARGE:
            out.append(
                f"  ({EPS} = 1/{self.parameter}: the series are in powers of 1/{self.parameter})"
            )
        return "\n".join(out)

    def _index(self, name: str) -> int:
        if isinstance(name, sp.Symbol):
            name = name.name
        try:
            return self.coordinates.index(name)
        except ValueError:
            raise InvalidParameterError(
                f"`name` = {name!r} is not a coordinate: choose from {list(self.coordinates)}"
            ) from None

    # ------------------------------------------------------------------ numerics
    @cached_property
    def numeric_digest(self) -> str | None:
        """SHA-256 (hex) of what the solution's numbers are computed from: the system's
        parameters, the frequency and every term's harmonic coefficients, as the disk cache
        digests them; None when they cannot be pickled.  What a cache of its numbers keys on: a
        warm run reads them back without building a sympy expression."""
        table = (
            tuple(self.system.parameters),
            tuple(self.frequency),
            tuple(
                tuple(tuple(t.coefficient(j) for j in range(t.max_harmonic + 1)) for t in row)
                for row in self.terms
            ),
        )
        try:
            return digest(table)
        except UNPICKLABLE:
            return None

    @cached_property
    def _compiled(self):
        """Lambdified harmonic coefficients, compiled once (common subexpressions shared)."""
        params = [p for p in self.system.parameters]
        harmonics = max((t.max_harmonic for row in self.terms for t in row), default=0)

        def exprs() -> list:
            cos_rows, sin_rows = [], []
            for row in self.terms:
                cos_rows.append(
                    [
                        sp.Add(*(EPS**k * t.coefficient(j)[0] for k, t in enumerate(row)))
                        for j in range(harmonics + 1)
                    ]
                )
                sin_rows.append(
                    [
                        sp.Add(*(EPS**k * t.coefficient(j)[1] for k, t in enumerate(row)))
                        for j in range(harmonics + 1)
                    ]
                )
            return [self.frequency_expr, cos_rows, sin_rows]

        key = self.numeric_digest
        fn = numpy_lambdify([EPS, *params], exprs if key is not None else exprs(), True, key=key)
        return fn, params, harmonics

    def _epsilon(self, value) -> np.ndarray:
        value = as_real_array(str(self.parameter), value)
        if self.system.regime is Regime.LARGE:
            if np.any(value == 0):
                raise InvalidParameterError(
                    f"`{self.parameter}` = 0: the large parameter must be non-zero"
                )
            return 1.0 / value
        return value

    def _params(self, values: Mapping | None) -> list:
        values = as_mapping("values", values)
        _, params, _ = self._compiled
        stray = [key for key in values if not isinstance(key, str | sp.Symbol)]
        if stray:
            raise bad_value("values", values, "key it by parameter names (str) or symbols")
        # Other names are ignored: callers pass every value of a problem, some of them already
        # substituted into the system before solving; the result does not depend on them.
        missing = [p.name for p in params if p.name not in values and p not in values]
        if missing:
            raise InvalidParameterError(
                f"`values` lacks {missing}: give a value for every free parameter of the solution"
                + (f" (got {sorted(map(str, values))})" if values else "")
            )
        return [
            as_real_array(f"values[{p.name!r}]", values[p.name] if p.name in values else values[p])
            for p in params
        ]

    @cached_property
    def _recent(self) -> dict:
        """The coefficients at the last few scalar parameter sets (see :meth:`coefficients`)."""
        return {}

    def coefficients(self, parameter_value, values: Mapping | None = None):
        """Numeric ``(Omega, cos, sin)``: cos/sin have shape ``(n, harmonics + 1, *broadcast)``.

        At one parameter set (scalars) the arrays are kept for the next calls at the same numbers
        (read-only, the last :data:`RECENT_COEFFICIENTS` sets): a state, its period and its initial
        state ask for them in turn, and a symbolic solution's coefficients can take milliseconds.
        """
        fn, _, h = self._compiled
        eps = self._epsilon(parameter_value)
        args = self._params(values)
        key = None
        if eps.ndim == 0 and all(a.ndim == 0 for a in args):
            key = (float(eps), *(float(a) for a in args))
            kept = self._recent.get(key)
            if kept is not None:
                self._warn_near_resonance(args)
                return kept
        with np.errstate(divide="ignore", invalid="ignore"):
            omega, cos_rows, sin_rows = fn(eps, *args)
        shape = np.broadcast_shapes(np.shape(eps), *(np.shape(a) for a in args))
        cos = np.array(
            [[np.broadcast_to(np.asarray(c, float), shape) for c in row] for row in cos_rows]
        )
        sin = np.array(
            [[np.broadcast_to(np.asarray(c, float), shape) for c in row] for row in sin_rows]
        )
        omega = np.broadcast_to(np.asarray(omega, float), shape)
        if not (
            np.all(np.isfinite(cos)) and np.all(np.isfinite(sin)) and np.all(np.isfinite(omega))
        ):
            raise SolutionFailed(
                f"the solution's coefficients are not finite at {self.parameter} = {parameter_value} "
                f"and {dict(values or {})}: a small divisor vanishes there (a resonance the "
                "construction assumed absent, or a vanishing detuning); choose other parameter values"
            )
        self._warn_near_resonance(args)
        if key is not None:
            for array in (omega, cos, sin):
                array.setflags(write=False)
            recent = self._recent
            if len(recent) >= RECENT_COEFFICIENTS:
                recent.pop(next(iter(recent)))
            recent[key] = (omega, cos, sin)
        return omega, cos, sin

    def _warn_near_resonance(self, args) -> None:
        """AccuracyWarning when a non-resonant frequency ratio comes close to a harmonic present."""
        harmonics = self.generating.harmonics
        if all(m is not None for m in harmonics):
            return
        params = self._compiled[1]
        subs = dict(zip(params, (np.asarray(a, float).ravel()[0] for a in args), strict=True))
        w_ref = float(sp.sympify(self.generating.reference_frequency).subs(subs))
        top = self._compiled[2]
        for i, m in enumerate(harmonics):
            if m is not None:
                continue
            ratio = float(sp.sympify(self.system.frequencies[i]).subs(subs)) / w_ref
            j = round(ratio)
            if 1 <= j <= top and abs(ratio - j) < NEAR_RESONANCE:
                warnings.warn(
                    f"{self.coordinates[i]}: frequency ratio {ratio:.6g} is within {NEAR_RESONANCE} of the "
                    f"harmonic {j}; the small divisor 1/(omega^2 - {j}^2) makes the solution inaccurate",
                    AccuracyWarning,
                    stacklevel=3,
                )

    def period_at(self, parameter_value, values: Mapping | None = None):
        """Period :math:`2\\pi/\\Omega` at the given parameter value(s)."""
        omega, _, _ = self.coefficients(parameter_value, values)
        return 2 * np.pi / omega

    def evaluate(self, t, parameter_value, values: Mapping | None = None) -> np.ndarray:
        """The state ``(x_1..x_n, xdot_1..xdot_n)`` at times ``t``.

        Parameters
        ----------
        t : array_like
            Times (physical time of the quasilinear system).
        parameter_value : float or array_like
            ε (or μ in the large-parameter regime). Arrays broadcast with the parameter ``values``;
            the result then has shape ``(2n, *param_shape, *t.shape)``.
        values : mapping, optional
            Values of the system's free parameters.

        Returns
        -------
        numpy.ndarray
            Shape ``(2n, *t.shape)`` for scalar parameters.
        """
        t = as_real_array("t", t)
        omega, cos, sin = self.coefficients(parameter_value, values)
        coeffs = cos - 1j * sin  # x = Re sum_j c_j exp(i j s)
        if omega.shape == ():
            return _evaluate_scalar(float(omega), coeffs, t)
        pshape = omega.shape
        omega_b = omega.reshape(pshape + (1,) * t.ndim)
        z = np.exp(1j * omega_b * t)
        n, nh = coeffs.shape[:2]
        out = np.empty((2 * n,) + z.shape)
        for i in range(n):
            c = coeffs[i].reshape((nh,) + pshape + (1,) * t.ndim)
            acc = np.broadcast_to(c[nh - 1], z.shape).astype(complex)
            dacc = (nh - 1) * acc
            for j in range(nh - 2, -1, -1):  # Horner in z = exp(i s)
                acc = acc * z + c[j]
                dacc = dacc * z + j * c[j]
            out[i] = acc.real
            out[n + i] = (omega_b * (1j * dacc)).real
        return out

    def initial_state(self, parameter_value, values: Mapping | None = None) -> np.ndarray:
        """State at ``t = 0`` (shape ``(2n, *param_shape)``)."""
        return self.evaluate(np.zeros(()), parameter_value, values)


def _evaluate_scalar(omega: float, coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """State at times ``t`` for scalar parameters: blocked, in-place Horner in exp(i Omega t)."""
    n, nh = coeffs.shape[:2]
    flat = t.ravel()
    out = np.empty((2 * n, flat.size))
    weights = np.arange(nh) * coeffs  # coefficients of d/ds, up to the factor i
    for lo in range(0, flat.size, EVAL_BLOCK):
        block = flat[lo : lo + EVAL_BLOCK]
        z = np.exp(1j * omega * block)
        for i in range(n):
            acc = np.full(block.shape, coeffs[i, nh - 1])
            dacc = np.full(block.shape, weights[i, nh - 1])
            for j in range(nh - 2, -1, -1):
                acc *= z
                acc += coeffs[i, j]
                dacc *= z
                dacc += weights[i, j]
            out[i, lo : lo + EVAL_BLOCK] = acc.real
            out[n + i, lo : lo + EVAL_BLOCK] = -omega * dacc.imag  # Re(i Omega dacc)
    out += 0.0  # turns the -0.0 of vanishing velocities into 0.0 (for printing)
    return out.reshape((2 * n,) + t.shape)


def _display(expr: sp.Expr) -> sp.Expr:
    """One fraction with common factors pulled out, for display, unless the expression is huge.

    (``factor`` would also factor the arguments of square roots, sqrt(1 - g**2) -> sqrt(-(g-1)(g+1)).)
    """
    expr = sp.sympify(expr)
    if expr.is_number or sp.count_ops(expr) > DISPLAY_SIMPLIFY_MAX_OPS:
        return expr
    return sp.factor_terms(sp.cancel(expr))
