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
        Index of the attractor (catalogued, then ``found``), or an :class:`perturb.dynamics.classify.Outcome`'s code.
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
    history = np.full((kmax, total, m), np.nan)  # the last kmax returns, oldest first
    recur = np.zeros((kmax, total), dtype=np.int64)  # returns in a row recurring at k = 1..kmax
    done = 0
    while active.size and done < cap:
        count = min(block, cap - done)
        samples = ensemble.returns(current, count)  # (count, A, m)
        attractors = [*catalogue.attractors, *found]  # those found so far capture from here
        size = active.size
        never = np.full(size, count)
        # escape: the first return not finite or past the bound (NaN compares false)
        with np.errstate(invalid="ignore"):
            fine = np.all(np.abs(samples) <= escape, axis=2)  # (count, A)
        escaped = np.where(np.any(~fine, axis=0), np.argmax(~fine, axis=0), never)
        # capture: the return that completes `need` in a row inside one attractor's radius
        inside = np.full((count, size), -1, dtype=np.int64)
        flat = samples.reshape(-1, m)
        for a, state in enumerate(attractors):
            with np.errstate(invalid="ignore"):
                hit = (inside < 0) & (state.distance(flat).reshape(count, size) <= state.radius)
            inside[hit] = a
        run, held = streak[active], holder[active]
        caught = never.copy()
        for b in range(count):
            same = (inside[b] >= 0) & (inside[b] == held)
            run = np.where(same, run + 1, (inside[b] >= 0).astype(np.int64))
            held = inside[b]
            caught[(caught == count) & (run >= need)] = b
        # recurrence of period k (the smallest), away from every attractor
        sequence = np.concatenate([history[:, active], samples], axis=0)  # oldest first
        again = recur[:, active]
        looped, period_of = never.copy(), np.zeros(size, dtype=np.int64)
        for b in range(count):
            z = sequence[kmax + b]
            past = sequence[b : kmax + b][::-1]  # past[k - 1]: k returns before
            with np.errstate(invalid="ignore"):
                close = np.linalg.norm(z[None] - past, axis=-1) <= recurrence
            again = np.where(close, again + 1, 0)
            ready = again >= need
            new = (looped == count) & np.any(ready, axis=0) & (inside[b] < 0)
            period_of[new] = np.argmax(ready[:, new], axis=0) + 1
            looped[new] = b
        # the earliest event of each state (escape, then capture, then recurrence at a tie)
        event = np.minimum(np.minimum(escaped, caught), looped)
        ended = event < count
        where = active[ended]
        at = event[ended]
        periods[where] = done + at + 1
        final[where] = samples[at, np.flatnonzero(ended)]
        kind = np.where(escaped[ended] == at, 0, np.where(caught[ended] == at, 1, 2))
        codes[where[kind == 0]] = Outcome.ESCAPED.code
        codes[where[kind == 1]] = inside[at[kind == 1], np.flatnonzero(ended)[kind == 1]]
        order = np.argsort(at[kind == 2], kind="stable")
        for j in np.flatnonzero(ended)[kind == 2][order]:
            k, b = int(period_of[j]), int(event[j])
            points = sequence[kmax + b - k + 1 : kmax + b + 1, j].copy()
            if any(s.distance(points[:1])[0] <= s.radius for s in saddles):
                codes[active[j]] = Outcome.ON_SADDLE.code
            else:
                code = _register(found, points, known_points, recurrence)
                codes[active[j]] = len(catalogue.attractors) + code
        alive = ~ended
        keep = active[alive]
        streak[keep], holder[keep] = run[alive], held[alive]
        recur[:, keep] = again[:, alive]
        history[:, keep] = sequence[-kmax:, alive]
        final[keep] = samples[count - 1][alive]
        done += count
        current = samples[count - 1][alive]
        active = keep
    return Classified(codes, periods, final, tuple(found))


def _register(found: list, points, known_points, tol: float) -> int:
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
