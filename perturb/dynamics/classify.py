"""Where each initial state goes: its stroboscopic returns against the catalogue, or a recurrence.

:func:`classify` integrates the states in blocks of :data:`~perturb._defaults.BASIN_BLOCK_PERIODS`
drive periods (:class:`~perturb.dynamics.ensemble.Ensemble`) and, after every return, decides
for each state still running:

* **an attractor of the catalogue** when its return has stayed within that attractor's capture
  radius for :data:`~perturb._defaults.BASIN_CAPTURE_RETURNS` returns in a row (code = the
  attractor's position in :attr:`Catalogue.attractors`);
* **a periodic orbit found on the way**, when no catalogued attractor holds it but its k-th
  return comes back within :data:`~perturb._defaults.BASIN_RECURRENCE_TOL` of it for that many
  returns in a row (k = 1 .. :data:`~perturb._defaults.BASIN_RECURRENCE_MAX_PERIOD`, the smallest
  k): a new attractor (kind :attr:`StateKind.FOUND`, named ``period-k-N``) with its k points,
  which then captures other states as the catalogued ones do;
* **at a saddle**, when that recurrence is at a catalogued unstable state (a state started on
  its stable manifold: the saddle itself, on a grid through it);
* **escaped**, when the state grows past :data:`~perturb._defaults.BASIN_ESCAPE_FACTOR` times
  the catalogue's scale or becomes non-finite (a blow-up);
* **no convergence within the cap**, when ``cap`` periods pass without any of these.

A state is never put into a known class it did not reach: what is not captured is told apart.
"""

from __future__ import annotations

import enum

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    BASIN_BLOCK_PERIODS,
    BASIN_CAPTURE_RETURNS,
    BASIN_CAPTURE_SHARE,
    BASIN_ESCAPE_FACTOR,
    BASIN_RECURRENCE_MAX_PERIOD,
    BASIN_RECURRENCE_TOL,
)
from perturb.dynamics.attractors import StateKind, SteadyOrbit

__all__ = ["Classified", "Outcome", "classify", "merge_found", "outcome_meanings"]


class Outcome(enum.Enum):
    """A state that reached no attractor; the values are the messages."""

    NO_CONVERGENCE = "no convergence within the cap of periods"
    ESCAPED = "escapes: the motion grows without bound (or blew up)"
    NOT_COMPUTED = "not computed"
    ON_SADDLE = "stays at an unstable steady state (started on its stable manifold)"

    @property
    def code(self) -> int:
        """Its (negative) code in a basin map."""
        return _CODES[self]


_CODES = {
    Outcome.NO_CONVERGENCE: -1,
    Outcome.ESCAPED: -2,
    Outcome.NOT_COMPUTED: -3,
    Outcome.ON_SADDLE: -4,
}


def outcome_meanings() -> dict[int, str]:
    """``{code: meaning}`` of the outcomes that are not attractors."""
    return {outcome.code: outcome.value for outcome in Outcome}


@frozen
class Classified:
    """The classification of M states.

    Attributes
    ----------
    codes : ndarray of int, shape (M,)
        Index of the attractor (catalogued, then ``found``), or an :class:`Outcome`'s code.
    periods : ndarray of int, shape (M,)
        Drive periods until classified (the cap when not converged; where it escaped).
    final : ndarray, shape (M, m)
        The last return computed of each state.
    found : tuple of SteadyOrbit
        Attractors found by recurrence (codes ``len(catalogue.attractors) + j``).
    """

    codes: np.ndarray = field(eq=False)
    periods: np.ndarray = field(eq=False)
    final: np.ndarray = field(eq=False)
    found: tuple = field(converter=tuple, factory=tuple)


def _found_radius(points: np.ndarray, known: list[np.ndarray]) -> float:
    gaps = [float(np.min(np.linalg.norm(points[:, None] - k[None], axis=-1))) for k in known]
    if points.shape[0] > 1:
        d = np.linalg.norm(points[:, None] - points[None], axis=-1)
        gaps.append(float(np.min(d[~np.eye(points.shape[0], dtype=bool)])))
    if not gaps:
        gaps.append(max(float(np.max(np.linalg.norm(points, axis=1))), 1.0))
    return BASIN_CAPTURE_SHARE * min(gaps)


def same_orbit(a: SteadyOrbit, b: SteadyOrbit, tol: float) -> bool:
    """Whether two found orbits are one: the same period, every point of one within ``tol`` of
    a point of the other."""
    if a.period != b.period:
        return False
    return bool(np.all(b.distance(a.points) <= tol))


