"""Free or driven: what a system's excitation decides, held by one object of the system's type.

A :class:`~perturb.QuasilinearSystem` with an :class:`~perturb.Excitation` is *driven*: its
right-hand side holds a phase θ = Ωt, its frequency is given instead of sought, its state carries
θ, its true orbit is shot over a known period, and one solution no longer serves every parameter
value (each point has its own steady state). Instead of testing for an excitation wherever
that matters, each system has a :attr:`~perturb.QuasilinearSystem.frame` — :class:`FreeFrame` or
:class:`DrivenFrame` — and asks it.

Subclass contract (a new kind of system, e.g. quasi-periodic forcing, is a new frame):

1. :meth:`Frame.extra_symbols` — symbols a right-hand side may use besides the state and the
   parameters, with their roles;
2. :meth:`Frame.polynomial_rhs` — a right-hand side in the form the engine expands;
3. :meth:`Frame.reference_index`, :meth:`Frame.cache_tag`, :meth:`Frame.state_names`;
4. :meth:`Frame.autonomous` — the first-order system the oracle integrates (θ' = Ω appended);
5. the answers :attr:`Frame.frequency_given`, :attr:`Frame.energy_may_be_conserved`,
   :attr:`Frame.one_solution_for_all_points`;
6. :meth:`Frame.require_driven` — refuse, in one line, what needs an excitation;
6a. :meth:`Frame.phase_state` — what the frame adds to a state along a solution (the drive's
   phase θ = Ωt);
7. :meth:`Frame.check` and :meth:`Frame.excitation_with` — the system's own checks and its
   parameters put in.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import attrs
import sympy as sp
from attrs import frozen

from perturb.errors import InvalidParameterError, InvalidSystemError, bad_value

__all__ = ["DrivenFrame", "Frame", "FreeFrame"]


class Frame(ABC):
    """What free vs driven decides (see the module docstring)."""

    #: Whether the frequency of the sought motion is given (the excitation's) or unknown.
    frequency_given: ClassVar[bool]
    #: Whether the system may keep an energy (a driven one exchanges energy with its drive).
    energy_may_be_conserved: ClassVar[bool]
    #: Whether one solution, symbolic in the parameters, serves every parameter value (a driven
    #: system's steady state is a different branch set at each point).
    one_solution_for_all_points: ClassVar[bool]

    @abstractmethod
    def extra_symbols(self) -> tuple[tuple[sp.Symbol, str], ...]:
        """``((symbol, role), ...)`` a right-hand side may use besides state and parameters."""

    @abstractmethod
    def polynomial_rhs(self, f: sp.Expr, where: str | None = None) -> sp.Expr:
        """``f`` in the form the engine expands (a driven phase as cos θ, sin θ symbols)."""

    @abstractmethod
    def reference_index(self, system) -> int:
        """The coordinate whose frequency the excitation's ratio refers to (0 when free)."""

    @abstractmethod
    def cache_tag(self) -> tuple[str, ...]:
        """What the frame adds to a construction's cache key."""

    @abstractmethod
    def state_names(self, system) -> tuple[str, ...]:
        """The names of the state the oracle integrates (the phase θ last when driven)."""

    @abstractmethod
    def autonomous(self, state: tuple, exprs: list, system, subs) -> tuple[tuple, list]:
        """The first-order system ``(state, right-hand sides)`` made autonomous (θ' = Ω)."""

    @abstractmethod
    def require_driven(self, argument: str, value, fix: str, error=InvalidParameterError) -> None:
        """Raise ``error`` (one line: ``argument``, ``value``, ``fix``) unless driven."""

    @abstractmethod
    def phase_state(self, system, subs, t) -> dict:
        """``{name: values at t}`` the frame adds to a state along a solution, ``subs`` the
        numbers of the system's symbols (ε included)."""


@frozen
class FreeFrame(Frame):
    """An autonomous system: the frequency is sought, the state is the coordinates'.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> x, v = sp.symbols("x v")
    >>> QuasilinearSystem([x], [v], [1], [-EPS * x**3]).frame
    FreeFrame()
    """

    frequency_given: ClassVar[bool] = False
    energy_may_be_conserved: ClassVar[bool] = True
    one_solution_for_all_points: ClassVar[bool] = True

    def extra_symbols(self) -> tuple:
        return ()

    def polynomial_rhs(self, f, where=None):
        return f

    def reference_index(self, system) -> int:
        return 0

    def cache_tag(self) -> tuple:
        return ()

    def state_names(self, system) -> tuple[str, ...]:
        return system.state_names

    def autonomous(self, state, exprs, system, subs):
        return tuple(state), list(exprs)

    def require_driven(self, argument, value, fix, error=InvalidParameterError) -> None:
        raise bad_value(argument, value, fix, error)

    def phase_state(self, system, subs, t) -> dict:
        return {}

    def check(self, system) -> None:
        return None

    def excitation_with(self, subs):
        return None


