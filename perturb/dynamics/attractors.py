"""The catalogue of a driven problem's steady states on a section: proved, with their multipliers.

:func:`catalogue` takes every order-N branch the series finds at the problem's values
(:func:`perturb.steady.steady_state`), shoots each from its analytic state with the period fixed
(:func:`perturb.oracle.find_forced_orbit`), and keeps what the shooting proves: a periodic orbit
with its Floquet multipliers. A stable one (every multiplier inside the unit circle by
:data:`~perturb._defaults.DYNAMICS_MULTIPLIER_MARGIN`) is an **attractor**; an unstable one a
**saddle** (drawn on a basin map; its stable manifold bounds the basins). Each is given by its
points on the section at the drive phase φ: the true orbit's state at θ = φ, φ + 2π, …, one point
per drive period of its response (p points for a response of p drive periods), and a capture
radius, :data:`~perturb._defaults.BASIN_CAPTURE_SHARE` of its distance to the nearest other
catalogued point.

Branches that shoot to one orbit are one state; a branch whose shooting fails is left out with
the reason (``notes``), never kept unproved.
"""

from __future__ import annotations

import enum
import math

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    BASIN_CAPTURE_SHARE,
    DEFAULT_RTOL,
    DYNAMICS_MULTIPLIER_MARGIN,
    SHOOTING_ITERATIONS,
)
from perturb.errors import InvalidParameterError, bad_value
from perturb.validation.capabilities import label_of

__all__ = [
    "Catalogue",
    "CatalogueStatus",
    "StateKind",
    "SteadyOrbit",
    "catalogue",
    "confirm",
    "decode",
    "decode_state",
    "encode",
    "encode_state",
    "orbit_points",
]


class StateKind(enum.Enum):
    """What a catalogued state is; the values are the messages."""

    ATTRACTOR = "stable steady state (proved by shooting)"
    SADDLE = "unstable steady state (proved by shooting)"
    FOUND = "periodic attractor found by the motion (not a branch of the series)"


class CatalogueStatus(enum.Enum):
    """Whether a catalogue can classify motions; the values are the messages."""

    OK = "the series' steady states, proved by shooting"
    NO_STABLE_STATE = "no stable steady state was found: nothing to classify the motion against"

    @property
    def success(self) -> bool:
        """True only for :attr:`OK`."""
        return self is CatalogueStatus.OK


@frozen
class SteadyOrbit:
    """One steady state on the section.

    Attributes
    ----------
    name : str
        The branch's name (``lower``, ``upper``, …), or ``period-k-N`` for one found by the motion.
    kind : StateKind
    points : ndarray, shape (p, m)
        Its states at θ = φ + 2πj, j = 0..p-1 (p drive periods in its period).
    multipliers : tuple of complex
        Floquet multipliers of the true orbit (over its period).
    radius : float
        Capture radius on the section.
    message : str
        The shooting's own sentence.
    """

    name: str
    kind: StateKind
    points: np.ndarray = field(eq=False, converter=lambda v: np.array(v, dtype=float, ndmin=2))
    multipliers: tuple = field(converter=tuple, factory=tuple)
    radius: float = math.nan
    message: str = ""

    @property
    def period(self) -> int:
        """Drive periods in its period."""
        return int(self.points.shape[0])

    @property
    def largest_multiplier(self) -> float:
        """The largest modulus of the multipliers (NaN when none)."""
        return max((abs(z) for z in self.multipliers), default=math.nan)

    def distance(self, states: np.ndarray) -> np.ndarray:
        """The distance of each of ``states`` (shape (M, m)) to the nearest of its points."""
        diff = states[:, None, :] - self.points[None, :, :]
        return np.min(np.sqrt(np.sum(diff * diff, axis=-1)), axis=1)


@frozen
class Catalogue:
    """A driven problem's steady states on the section at drive phase ``phase``.

    Attributes
    ----------
    problem : str
    values : dict
        The problem's parameters in force.
    order : int
        The series' order whose branches were shot.
    phase : float
        The section's drive phase φ (radians).
    omega : float
        The drive frequency.
    names : tuple of str
        The state's components (without θ).
    states : tuple of SteadyOrbit
        Attractors first (by amplitude), then saddles.
    status : CatalogueStatus
    notes : tuple of str
        Branches left out, and why.
    """

    problem: str
    values: dict
    order: int
    phase: float
    omega: float
    names: tuple = field(converter=tuple)
    states: tuple = field(converter=tuple)
    status: CatalogueStatus = CatalogueStatus.OK
    notes: tuple = field(converter=tuple, factory=tuple)

    @property
    def attractors(self) -> tuple:
        """The stable states (their codes are their positions here)."""
        return tuple(s for s in self.states if s.kind is not StateKind.SADDLE)

    @property
    def saddles(self) -> tuple:
        return tuple(s for s in self.states if s.kind is StateKind.SADDLE)

    @property
    def message(self) -> str:
        """The status, with the notes when it failed."""
        if self.status.success:
            return self.status.value
        return "; ".join([self.status.value, *self.notes])

    @property
    def scale(self) -> float:
        """The size of the catalogued states (the largest norm of their points, at least 1)."""
        norms = [float(np.max(np.linalg.norm(s.points, axis=1))) for s in self.states]
        return max([1.0, *norms])

    def with_found(self, found) -> Catalogue:
        """The catalogue with the attractors ``found`` by the motion appended to its attractors
        (their codes follow the series' ones)."""
        import attrs

        return attrs.evolve(self, states=(*self.attractors, *found, *self.saddles))


