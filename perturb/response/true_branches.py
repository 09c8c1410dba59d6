"""The whole diagram of the true responses: every branch born on a true curve, followed.

:mod:`perturb.response.true_curve` continues the true curves through the analytic branches'
seeds; this module follows what is born on them, as AUTO-07p and BifurcationKit.jl users do:

* **Branch points.** On a symmetric system (:func:`~perturb.response.true_maps.half_period_symmetry`)
  a curve of symmetric responses loses its symmetry at a pitchfork: the half-period map
  H = −φ_{T/2} has a multiplier −1 there. Its test function det(DH + I) is evaluated along the
  curve, each sign change located on it and refined as a regular zero of {R_H = 0, det(DH + I) = 0}
  (:func:`~perturb.response.true_maps.refine`). The kernel of the full map's [M − I | s] there
  is the symmetric curve's tangent and (v, 0), v the eigenvector of DH for −1: the asymmetric pair
  is tangent to ±(v, 0). Any other branch point (located by the bordered determinant) takes the
  direction of its kernel orthogonal to the tangent.
* **Period doublings.** A multiplier −1 of the k-period map, refined by {R_k = 0, det(M_k + I) = 0};
  the 2k-period map has the k-period curve and the doubled one crossing there, the latter tangent
  to (v, 0), v the eigenvector for −1; it is followed, its own doublings too, up to ``max_period``.
* **Switching.** From the birth point x*, the predictor x* + h d (d the new branch's direction, h
  ``BRANCH_SWITCH_FRACTION`` of the largest step), the corrector on the hyperplane through it
  across d (the parent crosses it only far away), then the continuation away from x*, with the
  same test functions. A start already on a branch of the same period (or the same orbit shifted
  by a period: a doubled orbit's other half) is not followed twice.
* **Neimark–Sacker.** The rotation number of the torus born there: the argument of the complex
  multiplier over 2π.
* **Linear systems** (a Mathieu equation): every response is a multiple of another, and what is
  born at a branch point is a line of responses at one λ, not a curve: the special points are
  located and listed, nothing is followed from them.

Each branch is a record: its period (in response periods of the parent problem), its parent and
the kind of point that bore it (``seed`` for the curves through the analytic branches).
"""

from __future__ import annotations

import math

import attrs
import numpy as np
from attrs import define, field, frozen

from perturb._defaults import (
    BRANCH_SWITCH_FRACTION,
    MAX_BRANCHES,
    TRUE_CURVE_SAME_ORBIT,
)
from perturb.response.true_family import floquet_tests
from perturb.response.true_maps import MapEquations, half_period_symmetry, refine
from perturb.response.true_results import BRANCH_POINT, PERIOD_DOUBLING

__all__ = ["Birth", "Record", "follow_births"]

#: How a record's branch was born.
SEED = "seed"


@frozen
class Birth:
    """A special point that bears a branch: its kind, where (``x``, scaled), the new branch's
    direction there and period, the record it lies on, whether it was refined (``note`` says how
    it was located)."""

    kind: str
    x: np.ndarray = field(converter=lambda v: np.asarray(v, dtype=float), eq=False)
    direction: np.ndarray = field(eq=False)
    period: int
    parent: object = field(eq=False)
    located: bool
    note: str
    symmetric: bool = False


@define(eq=False)
class Record:
    """One branch of the diagram, as it is built: its continued curve (scaled unknowns), the map
    equations it was followed on (its ``period`` in response periods), its parent record's index
    (None for a seeded curve), the kind of its birth and where (λ), its refined special points
    ``(kind, x, located, note)``, the analytic branches on it, the shots it took and its last
    failure."""

    curve: object
    equations: object
    period: int = field(converter=int)
    parent: int | None = None
    birth: str = SEED
    born_at: float = field(default=math.nan, converter=float)
    refined: list = field(factory=list)
    branches: list = field(factory=list)
    shots: int = 0
    failure: str = ""


def _on(curve, x) -> bool:
    if curve.points.shape[0] < 2:
        return False
    readings = curve.values_at([float(x[-1])])[0]
    scale = max(1.0, float(np.max(np.abs(x))))
    return any(float(np.max(np.abs(r - x))) <= 1e3 * TRUE_CURVE_SAME_ORBIT * scale
               for r in readings)  # fmt: skip