@frozen
class DrivenFrame(Frame):
    """A system driven by an :class:`~perturb.Excitation`: the frequency is the excitation's.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem
    >>> x, v, th, s = sp.symbols("x v theta sigma")
    >>> system = QuasilinearSystem([x], [v], [1], [EPS * sp.cos(th)], parameters=[s],
    ...     excitation=Excitation(th, 1, s))
    >>> system.frame.state_names(system)
    ('x', 'v', 'theta')
    """

    excitation: object

    frequency_given: ClassVar[bool] = True
    energy_may_be_conserved: ClassVar[bool] = False
    one_solution_for_all_points: ClassVar[bool] = False

    def extra_symbols(self) -> tuple:
        return ((self.excitation.phase, "excitation.phase"),)

    def polynomial_rhs(self, f, where=None):
        if where is None:
            return self.excitation.polynomial_form(f)
        return self.excitation.polynomial_form(f, where)

    def reference_index(self, system) -> int:
        if self.excitation.reference is None:
            return 0
        return [c.name for c in system.coordinates].index(self.excitation.reference)

    def cache_tag(self) -> tuple:
        return (repr(self.excitation),)

    def state_names(self, system) -> tuple[str, ...]:
        return (*system.state_names, self.excitation.phase.name)

    # The one place the drive's relation Ω = (p/q) ω_ref + ε σ is written: symbolic, as a
    # number, and solved for the detuning.
    def frequency(self, system, subs) -> sp.Expr:
        """Ω = (p/q) ω_ref + ε σ, with ``subs`` put in (ε included)."""
        w_ref = system.frequencies[self.reference_index(system)]
        eps = system.parameter if system.regime.value == "small" else 1 / system.parameter
        return sp.sympify(self.excitation.ratio * w_ref + eps * self.excitation.detuning).subs(subs)

    def _parts(self, system, values) -> tuple[sp.Expr, sp.Expr]:
        """``((p/q) ω_ref, σ)`` at the system parameter ``values`` (by name)."""
        subs = {p: values[p.name] for p in system.parameters if p.name in values}
        w_ref = sp.sympify(system.frequencies[self.reference_index(system)]).xreplace(subs)
        return self.excitation.ratio * w_ref, sp.sympify(self.excitation.detuning).xreplace(subs)

    def frequency_value(self, system, values, eps: float) -> float:
        """Ω at the system parameter ``values`` (by name) and ε = ``eps``, a number.

        Raises
        ------
        InvalidParameterError
            When Ω <= 0: a forcing frequency must be positive (one line, with the detuning that
            gives it).
        """
        resonance, sigma = self._parts(system, values)
        omega = float(resonance + eps * sigma)
        if not omega > 0:
            detuning = self.excitation.detuning
            raise InvalidParameterError(
                f"`{detuning}` = {float(sigma):g} is invalid: it makes the excitation frequency "
                f"Omega = {float(resonance):g} + {eps:g}*{detuning} = {omega:g} <= 0; "
                f"give {detuning} > {-float(resonance) / eps:g} (Omega > 0)"
            )
        return omega

    def detuning_value(self, system, omega: float, values, eps: float) -> float:
        """The detuning σ at which the excitation frequency is ``omega`` (the relation solved
        for σ), the other system parameters at ``values`` and ε = ``eps``."""
        resonance, _ = self._parts(system, values)
        return (omega - float(resonance)) / eps

    def autonomous(self, state, exprs, system, subs):
        return (*state, self.excitation.phase), [*exprs, self.frequency(system, subs)]

    def require_driven(self, argument, value, fix, error=InvalidParameterError) -> None:
        return None

    def phase_state(self, system, subs, t) -> dict:
        """The phase θ = Ωt along the times ``t``."""
        import numpy as np

        omega = float(self.frequency(system, subs))
        return {self.excitation.phase.name: omega * np.asarray(t, dtype=float)}

    def check(self, system) -> None:
        """The excitation fits the system: a real coordinate as reference, a detuning in its
        parameters, no clash with the engine's cos/sin symbols, a forcing periodic in t."""
        drive = self.excitation
        names = [c.name for c in system.coordinates]
        if drive.reference is not None and drive.reference not in names:
            raise bad_value(
                "excitation.reference", drive.reference, f"name a coordinate, one of {names}",
                InvalidSystemError,
            )  # fmt: skip
        stray = drive.detuning.free_symbols - set(system.parameters)
        if stray:
            raise bad_value(
                "excitation.detuning", drive.detuning,
                f"it depends on {sorted(map(str, stray))}: declare them in `parameters`",
                InvalidSystemError,
            )  # fmt: skip
        taken = {drive.cos_symbol.name, drive.sin_symbol.name}
        own = {*system.state_symbols, *system.parameters, *system.initial_values, system.parameter}
        clash = sorted(taken & {s.name for s in own})
        if clash:
            raise bad_value(
                "excitation.phase", drive.phase,
                f"{clash} stand for its cosine and sine inside the engine: rename that symbol",
                InvalidSystemError,
            )  # fmt: skip
        for i, f in enumerate(system.rhs):
            drive.polynomial_form(f, f"rhs[{i}]")  # refuses a forcing not periodic in t

    def excitation_with(self, subs):
        """The excitation with some parameters put in (its detuning may hold them)."""
        return attrs.evolve(self.excitation, detuning=self.excitation.detuning.subs(subs))