def orbit_points(motion, y0: np.ndarray, phase: float) -> np.ndarray:
    """The orbit through ``y0`` (at θ = 0) at θ = φ + 2πj, j = 0..p-1: shape (p, m)."""
    from perturb.oracle import choose

    p = motion.response_periods
    t0 = (phase % (2 * math.pi)) / motion.omega
    times = t0 + motion.drive_period * np.arange(p)
    if times[-1] == 0.0:
        return y0[None, :].copy()
    solver = choose(None, rtol=DEFAULT_RTOL, symbolic=True)
    traj = solver.integrate(motion.rhs, (0.0, float(times[-1])), np.append(y0, 0.0), t_eval=times)
    traj.raise_for_status()
    return np.asarray(traj.y, dtype=float)[: motion.m].T


def _radius(states: list, k: int) -> float:
    """The capture radius of ``states[k]``: a share of its distance to any other point."""
    own = states[k][1]
    others = [pts for j, (_, pts) in enumerate(states) if j != k]
    gaps = []
    for pts in others:
        gaps.append(float(np.min(np.linalg.norm(own[:, None, :] - pts[None, :, :], axis=-1))))
    if own.shape[0] > 1:
        d = np.linalg.norm(own[:, None, :] - own[None, :, :], axis=-1)
        gaps.append(float(np.min(d[~np.eye(own.shape[0], dtype=bool)])))
    if not gaps:  # alone: the size of the state itself (at least 1)
        gaps.append(max(float(np.max(np.linalg.norm(own, axis=1))), 1.0))
    return BASIN_CAPTURE_SHARE * min(gaps)


def catalogue(problem, order: int = 1, phase: float = 0.0, motion=None) -> Catalogue:
    """The steady states of the driven ``problem`` on the section at drive phase ``phase``.

    Parameters
    ----------
    problem : problems.base.Problem or perturb.validation.Model
        A driven problem at its parameter values.
    order : int
        The order N of the series whose branches seed the shooting.
    phase : float
        φ, radians.
    motion : DrivenMotion, optional
        The problem's motion (:func:`perturb.dynamics.motion.motion_of`), if already built.

    Returns
    -------
    Catalogue
        ``status`` :attr:`CatalogueStatus.NO_STABLE_STATE` (a failed study, with the reasons in
        ``notes``) when no branch shoots to a stable orbit.

    Raises
    ------
    InvalidParameterError
        A problem that is not driven, an order below 1, a phase not finite.
    """
    from perturb.dynamics.motion import motion_of
    from perturb.oracle import find_forced_orbit
    from perturb.steady import branch_solution, steady_state

    if isinstance(order, bool) or not isinstance(order, int) or order < 1:
        raise bad_value("order", order, "give an integer >= 1", InvalidParameterError)
    if not math.isfinite(phase):
        raise bad_value("phase", phase, "give a finite drive phase (radians)",
                        InvalidParameterError)  # fmt: skip
    motion = motion_of(problem) if motion is None else motion
    steady = steady_state(problem.system(), problem.symbol_values(), problem.epsilon(), order)
    notes = [f"the series found no steady state: {steady.why}"] if steady.why else []
    period = motion.response_periods * motion.drive_period
    proved: list[tuple[str, np.ndarray, object]] = []
    for point, name in zip(steady.points, steady.names, strict=True):
        solution = branch_solution(steady.equations, point, name)
        at = problem.state(solution, np.array([0.0]))
        y0 = np.array([float(np.asarray(at[n]).ravel()[0]) for n in motion.names])
        orbit = find_forced_orbit(motion.rhs, y0, period, max_iter=SHOOTING_ITERATIONS)
        if not orbit.success:
            notes.append(f"branch {name}: the shooting failed ({orbit.message})")
            continue
        start = np.asarray(orbit.initial_state, dtype=float)
        scale = max(float(np.max(np.abs(start))), 1.0)
        same = [n for n, y, _ in proved if float(np.max(np.abs(y - start))) <= 1e-6 * scale]
        if same:
            notes.append(f"branch {name}: shoots to the orbit of branch {same[0]}")
            continue
        proved.append((name, start, orbit))
    states = []
    for name, start, orbit in proved:
        largest = max(abs(z) for z in orbit.multipliers)
        if largest < 1 - DYNAMICS_MULTIPLIER_MARGIN:
            kind = StateKind.ATTRACTOR
        elif largest > 1 + DYNAMICS_MULTIPLIER_MARGIN:
            kind = StateKind.SADDLE
        else:
            notes.append(f"branch {name}: marginal (largest |multiplier| {largest:.9f}), left out")
            continue
        states.append((name, orbit_points(motion, start, phase), orbit, kind))
    placed = [(name, pts) for name, pts, _, _ in states]
    out = [
        SteadyOrbit(
            name,
            kind,
            pts,
            tuple(complex(z) for z in orbit.multipliers),
            _radius(placed, k),
            orbit.message,
        )  # fmt: skip
        for k, (name, pts, orbit, kind) in enumerate(states)
    ]
    attractors = [s for s in out if s.kind is StateKind.ATTRACTOR]
    saddles = [s for s in out if s.kind is StateKind.SADDLE]
    status = CatalogueStatus.OK if attractors else CatalogueStatus.NO_STABLE_STATE
    return Catalogue(
        problem=label_of(problem), values=dict(problem.case().values), order=order,
        phase=float(phase), omega=motion.omega, names=motion.names,
        states=(*attractors, *saddles), status=status, notes=tuple(notes),
    )  # fmt: skip


