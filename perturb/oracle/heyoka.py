"""The adaptive Taylor method of heyoka.py (an optional dependency), in double or extended precision.

heyoka builds the Taylor series of the solution from the *expressions* of the rhs, so it needs the
rhs as a :class:`~perturb.oracle.symbolic.SymbolicRHS`; the translation is
:func:`perturb.oracle.translate.to_heyoka`.  heyoka is imported lazily, inside the functions.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import math
import platform
import threading
from typing import Any

import attrs
import numpy as np
from attrs import frozen

from perturb._checks import check_bool, check_count
from perturb._defaults import (
    DEFAULT_HEYOKA_TOL,
    HEYOKA_COMPACT_MODE_MIN_DIM,
    MAX_STEPS,
    TAYLOR_CACHE_ENTRIES,
)
from perturb._install import install_hint
from perturb.cache import cached
from perturb.errors import bad_value
from perturb.oracle.base import IntegratorBase, Run, TrajectoryStatus, check_positive
from perturb.oracle.symbolic import SymbolicRHS
from perturb.oracle.translate import to_heyoka

__all__ = ["Heyoka", "heyoka_available"]


@functools.cache
def heyoka_available() -> bool:
    """True if heyoka.py can be imported.

    Returns
    -------
    bool
        Whether the ``fast`` extra (heyoka.py) is installed; cached for the process.

    Examples
    --------
    >>> from perturb.oracle import choose, heyoka_available
    >>> choose().name.startswith("heyoka") == heyoka_available()
    True
    """
    try:
        import heyoka  # noqa: F401
    except ImportError:
        return False
    return True


#: The machine epsilon of each floating point type, heyoka's default tolerance in it.
_EPSILON = {"double": 2.0**-52, "long double": 2.0**-63, "real128": 2.0**-112}


@functools.cache  # the platform and the heyoka build do not change during a run
def _fp_types() -> dict[str, type]:
    import heyoka as hy

    types: dict[str, type] = {"double": float}
    if np.finfo(np.longdouble).eps < np.finfo(np.float64).eps:  # x86 80-bit long double
        types["long double"] = np.longdouble
    if hasattr(hy, "real128"):
        types["real128"] = hy.real128
    return types


def _to_fp(values, fp: type) -> np.ndarray:
    """An array of ``values`` in the floating point type ``fp`` (float, longdouble or real128)."""
    if fp is float or fp is np.longdouble:
        return np.asarray(values, dtype=fp)
    # real128: go through the decimal string, which keeps all digits of a long double input
    return np.array([v if isinstance(v, fp) else fp(str(v)) for v in values])


#: The fields of ``/proc/cpuinfo`` that say which instructions the processor has (x86 and ARM):
#: compiled code is kept on disk only for the processor it was compiled for.
_CPU_FIELDS = frozenset(
    (
        "vendor_id", "cpu family", "model", "model name", "stepping", "flags",
        "CPU implementer", "CPU architecture", "CPU variant", "CPU part", "CPU revision",
        "Features",
    )
)  # fmt: skip


@functools.cache
def _host_cpu() -> str | None:
    """SHA-256 (hex) of the machine and its first processor's model and instruction sets, or
    ``None`` where they cannot be read (then compiled integrators are not kept on disk).

    heyoka compiles for the processor it runs on, so an integrator read back from a cache folder
    that another machine shares (a network home) must have been compiled for this processor.
    """
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as fh:
            text = fh.read()
    except OSError:
        return None
    first = text.split("\n\n", 1)[0]
    fields = sorted(
        (name.strip(), value.strip())
        for name, _, value in (line.partition(":") for line in first.splitlines())
        if name.strip() in _CPU_FIELDS
    )
    if not fields:
        return None
    return hashlib.sha256(repr((platform.machine(), fields)).encode()).hexdigest()


@functools.lru_cache(maxsize=64)
def _compiled_taylor(rhs: SymbolicRHS, fp_name: str, tol: float | None, compact_mode: bool):
    """A heyoka integrator for ``rhs``, JIT-compiled once per rhs, precision and tolerance.

    Kept on disk (:func:`perturb.cache.cached`, kind ``taylor``) with its machine code, keyed on
    the field, the options, heyoka's version and this processor (:func:`_host_cpu`): reading it
    back costs a few milliseconds where compiling costs a tenth of a second or more, and it is
    the same code, so the same numbers.  Not kept where the processor cannot be identified; at
    most :data:`~perturb._defaults.TAYLOR_CACHE_ENTRIES` are kept, the most recently written.
    """
    build = functools.partial(_build_taylor, rhs, fp_name, tol, compact_mode)
    host = _host_cpu()
    if host is None:
        return build()

    def key() -> tuple:
        import heyoka as hy

        return (*rhs.cache_parts(), fp_name, repr(tol), compact_mode, hy.__version__, host)

    return cached("taylor", key, build, keep=TAYLOR_CACHE_ENTRIES)


def _build_taylor(rhs: SymbolicRHS, fp_name: str, tol: float | None, compact_mode: bool):
    """JIT-compile a heyoka integrator for ``rhs`` (its state zero, at time zero)."""
    import heyoka as hy

    fp_type = _fp_types()[fp_name]
    variables = hy.make_vars(*[f"y{i}" for i in range(rhs.n)])
    if rhs.n == 1:
        variables = [variables]
    table = dict(zip(rhs.state, variables, strict=True))
    system = [
        (v, to_heyoka(e, table, fp_type)) for v, e in zip(variables, rhs.expressions, strict=True)
    ]
    kwargs: dict[str, Any] = {"compact_mode": compact_mode}
    if fp_type is not float:
        kwargs["fp_type"] = fp_type
    if tol is not None:
        kwargs["tol"] = fp_type(tol) if fp_type is not float else tol
    return hy.taylor_adaptive(system, _to_fp(np.zeros(rhs.n), fp_type), **kwargs)


_THREAD_STATE = threading.local()


def _thread_integrator(rhs: SymbolicRHS, fp_name: str, tol: float | None, compact_mode: bool):
    """This thread's own copy of the compiled integrator, reused across calls.

    Copying a compiled ``taylor_adaptive`` costs ~0.7 ms (its Taylor buffers): paying it once per
    thread rather than per call keeps short oracle runs within a few percent of bare heyoka. Every
    call resets the time and the state, which is all a propagation depends on.
    """
    cache = getattr(_THREAD_STATE, "integrators", None)
    if cache is None:
        cache = _THREAD_STATE.integrators = {}
    key = (rhs, fp_name, tol, compact_mode)
    if key not in cache:
        cache[key] = copy.copy(_compiled_taylor(rhs, fp_name, tol, compact_mode))
    return cache[key]


@frozen
class Heyoka(IntegratorBase):
    """Adaptive Taylor integrator of heyoka.py (``taylor_adaptive``).

    Parameters
    ----------
    tol : float, optional
        Tolerance (relative and absolute) of the Taylor method; default: the machine epsilon of the
        floating point type, heyoka's default.
    high_precision : bool
        Run in extended precision: 80-bit long double where the platform has it, else real128
        (quadruple).  Used for reference runs; the trajectory then keeps the extended dtype.
    fp_type : {'double', 'long double', 'real128'}, optional
        Explicit floating point type; overrides ``high_precision``.
    compact_mode : bool, optional
        heyoka's compact mode (faster compilation of large systems); default: on for systems with at
        least ``HEYOKA_COMPACT_MODE_MIN_DIM`` equations.
    max_steps : int
        Step budget; exceeding it returns a failed :class:`Trajectory`.

    Notes
    -----
    heyoka builds the Taylor series of the solution from the *expressions* of the rhs, so ``rhs``
    must be a :class:`~perturb.oracle.symbolic.SymbolicRHS`.  The compiled integrator is cached per
    (rhs, precision, tolerance); the first call pays the JIT compilation (~0.05 s for a 2-D system,
    about a second for a 42-equation variational system).

    Examples
    --------
    heyoka integrates a :class:`~perturb.oracle.SymbolicRHS` (it compiles the expressions); half a
    period of the harmonic oscillator, at machine precision:

    >>> import sympy as sp
    >>> from perturb.oracle import Heyoka, SymbolicRHS
    >>> x, v = sp.symbols("x v")
    >>> trajectory = Heyoka().integrate(SymbolicRHS((x, v), (v, -x)), (0.0, float(sp.pi)), [1.0, 0.0])
    >>> trajectory.y[:, -1].round(12) + 0.0  # (+ 0.0 turns a -0.0 into 0.0)
    array([-1.,  0.])
    """

    tol: float | None = DEFAULT_HEYOKA_TOL
    high_precision: bool = False
    fp_type: str | None = None
    compact_mode: bool | None = None
    max_steps: int = MAX_STEPS

    def __attrs_post_init__(self):
        if self.tol is not None:
            check_positive("tol", self.tol)
        if self.fp_type is not None and self.fp_type not in ("double", "long double", "real128"):
            raise bad_value("fp_type", self.fp_type, "use 'double', 'long double' or 'real128'")
        check_count("max_steps", self.max_steps)
        check_bool("high_precision", self.high_precision)
        if self.compact_mode is not None:
            check_bool("compact_mode", self.compact_mode)

    @property
    def precision(self) -> str:
        """Name of the floating point type used: ``'double'``, ``'long double'`` or ``'real128'``."""
        if self.fp_type is not None:
            return self.fp_type
        if not self.high_precision:
            return "double"
        if not heyoka_available():
            return "long double"
        types = _fp_types()
        return "long double" if "long double" in types else "real128"

    def loosened(self, factor: float) -> Heyoka:
        """A copy whose tolerance is ``factor`` times this one's (the type's epsilon by default)."""
        tol = _EPSILON[self.precision] if self.tol is None else self.tol
        return attrs.evolve(self, fp_type=self.precision, tol=float(tol) * factor)

    @property
    def name(self) -> str:
        """Description, e.g. ``"heyoka taylor_adaptive (double, tol=1e-15)"``."""
        tol = "eps" if self.tol is None else f"{self.tol:g}"
        return f"heyoka taylor_adaptive ({self.precision}, tol={tol})"

    def _accept_rhs(self, rhs) -> None:
        """heyoka must be installed, and the rhs symbolic."""
        if not heyoka_available():
            raise bad_value(
                "integrator",
                "heyoka",
                f"heyoka is not installed: {install_hint('fast')}, or use 'dop853'",
            )
        if not isinstance(rhs, SymbolicRHS):
            raise bad_value(
                "rhs",
                rhs,
                "heyoka needs a symbolic rhs: pass perturb.oracle.SymbolicRHS(state_symbols, "
                "sympy_expressions), or use a numeric integrator such as get_integrator('dop853')",
            )

    def _integrate_impl(self, rhs, t0, t1, y0, grid, jac) -> Run:
        types = _fp_types()
        if self.precision not in types:
            raise bad_value(
                "fp_type", self.precision, f"this platform/heyoka build offers {sorted(types)}"
            )
        fp = types[self.precision]
        compact = (
            rhs.n >= HEYOKA_COMPACT_MODE_MIN_DIM if self.compact_mode is None else self.compact_mode
        )
        ta = _thread_integrator(rhs, self.precision, self.tol, compact)
        ta.time = _to_fp([t0], fp)[0]
        ta.state[:] = _to_fp(y0, fp)

        import heyoka as hy

        grid_fp = _to_fp(grid, fp)
        n_steps = 0
        outcome = hy.taylor_outcome.time_limit
        if grid[0] > t0:
            outcome, _, _, n, *_ = ta.propagate_until(grid_fp[0], max_steps=self.max_steps)
            n_steps += n
        if outcome == hy.taylor_outcome.time_limit:
            t_before = ta.time
            outcome, _, _, n, _, states = ta.propagate_grid(grid_fp, max_steps=self.max_steps)
            n_steps += n
            reached = float(ta.time) if math.isfinite(float(ta.time)) else float(t_before)
            # on failure heyoka returns only the rows of the grid points it reached
            states = np.asarray(states)[: len(grid)]
            good = np.all(np.isfinite(states.astype(float)), axis=1)
            ts, ys = grid[: len(states)][good], states[good]
        else:
            reached = float(ta.time)
            ts, ys = grid[:0], np.empty((0, y0.size))
        status, message = TrajectoryStatus.SUCCESS, None
        if outcome == hy.taylor_outcome.step_limit:
            status = TrajectoryStatus.MAX_STEPS
            message = (
                f"heyoka stopped at the step budget max_steps = {self.max_steps} "
                f"({outcome}); raise `max_steps` or check the motion for blow-up."
            )
        elif outcome != hy.taylor_outcome.time_limit:
            status = (
                TrajectoryStatus.NON_FINITE
                if outcome == hy.taylor_outcome.err_nf_state
                else TrajectoryStatus.SOLVER_FAILED
            )
            message = f"heyoka stopped with outcome {outcome} (non-finite state or step size)."
        return Run(
            t=ts, states=ys, t_reached=reached, nfev=int(n_steps), status=status, message=message
        )
