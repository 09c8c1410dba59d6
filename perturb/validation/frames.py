"""What a case solves, checks and prints, by the type of its frame: one table (:data:`WORK`).

A free system's frequency is sought: one solution, symbolic in the parameters, serves every
point; its families are found once (:func:`perturb.find_families`); its true orbit is shot on a
Poincaré section with the period unknown, and the fourth measurement of the verdict is the
period. A driven system's frequency is the drive's: each point has its own steady states (the
branches of its response, :func:`perturb.steady.steady_state`), the true orbit is shot with the
period given, and the fourth measurement is stability. Instead of a question asked of the frame
wherever that matters, the models (``problems.Problem``, :class:`~perturb.validation.SystemModel`),
:func:`~perturb.validation.validate` and the CLI take the entry for their system's frame
(:func:`work_of`) and let it do the work:

============================  ============================  ==================================
                              free (:class:`FreeWork`)      driven (:class:`DrivenWork`)
============================  ============================  ==================================
a point's solution            the one symbolic solution     the point's steady-state branch
the families                  :func:`perturb.find_families` the point's branches
the state along a solution    the solution's own            the solution's, the phase appended
the true orbit                shot on a section (+ the      shot over the given period
                              model's own finder)
the fourth measurement        the period                    stability (Floquet)
a family name not found       unknown (exit 2)              a branch that exists elsewhere
the default order             FREE_ORDER (1)                DRIVEN_ORDER (3)
the families' marks           the domain flags alone        the response's marks (stability
                                                            within the series' error of 1)
============================  ============================  ==================================
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping

from perturb._defaults import DRIVEN_ORDER, FREE_ORDER
from perturb.frame import DrivenFrame, FreeFrame
from perturb.validation.capabilities import label_of
from perturb.validation.forced import analytic_stability, forced_orbit_check, stability_check
from perturb.validation.orbit import orbit_check, with_model_true_orbit

__all__ = ["WORK", "DrivenWork", "FrameWork", "FreeWork", "steady_states", "work_of"]

#: The steady states of driven systems, by system, order and point (every branch at once: a
#: family asked for by name at a point already solved costs a lookup).
_STEADY: dict[tuple, object] = {}


def steady_states(system, order: int, symbol_values: Mapping[str, float], epsilon: float):
    """Every branch of the driven ``system``'s response at a point
    (:func:`perturb.steady.steady_state`), kept per system, order and point (the order below,
    whose names the branches inherit, kept with it)."""
    from perturb.steady import steady_state

    key = (system, order, tuple(sorted(symbol_values.items())), epsilon)
    if key not in _STEADY:
        lower = steady_states(system, order - 1, symbol_values, epsilon) if order > 0 else None
        _STEADY[key] = steady_state(system, dict(symbol_values), epsilon, order, lower)
    return _STEADY[key]


class FrameWork(ABC):
    """What a case of one frame type solves, checks and prints (an entry of :data:`WORK`).

    ``model`` below is a :class:`~perturb.validation.Model` at a point (a problem, a bare
    system with numbers); ``options`` its method options.
    """

    @abstractmethod
    def point_key(self, model) -> tuple:
        """What a solution depends on besides the system and the method options (a cache key)."""

    @abstractmethod
    def solve(self, model, order: int, options: dict, family=None, named=None):
        """The solution: the family ``family`` (a name; ``named(name)`` gives a named family
        where the frame has one solution for all points) or the default one."""

    @abstractmethod
    def families(self, model, system, order: int, options: dict):
        """Every family (:class:`perturb.FamilyList`; ``system`` and ``options``: the frame of
        the families, e.g. a reduced system)."""

    @abstractmethod
    def state_is_solution(self) -> bool:
        """Whether the state along a solution is the solution's own ``evaluate`` (nothing added
        by the frame), so that many points are one vectorised evaluation."""

    @abstractmethod
    def measure_orbit(self, model, solution, equations, y0, period, integrator, rtol, stiff,
                      setup: Callable, budget):  # fmt: skip
        """The true orbit near the analytic one, measured (:class:`~perturb.validation.OrbitCheck`);
        ``setup()`` gives the shooting set-up where the frame needs one."""

    @abstractmethod
    def checks(self, checks: tuple, model, solution, orbit, why_no_orbit: str) -> tuple:
        """The verdict's four measurements, the fourth the frame's own."""

    @abstractmethod
    def family_elsewhere(self, name: str) -> bool:
        """Whether ``name``, not a family here, may name one at other parameter values (the run
        then fails with the families there are, instead of refusing the name)."""

    @property
    @abstractmethod
    def default_order(self) -> int:
        """The order every command uses when none is given (printed in each header)."""

    @property
    @abstractmethod
    def families_are_steady_states(self) -> bool:
        """Whether the families are steady states with a stability of their own (the response's
        marks then apply to them)."""


class FreeWork(FrameWork):
    """A free system: the frequency sought (see the module docstring)."""

    def point_key(self, model) -> tuple:
        return ()  # one solution, symbolic in the parameters, for every point

    def solve(self, model, order, options, family=None, named=None):
        if family is not None and named is not None:
            return named(family)
        from perturb.method import PoincareMethod

        return PoincareMethod(order=order, **options).solve(model.system())

    def families(self, model, system, order, options):
        from perturb import find_families

        return find_families(system, order, **options)

    def state_is_solution(self) -> bool:
        return True

    def measure_orbit(self, model, solution, equations, y0, period, integrator, rtol, stiff,
                      setup, budget):  # fmt: skip
        orbit = orbit_check(
            model, solution, equations, y0, period, setup(), integrator, rtol, stiff, budget
        )
        if orbit.success and not orbit.resolved:
            orbit = with_model_true_orbit(
                model, solution, equations, y0, period, orbit, integrator, rtol, stiff
            )
        return orbit

    def checks(self, checks, model, solution, orbit, why_no_orbit) -> tuple:
        return checks

    def family_elsewhere(self, name: str) -> bool:
        return False

    @property
    def default_order(self) -> int:
        return FREE_ORDER  # a rigid body's derivation grows steeply with the order

    @property
    def families_are_steady_states(self) -> bool:
        return False


class DrivenWork(FrameWork):
    """A driven system: the frequency the drive's (see the module docstring)."""

    def point_key(self, model) -> tuple:
        return (repr(sorted(model.symbol_values().items())), model.epsilon())

    def _state(self, model, order: int):
        return steady_states(model.system(), order, model.symbol_values(), model.epsilon())

    def solve(self, model, order, options, family=None, named=None):
        return self._state(model, order).solution(family)

    def families(self, model, system, order, options):
        return self._state(model, order).families(label_of(model), order)

    def state_is_solution(self) -> bool:
        return False  # the state carries the drive's phase

    def measure_orbit(self, model, solution, equations, y0, period, integrator, rtol, stiff,
                      setup, budget):  # fmt: skip
        return forced_orbit_check(
            model, solution, equations, y0, period, integrator, rtol, stiff
        )  # the period is the excitation's: no section

    def checks(self, checks, model, solution, orbit, why_no_orbit) -> tuple:
        existence, accuracy, _, order_check = checks  # stability is the fourth measurement
        stable = analytic_stability(model, solution) if orbit is not None else None
        return (existence, accuracy, stability_check(orbit, stable, why_no_orbit), order_check)

    def family_elsewhere(self, name: str) -> bool:
        from perturb.steady.branches import count_name

        return bool(count_name(name))  # a branch that exists elsewhere, not here

    @property
    def default_order(self) -> int:
        return DRIVEN_ORDER  # the response is continued: order 3 costs about what order 1 does

    @property
    def families_are_steady_states(self) -> bool:
        return True


#: The work of each frame type (a new kind of system is a new frame and an entry here).
WORK: dict[type, FrameWork] = {FreeFrame: FreeWork(), DrivenFrame: DrivenWork()}


def work_of(system) -> FrameWork:
    """The entry of :data:`WORK` for ``system``'s frame.

    Parameters
    ----------
    system : QuasilinearSystem

    Returns
    -------
    FrameWork

    Examples
    --------
    >>> from perturb.validation.frames import work_of
    >>> from problems import get_problem
    >>> type(work_of(get_problem("duffing").system())).__name__
    'FreeWork'
    >>> type(work_of(get_problem("forced-duffing").system())).__name__
    'DrivenWork'
    """
    return WORK[type(system.frame)]