def classify(
    ensemble, catalogue, states, cap: int, *, block: int = BASIN_BLOCK_PERIODS
) -> Classified:
    """Classify each of ``states`` (shape (M, m), on the catalogue's section) by where its
    motion goes within ``cap`` drive periods (see the module notes).

    Parameters
    ----------
    ensemble : Ensemble
        The integrator, on the catalogue's section.
    catalogue : Catalogue
        Its attractors capture; its saddles only bound the found orbits' radii.
    states : array_like, shape (M, m)
    cap : int
        The most drive periods a state is followed (>= 1).
    block : int
        Drive periods integrated between two decisions.
    """
    y = np.array(states, dtype=float, ndmin=2)
    total, m = y.shape
    attractors = list(catalogue.attractors)
    saddles = list(catalogue.saddles)
    known_points = [s.points for s in catalogue.states]
    scale = catalogue.scale
    escape = BASIN_ESCAPE_FACTOR * scale
    recurrence = BASIN_RECURRENCE_TOL * scale
    codes = np.full(total, Outcome.NO_CONVERGENCE.code, dtype=np.int64)
    periods = np.full(total, int(cap), dtype=np.int64)
    final = y.copy()
    found: list[SteadyOrbit] = []
    kmax = BASIN_RECURRENCE_MAX_PERIOD
    need = BASIN_CAPTURE_RETURNS
    active = np.arange(total)
    current = y.copy()
    streak = np.zeros(total, dtype=np.int64)  # returns in a row inside one attractor's radius
    holder = np.full(total, -1, dtype=np.int64)  # that attractor
    history = np.full((kmax, total, m), np.nan)  # the last kmax returns, newest first
    recur = np.zeros((kmax, total), dtype=np.int64)  # returns in a row recurring at k = 1..kmax
    done = 0
    while active.size and done < cap:
        count = min(block, cap - done)
        samples = ensemble.returns(current, count)  # (count, A, m)
        alive = np.ones(active.size, dtype=bool)
        for b in range(count):
            z = samples[b]
            n = done + b + 1
            # escape
            bad = alive & ~(np.all(np.isfinite(z), axis=1) & (np.max(np.abs(z), axis=1) <= escape))
            if np.any(bad):
                codes[active[bad]] = Outcome.ESCAPED.code
                periods[active[bad]] = n
                final[active[bad]] = z[bad]
                alive &= ~bad
            # capture by an attractor (the radii do not overlap: a tenth of the gaps)
            inside = np.full(active.size, -1, dtype=np.int64)
            for a, state in enumerate(attractors):
                hit = (inside < 0) & (state.distance(z) <= state.radius)
                inside[hit] = a
            same = (inside >= 0) & (inside == holder[active])
            streak[active] = np.where(same, streak[active] + 1, (inside >= 0).astype(np.int64))
            holder[active] = inside
            caught = alive & (streak[active] >= need)
            if np.any(caught):
                codes[active[caught]] = inside[caught]
                periods[active[caught]] = n
                final[active[caught]] = z[caught]
                alive &= ~caught
            # recurrence of period k (the smallest), away from every attractor
            past = history[:, active]
            close = np.linalg.norm(z[None] - past, axis=-1) <= recurrence  # (kmax, A)
            recur[:, active] = np.where(close, recur[:, active] + 1, 0)
            history[1:, active] = past[:-1]
            history[0, active] = z
            ready = recur[:, active] >= need
            looped = alive & np.any(ready, axis=0) & (inside < 0)
            for j in np.flatnonzero(looped):
                k = int(np.argmax(ready[:, j])) + 1
                points = history[:k, active[j]][::-1].copy()
                if any(s.distance(points[:1])[0] <= s.radius for s in saddles):
                    codes[active[j]] = Outcome.ON_SADDLE.code
                else:
                    code = _register(found, points, known_points, attractors, recurrence)
                    codes[active[j]] = len(catalogue.attractors) + code
                periods[active[j]] = n
                final[active[j]] = z[j]
                alive[j] = False
            attractors = [*catalogue.attractors, *found]
        final[active[alive]] = samples[count - 1][alive]
        done += count
        current = samples[count - 1][alive]
        active = active[alive]
    return Classified(codes, periods, final, tuple(found))


def _register(found: list, points, known_points, attractors, tol: float) -> int:
    """The index in ``found`` of the orbit through ``points`` (added when new)."""
    k = points.shape[0]
    candidate = SteadyOrbit(f"period-{k}", StateKind.FOUND, points)
    for i, orbit in enumerate(found):
        if same_orbit(candidate, orbit, max(orbit.radius, tol)):
            return i
    known = [*known_points, *(f.points for f in found)]
    radius = _found_radius(points, known)
    name = f"period-{k}-{sum(f.period == k for f in found) + 1}"
    found.append(SteadyOrbit(name, StateKind.FOUND, points, radius=radius,
                             message=f"a period-{k} recurrence of the stroboscopic map"))  # fmt: skip
    return len(found) - 1


def merge_found(known: list, new: tuple, scale: float) -> dict[int, int]:
    """Add the orbits ``new`` (found in one chunk) to ``known`` (those of the whole map, kept
    in order) where they are not there yet; ``{index in new: index in known}``."""
    mapping = {}
    for i, orbit in enumerate(new):
        for j, other in enumerate(known):
            if same_orbit(orbit, other, max(other.radius, BASIN_RECURRENCE_TOL * scale)):
                mapping[i] = j
                break
        else:
            k = orbit.period
            name = f"period-{k}-{sum(o.period == k for o in known) + 1}"
            known.append(
                SteadyOrbit(
                    name,
                    StateKind.FOUND,
                    orbit.points,
                    orbit.multipliers,
                    orbit.radius,
                    orbit.message,
                )  # fmt: skip
            )
            mapping[i] = len(known) - 1
    return mapping
