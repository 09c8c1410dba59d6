"""The steady-state branches of a driven system at one parameter point, and their solutions.

:func:`branches_at` finds every real root of the first-order amplitude equations at the given
values (exact rationals, :func:`~perturb.response.roots.real_roots`), continues each to order N on
the displacement function, and judges its stability (:func:`perturb.method.driven.slow_flow`);
:func:`branch_solution` is the :class:`~perturb.PeriodicSolution` of one branch (its amplitudes put
in), which evaluates, validates and exports like any other; :func:`branch_names` names them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import attrs
import numpy as np
import sympy as sp

from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import AmplitudeEquations
from perturb.method.family_names import response_shape
from perturb.response.compiled import CompiledEquations, compiled
from perturb.response.roots import real_roots
from perturb.solution import PeriodicSolution, Status

__all__ = [
    "BranchPoint",
    "SteadyState",
    "branch_names",
    "branch_solution",
    "branches_at",
    "exact_number",
    "steady_state",
]

#: Newton iterations of the order-N continuation from a first-order root.
CONTINUATION_ITERATIONS = 12
#: Relative residual of D_N at which the continuation has converged.
CONTINUATION_TOL = 1e-12
#: A continued root that moves by more than this fraction of its amplitude (plus ε) has left its
#: first-order root: a spurious root of the truncated series, not that branch.
CONTINUATION_LEAP = 0.5
#: What a point says when its slow flow's verdict lies within the slow flow's own error.
UNCERTAIN_NOTE = (
    "stability uncertain: a slow-flow pair turns fast and its real part lies within the error of "
    "the first-order slow flow (near a Neimark-Sacker point): check it with --validate"
)
#: A response whose amplitudes are all below this is the trivial one (x = 0).
TRIVIAL = 1e-12
#: Two roots this close (relative) are one: far above the isolation width, far below any
#: distinct branch.
DUPLICATE = 1e-8


@attrs.frozen
class BranchPoint:
    """One steady-state response at one parameter point.

    Attributes
    ----------
    amplitudes : dict
        ``{"a_x": ..., "b_x": ...}``: the cosine and sine amplitudes (strained time) at order N.
    norms : dict
        ``{coordinate: sqrt(a**2 + b**2)}`` of each resonant coordinate.
    stable : bool or None
        From the slow flow (None: on a fold, or undamped).
    eigenvalues, multipliers : tuple of complex
        The slow flow's eigenvalues (per unit ε, per period) and the Floquet multipliers they
        predict.
    first_order : dict
        The first-order root it was continued from.
    note : str
        Empty, or why the order-N continuation kept the first-order amplitudes.
    """

    amplitudes: dict
    norms: dict
    stable: bool | None
    eigenvalues: tuple = attrs.field(converter=tuple)
    multipliers: tuple = attrs.field(converter=tuple)
    first_order: dict = attrs.field(factory=dict)
    note: str = ""

    @property
    def trivial(self) -> bool:
        return all(n <= TRIVIAL for n in self.norms.values())

    def norm(self, coordinate: str | None = None) -> float:
        """The response amplitude of ``coordinate`` (default: the first resonant one)."""
        if coordinate is None:
            return next(iter(self.norms.values()))
        return self.norms[coordinate]


def exact_number(value) -> sp.Rational:
    """A number as the exact rational of its shortest decimal (what the user typed)."""
    if isinstance(value, sp.Basic) and value.is_Rational:
        return value
    value = float(value)
    if not math.isfinite(value):
        raise bad_value("value", value, "give a finite number", InvalidParameterError)
    return sp.Rational(repr(value))


def _fixed(equations: AmplitudeEquations, values: Mapping) -> dict:
    names = {p.name: p for p in equations.system.parameters}
    missing = sorted(set(names) - set(values))
    if missing:
        raise bad_value("values", dict(values), f"give values for {missing}", InvalidParameterError)
    return {names[k]: exact_number(values[k]) for k in names}


def branches_at(
    equations: AmplitudeEquations, values: Mapping, epsilon: float, order: int = 1
) -> tuple[list[BranchPoint], str]:
    """Every steady-state response at these parameter values.

    Returns
    -------
    (list of BranchPoint, str)
        The branches sorted by amplitude, and "" or why the roots could not be enumerated (then
        the list is empty: never a silent drop).
    """
    fixed = _fixed(equations, values)
    ready = compiled(equations, order)
    first = ready.first_order(fixed)
    unknowns = list(equations.amplitudes)
    roots = real_roots(first, unknowns, floats=True)
    if not roots.status.success:
        return [], f"{roots.status.value} ({roots.message})"
    point_values = {k.name: float(v) for k, v in fixed.items()}
    refine = _continuation(ready, point_values, float(epsilon))
    out = []
    for root in _distinct_orbits(roots.roots, equations):
        amplitudes, note = refine(root)
        # the slow flow of the displacement function whose root this is (order 0 when the
        # continuation kept the first-order root): a Jacobian off its own root means nothing
        vector = [amplitudes[s.name] for s in unknowns]
        flow = ready.slow_flow(vector, point_values, float(epsilon), first=bool(note))
        if flow.uncertain:
            note = "; ".join(filter(None, [note, UNCERTAIN_NOTE]))
        norms = {
            c: math.hypot(amplitudes[f"a_{c}"], amplitudes[f"b_{c}"]) for c in equations.coordinates
        }
        out.append(
            BranchPoint(
                amplitudes=amplitudes,
                norms=norms,
                stable=flow.stable,
                eigenvalues=tuple(complex(z) for z in flow.eigenvalues),
                multipliers=tuple(complex(z) for z in flow.multipliers),
                first_order={s.name: float(v) for s, v in root.items()},
                note=note,
            )
        )
    return sorted(out, key=lambda p: tuple(p.norms.values())), ""


def _distinct_orbits(roots, equations: AmplitudeEquations) -> list[dict]:
    """The roots that are different orbits: a response of p forcing periods shifted by k forcing
    periods (s -> s + 2 pi k/p) is the same orbit, its harmonic-m amplitudes rotated by
    2 pi k m/p (p = 2: the parametric response's (a, b) and (-a, -b))."""
    p = equations.system.excitation.p
    symbols = equations.amplitudes
    kept: list[dict] = []

    def vector(root):
        return np.array([float(root[s]) for s in symbols])

    def rotated(v, k):
        out = v.copy()
        for i, m in enumerate(equations.harmonics):
            angle = 2 * math.pi * k * m / p
            c, s_ = math.cos(angle), math.sin(angle)
            a, b = v[2 * i], v[2 * i + 1]
            out[2 * i], out[2 * i + 1] = c * a + s_ * b, -s_ * a + c * b
        return out

    for root in roots:
        v = vector(root)
        size = max(1.0, float(np.max(np.abs(v))))
        images = [rotated(v, k) for k in range(1, p)]
        if any(
            np.max(np.abs(image - vector(other))) <= DUPLICATE * size
            for other in kept
            for image in images
        ):
            continue
        kept.append(root)
    return kept


def _continuation(ready: CompiledEquations, values: dict, eps: float):
    """Newton on D_N from a first-order root (the identity at order 0)."""
    symbols = list(ready.equations.amplitudes)
    names = [s.name for s in symbols]
    order = ready.order
    if order == 0:
        return lambda root: ({s.name: float(v) for s, v in root.items()}, "")

    def refine(root):
        x = np.array([float(root[s]) for s in symbols])
        start = x.copy()
        size = max(1.0, float(np.max(np.abs(x))))
        residual = ready.residual(x, values, eps)
        for _ in range(CONTINUATION_ITERATIONS):
            if np.max(np.abs(residual)) <= CONTINUATION_TOL * size:
                break
            try:
                x = x + np.linalg.solve(ready.jacobian(x, values, eps), -residual)
            except np.linalg.LinAlgError:
                break
            residual = ready.residual(x, values, eps)
        converged = bool(np.max(np.abs(residual)) <= CONTINUATION_TOL * size * 1e3)
        leap = float(np.max(np.abs(x - start)))
        if not converged or leap > CONTINUATION_LEAP * max(float(np.max(np.abs(start))), eps):
            return (
                dict(zip(names, start.tolist(), strict=True)),
                f"the order-{order} continuation did not converge from this first-order root "
                "(near a fold): its first-order amplitudes are kept",
            )
        return dict(zip(names, x.tolist(), strict=True)), ""

    return refine


def branch_names(points: list[BranchPoint]) -> list[str]:
    """Stable names for the branches at one point, sorted by amplitude: ``trivial`` (x = 0), then
    ``response`` (one), ``lower``/``upper`` (two), ``lower``/``middle``/``upper`` (three),
    else ``branch-1``, ``branch-2``, …

    With several resonant coordinates each branch is named by its mode shape first
    (:func:`perturb.method.family_names.response_shape`: ``in-phase``, ``anti-phase``,
    ``shape-pn0``, ``-localised-x2``), and the branches of one shape by amplitude as above:
    ``in-phase`` alone, ``in-phase-lower`` and ``in-phase-upper``, ``in-phase-1``, …"""
    trivial = [p for p in points if p.trivial]
    others = [p for p in points if not p.trivial]
    out = {id(p): "trivial" for p in trivial}
    if others and len(others[0].norms) > 1:
        groups: dict[str, list] = {}
        for p in others:
            groups.setdefault(response_shape(_complex(p)), []).append(p)
        for shape, members in groups.items():
            members.sort(key=lambda p: math.hypot(*p.norms.values()))
            for p, rank in zip(members, _ranks(len(members)), strict=True):
                out[id(p)] = f"{shape}-{rank}" if rank else shape
        return [out[id(p)] for p in points]
    names = _ranks(len(others)) if len(others) <= 3 else []
    names = [n or "response" for n in names] or [f"branch-{k + 1}" for k in range(len(others))]
    out.update({id(p): n for p, n in zip(others, names, strict=True)})
    return [out[id(p)] for p in points]


def _ranks(count: int) -> list[str]:
    """Names of ``count`` branches of one kind by amplitude ("" for a single one)."""
    labels = {1: [""], 2: ["lower", "upper"], 3: ["lower", "middle", "upper"]}
    return labels.get(count, [str(k + 1) for k in range(count)])


def _complex(point: BranchPoint) -> dict:
    """``{coordinate: a - ib}`` of a response point."""
    return {
        c: complex(point.amplitudes[f"a_{c}"], -point.amplitudes[f"b_{c}"]) for c in point.norms
    }


def branch_solution(
    equations: AmplitudeEquations, point: BranchPoint, name: str = ""
) -> PeriodicSolution:
    """The periodic solution of one branch: the series with its amplitudes put in.

    The solution's system is the driven system itself (its parameters stay symbols, evaluated
    with the problem's values); the amplitudes are numbers (30 significant digits of the
    double-precision root). ``message`` says which branch it is and its stability.
    """
    series = equations.solution
    amplitude_symbols = set(equations.amplitudes)
    subs = {s: sp.Float(point.amplitudes[s.name], 30) for s in equations.amplitudes}
    terms = tuple(
        tuple(t.map(lambda c, s=subs: c.xreplace(s)) for t in row) for row in series.terms
    )
    generating = attrs.evolve(
        series.generating,
        cos_amplitudes=tuple(
            sp.sympify(a).xreplace(subs) for a in series.generating.cos_amplitudes
        ),
        sin_amplitudes=tuple(
            sp.sympify(b).xreplace(subs) for b in series.generating.sin_amplitudes
        ),
    )
    system = attrs.evolve(
        series.system,
        parameters=tuple(p for p in series.system.parameters if p not in amplitude_symbols),
    )
    deviations = {
        k: tuple(sp.sympify(v).xreplace(subs) for v in vs) for k, vs in series.deviations.items()
    }
    stability = {True: "stable", False: "unstable", None: "on a fold (marginal)"}[point.stable]
    message = (
        f"branch {name or 'of the response'}: amplitudes "
        + ", ".join(f"{k} = {v:.6g}" for k, v in point.amplitudes.items())
        + f"; {stability} (slow flow)"
        + (f"; {point.note}" if point.note else "")
    )
    return attrs.evolve(
        series,
        system=system,
        terms=terms,
        generating=generating,
        deviations=deviations,
        status=Status.SUCCESS,
        message=message,
    )


@attrs.frozen
class SteadyState:
    """Every branch of a driven system's response at one parameter point.

    Attributes
    ----------
    points : tuple of BranchPoint
        Sorted by amplitude.
    names : tuple of str
        :func:`branch_names` of ``points``.
    equations : AmplitudeEquations
    why : str
        Empty, or why the roots could not be enumerated (then ``points`` is empty).
    """

    points: tuple = attrs.field(converter=tuple)
    names: tuple = attrs.field(converter=tuple)
    equations: AmplitudeEquations = attrs.field(eq=False)
    why: str = ""

    def solution(self, name: str | None = None) -> PeriodicSolution:
        """The branch ``name`` (default: the largest non-trivial amplitude) as a solution; a
        failed one (``NO_ROOT`` with the reason) when there is none."""
        from perturb.errors import UnknownNameError

        if self.why or not self.points:
            return attrs.evolve(
                self.equations.solution,
                status=Status.NO_ROOT,
                message=self.why or "the response equations have no real root at these values",
            )
        if name is None:
            nontrivial = [i for i, p in enumerate(self.points) if not p.trivial]
            index = nontrivial[-1] if nontrivial else len(self.points) - 1
        elif name in self.names:
            index = self.names.index(name)
        else:
            raise UnknownNameError(
                f"`family` = {name!r} is not a branch of the response here: choose from "
                f"{list(self.names)}"
            )
        return branch_solution(self.equations, self.points[index], self.names[index])

    def families(self, system_name: str, order: int):
        """The branches as a :class:`perturb.FamilyList` (isolated families, by name)."""
        from perturb.method.families import Family, FamilyList

        families = [
            Family(
                name=name,
                kind="isolated",
                amplitudes={k: float(v) for k, v in point.amplitudes.items()},
                free=(),
                solution=branch_solution(self.equations, point, name),
                phase_coordinate=self.equations.coordinates[0],
            )
            for point, name in zip(self.points, self.names, strict=True)
        ]
        return FamilyList(system=system_name, order=order, family_order=1, families=families)


def steady_state(system, values: Mapping, epsilon: float, order: int = 1) -> SteadyState:
    """Every branch of the driven ``system``'s response at ``values`` (:class:`SteadyState`)."""
    from perturb.method.driven import amplitude_equations

    equations = amplitude_equations(system, order)
    points, why = branches_at(equations, values, epsilon, order)
    return SteadyState(points, branch_names(points), equations, why)