def _symmetric(half: MapEquations, curve) -> bool:
    """Whether the curve's responses are symmetric: H(y) = y at its middle point."""
    x = curve.points[len(curve.points) // 2]
    residual = half.residual(x)
    return bool(np.all(np.isfinite(residual))) and float(np.max(np.abs(residual))) <= (
        1e3 * TRUE_CURVE_SAME_ORBIT * max(1.0, float(np.max(np.abs(x))))
    )


def _half_test(mono) -> float:
    return float(np.linalg.det(mono + np.eye(mono.shape[0])))


def _eigenvector(mono, target: float) -> np.ndarray:
    values, vectors = np.linalg.eig(mono)
    k = int(np.argmin(np.abs(values - target)))
    v = np.real(vectors[:, k])
    return v / float(np.linalg.norm(v))


def _pitchforks(record: Record, half: MapEquations) -> list[Birth]:
    """The symmetry-breaking pitchforks on a symmetric record's curve (module notes)."""
    from perturb.continuation import TestFunction, locate_on_curve

    curve = record.curve
    values = []
    for x in curve.points:
        mono = half.monodromy(x)
        values.append(math.nan if mono is None else _half_test(mono))
    test = TestFunction(
        "pitchfork",
        lambda x, t, j: (
            _half_test(half.monodromy(x)) if half.monodromy(x) is not None else math.nan
        ),
    )
    out = []
    for k in range(len(values) - 1):
        a, b = values[k], values[k + 1]
        if not (math.isfinite(a) and math.isfinite(b)) or a == 0 or (a > 0) == (b > 0):
            continue
        point = locate_on_curve(curve, test, k, a, b)
        # beside a branch point the full map's corrector may fail on the segment: Newton on the
        # augmented system (regular there) starts from the end nearer the zero instead
        start = point.x if point is not None else curve.points[k if abs(a) < abs(b) else k + 1]
        x, _ = refine(half, _half_test, start)
        located, note = x is not None, "symmetry-breaking pitchfork (half-period map at -1)"
        if x is None:
            x = start
            note += "; Newton on the augmented system did not converge: the secant's point"
        mono = half.monodromy(x)
        if mono is None:
            continue
        v = _eigenvector(mono, -1.0)
        direction = np.append(v, 0.0)
        out.append(Birth(BRANCH_POINT, x, direction, record.period, record, located, note, True))
    return out


def _other_branch_points(record: Record, known: list[Birth], records) -> list[Birth]:
    """Branch points of the bordered determinant not among the refined pitchforks and doublings
    (this record's, or another's where this curve meets it: its birth, or where it rejoins its
    parent): the second kernel direction of [M − I | s] orthogonal to the tangent."""
    out = []
    eqs = record.equations
    refined = [b.x for b in known] + [r[1] for other in records for r in other.refined]
    for p in record.curve.of_kind(BRANCH_POINT):
        reach = 1e-6 if p.located else 1e-3  # a secant that did not converge: its bracket
        if any(abs(p.x[-1] - x[-1]) <= reach * max(1.0, abs(p.x[-1])) for x in refined):
            continue
        jac = eqs.jacobian(p.x)
        if not np.all(np.isfinite(jac)):
            continue
        _, _, vt = np.linalg.svd(jac)
        kernel = vt[-2:]
        t = p.tangent / float(np.linalg.norm(p.tangent))
        candidates = [v - float(v @ t) * t for v in kernel]
        d = max(candidates, key=lambda v: float(np.linalg.norm(v)))
        d = d / float(np.linalg.norm(d))
        out.append(Birth(BRANCH_POINT, p.x, d, record.period, record, p.located, p.note))
    return out


def _doublings(record: Record, max_period: int) -> list[Birth]:
    """The period doublings on a record's curve, refined; a birth each when 2k <= max_period."""
    out = []
    eqs = record.equations
    for p in record.curve.of_kind(PERIOD_DOUBLING):  # the map's corrector is regular there
        x, _ = refine(eqs, _half_test, p.x)  # det(M + I): the same function of the map's M
        located = x is not None
        note = "" if located else "Newton on the augmented system did not converge"
        x = p.x if x is None else x
        record.refined.append((PERIOD_DOUBLING, x, located, note))
        if 2 * record.period > max_period:
            continue
        mono = eqs.monodromy(x)
        if mono is None:
            continue
        direction = np.append(_eigenvector(mono, -1.0), 0.0)
        out.append(Birth(PERIOD_DOUBLING, x, direction, 2 * record.period, record, located, note))
    return out


def _switch(equations, birth: Birth, step: float):
    """The first point of the branch born at ``birth`` on ``equations``: the corrector on the
    hyperplane across its direction, ``BRANCH_SWITCH_FRACTION`` of ``step`` from it."""
    from perturb.continuation.newton import correct

    d = birth.direction / float(np.linalg.norm(birth.direction))
    for fraction in (
        BRANCH_SWITCH_FRACTION,
        BRANCH_SWITCH_FRACTION / 4,
        BRANCH_SWITCH_FRACTION * 2,
    ):
        predictor = birth.x + fraction * step * d
        corr = correct(equations, predictor, d)
        if corr.converged:
            return corr.x, d
    return None, d


def follow_births(setup, base, seeded, *, lam_range, step, budget, max_period, grid):
    """Every branch born on the ``seeded`` curves, and on those born of them (module notes).

    Parameters
    ----------
    setup : TrueFamily
    base : ScaledEquations
        The one-period equations the seeded curves were followed on.
    seeded : list of (Curve, list of str, int, str)
        The seeded curves, their analytic branches, shots and last failure.
    lam_range : (float, float)
    step : float
        The continuation's largest step.
    budget : int
        The most points of each curve.
    max_period : int
        Period doublings are followed while the period stays at most this.
    grid : ndarray

    Returns
    -------
    (list of Record, list of str)
        The records (the seeded first) and the births not followed, with why.
    """
    from perturb.continuation import continue_curve

    one = MapEquations(base, 1)
    records = []
    for curve, names, shots, failure in seeded:
        record = Record(curve, one, 1)
        record.branches, record.shots, record.failure = list(names), shots, failure
        records.append(record)
    symmetric = half_period_symmetry(setup)
    linear = _linear(setup)
    half = MapEquations(base, half=True) if symmetric else None
    maps = {1: one}
    failures: list[str] = []
    k = 0
    while k < len(records):
        record = records[k]
        k += 1
        births: list[Birth] = []
        if half is not None and record.period == 1 and _symmetric(half, record.curve):
            pitchforks = _pitchforks(record, half)
            for b in pitchforks:
                record.refined.append((BRANCH_POINT, b.x, b.located, b.note))
            births += pitchforks
        births += _other_branch_points(record, births, records)
        births += _doublings(record, max_period)
        if linear:  # refined and listed, but what is born there is a line of responses
            births = []
        for birth in births:
            if len(records) >= MAX_BRANCHES:
                failures.append(
                    f"the branch born at the {birth.kind} at {setup.parameter} = "
                    f"{birth.x[-1]:.10g}: not followed (the diagram's {MAX_BRANCHES} branches "
                    "are spent)"
                )
                continue
            equations = maps.setdefault(birth.period, MapEquations(base, birth.period))
            signs = (1.0, -1.0) if birth.kind == BRANCH_POINT else (1.0,)
            for sign in signs:
                oriented = attrs.evolve(birth, direction=sign * birth.direction)
                start, d = _switch(equations, oriented, step)
                if start is None:
                    failures.append(
                        f"the branch born at the {birth.kind} at {setup.parameter} = "
                        f"{birth.x[-1]:.10g}: the corrector did not reach it from the null "
                        "direction"
                    )
                    continue
                if _known(records, equations, start):
                    continue
                before = base.shots
                curve = continue_curve(
                    equations, start, lam_range=lam_range, direction=d, max_step=step,
                    tests=floquet_tests(), domain=equations.domain,
                    max_points=max(2, (budget + 1) // 2),
                )  # fmt: skip
                child = Record(curve, equations, birth.period, records.index(birth.parent),
                               birth.kind, equations.unscale(birth.x)[1])  # fmt: skip
                child.shots, child.failure = base.shots - before, equations.last_failure
                records.append(child)
    return records, failures


def _linear(setup) -> bool:
    """Whether the equations of motion are linear in the state (a Mathieu equation): every
    response is then a multiple of another, and a branch point bears a line of them."""
    import sympy as sp

    state = list(setup.system.state_symbols)
    return all(sp.diff(e, a, b) == 0 for e in setup.expressions for a in state for b in state)


def _known(records, equations, x) -> bool:
    """Whether x lies on a record of the same period, or its image shifted by one period of the
    parent (the other half of a doubled orbit) does."""
    if any(_on(r.curve, x) for r in records if equations.multiple % r.period == 0):
        return True  # a response of k periods is a fixed point of the 2k map too
    same = [r for r in records if r.period == equations.multiple]
    if equations.multiple > 1:
        y0, lam = equations.unscale(x)
        half_map = MapEquations(equations.base, equations.multiple // 2)
        shifted = half_map.compose(y0, lam)
        if shifted is not None:
            image = equations.scaled(shifted[0], lam)
            return any(_on(r.curve, image) for r in same)
    return False