def encode(catalogue: Catalogue) -> str:
    """The catalogue as JSON (kept beside a basin map, so that a resumed run classifies the same
    way: :func:`perturb.dynamics.attractors.decode`)."""
    import json

    return json.dumps(
        {
            "problem": catalogue.problem,
            "values": {k: float(v) for k, v in catalogue.values.items()},
            "order": catalogue.order,
            "phase": catalogue.phase,
            "omega": catalogue.omega,
            "names": list(catalogue.names),
            "status": catalogue.status.name,
            "notes": list(catalogue.notes),
            "states": [encode_state(s) for s in catalogue.states],
        }
    )


def encode_state(state: SteadyOrbit) -> dict:
    """One state as :func:`perturb.dynamics.attractors.encode` writes it (JSON-ready)."""
    return {
        "name": state.name,
        "kind": state.kind.name,
        "points": state.points.tolist(),
        "multipliers": [[z.real, z.imag] for z in state.multipliers],
        "radius": state.radius,
        "message": state.message,
    }


def decode_state(data: dict) -> SteadyOrbit:
    """A state from :func:`perturb.dynamics.attractors.encode`'s form."""
    return SteadyOrbit(
        data["name"], StateKind[data["kind"]], np.array(data["points"], dtype=float),
        tuple(complex(re, im) for re, im in data.get("multipliers", ())),
        float(data.get("radius", math.nan)), data.get("message", ""),
    )  # fmt: skip


def decode(text: str) -> Catalogue:
    """The catalogue :func:`perturb.dynamics.attractors.encode` wrote."""
    import json

    data = json.loads(text)
    return Catalogue(
        problem=data["problem"], values=data["values"], order=int(data["order"]),
        phase=float(data["phase"]), omega=float(data["omega"]), names=data["names"],
        states=[decode_state(s) for s in data["states"]],
        status=CatalogueStatus[data["status"]], notes=data["notes"],
    )  # fmt: skip


def confirm(motion, orbit: SteadyOrbit, phase: float) -> SteadyOrbit:
    """An orbit found by the motion (on the section at ``phase``), shot with its period fixed:
    the same orbit with the shooting's multipliers and sentence, or its message saying that the
    shooting did not confirm it (it is kept: the motion recurred there)."""
    import attrs

    from perturb.oracle import choose, find_forced_orbit

    back = (-phase) % (2 * math.pi) / motion.omega  # from theta = phase on to theta = 0 (mod 2 pi)
    start = orbit.points[0]
    if back > 0:
        solver = choose(None, rtol=DEFAULT_RTOL, symbolic=True)
        traj = solver.integrate(motion.rhs, (0.0, back), np.append(start, phase))
        if not traj.success:
            return attrs.evolve(orbit, message=f"{orbit.message}; not shot ({traj.message})")
        start = np.asarray(traj.y_final, dtype=float)[: motion.m]
    shot = find_forced_orbit(
        motion.rhs, start, orbit.period * motion.drive_period, max_iter=SHOOTING_ITERATIONS
    )
    if not shot.success:
        return attrs.evolve(orbit, message=f"{orbit.message}; the shooting did not confirm it "
                            f"({shot.message})")  # fmt: skip
    return attrs.evolve(
        orbit,
        multipliers=tuple(complex(z) for z in shot.multipliers),
        message=f"{orbit.message}; proved by shooting: {shot.message}",
    )
